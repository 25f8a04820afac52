//! Mitsuba's `hair` (`spectrace::material::Hair`, Chiang et al. 2016):
//! - values and densities against Mitsuba 3.9.1's own BSDF at fixed directions and wavelengths
//!   (`tests/data/hair_eval.toml`, written by `scripts/gen_hair_eval.py`);
//! - a closed form: the fibre's lobes are each normalised, so ∫ f·|cos θ| dω over the sphere is
//!   the sum of the attenuations, f + (1 − f)²T/(1 − fT) for a grey σₐ (1 without absorption,
//!   the white furnace), with f the Fresnel reflectance at the entry and T the transmittance
//!   of one chord (Chiang §4.2), estimated by uniform sampling of the sphere;
//! - the sampler against its own density (χ²).
//!
//! The end-to-end check (a fibre on a `bsplinecurve` against a Mitsuba render) is in
//! `tests/mitsuba_data_plugins.rs`.

#[path = "support/chi2.rs"]
mod chi2;
mod support;

use std::collections::BTreeMap;
use std::f32::consts::PI;
use std::sync::Arc;

use chi2::{Grid, chi2_test, sidak};
use glam::{Vec2, Vec3};
use serde::Deserialize;
use spectrace::material::fresnel::fresnel_dielectric;
use spectrace::material::{Hair, Material, TransportMode};
use spectrace::spectrum::{PiecewiseLinear, SampledWavelengths, Spectrum};
use support::Rng;

#[derive(Deserialize)]
struct Data {
    case: Vec<Case>,
}

#[derive(Clone, Deserialize)]
struct Case {
    name: String,
    params: BTreeMap<String, toml::Value>,
    rows: Vec<Row>,
}

#[derive(Clone, Deserialize)]
struct Row {
    view: [f32; 3],
    light: [f32; 3],
    lambda: [f32; 4],
    value: [f32; 4],
    pdf: f32,
}

/// The material Mitsuba's plugin makes of these parameters (its defaults: pigments 1.3 and
/// 0.2, roughness 0.3 and 0.3, tilt 2°, amber in air); with `mitsuba_bessel`, its I₀ too.
fn hair_with(params: &BTreeMap<String, toml::Value>, mitsuba_bessel: bool) -> Material {
    let num = |k: &str, d: f64| params.get(k).map_or(d, |v| v.as_float().unwrap_or(d));
    let sigma_a = match params.get("sigma_a") {
        Some(toml::Value::Array(a)) => {
            let pair = |p: &toml::Value, i: usize| {
                let x = &p.as_array().unwrap()[i];
                x.as_float().or(x.as_integer().map(|i| i as f64)).unwrap()
            };
            let (l, v) = a
                .iter()
                .map(|p| (pair(p, 0) as f32, (pair(p, 1) * num("scale", 1.0)) as f32))
                .unzip();
            let table = PiecewiseLinear::new(l, v).unwrap();
            [
                Spectrum::Piecewise(Arc::new(table)),
                Spectrum::Constant(0.0),
            ]
        }
        Some(v) => [
            Spectrum::Constant((v.as_float().unwrap() * num("scale", 1.0)) as f32),
            Spectrum::Constant(0.0),
        ],
        None => Hair::pigments(num("eumelanin", 1.3) as f32, num("pheomelanin", 0.2) as f32),
    };
    let h = Hair::new(
        sigma_a,
        (num("int_ior", 1.55) / 1.000277) as f32,
        num("longitudinal_roughness", 0.3) as f32,
        num("azimuthal_roughness", 0.3) as f32,
        (num("scale_tilt", 2.0) as f32).to_radians(),
    );
    Material::Hair(Box::new(if mitsuba_bessel {
        h.with_mitsuba_bessel()
    } else {
        h
    }))
}

fn hair(params: &BTreeMap<String, toml::Value>) -> Material {
    hair_with(params, false)
}

