//! BSDF properties: reciprocity (and Veach's generalised reciprocity across a refracting
//! interface), `sample` agreeing with `eval`/`pdf`, one-sidedness, finiteness at grazing
//! angles, the rough models' smooth limits, and `Phong::new` validation.

mod support;

use std::sync::Arc;

use glam::{Vec2, Vec3};
use spectrace::material::fresnel::{fresnel_conductor, fresnel_dielectric};
use spectrace::material::{
    Conductor, Dielectric, Lambert, Material, Phong, RoughConductor, RoughDielectric, TransportMode,
};
use spectrace::spectrum::ior::{ComplexIor, Ior};
use spectrace::spectrum::named::{Named, lookup};
use spectrace::spectrum::{PiecewiseLinear, SampledWavelengths, Spectrum};
use support::Rng;

const RAD: TransportMode = TransportMode::Radiance;
const IMP: TransportMode = TransportMode::Importance;

fn bk7() -> Ior {
    match lookup("glass:N-BK7") {
        Ok(Named::Dielectric(g)) => g.ior,
        other => panic!("{other:?}"),
    }
}

fn gold() -> ComplexIor {
    match lookup("metal:Au") {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    }
}

fn wl() -> SampledWavelengths<4> {
    SampledWavelengths {
        lambda: [530.0, 410.0, 620.0, 760.0],
        pdf: [1.0; 4],
    }
}

fn ramp(a: f32, b: f32) -> Spectrum {
    Spectrum::Piecewise(Arc::new(
        PiecewiseLinear::new(vec![360.0, 830.0], vec![a, b]).unwrap(),
    ))
}

/// Uniform direction on the sphere.
fn random_dir(rng: &mut Rng) -> Vec3 {
    let z = 1.0 - 2.0 * rng.uniform();
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * rng.uniform();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

fn opaque_materials() -> Vec<(&'static str, Material)> {
    vec![
        ("Lambert", Material::Diffuse(Lambert::new(ramp(0.2, 0.9)))),
        (
            "Phong n=1",
            Material::Phong(Phong::new(ramp(0.1, 0.5), ramp(0.8, 0.4), 1.0).unwrap()),
        ),
        (
            "Phong n=30",
            Material::Phong(Phong::new(ramp(0.1, 0.5), ramp(0.8, 0.4), 30.0).unwrap()),
        ),
        (
            "Phong n=300",
            Material::Phong(
                Phong::new(Spectrum::Constant(0.0), Spectrum::Constant(1.0), 300.0).unwrap(),
            ),
        ),
        (
            "RoughConductor α=0.05",
            Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.05)),
        ),
        (
            "RoughConductor α=0.3",
            Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.3)),
        ),
        (
            "RoughConductor α=0.8",
            Material::RoughConductor(RoughConductor::new(gold(), 1.33, 0.8)),
        ),
    ]
}

fn rough_dielectrics() -> Vec<(&'static str, Material)> {
    vec![
        (
            "RoughDielectric 1.5 α=0.1",
            Material::RoughDielectric(RoughDielectric::new(Ior::Constant(1.5), 1.0, 0.1)),
        ),
        (
            "RoughDielectric BK7/water α=0.4",
            Material::RoughDielectric(RoughDielectric::new(bk7(), 1.333, 0.4)),
        ),
    ]
}

fn close(a: f32, b: f32, rel: f32) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()) + 1e-30
}

#[test]
fn reciprocity() {
    let w = wl();
    let mut rng = Rng::new(11);
    let mut nonzero = 0;
    for (name, m) in opaque_materials().into_iter().chain(rough_dielectrics()) {
        for _ in 0..20_000 {
            let (mut a, mut b) = (random_dir(&mut rng), random_dir(&mut rng));
            // Reflection pairs: both on one side (the +z side for the opaque materials).
            let side = if matches!(m, Material::RoughDielectric(_)) && rng.uniform() < 0.5 {
                -1.0
            } else {
                1.0
            };
            a.z = a.z.abs() * side;
            b.z = b.z.abs() * side;
            for mode in [RAD, IMP] {
                let (f, g) = (m.eval(a, b, &w, mode), m.eval(b, a, &w, mode));
                for l in 0..4 {
                    assert!(
                        close(f[l], g[l], 2e-5),
                        "{name}: f(a,b) = {} ≠ f(b,a) = {} at a {a} b {b}",
                        f[l],
                        g[l]
                    );
                }
                nonzero += (f[0] > 0.0) as usize;
            }
        }
    }
    assert!(nonzero > 100_000, "{nonzero}");
}

