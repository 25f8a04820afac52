//! Fresnel reflectance against closed forms and independent formulas, Snell's law and BK7's
//! dispersion through the smooth dielectric's sampled refraction.

use glam::{Vec2, Vec3};
use spectrace::material::fresnel::{
    fresnel_conductor, fresnel_dielectric, fresnel_dielectric_sp, refract,
};
use spectrace::material::{Dielectric, Material, TransportMode};
use spectrace::spectrum::SampledWavelengths;
use spectrace::spectrum::ior::Ior;
use spectrace::spectrum::named::{Named, lookup};

/// Unpolarised dielectric reflectance straight from PHYSICS.md in f64: light in medium n1 at
/// angle θ₁ onto medium n2.
fn reference_dielectric(n1: f64, n2: f64, theta1: f64) -> f64 {
    let sin_t = n1 / n2 * theta1.sin();
    if sin_t >= 1.0 {
        return 1.0;
    }
    let (ci, ct) = (theta1.cos(), (1.0 - sin_t * sin_t).sqrt());
    let rs = ((n1 * ci - n2 * ct) / (n1 * ci + n2 * ct)).powi(2);
    let rp = ((n1 * ct - n2 * ci) / (n1 * ct + n2 * ci)).powi(2);
    0.5 * (rs + rp)
}

/// Conductor reflectance by the real-arithmetic form of the Fresnel equations (Born & Wolf
/// §14.2; as in e.g. Cook & Torrance's appendix), in f64 — a different derivation from the
/// crate's complex one.
fn reference_conductor(n: f64, k: f64, theta: f64) -> f64 {
    let (c, s) = (theta.cos(), theta.sin());
    let t0 = n * n - k * k - s * s;
    let a2b2 = (t0 * t0 + 4.0 * n * n * k * k).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let rs = (a2b2 - 2.0 * a * c + c * c) / (a2b2 + 2.0 * a * c + c * c);
    let t1 = a2b2 * c * c + s.powi(4);
    let t2 = 2.0 * a * c * s * s;
    let rp = rs * (t1 - t2) / (t1 + t2);
    0.5 * (rs + rp)
}

/// N-BK7 by the Sellmeier formula with the Schott catalogue coefficients, in f64, independent
/// of the crate's `Ior`.
fn bk7_sellmeier(lambda_nm: f64) -> f64 {
    let b = [1.03961212, 0.231792344, 1.01046945];
    let c = [0.00600069867, 0.0200179144, 103.560653];
    let l2 = (lambda_nm * 1e-3).powi(2);
    (1.0 + (0..3).map(|i| b[i] * l2 / (l2 - c[i])).sum::<f64>()).sqrt()
}

fn bk7() -> Ior {
    match lookup("glass:N-BK7") {
        Ok(Named::Dielectric(g)) => g.ior,
        other => panic!("{other:?}"),
    }
}

fn hero(l: f32) -> SampledWavelengths<4> {
    SampledWavelengths {
        lambda: [l, 420.0, 530.0, 690.0],
        pdf: [1.0; 4],
    }
}

#[test]
fn dielectric_normal_incidence() {
    for n in [1.2f32, 1.333, 1.5, 1.9, 2.42] {
        let want = ((n as f64 - 1.0) / (n as f64 + 1.0)).powi(2);
        for (c, eta) in [(1.0f32, n), (1.0, 1.0 / n), (-1.0, n), (-1.0, 1.0 / n)] {
            let r = fresnel_dielectric(c, eta) as f64;
            assert!(
                (r - want).abs() < 1e-6,
                "n {n} cos {c} eta {eta}: {r} vs {want}"
            );
        }
    }
}

#[test]
fn brewster_angle_kills_p_polarisation() {
    for n in [1.333f32, 1.5, 2.42] {
        // From outside, tan θ_B = n; from inside, tan θ_B = 1/n.
        for eta in [n, 1.0 / n] {
            let tb = (eta as f64).atan();
            let (rs, rp) = fresnel_dielectric_sp(tb.cos() as f32, eta);
            assert!(rp < 1e-7, "eta {eta}: R_p(θ_B) = {rp}");
            assert!(rs > 0.01, "eta {eta}: R_s(θ_B) = {rs}");
            for d in [-0.05f64, 0.05] {
                let (_, rp) = fresnel_dielectric_sp((tb + d).cos() as f32, eta);
                assert!(rp > 1e-5, "eta {eta}: R_p(θ_B{d:+}) = {rp}");
            }
        }
    }
}