fn data() -> Data {
    let p = support::data_path("hair_eval.toml");
    toml::from_str(&std::fs::read_to_string(&p).expect("hair_eval.toml"))
        .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn wavelengths(lambda: [f32; 4]) -> SampledWavelengths<4> {
    SampledWavelengths {
        lambda,
        pdf: [1.0 / 470.0; 4],
    }
}

/// With Mitsuba's I₀, spectrace's f·|cos θ| and pdf equal Mitsuba's eval and pdf at every
/// tabulated pair to relative 2·10⁻⁴ (f32 rounding; the lobe choice weighs by each renderer's
/// own CIE ȳ table). With its own, exact I₀ they differ by Mitsuba's I₀ error alone, under
/// 0.8 % (see `Hair::with_mitsuba_bessel`).
#[test]
fn values_and_densities_match_mitsuba() {
    let mut failures = Vec::new();
    let mut rows = 0;
    for (c, (mitsuba_bessel, tol)) in data()
        .case
        .into_iter()
        .flat_map(|c| [(c.clone(), (true, 2e-4)), (c, (false, 8e-3))])
    {
        let m = hair_with(&c.params, mitsuba_bessel);
        for (k, r) in c.rows.iter().enumerate() {
            let (wo, wi) = (Vec3::from(r.view), Vec3::from(r.light));
            let w = wavelengths(r.lambda);
            let f = m.eval(wo, wi, &w, TransportMode::Radiance);
            let pdf = m.pdf(wo, wi, &w, TransportMode::Radiance);
            let close = |a: f32, b: f32| (a - b).abs() <= tol * b.abs().max(a.abs()) + 1e-9;
            for i in 0..4 {
                let ours = f[i] * wi.z.abs();
                if !close(ours, r.value[i]) {
                    failures.push(format!(
                        "{} (Mitsuba's I₀: {mitsuba_bessel}) row {k} λ={}: value {ours} vs Mitsuba {}",
                        c.name, r.lambda[i], r.value[i]
                    ));
                }
            }
            if !close(pdf, r.pdf) {
                failures.push(format!(
                    "{} (Mitsuba's I₀: {mitsuba_bessel}) row {k}: pdf {pdf} vs Mitsuba {}",
                    c.name, r.pdf
                ));
            }
            rows += 1;
        }
    }
    assert!(rows >= 160, "only {rows} rows");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A uniformly random unit vector.
fn uniform_sphere(rng: &mut Rng) -> Vec3 {
    let z = 1.0 - 2.0 * rng.uniform();
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * rng.uniform();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// ∫ f·|cos θ| dω over the sphere equals the sum of the attenuations (the module's closed
/// form) for views across the fibre, with and without absorption, within 5 standard errors.
#[test]
fn albedo_is_the_sum_of_the_attenuations() {
    let w = wavelengths([550.0, 450.0, 650.0, 500.0]);
    let eta = 1.55f32 / 1.000277;
    let mut failures = Vec::new();
    for (sigma, beta_m, beta_n, tilt) in [
        (0.0f32, 0.3f32, 0.3f32, 2.0f32),
        (0.0, 0.6, 0.8, 0.0),
        (0.0, 0.2, 0.5, -4.0),
        (0.4, 0.4, 0.3, 2.0),
        (1.5, 0.5, 0.6, 3.0),
    ] {
        let m = Material::Hair(Box::new(Hair::new(
            [Spectrum::Constant(sigma), Spectrum::Constant(0.0)],
            eta,
            beta_m,
            beta_n,
            tilt.to_radians(),
        )));
        for (k, view) in [
            Vec3::new(0.3, 0.1, 0.9),
            Vec3::new(-0.7, 0.5, 0.4),
            Vec3::new(0.05, -0.3, 0.95),
        ]
        .into_iter()
        .enumerate()
        {
            let view = view.normalize();
            // the closed form: h = sin γ from the view's projection on the normal plane
            let (sin_t, cos_t) = (view.y, (1.0 - view.y * view.y).sqrt());
            let h = view.x.abs() / (view.x * view.x + view.z * view.z).sqrt();
            let cos_gamma = (1.0 - h * h).sqrt();
            let f = fresnel_dielectric(cos_t * cos_gamma, eta);
            let eta_p = (eta * eta - sin_t * sin_t).sqrt() / cos_t;
            let cos_gamma_t = (1.0 - (h / eta_p).powi(2)).sqrt();
            let cos_theta_t = (1.0 - (sin_t / eta).powi(2)).sqrt();
            let t = (-sigma * 2.0 * cos_gamma_t / cos_theta_t).exp();
            let want = (f + (1.0 - f).powi(2) * t / (1.0 - f * t)) as f64;
            let mut rng =
                Rng::new(0x4a1e + k as u64 + 1000 * (sigma * 10.0 + beta_m * 100.0 + tilt) as u64);
            let n = 2_000_000;
            let (mut sum, mut sum2) = (0.0f64, 0.0f64);
            for _ in 0..n {
                let wi = uniform_sphere(&mut rng);
                let x = (m.eval(view, wi, &w, TransportMode::Radiance)[0] * wi.z.abs()) as f64
                    * 4.0
                    * std::f64::consts::PI;
                sum += x;
                sum2 += x * x;
            }
            let mean = sum / n as f64;
            let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
            println!("σ={sigma} β=({beta_m}, {beta_n}) view {k}: {mean:.5} ± {se:.5} vs {want:.5}");
            if (mean - want).abs() > 5.0 * se {
                failures.push(format!(
                    "σ={sigma} β=({beta_m}, {beta_n}) α={tilt}° view {k}: ∫ = {mean} ± {se}, closed form {want}"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The sampler draws directions with the density `pdf` states (χ², Šidák over the cases).
#[test]
fn chi2_sampling_matches_the_pdf() {
    let grid = Grid {
        n_cos: 16,
        n_phi: 32,
        both_hemispheres: true,
    };
    let mut cases = Vec::new();
    for c in data().case {
        for view in [Vec3::new(0.4, 0.3, 0.8), Vec3::new(-0.8, -0.5, 0.2)] {
            cases.push((c.name.clone(), hair(&c.params), view.normalize()));
        }
    }
    let level = sidak(0.01, cases.len());
    let w = wavelengths([550.0, 430.0, 610.0, 480.0]);
    let mut failures = Vec::new();
    for (k, (name, m, wo)) in cases.iter().enumerate() {
        let mut rng = Rng::new(0x4a12_0000 + k as u64);
        let mode = TransportMode::Radiance;
        let r = chi2_test(
            grid,
            400_000,
            || {
                let uc = rng.uniform();
                let u = Vec2::new(rng.uniform(), rng.uniform());
                m.sample(*wo, &w, uc, u, mode).map(|s| s.wi)
            },
            |d| m.pdf(*wo, d, &w, mode) as f64,
        );
        println!("{name} wo={wo}: p={:.4} ∫pdf={:.4}", r.p_value, r.integral);
        if r.p_value < level || r.in_empty_cells > 0 || (r.integral - 1.0).abs() > 2e-3 {
            failures.push(format!("{name} wo={wo}: {r:?}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A sample's weight f·|cos θ|/pdf is the value Mitsuba's `sample` returns: the value over the
/// density at the drawn direction, and with paths from the lights the adjoint, f(wi, wo).
#[test]
fn sample_weights_and_the_adjoint() {
    let m = hair(&BTreeMap::new());
    let w = wavelengths([550.0, 430.0, 610.0, 480.0]);
    let wo = Vec3::new(0.3, 0.4, 0.8).normalize();
    let mut rng = Rng::new(7);
    for _ in 0..1000 {
        let (uc, u) = (rng.uniform(), Vec2::new(rng.uniform(), rng.uniform()));
        let Some(s) = m.sample(wo, &w, uc, u, TransportMode::Radiance) else {
            continue;
        };
        let f = m.eval(wo, s.wi, &w, TransportMode::Radiance);
        let pdf = m.pdf(wo, s.wi, &w, TransportMode::Radiance);
        for i in 0..4 {
            assert!((s.f[i] - f[i]).abs() <= 1e-5 * f[i].abs() + 1e-12);
        }
        assert!((s.pdf - pdf).abs() <= 1e-3 * pdf);
        let adj = m.eval(s.wi, wo, &w, TransportMode::Importance);
        let fwd = m.eval(wo, s.wi, &w, TransportMode::Radiance);
        assert_eq!(adj.0, fwd.0);
    }
}