/// Veach (1997, §5.2) across a refracting interface: f(wo, wi)/n_o² = f(wi, wo)/n_i² for the
/// radiance BTDF, and the Importance BSDF is the adjoint f*(wo, wi) = f(wi, wo).
#[test]
fn generalised_reciprocity_of_transmission() {
    let w = wl();
    let mut rng = Rng::new(12);
    let mut nonzero = 0;
    for (name, m) in rough_dielectrics() {
        let Material::RoughDielectric(rd) = &m else {
            unreachable!()
        };
        // Constant index: every wavelength is meaningful; BK7: the hero only.
        let check = if rd.int_ior.is_dispersive() { 1 } else { 4 };
        let n_in = rd.int_ior.eval(w.lambda[0]);
        for _ in 0..80_000 {
            let (mut a, mut b) = (random_dir(&mut rng), random_dir(&mut rng));
            a.z = a.z.abs();
            b.z = -b.z.abs();
            if rng.uniform() < 0.5 {
                std::mem::swap(&mut a, &mut b);
            }
            let n = |d: Vec3| if d.z > 0.0 { rd.ext_ior } else { n_in };
            let (fab, fba) = (m.eval(a, b, &w, RAD), m.eval(b, a, &w, RAD));
            let adj = m.eval(b, a, &w, IMP);
            // f32 accuracy: f contains |wo·wm|, and 1 − F ∝ |wo·wm| near grazing microfacets;
            // wo·wm is a dot product with cancellation, so the relative rounding error grows
            // like ε/min|w·wm|. The half vector is recomputed here in f64.
            let (ad, bd) = (a.as_dvec3(), b.as_dvec3());
            let wm = (ad * n(a) as f64 + bd * n(b) as f64).normalize();
            let min_cos = ad.dot(wm).abs().min(bd.dot(wm).abs()).min(1.0) as f32;
            let tol = 2e-5 + 100.0 * f32::EPSILON / min_cos;
            for l in 0..check {
                let lhs = fab[l] / (n(a) * n(a));
                let rhs = fba[l] / (n(b) * n(b));
                assert!(close(lhs, rhs, tol), "{name}: {lhs} vs {rhs} at {a} {b}");
                assert!(
                    close(fab[l], adj[l], tol),
                    "{name}: adjoint {} vs {}",
                    fab[l],
                    adj[l]
                );
            }
            nonzero += (fab[0] > 0.0) as usize;
        }
    }
    assert!(nonzero > 10_000, "{nonzero}");
}

#[test]
fn samples_agree_with_eval_and_pdf() {
    let w = wl();
    let mut rng = Rng::new(13);
    for (name, m) in opaque_materials().into_iter().chain(rough_dielectrics()) {
        let two_sided = matches!(m, Material::RoughDielectric(_));
        let dispersive = m.is_dispersive();
        let (mut got, mut trans) = (0, 0);
        for _ in 0..20_000 {
            let mut wo = random_dir(&mut rng);
            if !two_sided {
                wo.z = wo.z.abs();
            }
            let (uc, u) = (rng.uniform(), Vec2::new(rng.uniform(), rng.uniform()));
            for mode in [RAD, IMP] {
                let Some(s) = m.sample(wo, &w, uc, u, mode) else {
                    continue;
                };
                got += 1;
                assert!(
                    (s.wi.length() - 1.0).abs() < 1e-5,
                    "{name}: |wi| = {}",
                    s.wi.length()
                );
                assert!(
                    !s.specular && s.pdf > 0.0 && s.f.is_finite(),
                    "{name}: {s:?}"
                );
                assert_eq!(s.transmission, s.wi.z * wo.z < 0.0, "{name}");
                assert_eq!(s.dispersive, s.transmission && dispersive, "{name}");
                let (f, pdf) = (m.eval(wo, s.wi, &w, mode), m.pdf(wo, s.wi, &w, mode));
                assert!(close(s.pdf, pdf, 1e-4), "{name}: pdf {} vs {pdf}", s.pdf);
                for l in 0..4 {
                    assert!(
                        close(s.f[l], f[l], 1e-4),
                        "{name}: f {} vs {}",
                        s.f[l],
                        f[l]
                    );
                }
                if let Material::RoughDielectric(rd) = &m {
                    let n_in = rd.int_ior.eval(w.lambda[0]);
                    let want = match (s.transmission, wo.z > 0.0) {
                        (false, _) => 1.0,
                        (true, true) => n_in / rd.ext_ior,
                        (true, false) => rd.ext_ior / n_in,
                    };
                    assert!(close(s.eta, want, 1e-6), "{name}: eta {} vs {want}", s.eta);
                    trans += s.transmission as usize;
                } else {
                    assert_eq!(s.eta, 1.0);
                }
            }
        }
        assert!(got > 20_000, "{name}: only {got} samples");
        if two_sided {
            assert!(trans > 5_000, "{name}: only {trans} transmissions");
        }
    }
}

