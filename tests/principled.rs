//! Mitsuba's `principled` and `principledthin` (`spectrace::material::Principled`):
//! - values and densities against Mitsuba 3.9.1's own BSDF at fixed directions and wavelengths
//!   (`tests/data/principled_eval.toml`, written by `scripts/gen_principled_eval.py`);
//! - closed forms: the diffuse lobe alone at normal incidence, the metal's Schlick lobe;
//! - the sampler against its own density (χ²), from both sides.
//!
//! The scenes that use them (Mitsuba's `test_texturedprincipled*`) are compared with Mitsuba's
//! official references by `scripts/mitsuba_data_run.py --compare-spp`, and end to end by
//! `tests/mitsuba_data_plugins.rs`.

#[path = "support/chi2.rs"]
mod chi2;
mod support;

use std::collections::BTreeMap;

use chi2::{Grid, chi2_test, sidak};
use glam::{Vec2, Vec3};
use serde::Deserialize;
use spectrace::material::{Material, Principled, TransportMode};
use spectrace::spectrum::{SampledWavelengths, Spectrum};
use spectrace::texture::Texture;
use support::Rng;

#[derive(Deserialize)]
struct Data {
    case: Vec<Case>,
}

#[derive(Deserialize)]
struct Case {
    plugin: String,
    name: String,
    params: BTreeMap<String, f64>,
    rows: Vec<Row>,
}

#[derive(Deserialize)]
struct Row {
    view: [f32; 3],
    light: [f32; 3],
    lambda: [f32; 4],
    value: [f32; 4],
    pdf: f32,
}

/// The material Mitsuba's plugin makes of these numeric parameters (its defaults, and its
/// reading of `specular` as an index; a parameter given as 0 turns its lobe off).
fn principled(thin: bool, params: &BTreeMap<String, f64>) -> Material {
    let tex = |v: f64| -> Texture { Spectrum::Constant(v as f32).into() };
    let get = |k: &str, d: f64| tex(params.get(k).copied().unwrap_or(d));
    let flag = |k: &str| params.get(k).filter(|v| **v != 0.0).map(|v| tex(*v));
    let has_t = flag("spec_trans").is_some();
    let eta = match (params.get("eta"), params.get("specular")) {
        (Some(e), _) => *e,
        (None, s) => {
            let mut s = s.copied().unwrap_or(0.5);
            if has_t && s == 0.0 {
                s = 1e-3;
            }
            2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
        }
    };
    Material::Principled(Box::new(Principled {
        base_color: get("base_color", 0.5),
        roughness: get("roughness", 0.5),
        anisotropic: flag("anisotropic"),
        spec_trans: flag("spec_trans"),
        metallic: flag("metallic"),
        clearcoat: flag("clearcoat"),
        clearcoat_gloss: get("clearcoat_gloss", 0.0),
        sheen: flag("sheen"),
        sheen_tint: flag("sheen_tint"),
        flatness: flag("flatness"),
        spec_tint: flag("spec_tint"),
        diff_trans: flag("diff_trans"),
        eta: eta as f32,
        rates: [1.0; 4],
        thin,
    }))
}

