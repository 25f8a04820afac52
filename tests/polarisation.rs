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
        if support::prism::tir_retardance(nd, mid) > std::f64::consts::FRAC_PI_4 {
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
        let want = 2.0 * support::prism::tir_retardance(n_bk7(l), theta);
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

/// Every material's Mueller matrix in the polarised mode is physically realisable (Cloude's
/// criterion, `elements::realisable`) for random pairs of directions and wavelengths: smooth
/// and rough N-BK7 (reflection, transmission, total internal reflection), smooth and rough
/// gold, Mitsuba's polarising plastic, a polariser and a retarder at oblique incidence.
#[test]
fn every_material_mueller_matrix_is_realisable() {
    use glam::Vec3;
    use spectrace::geometry::Frame;
    use spectrace::material::microfacet::{Distribution, Microfacet};
    use spectrace::material::{
        Conductor, Dielectric, Element, Material, PPlastic, Polarising, RoughConductor,
        RoughDielectric,
    };
    use spectrace::spectrum::{SampledWavelengths, Spectrum};
    let bk7 = match lookup("glass:N-BK7") {
        Ok(Named::Dielectric(g)) => g.ior,
        other => panic!("{other:?}"),
    };
    let gold = match lookup("metal:Au") {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    };
    let materials = [
        Material::Dielectric(Dielectric::new(bk7.clone(), 1.0)),
        Material::RoughDielectric(RoughDielectric::new(bk7, 1.0, 0.3)),
        Material::Conductor(Conductor::new(gold.clone(), 1.0)),
        Material::RoughConductor(RoughConductor::new(gold, 1.0, 0.2)),
        Material::PPlastic(PPlastic::new(
            Spectrum::Constant(0.4).into(),
            0.4,
            1.0,
            1.49,
            Microfacet::new(0.1, Distribution::Beckmann),
        )),
        Material::Element(Element::Polariser {
            theta: 0.4,
            transmittance: 0.9,
            polarizing: true,
        }),
        Material::Element(Element::Retarder {
            theta: 0.7,
            delta: 1.2,
        }),
    ];
    let mut k = 7u64;
    let mut u = || {
        k = k
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((k >> 40) as f32 + 0.5) / (1u64 << 24) as f32
    };
    let frame = Frame::from_normal(Vec3::new(0.2, -0.3, 0.93).normalize());
    let mut checked = 0;
    for m in &materials {
        for _ in 0..400 {
            let dir = |a: f32, b: f32, below: bool| {
                let z = if below { -a } else { a };
                let r = (1.0 - a * a).max(0.0).sqrt();
                let p = std::f32::consts::TAU * b;
                Vec3::new(r * p.cos(), r * p.sin(), z)
            };
            let w = SampledWavelengths {
                lambda: [400.0 + 300.0 * u(), 550.0, 480.0, 650.0],
                pdf: [1.0 / 470.0; 4],
            };
            let bsdf = m.at(glam::Vec2::ZERO, &w);
            let wo = dir(u().max(0.05), u(), u() < 0.3);
            // a sampled direction (delta lobes), else any on either side
            let wi = match bsdf.sample(
                wo,
                &w,
                u(),
                glam::Vec2::new(u(), u()),
                spectrace::material::TransportMode::Radiance,
            ) {
                Some(s) if u() < 0.7 => s.wi,
                _ => dir(u().max(0.05), u(), u() < 0.5),
            };
            if let Polarising::Matrix(p) = bsdf.mueller(&frame, wo, wi, &w) {
                for (j, mj) in p.iter().enumerate() {
                    assert!(
                        (mj.0[0][0] - 1.0).abs() < 1e-4,
                        "{m:?}: normalised, (0, 0) = {}",
                        mj.0[0][0]
                    );
                    assert!(
                        elements::realisable(mj, 1e-4),
                        "{m:?} wo {wo} wi {wi} λ{j} {}: {mj:?}",
                        w.lambda[j]
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 1500, "{checked} matrices checked");
}

/// Mitsuba's polarising plastic gives finite sample weights and Mueller matrices everywhere,
/// grazing directions included, with and without its diffuse term.
#[test]
fn pplastic_samples_and_matrices_are_finite() {
    use glam::{Vec2, Vec3};
    use spectrace::geometry::Frame;
    use spectrace::material::microfacet::{Distribution, Microfacet};
    use spectrace::material::{Material, PPlastic, Polarising, TransportMode};
    use spectrace::spectrum::{SampledWavelengths, Spectrum};
    let w = SampledWavelengths {
        lambda: [550.0, 450.0, 650.0, 500.0],
        pdf: [1.0 / 470.0; 4],
    };
    let frame = Frame::from_normal(Vec3::Z);
    for rho in [0.0, 0.3] {
        let m = Material::PPlastic(PPlastic::new(
            Spectrum::Constant(rho).into(),
            rho,
            1.0,
            1.49,
            Microfacet::new(0.06, Distribution::Beckmann),
        ));
        let bsdf = m.at(Vec2::ZERO, &w);
        let n = 200;
        for a in 0..n {
            for b in 0..n {
                let cos = ((a as f32 + 0.5) / n as f32).powi(4);
                let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
                let u = Vec2::new((b as f32 + 0.5) / n as f32, (a * 7 % n) as f32 / n as f32);
                let Some(s) = bsdf.sample(
                    wo,
                    &w,
                    (b * 13 % n) as f32 / n as f32,
                    u,
                    TransportMode::Radiance,
                ) else {
                    continue;
                };
                let wt = s.f[0] * s.wi.z.abs() / s.pdf;
                assert!(
                    wt.is_finite(),
                    "ρ {rho}, wo {wo}, wi {}: f {:?} pdf {}",
                    s.wi,
                    s.f,
                    s.pdf
                );
                if let Polarising::Matrix(p) = bsdf.mueller(&frame, wo, s.wi, &w) {
                    assert!(
                        p.iter()
                            .all(|m| m.0.iter().flatten().all(|v| v.is_finite())),
                        "ρ {rho}, wo {wo}, wi {}: {p:?}",
                        s.wi
                    );
                }
            }
        }
    }
}