/// `eval_pdf` (next-event estimation's one call) returns exactly what `eval` and `pdf` return,
/// for every material, direction pair and transport mode.
#[test]
fn eval_pdf_is_eval_and_pdf() {
    let w = wl();
    let mut rng = Rng::new(29);
    for (name, m) in opaque_materials().into_iter().chain(rough_dielectrics()) {
        for _ in 0..20_000 {
            let (wo, wi) = (random_dir(&mut rng), random_dir(&mut rng));
            for mode in [RAD, IMP] {
                let (f, pdf) = m.eval_pdf(wo, wi, &w, mode);
                let want = (m.eval(wo, wi, &w, mode), m.pdf(wo, wi, &w, mode));
                assert_eq!(
                    (f.0.map(f32::to_bits), pdf.to_bits()),
                    (want.0.0.map(f32::to_bits), want.1.to_bits()),
                    "{name}: wo {wo}, wi {wi}"
                );
            }
        }
    }
}

#[test]
fn opaque_materials_are_one_sided() {
    let w = wl();
    let mut rng = Rng::new(14);
    for (name, m) in opaque_materials() {
        for _ in 0..2_000 {
            let (a, b) = (random_dir(&mut rng), random_dir(&mut rng));
            if a.z > 0.0 && b.z > 0.0 {
                continue;
            }
            assert!(m.eval(a, b, &w, RAD).is_zero(), "{name}");
            assert_eq!(m.pdf(a, b, &w, RAD), 0.0, "{name}");
            if a.z <= 0.0 {
                assert!(m.sample(a, &w, 0.5, Vec2::new(0.3, 0.6), RAD).is_none());
            }
        }
    }
}

#[test]
fn finite_at_grazing_and_degenerate_directions() {
    let w = wl();
    let mut all = opaque_materials();
    all.extend(rough_dielectrics());
    all.push((
        "RoughConductor α=0",
        Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.0)),
    ));
    all.push((
        "Dielectric",
        Material::Dielectric(Dielectric::new(bk7(), 1.0)),
    ));
    all.push((
        "Conductor",
        Material::Conductor(Conductor::new(gold(), 1.0)),
    ));
    let special = [
        Vec3::Z,
        -Vec3::Z,
        Vec3::X,
        Vec3::new(0.6, 0.8, 0.0),
        Vec3::new(1.0, 0.0, 1e-7).normalize(),
        Vec3::new(1.0, 0.0, -1e-7).normalize(),
        Vec3::new(-1.0, 0.0, 1e-4).normalize(),
        Vec3::new(0.0, 0.0, 1.0 - 1e-7),
    ];
    let us = [0.0f32, 0.5, 0.999_999_9];
    for (name, m) in &all {
        for &a in &special {
            for &b in &special {
                let f = m.eval(a, b, &w, RAD);
                let p = m.pdf(a, b, &w, RAD);
                assert!(
                    f.is_finite() && f.min_component() >= 0.0,
                    "{name}: f({a}, {b}) = {f:?}"
                );
                assert!(p.is_finite() && p >= 0.0, "{name}: pdf({a}, {b}) = {p}");
            }
            for uc in us {
                for (x, y) in [(0.0, 0.0), (0.999_999_9, 0.5), (0.5, 0.999_999_9)] {
                    if let Some(s) = m.sample(a, &w, uc, Vec2::new(x, y), RAD) {
                        assert!(
                            s.f.is_finite() && s.pdf > 0.0 && s.pdf.is_finite(),
                            "{name}: {s:?}"
                        );
                        assert!(s.wi.is_finite() && s.wi.z != 0.0, "{name}: {s:?}");
                    }
                }
            }
        }
    }
}