#[test]
fn total_internal_reflection_starts_at_the_critical_angle() {
    for n in [1.333f64, 1.5, 2.42] {
        let tc = (1.0 / n).asin();
        let r = |theta: f64| {
            // From inside: either eta = 1/n with cos > 0, or eta = n with cos < 0.
            let a = fresnel_dielectric(theta.cos() as f32, 1.0 / n as f32);
            let b = fresnel_dielectric(-theta.cos() as f32, n as f32);
            assert_eq!(a, b, "θ {theta}");
            a
        };
        for d in [1e-3, 1e-2, 0.1] {
            assert!(r(tc - d) < 1.0, "n {n}: R(θc − {d}) = {}", r(tc - d));
        }
        assert!(r(tc - 0.1) < 0.5, "n {n}");
        assert!(r(tc) > 0.99, "n {n}: R(θc) = {}", r(tc));
        for d in [1e-5, 1e-3, 0.1] {
            assert_eq!(r(tc + d), 1.0, "n {n}: R(θc + {d})");
        }
        assert_eq!(r(89.0f64.to_radians()), 1.0);
        // refract agrees: a transmitted direction just below θc, none just above.
        let wi = |t: f64| Vec3::new(t.sin() as f32, 0.0, -(t.cos() as f32));
        assert!(refract(wi(tc - 1e-3), Vec3::Z, n as f32).is_some());
        assert!(refract(wi(tc + 1e-4), Vec3::Z, n as f32).is_none());
    }
}