fn data() -> Data {
    let p = support::data_path("principled_eval.toml");
    toml::from_str(&std::fs::read_to_string(&p).expect("principled_eval.toml"))
        .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn wavelengths(lambda: [f32; 4]) -> SampledWavelengths<4> {
    SampledWavelengths {
        lambda,
        pdf: [1.0 / 470.0; 4],
    }
}

/// spectrace's f·|cos θ| and pdf equal Mitsuba's eval and pdf at every tabulated pair, to f32
/// rounding (relative 2·10⁻⁴; the tints' luminance uses each renderer's own CIE ȳ table).
#[test]
fn values_and_densities_match_mitsuba() {
    let mut failures = Vec::new();
    let mut rows = 0;
    for c in data().case {
        let m = principled(c.plugin == "principledthin", &c.params);
        for (k, r) in c.rows.iter().enumerate() {
            let (wo, wi) = (Vec3::from(r.view), Vec3::from(r.light));
            let w = wavelengths(r.lambda);
            let f = m.eval(wo, wi, &w, TransportMode::Radiance);
            let pdf = m.pdf(wo, wi, &w, TransportMode::Radiance);
            let close = |a: f32, b: f32| (a - b).abs() <= 2e-4 * b.abs().max(a.abs()) + 1e-6;
            for i in 0..4 {
                let ours = f[i] * wi.z.abs();
                if !close(ours, r.value[i]) {
                    failures.push(format!(
                        "{} row {k} λ={}: value {ours} vs Mitsuba {}",
                        c.name, r.lambda[i], r.value[i]
                    ));
                }
            }
            // Mitsuba's pdf is NaN where no lobe can be chosen (all probabilities 0), and not 0
            // seen from inside an opaque one, where its sampler refuses (and f = 0): ours is 0
            let opaque_inside =
                c.plugin == "principled" && wo.z < 0.0 && !c.params.contains_key("spec_trans");
            let theirs = if r.pdf.is_nan() || opaque_inside {
                0.0
            } else {
                r.pdf
            };
            if !close(pdf, theirs) {
                failures.push(format!("{} row {k}: pdf {pdf} vs Mitsuba {theirs}", c.name));
            }
            rows += 1;
        }
    }
    assert!(rows >= 60, "only {rows} rows");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Closed forms: with no specular lobe (specular 0 makes η = 1, so F = 0) and roughness 0, at
/// normal incidence and exitance f = base/π exactly (Burley's diffuse is Lambert there); a
/// full metal is Schlick's F with F0 = base colour times D·G/(4 cos θₒ cos θᵢ), and at the
/// mirror direction of normal incidence D = 1/(π α²), G = 1, F = F0.
#[test]
fn diffuse_and_metal_extremes() {
    let w = wavelengths([550.0, 450.0, 650.0, 500.0]);
    let params = |kv: &[(&str, f64)]| kv.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let diffuse = principled(
        false,
        &params(&[("base_color", 0.6), ("roughness", 0.0), ("specular", 0.0)]),
    );
    let f = diffuse.eval(Vec3::Z, Vec3::Z, &w, TransportMode::Radiance);
    let want = 0.6 / std::f32::consts::PI;
    assert!(
        (f[0] - want).abs() < 1e-6 * want.max(1.0),
        "{} vs {want}",
        f[0]
    );
    let (rough, base) = (0.3f64, 0.8f32);
    let metal = principled(
        false,
        &params(&[
            ("base_color", base as f64),
            ("roughness", rough),
            ("metallic", 1.0),
        ]),
    );
    let f = metal.eval(Vec3::Z, Vec3::Z, &w, TransportMode::Radiance);
    let alpha = (rough * rough) as f32;
    let want = base / (std::f32::consts::PI * alpha * alpha) / 4.0;
    assert!((f[0] - want).abs() < 1e-4 * want, "{} vs {want}", f[0]);
}

/// The sampler draws directions with the density `pdf` states (χ², Šidák over the cases),
/// from outside and from inside, for the solid and the thin variant.
#[test]
fn chi2_sampling_matches_the_pdf() {
    let grid = Grid {
        n_cos: 16,
        n_phi: 32,
        both_hemispheres: true,
    };
    let mut cases = Vec::new();
    for c in data().case {
        for view in [(35.0f32, false), (70.0, false), (40.0, true)] {
            cases.push((
                c.name.clone(),
                principled(c.plugin == "principledthin", &c.params),
                view,
            ));
        }
    }
    let level = sidak(0.01, cases.len());
    let w = wavelengths([550.0, 430.0, 610.0, 480.0]);
    let mut failures = Vec::new();
    for (k, (name, m, (theta, below))) in cases.iter().enumerate() {
        let t = theta.to_radians();
        let wo = Vec3::new(
            t.sin() * 0.8,
            t.sin() * 0.6,
            if *below { -t.cos() } else { t.cos() },
        );
        let mut rng = Rng::new(0x9121_0000 + k as u64);
        let mode = TransportMode::Radiance;
        let r = chi2_test(
            grid,
            400_000,
            || {
                let uc = rng.uniform();
                let u = Vec2::new(rng.uniform(), rng.uniform());
                m.sample(wo, &w, uc, u, mode).map(|s| s.wi)
            },
            |d| m.pdf(wo, d, &w, mode) as f64,
        );
        println!(
            "{name} θ={theta} below={below}: p={:.4} ∫pdf={:.4}",
            r.p_value, r.integral
        );
        if r.p_value < level || r.in_empty_cells > 0 || r.integral > 1.0 + 1e-3 {
            failures.push(format!("{name} θ={theta} below={below}: {r:?}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
