//! The Fresnel equations with their phases, and the Mueller matrices of specular reflection and
//! transmission at a dielectric or conducting interface (Born and Wolf, *Principles of Optics*,
//! §1.5.2 and §1.5.4 for total internal reflection; Azzam and Bashara 1977 for the Mueller
//! form).
//!
//! Conventions: light arrives from a medium of index n₁ onto one of complex index n₂ = n + ik,
//! `eta` = n₂/n₁; cos θᵢ ≥ 0. The s (TE) component's basis is perpendicular to the plane of
//! incidence, and the Mueller matrices below act in the frame whose basis vector is the s
//! direction, on both the incident and the outgoing beam (see [`super`] for the Stokes
//! conventions). The p amplitude has the sign for which normal incidence on glass gives
//! r_p = −r_s, so that a mirror at normal incidence flips the handedness of circular light
//! (S2, S3 → −S2, −S3), as Mitsuba 3's `specular_reflection` does.

use super::{Complex, Mueller};

/// The complex amplitude reflection coefficients (r_s, r_p) and cos θₜ (complex: imaginary
/// past the critical angle, where the transmitted wave is evanescent) for relative index
/// `eta` and cos θᵢ = `cos_i` in [0, 1]:
/// r_s = (cos θᵢ − η cos θₜ)/(cos θᵢ + η cos θₜ), r_p = (η cos θᵢ − cos θₜ)/(η cos θᵢ + cos θₜ),
/// cos θₜ = √(1 − sin²θᵢ/η²), the principal root.
pub fn amplitudes(cos_i: f32, eta: Complex) -> (Complex, Complex, Complex) {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_i = 1.0 - cos_i * cos_i;
    let cos_t = (Complex::new(1.0, 0.0) - Complex::new(sin2_i, 0.0) / (eta * eta)).sqrt();
    let ci = Complex::new(cos_i, 0.0);
    let (eta_ct, eta_ci) = (eta * cos_t, eta.scale(cos_i));
    let rs = (ci - eta_ct) / (ci + eta_ct);
    let rp = (eta_ci - cos_t) / (eta_ci + cos_t);
    (rs, rp, cos_t)
}

/// The Mueller matrix of specular reflection (dimensionless; (0, 0) is the unpolarised
/// reflectance): with R_s = |r_s|², R_p = |r_p|² and the retardance δ = arg r_s − arg r_p
/// (the sign Mitsuba 3.9.1's `specular_reflection` computes, measured: for a conductor of
/// η = 0.27 + 2.78i at cos θᵢ = 0.5 its element (2, 3) is −0.712, and −0.428 for total
/// internal reflection at η = 1/1.5, cos θᵢ = 0.3; so that S3's handedness reads as in its
/// polarised renders),
/// ```text
/// | (R_s+R_p)/2  (R_s−R_p)/2        0             0        |
/// | (R_s−R_p)/2  (R_s+R_p)/2        0             0        |
/// |      0            0        √(R_sR_p)cos δ  −√(R_sR_p)sin δ |
/// |      0            0        √(R_sR_p)sin δ   √(R_sR_p)cos δ |
/// ```
/// Past the critical angle R_s = R_p = 1 and δ is the retardance of total internal
/// reflection.
pub fn reflection(cos_i: f32, eta: Complex) -> Mueller {
    let (rs, rp, _) = amplitudes(cos_i, eta);
    let (r_s, r_p) = (rs.norm2(), rp.norm2());
    let c = (r_s * r_p).sqrt();
    let (sin_d, cos_d) = if c > 0.0 {
        (rs.arg() - rp.arg()).sin_cos()
    } else {
        (0.0, 0.0)
    };
    let (a, b) = (0.5 * (r_s + r_p), 0.5 * (r_s - r_p));
    Mueller([
        [a, b, 0.0, 0.0],
        [b, a, 0.0, 0.0],
        [0.0, 0.0, c * cos_d, -c * sin_d],
        [0.0, 0.0, c * sin_d, c * cos_d],
    ])
}

/// The Mueller matrix of specular transmission into a dielectric of real relative index `eta`
/// (power transmittances: T = (η cos θₜ / cos θᵢ)·|t|² with t_s = 1 + r_s and t_p = (1 + r_p)/η,
/// so that T + R = 1 for each of s and p; no retardance). Zero past the critical angle.
pub fn transmission(cos_i: f32, eta: f32) -> Mueller {
    let (rs, rp, cos_t) = amplitudes(cos_i, Complex::new(eta, 0.0));
    let cos_i = cos_i.clamp(0.0, 1.0);
    if cos_t.im != 0.0 || cos_t.re <= 0.0 || cos_i <= 0.0 {
        return Mueller([[0.0; 4]; 4]);
    }
    let factor = eta * cos_t.re / cos_i;
    let t_s = factor * (1.0 + rs.re).powi(2);
    let t_p = factor * ((1.0 + rp.re) / eta).powi(2);
    let (a, b, c) = (0.5 * (t_s + t_p), 0.5 * (t_s - t_p), (t_s * t_p).sqrt());
    Mueller([
        [a, b, 0.0, 0.0],
        [b, a, 0.0, 0.0],
        [0.0, 0.0, c, 0.0],
        [0.0, 0.0, 0.0, c],
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::fresnel::fresnel_dielectric_sp;

    #[test]
    fn reflectances_are_the_unpolarised_fresnel_equations() {
        for eta in [1.5f32, 1.0 / 1.5, 2.4] {
            for k in 0..=20 {
                let cos_i = k as f32 / 20.0;
                let m = reflection(cos_i, Complex::new(eta, 0.0));
                let (rs, rp) = fresnel_dielectric_sp(cos_i, eta);
                assert!((m.0[0][0] - 0.5 * (rs + rp)).abs() < 1e-5, "{eta} {cos_i}");
                assert!((m.0[0][1] - 0.5 * (rs - rp)).abs() < 1e-5, "{eta} {cos_i}");
            }
        }
    }

    #[test]
    fn reflection_and_transmission_conserve_energy_per_component() {
        for eta in [1.33f32, 1.5, 1.9] {
            for k in 0..20 {
                let cos_i = (k as f32 + 0.5) / 20.0;
                let (r, t) = (
                    reflection(cos_i, Complex::new(eta, 0.0)),
                    transmission(cos_i, eta),
                );
                // s: (1, 1, 0, 0) row sums; p: (1, −1, 0, 0)
                let rs = r.0[0][0] + r.0[0][1];
                let ts = t.0[0][0] + t.0[0][1];
                let rp = r.0[0][0] - r.0[0][1];
                let tp = t.0[0][0] - t.0[0][1];
                assert!(
                    (rs + ts - 1.0).abs() < 1e-5,
                    "s: {eta} {cos_i}: {rs} + {ts}"
                );
                assert!(
                    (rp + tp - 1.0).abs() < 1e-5,
                    "p: {eta} {cos_i}: {rp} + {tp}"
                );
            }
        }
    }

    #[test]
    fn a_mirror_at_normal_incidence_flips_handedness() {
        let m = reflection(1.0, Complex::new(1.5, 0.0));
        let r = 0.04f32;
        let want = [r, r, -r, -r];
        for (i, w) in want.iter().enumerate() {
            assert!((m.0[i][i] - w).abs() < 1e-6, "{:?}", m.0);
        }
    }
}