#[test]
fn dielectric_matches_physics_md_formula() {
    for n in [1.333f64, 1.5, 2.42] {
        for i in 0..=90 {
            let t = (i as f64)
                .to_radians()
                .min(std::f64::consts::FRAC_PI_2 - 1e-6);
            let c = t.cos() as f32;
            // outside → inside
            let (got, want) = (
                fresnel_dielectric(c, n as f32) as f64,
                reference_dielectric(1.0, n, t),
            );
            assert!((got - want).abs() < 2e-6, "n {n} θ {i}°: {got} vs {want}");
            // inside → outside, away from the ill-conditioned critical angle
            if (t - (1.0 / n).asin()).abs() > 1e-2 {
                let (got, want) = (
                    fresnel_dielectric(-c, n as f32) as f64,
                    reference_dielectric(n, 1.0, t),
                );
                assert!(
                    (got - want).abs() < 2e-5,
                    "inside n {n} θ {i}°: {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn conductor_normal_incidence() {
    let metal = |name: &str| match lookup(name) {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    };
    let mut pairs = vec![
        (0.2f32, 3.0f32),
        (1.5, 0.0),
        (2.9, 3.0),
        (0.05, 4.0),
        (1.0, 0.5),
    ];
    for name in ["metal:Au", "metal:Cu"] {
        for l in [450.0, 550.0, 650.0] {
            pairs.push(metal(name).eval(l));
        }
    }
    for (n, k) in pairs {
        let (nd, kd) = (n as f64, k as f64);
        let want = ((nd - 1.0).powi(2) + kd * kd) / ((nd + 1.0).powi(2) + kd * kd);
        let got = fresnel_conductor(1.0, n, k) as f64;
        assert!(
            (got - want).abs() < 2e-6 * want.max(1e-2),
            "n {n} k {k}: {got} vs {want}"
        );
    }
}

#[test]
fn conductor_matches_real_form_at_all_angles() {
    for (n, k) in [
        (0.2f32, 3.0f32),
        (0.27, 2.78),
        (1.1, 6.8),
        (2.9, 3.0),
        (1.5, 0.3),
    ] {
        for i in 0..=179 {
            let t = (i as f64 * 0.5).to_radians();
            let got = fresnel_conductor(t.cos() as f32, n, k) as f64;
            let want = reference_conductor(n as f64, k as f64, t);
            assert!(
                (got - want).abs() < 2e-5,
                "n {n} k {k} θ {}°: {got} vs {want}",
                i as f64 * 0.5
            );
        }
        assert!((fresnel_conductor(0.0, n, k) - 1.0).abs() < 1e-6, "grazing");
    }
}

#[test]
fn conductor_with_k0_is_the_dielectric() {
    for eta in [0.7f32, 1.2, 1.5, 2.42] {
        for i in 0..=90 {
            let t = (i as f32).to_radians();
            if eta < 1.0 && (t - eta.asin()).abs() < 0.02 {
                continue; // ill-conditioned at the critical angle
            }
            let (c, d) = (
                fresnel_conductor(t.cos(), eta, 0.0),
                fresnel_dielectric(t.cos(), eta),
            );
            assert!((c - d).abs() < 1e-5, "eta {eta} θ {i}°: {c} vs {d}");
        }
    }
}

/// Samples the transmission lobe of a smooth BK7 interface.
fn transmit(
    m: &Material,
    wo: Vec3,
    l: f32,
    mode: TransportMode,
) -> spectrace::material::BsdfSample<4> {
    let s = m
        .sample(wo, &hero(l), 1.0 - 1e-7, Vec2::new(0.5, 0.5), mode)
        .expect("a sample");
    assert!(s.transmission && s.specular, "λ {l} wo {wo}: {s:?}");
    s
}

#[test]
fn snell_per_wavelength_in_the_plane_of_incidence() {
    let ior = bk7();
    let m = Material::Dielectric(Dielectric::new(ior.clone(), 1.0));
    let mut checked = 0;
    for l in [380.0f32, 435.8, 486.1, 550.0, 587.6, 656.3, 780.0] {
        let n = ior.eval(l) as f64;
        for inside in [false, true] {
            for deg in [0.0f64, 5.0, 20.0, 35.0, 40.0, 45.0, 60.0, 75.0, 85.0] {
                let (n1, n2) = if inside { (n, 1.0) } else { (1.0, n) };
                let t = deg.to_radians();
                if n1 * t.sin() >= n2 {
                    continue; // total internal reflection
                }
                let phi = 0.3 + deg * 0.05;
                let z = if inside { -t.cos() } else { t.cos() };
                let wo = Vec3::new(
                    (t.sin() * phi.cos()) as f32,
                    (t.sin() * phi.sin()) as f32,
                    z as f32,
                );
                for mode in [TransportMode::Radiance, TransportMode::Importance] {
                    let s = transmit(&m, wo, l, mode);
                    let wi = s.wi.as_dvec3();
                    assert!((wi.length() - 1.0).abs() < 1e-6);
                    assert!(wi.z * z < 0.0, "crosses the surface");
                    let sin2 = (wi.x * wi.x + wi.y * wi.y).sqrt();
                    assert!(
                        (n1 * t.sin() - n2 * sin2).abs() < 2e-6,
                        "λ {l} θ {deg} inside {inside}: n1 sin θ1 = {}, n2 sin θ2 = {}",
                        n1 * t.sin(),
                        n2 * sin2
                    );
                    // In the plane of incidence (spanned by wo and the normal), on the far side.
                    let normal_of_plane = wo.as_dvec3().cross(glam::DVec3::Z);
                    assert!(normal_of_plane.dot(wi).abs() < 1e-6, "out of plane");
                    assert!(wo.x as f64 * wi.x + wo.y as f64 * wi.y <= 1e-9);
                    assert!((s.eta as f64 - n2 / n1).abs() < 1e-5, "eta {}", s.eta);
                    // Weight (1 − F)/η'² in Radiance mode, (1 − F) in Importance mode, with the
                    // hero's own F and η'.
                    let want = (1.0 - reference_dielectric(n1, n2, t))
                        / if mode == TransportMode::Radiance {
                            (n2 / n1).powi(2)
                        } else {
                            1.0
                        };
                    let got = s.f[0] as f64 * wi.z.abs();
                    assert!((got - want).abs() < 1e-5, "λ {l} θ {deg}: {got} vs {want}");
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 150, "{checked}");
}

#[test]
fn bk7_dispersion_at_fraunhofer_lines() {
    let m = Material::Dielectric(Dielectric::new(bk7(), 1.0));
    let t = 45.0f64.to_radians();
    let wo = Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
    let mut angles = Vec::new();
    for l in [486.1f64, 587.6, 656.3] {
        let want = (t.sin() / bk7_sellmeier(l)).asin();
        let s = transmit(&m, wo, l as f32, TransportMode::Radiance);
        assert!(s.dispersive, "BK7 refraction must be flagged dispersive");
        let wi = s.wi.as_dvec3();
        let got = (wi.x * wi.x + wi.y * wi.y).sqrt().atan2(-wi.z);
        assert!(
            (got - want).abs() < 1e-4,
            "λ {l}: θt = {got} rad, want {want}"
        );
        angles.push(got);
    }
    // Normal dispersion: blue bends most. The F–C spread is ~3.5 mrad, far above 1e-4 rad.
    assert!(angles[0] < angles[1] && angles[1] < angles[2], "{angles:?}");
    assert!(angles[2] - angles[0] > 2e-3, "{angles:?}");
    // Reflection is not dispersive; neither is refraction through a constant index.
    let r = m
        .sample(wo, &hero(500.0), 0.0, Vec2::ZERO, TransportMode::Radiance)
        .unwrap();
    assert!(!r.transmission && !r.dispersive);
    let flat = Material::Dielectric(Dielectric::new(Ior::Constant(1.5), 1.0));
    assert!(!transmit(&flat, wo, 500.0, TransportMode::Radiance).dispersive);
}