/// Nearly smooth rough models behave like their smooth counterparts: sample weights → Fresnel.
#[test]
fn rough_models_approach_the_smooth_ones() {
    let w = wl();
    let mut rng = Rng::new(15);
    let t = 50.0f32.to_radians();
    let wo = Vec3::new(t.sin(), 0.0, t.cos());
    let rc = Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.002));
    let rd = Material::RoughDielectric(RoughDielectric::new(Ior::Constant(1.5), 1.0, 0.002));
    let (mut wc, mut nr, mut wr, mut wt) = (0.0f64, 0usize, 0.0f64, 0.0f64);
    let (n, mut nt, mut snell_ok) = (100_000, 0usize, 0usize);
    for _ in 0..n {
        let (uc, u) = (rng.uniform(), Vec2::new(rng.uniform(), rng.uniform()));
        // A rejected sample (a tail normal scattering to the wrong side) has weight 0.
        if let Some(s) = rc.sample(wo, &w, uc, u, IMP) {
            wc += (s.f[0] * s.wi.z / s.pdf) as f64;
        }
        let Some(s) = rd.sample(wo, &w, uc, u, IMP) else {
            continue;
        };
        let x = (s.f[0] * s.wi.z.abs() / s.pdf) as f64;
        if s.transmission {
            wt += x;
            nt += 1;
            // Snell within the roughness: sin θt ≈ sin θo / 1.5 (GGX's heavy tail puts a few
            // normals far from +z, hence a fraction rather than every sample).
            let st = (s.wi.x * s.wi.x + s.wi.y * s.wi.y).sqrt();
            snell_ok += ((st - t.sin() / 1.5).abs() < 0.01) as usize;
        } else {
            nr += 1;
            wr += x;
        }
    }
    assert!(
        snell_ok as f64 > 0.98 * nt as f64,
        "{snell_ok} of {nt} obey Snell"
    );
    let (nk, kk) = gold().eval(w.lambda[0]);
    let fc = fresnel_conductor(t.cos(), nk, kk) as f64;
    assert!(
        (wc / n as f64 - fc).abs() < 2e-3,
        "{} vs {fc}",
        wc / n as f64
    );
    let fd = fresnel_dielectric(t.cos(), 1.5) as f64;
    let pr = nr as f64 / n as f64;
    assert!(
        (pr - fd).abs() < 4.0 * (fd * (1.0 - fd) / n as f64).sqrt(),
        "P(R) {pr} vs {fd}"
    );
    assert!(
        ((wr + wt) / n as f64 - 1.0).abs() < 2e-3,
        "R + T = {}",
        (wr + wt) / n as f64
    );
}

#[test]
fn phong_new_validates_every_wavelength() {
    // kd + ks = 1 exactly is allowed.
    assert!(Phong::new(ramp(0.2, 0.6), ramp(0.8, 0.4), 5.0).is_ok());
    // A spike between the 1 nm grid points must be caught at its tabulated wavelength.
    let spike = Spectrum::Piecewise(Arc::new(
        PiecewiseLinear::new(
            vec![360.0, 500.2, 500.5, 500.8, 830.0],
            vec![0.3, 0.3, 0.9, 0.3, 0.3],
        )
        .unwrap(),
    ));
    let e = Phong::new(spike, Spectrum::Constant(0.5), 5.0).unwrap_err();
    assert!(e.contains("500.5 nm"), "{e}");
    // Failing only at the red end.
    let e = Phong::new(ramp(0.2, 0.7), ramp(0.5, 0.35), 5.0).unwrap_err();
    assert!(e.contains("nm") && e.contains("kd + ks"), "{e}");
    assert!(Phong::new(ramp(0.2, 0.7), ramp(0.5, 0.3), 5.0).is_ok());
    let e = Phong::new(Spectrum::Constant(0.2), ramp(0.1, -0.1), 5.0).unwrap_err();
    assert!(e.contains("ks"), "{e}");
    for bad in [-1.0, f32::INFINITY, f32::NAN] {
        assert!(Phong::new(Spectrum::Constant(0.2), Spectrum::Constant(0.2), bad).is_err());
    }
}

#[test]
fn specular_and_dispersive_flags() {
    let cases = [
        (
            Material::Diffuse(Lambert::new(Spectrum::Constant(0.5))),
            false,
            false,
        ),
        (
            Material::Phong(
                Phong::new(Spectrum::Constant(0.5), Spectrum::Constant(0.5), 2.0).unwrap(),
            ),
            false,
            false,
        ),
        (
            Material::Dielectric(Dielectric::new(bk7(), 1.0)),
            true,
            true,
        ),
        (
            Material::Dielectric(Dielectric::new(Ior::Constant(1.5), 1.0)),
            true,
            false,
        ),
        (
            Material::RoughDielectric(RoughDielectric::new(bk7(), 1.0, 0.2)),
            false,
            true,
        ),
        (
            Material::Conductor(Conductor::new(gold(), 1.0)),
            true,
            false,
        ),
        (
            Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.2)),
            false,
            false,
        ),
    ];
    for (m, specular, dispersive) in cases {
        assert_eq!(m.is_specular(), specular, "{m:?}");
        assert_eq!(m.is_dispersive(), dispersive, "{m:?}");
    }
}
