//! Fresnel reflectance for dielectrics and conductors, and the mirror and refraction directions.
//!
//! All reflectances are unpolarised, R = (R_s + R_p)/2, where R_s and R_p are the *squared*
//! magnitudes of the amplitude ratios (`../shared/PHYSICS.md`, "Dielectrics"; the lecture notes
//! print R_s without the square, see the errata there).
//!
//! Relative indices are `eta = n_t / n_i`: the index of the medium the light is transmitted into
//! over the index of the medium it comes from. In the local shading frame "outside" is the +z side.

use glam::Vec3;

use crate::polarisation::Complex;

/// (R_s, R_p) for light hitting an interface of relative index `eta = n_t/n_i` with
/// cos θᵢ = `cos_theta_i`.
///
/// A negative `cos_theta_i` means the light arrives from the other side (−z): the interface is
/// then seen with the reciprocal index 1/`eta` and |cos θᵢ|. Past the critical angle (total
/// internal reflection) both are 1.
#[inline]
pub fn fresnel_dielectric_sp(cos_theta_i: f32, eta: f32) -> (f32, f32) {
    let (cos_i, eta) = if cos_theta_i < 0.0 {
        (-cos_theta_i, 1.0 / eta)
    } else {
        (cos_theta_i, eta)
    };
    let cos_i = cos_i.min(1.0);
    // Snell: sin θₜ = sin θᵢ / eta.
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return (1.0, 1.0);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    // PHYSICS.md forms divided through by n_i:
    // r_s = (n_i cos θᵢ − n_t cos θₜ)/(n_i cos θᵢ + n_t cos θₜ),
    // r_p = (n_i cos θₜ − n_t cos θᵢ)/(n_i cos θₜ + n_t cos θᵢ).
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (cos_t - eta * cos_i) / (cos_t + eta * cos_i);
    (rs * rs, rp * rp)
}

/// Unpolarised dielectric reflectance R = (R_s + R_p)/2 for relative index `eta = n_t/n_i`.
/// Handles `cos_theta_i < 0` by flipping the interface; returns 1 under total internal
/// reflection.
#[inline]
pub fn fresnel_dielectric(cos_theta_i: f32, eta: f32) -> f32 {
    let (rs, rp) = fresnel_dielectric_sp(cos_theta_i, eta);
    0.5 * (rs + rp)
}

/// Unpolarised dielectric reflectance from *both* cosines of a refracted pair: |cos θᵢ| =
/// `cos_i`, |cos θₜ| = `cos_t`, relative index `eta = n_t/n_i` (the PHYSICS.md forms divided by
/// n_i). The caller guarantees that the pair obeys Snell's law.
///
/// Near the critical angle, seen from the denser side, [`fresnel_dielectric`] must recover
/// cos θₜ = √(1 − sin²θᵢ/η²) through a catastrophic cancellation; when both directions are known
/// (microfacet transmission) this form is well-conditioned, and it is symmetric under swapping
/// the two sides, (cos_i, cos_t, eta) → (cos_t, cos_i, 1/eta).
#[inline]
pub fn fresnel_dielectric_pair(cos_i: f32, cos_t: f32, eta: f32) -> f32 {
    let (ci, ct) = (cos_i.abs(), cos_t.abs());
    let rs = (ci - eta * ct) / (ci + eta * ct);
    let rp = (ct - eta * ci) / (ct + eta * ci);
    0.5 * (rs * rs + rp * rp)
}

