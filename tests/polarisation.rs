//! Polarisation optics against closed forms (issue 28), on the Mueller matrices the polarised
//! mode is built from: Malus's law, Brewster's angle per wavelength with the catalogue glasses,
//! and the retardance of a Fresnel rhomb's total internal reflections, each to 0.1 %.

mod support;

use spectrace::polarisation::{Complex, Mueller, Stokes, elements, fresnel, rotated_element};
use spectrace::spectrum::named::{Named, lookup};
use support::prism::n_bk7;

/// The catalogue glass `name`'s index at `l` nm, as the renderer evaluates it.
fn catalogue(name: &str, l: f32) -> f32 {
    match lookup(&format!("glass:{name}")) {
        Ok(Named::Dielectric(g)) => g.ior.eval(l),
        other => panic!("{name}: {other:?}"),
    }
}

/// N-SF11 (SCHOTT's Sellmeier coefficients), λ in nm, evaluated here independently.
fn n_sf11(l_nm: f64) -> f64 {
    let l2 = (l_nm * 1e-3).powi(2);
    let b = [1.73759695, 0.313747346, 1.89878101];
    let c = [0.013188707, 0.0623068142, 155.23629];
    (1.0 + (0..3).map(|i| b[i] * l2 / (l2 - c[i])).sum::<f64>()).sqrt()
}

/// Malus's law: unpolarised light of intensity 1 through two ideal linear polarisers whose
/// axes differ by θ leaves with ½·cos²θ, fully polarised along the second, within 0.1 % (of
/// the incident intensity where the closed form is near 0).
#[test]
fn malus_law() {
    for k in 0..=36 {
        let theta = (k as f32 * 5.0).to_radians();
        let first = elements::linear_polariser();
        let second = rotated_element(theta, &elements::linear_polariser());
        let out = second * (first * Stokes::unpolarised(1.0));
        let want = 0.5 * theta.cos().powi(2);
        assert!(
            (out.0[0] - want).abs() < 1e-3 * want.max(1.0) * 0.5,
            "θ = {} deg: {} vs {want}",
            k * 5,
            out.0[0]
        );
        if want > 1e-3 {
            assert!((out.degree() - 1.0).abs() < 1e-3, "{out:?}");
            let angle = out.angle_linear().rem_euclid(std::f32::consts::PI);
            let axis = theta.rem_euclid(std::f32::consts::PI);
            let diff = (angle - axis).abs();
            assert!(
                diff.min(std::f32::consts::PI - diff) < 1e-3,
                "θ = {} deg: angle {angle}",
                k * 5
            );
        }
    }
}

/// Brewster: at θ_B = atan n(λ), with n from SCHOTT's Sellmeier formula evaluated here, the
/// renderer's catalogue glass reflects no p-polarised light (R_p below 10⁻⁶ of R_s) while
/// reflecting s-polarised light by the closed form R_s = cos²(2θ_B) (at Brewster's angle
/// θ_t = 90° − θ_B), within 0.1 %, for N-BK7 and N-SF11 at the F, d and C lines; one degree
/// either side, R_p is clearly not zero (the minimum is where Brewster puts it for each
/// wavelength).
#[test]
fn brewster_angle_moves_with_the_index() {
    type Sellmeier = fn(f64) -> f64;
    let glasses: [(&str, Sellmeier); 2] = [("N-BK7", n_bk7), ("N-SF11", n_sf11)];
    for (name, n_of) in glasses {
        for l in [486.1, 587.6, 656.3] {
            let n = n_of(l);
            let theta_b = n.atan();
            let eta = catalogue(name, l as f32);
            let m = |theta: f64| fresnel::reflection(theta.cos() as f32, Complex::new(eta, 0.0));
            let at = m(theta_b);
            let (r_s, r_p) = (at.0[0][0] + at.0[0][1], at.0[0][0] - at.0[0][1]);
            let want_s = (2.0 * theta_b).cos().powi(2) as f32;
            assert!(
                r_p.abs() < 1e-6 * r_s,
                "{name} at {l} nm: R_p {r_p} at θ_B {:.3}°",
                theta_b.to_degrees()
            );
            assert!(
                (r_s / want_s - 1.0).abs() < 1e-3,
                "{name} at {l} nm: R_s {r_s} vs cos²2θ_B {want_s}"
            );
            for off in [-1.0f64, 1.0] {
                let side = m(theta_b + off.to_radians());
                let r_p_side = side.0[0][0] - side.0[0][1];
                assert!(
                    r_p_side > 1e-5,
                    "{name} at {l} nm: R_p {r_p_side} at θ_B {off:+}°"
                );
            }
        }
    }
}

/// The retardance of one total internal reflection from inside glass of index n at incidence
/// θ (Born and Wolf §1.5.4): tan(δ/2) = cos θ √(sin²θ − 1/n²) / sin²θ.
fn tir_retardance(n: f64, theta: f64) -> f64 {
    let s2 = theta.sin().powi(2);
    2.0 * (theta.cos() * (s2 - 1.0 / (n * n)).sqrt() / s2).atan()
}

/// A Fresnel rhomb of N-BK7: light linearly polarised at 45° to the plane of incidence meets
/// two total internal reflections at the design angle (the larger θ at which one reflection
/// retards by 45° for the d line, n_d = 1.5168: θ ≈ 55.2°; the textbook 54.6° is for
/// n = 1.51). At 587.6 nm it leaves circularly polarised (|S3| = 1 within 0.1 %, S1 = S2 = 0);
/// at 400–800 nm its retardance, read from the Stokes vector as atan2(|S3|, S2), is twice the
/// closed form at the catalogue's n(λ) within 0.1 %, and the light stays fully polarised
/// (lossless reflections).
#[test]
fn a_fresnel_rhomb_is_a_quarter_wave_retarder_at_its_design_wavelength() {
    let nd = n_bk7(587.6);
    // the design angle: δ(θ) = 45°, on the branch above δ's maximum (bisection)
    let theta_max = ((2.0 / (1.0 + nd * nd)).sqrt())
        .asin()
        .max((1.0 / nd).asin());
    let (mut lo, mut hi) = (theta_max, 89f64.to_radians());
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if tir_retardance(nd, mid) > std::f64::consts::FRAC_PI_4 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta = 0.5 * (lo + hi);
    assert!(
        (theta.to_degrees() - 55.2).abs() < 0.1,
        "design angle {}",
        theta.to_degrees()
    );
    let input = Stokes::linear(1.0, std::f32::consts::FRAC_PI_4);
    for l in [400.0f64, 486.1, 587.6, 656.3, 800.0] {
        let n = catalogue("N-BK7", l as f32);
        // from inside the glass: relative index 1/n
        let tir: Mueller = fresnel::reflection(theta.cos() as f32, Complex::new(1.0 / n, 0.0));
        let out = tir * (tir * input);
        let got = out.0[3].abs().atan2(out.0[2]) as f64;
        let want = 2.0 * tir_retardance(n_bk7(l), theta);
        assert!(
            (got / want - 1.0).abs() < 1e-3,
            "{l} nm: retardance {:.4}° vs {:.4}°",
            got.to_degrees(),
            want.to_degrees()
        );
        assert!((out.0[0] - 1.0).abs() < 1e-5 && (out.degree() - 1.0).abs() < 1e-4);
        if l == 587.6 {
            assert!(
                (out.0[3].abs() - 1.0).abs() < 1e-3
                    && out.0[1].abs() < 1e-3
                    && out.0[2].abs() < 1e-3,
                "at the design wavelength: {out:?}"
            );
        }
    }
}