/// Unpolarised reflectance of a conductor of complex relative index `eta + i·k` (both already
/// divided by the outside medium's index) for light from outside with cos θᵢ = `cos_theta_i`.
///
/// This is the full complex Fresnel formula (no Schlick approximation): with η̃ = eta + ik,
/// cos θₜ = √(1 − sin²θᵢ/η̃²) (principal root), r_s = (cos θᵢ − η̃ cos θₜ)/(cos θᵢ + η̃ cos θₜ),
/// r_p = (η̃ cos θᵢ − cos θₜ)/(η̃ cos θᵢ + cos θₜ), R = (|r_s|² + |r_p|²)/2. With k = 0 it is
/// [`fresnel_dielectric`] (including total internal reflection for eta < 1). `cos_theta_i` is
/// clamped to [0, 1]: a conductor is lit from outside only.
#[inline]
pub fn fresnel_conductor(cos_theta_i: f32, eta: f32, k: f32) -> f32 {
    if eta == 0.0 && k == 0.0 {
        // the limit of n + ik → 0: total reflection at every angle (Mitsuba 3.9.1 returns 1
        // there too, NaN at exactly normal incidence), where the formula below divides 0 by 0
        return 1.0;
    }
    let cos_i = cos_theta_i.clamp(0.0, 1.0);
    let sin2_i = 1.0 - cos_i * cos_i;
    let eta_c = Complex::new(eta, k);
    let eta2 = eta_c * eta_c;
    let sin2_t = Complex::new(sin2_i, 0.0) / eta2;
    let cos_t = (Complex::new(1.0, 0.0) - sin2_t).sqrt();
    let ci = Complex::new(cos_i, 0.0);
    let eta_cos_t = eta_c * cos_t;
    let eta_cos_i = eta_c.scale(cos_i);
    let rs = Complex::ratio_norm2(ci - eta_cos_t, ci + eta_cos_t);
    let rp = Complex::ratio_norm2(eta_cos_i - cos_t, eta_cos_i + cos_t);
    0.5 * (rs + rp)
}

/// Mirror direction of `wo` about the unit normal `n`: 2n(n·wo) − wo. Both `wo` and the result
/// point away from the surface (PHYSICS.md errata: the notes' form reflects an incoming ray).
#[inline]
pub fn reflect(wo: Vec3, n: Vec3) -> Vec3 {
    2.0 * wo.dot(n) * n - wo
}

/// Refracts `wi` (pointing away from the surface) through an interface with unit normal `n`
/// and relative index `eta = n(−n side)/n(+n side)`, i.e. the index of the medium on the other
/// side of `n` from where `n` points over the index on the side `n` points to.
///
/// If `wi` is on the −n side the interface is flipped (normal −n, index 1/`eta`). Returns the
/// transmitted direction (pointing away from the surface, on the other side) and the relative
/// index actually used, `etap = n_t/n_i` for this crossing, or `None` under total internal
/// reflection.
#[inline]
pub fn refract(wi: Vec3, n: Vec3, eta: f32) -> Option<(Vec3, f32)> {
    let mut cos_i = n.dot(wi);
    let (mut n, mut etap) = (n, eta);
    if cos_i < 0.0 {
        etap = 1.0 / etap;
        cos_i = -cos_i;
        n = -n;
    }
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (etap * etap);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let wt = -wi / etap + (cos_i / etap - cos_t) * n;
    Some((wt, etap))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dielectric_symmetry_and_tir() {
        // Same reflectance from either side for the refracted pair of angles.
        let eta = 1.5f32;
        let cos_i = 0.8f32;
        let sin_t = (1.0 - cos_i * cos_i).sqrt() / eta;
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        let a = fresnel_dielectric(cos_i, eta);
        let b = fresnel_dielectric(cos_t, 1.0 / eta);
        let c = fresnel_dielectric(-cos_t, eta); // from inside of the same interface
        assert!((a - b).abs() < 1e-6 && (a - c).abs() < 1e-6, "{a} {b} {c}");
        assert_eq!(fresnel_dielectric(-0.1, 1.5), 1.0);
    }

    #[test]
    fn refract_round_trip() {
        let n = Vec3::Z;
        let wi = Vec3::new(0.3, -0.4, 0.866).normalize();
        let (wt, etap) = refract(wi, n, 1.5).unwrap();
        assert_eq!(etap, 1.5);
        assert!(wt.z < 0.0 && (wt.length() - 1.0).abs() < 1e-6);
        let (back, etap2) = refract(wt, n, 1.5).unwrap();
        assert!((etap2 - 1.0 / 1.5).abs() < 1e-7);
        assert!((back - wi).length() < 1e-5);
        assert!((reflect(wi, n) - Vec3::new(-wi.x, -wi.y, wi.z)).length() < 1e-7);
    }

    #[test]
    fn conductor_k0_is_dielectric() {
        for i in 0..=20 {
            let c = i as f32 / 20.0;
            for eta in [0.6f32, 1.0, 1.33, 2.4] {
                // Skip the neighbourhood of the critical angle, where R is ill-conditioned.
                if eta < 1.0 && ((1.0 - c * c).sqrt() - eta).abs() < 0.05 {
                    continue;
                }
                let d = fresnel_dielectric(c, eta);
                let m = fresnel_conductor(c, eta, 0.0);
                assert!((d - m).abs() < 2e-6, "cos {c} eta {eta}: {d} vs {m}");
            }
        }
    }
}
