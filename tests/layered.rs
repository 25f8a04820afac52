//! pbrt-v4's layered materials (`spectrace::material::Layered`: `coateddiffuse`,
//! `coatedconductor`) against closed forms. With a smooth coating the slab's walk has a closed
//! form once it is long enough not to be cut (`max_depth` 400 here; pbrt-v4's default of 10
//! cuts it, which is the renders' business, `tests/pbrt_import.rs`):
//! - over a Lambertian base ρ, with the slab absorbing exp(−t/μ) per crossing at |cos| μ, the
//!   directional albedo is F(θₒ) + (1 − F(θₒ))·e^{−t/μₜ}·ρ·E_out/(1 − ρ·E_back), where μₜ is
//!   the refracted cosine, E_out = ∫ 2μ e^{−t/μ} (1 − Fᵢ(μ)) dμ the diffuse light's escape and
//!   E_back = ∫ 2μ e^{−2t/μ} Fᵢ(μ) dμ its return to the base, Fᵢ the Fresnel reflectance from
//!   inside (1 under total internal reflection); without absorption and with ρ = 1 it is 1;
//! - over a smooth conductor of reflectance R_c at μₜ, the specular chain sums to
//!   F + (1 − F)²·R_c·x/(1 − F·R_c·x), x = e^{−2t/μₜ}.
//!
//! The albedo is the mean of the samples' weights f·|cos θ|/pdf; the non-specular part of it
//! also as ∫ f·cos θ dω of the evaluated f (cosine-weighted directions), which checks `eval`
//! against `sample`.

mod support;

use std::sync::Arc;

use glam::{Vec2, Vec3};
use spectrace::material::fresnel::{fresnel_conductor, fresnel_dielectric};
use spectrace::material::{Layered, LayeredBase, Material, TransportMode};
use spectrace::spectrum::ior::{ComplexIor, Ior};
use spectrace::spectrum::{PiecewiseLinear, SampledWavelengths, Spectrum};
use support::Rng;

fn wavelengths() -> SampledWavelengths<4> {
    SampledWavelengths {
        lambda: [450.0, 520.0, 600.0, 680.0],
        pdf: [1.0 / 470.0; 4],
    }
}

fn coated(base: LayeredBase, rho: f32, eta: f32, thickness: f32) -> Material {
    Material::Layered(Box::new(Layered {
        base,
        reflectance: Spectrum::Constant(rho).into(),
        eta: Ior::Constant(eta),
        alpha: None,
        alpha_texture: None,
        thickness,
        albedo: Spectrum::Constant(0.0).into(),
        g: 0.0,
        max_depth: 400,
        n_samples: 1,
        pbrt_exit_weight: false,
    }))
}

/// The mean and standard error of `n` draws of `f`.
fn mean_se(n: usize, mut f: impl FnMut() -> f64) -> (f64, f64) {
    let (mut s, mut s2) = (0.0, 0.0);
    for _ in 0..n {
        let x = f();
        s += x;
        s2 += x * x;
    }
    let m = s / n as f64;
    (m, ((s2 / n as f64 - m * m).max(0.0) / n as f64).sqrt())
}

fn view(cos: f32) -> Vec3 {
    Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos)
}

/// The albedo of the samples' weights at wavelength index 0, and of ∫ f cos dω by
/// cosine-weighted directions (the non-specular part).
fn albedos(m: &Material, wo: Vec3, n: usize, seed: u64) -> ((f64, f64), (f64, f64)) {
    let w = wavelengths();
    let mut rng = Rng::new(seed);
    let sampled = mean_se(n, || {
        let (uc, u) = (rng.uniform(), Vec2::new(rng.uniform(), rng.uniform()));
        match m.sample(wo, &w, uc, u, TransportMode::Radiance) {
            Some(s) => (s.f[0] * s.wi.z.abs() / s.pdf) as f64,
            None => 0.0,
        }
    });
    let evaluated = mean_se(n, || {
        let u = Vec2::new(rng.uniform(), rng.uniform());
        let r = u.x.sqrt();
        let phi = 2.0 * std::f32::consts::PI * u.y;
        let wi = Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt());
        if wi.z <= 0.0 {
            return 0.0;
        }
        // cosine-weighted: f cos / (cos/π) = π f
        (m.eval(wo, wi, &w, TransportMode::Radiance)[0] * std::f32::consts::PI) as f64
    });
    (sampled, evaluated)
}

/// 2∫₀¹ μ g(μ) dμ by the midpoint rule.
fn hemi(g: impl Fn(f64) -> f64) -> f64 {
    let n = 200_000;
    (0..n)
        .map(|i| {
            let mu = (i as f64 + 0.5) / n as f64;
            2.0 * mu * g(mu)
        })
        .sum::<f64>()
        / n as f64
}

/// The refracted cosine inside a coating of index η for an outside cosine `c`.
fn mu_t(c: f64, eta: f64) -> f64 {
    (1.0 - (1.0 - c * c) / (eta * eta)).sqrt()
}

fn check(what: &str, (m, se): (f64, f64), truth: f64) {
    // a floor of f32 rounding: the white furnace's weights are all 1, so its spread is 0
    let z = (m - truth) / se.max(1e-6);
    println!("{what}: {m:.5} ± {se:.5} against {truth:.5} (z {z:.2})");
    assert!(
        z.abs() < 5.0,
        "{what}: {m} ± {se} against the closed form {truth} (z {z:.1})"
    );
}

#[test]
fn coated_diffuse_matches_its_closed_form() {
    for &(rho, eta, t) in &[
        (1.0f32, 1.5f32, 0.0f32),
        (0.5, 1.5, 0.0),
        (0.8, 1.33, 0.1),
        (0.3, 2.0, 0.5),
    ] {
        let m = coated(LayeredBase::Diffuse, rho, eta, t);
        let (e, td) = (eta as f64, t as f64);
        let f_in = |mu: f64| fresnel_dielectric(mu as f32, 1.0 / eta) as f64;
        let e_out = hemi(|mu| (-td / mu).exp() * (1.0 - f_in(mu)));
        let e_back = hemi(|mu| (-2.0 * td / mu).exp() * f_in(mu));
        for &c in &[1.0f32, 0.6, 0.2] {
            let f = fresnel_dielectric(c, eta) as f64;
            let inner = (1.0 - f) * (-td / mu_t(c as f64, e)).exp() * rho as f64 * e_out
                / (1.0 - rho as f64 * e_back);
            let (sampled, evaluated) = albedos(&m, view(c), 200_000, 7);
            let tag = format!("ρ {rho} η {eta} t {t} cos {c}");
            check(&format!("{tag}, sampled"), sampled, f + inner);
            check(&format!("{tag}, evaluated"), evaluated, inner);
        }
    }
}

#[test]
fn coated_smooth_conductor_matches_its_closed_form() {
    let (n, k) = (0.2f32, 3.0f32);
    let table = |v: f32| Arc::new(PiecewiseLinear::new(vec![360.0, 830.0], vec![v; 2]).unwrap());
    for &(eta, t) in &[(1.5f32, 0.0f32), (1.5, 0.2), (1.2, 0.05)] {
        let base = LayeredBase::Conductor {
            ior: Some(ComplexIor {
                n: table(n),
                k: table(k),
            }),
            alpha: None,
        };
        let m = coated(base, 0.0, eta, t);
        for &c in &[1.0f32, 0.5, 0.15] {
            let f = fresnel_dielectric(c, eta) as f64;
            let mt = mu_t(c as f64, eta as f64);
            let rc = fresnel_conductor(mt as f32, n / eta, k / eta) as f64;
            let x = (-2.0 * t as f64 / mt).exp();
            let truth = f + (1.0 - f).powi(2) * rc * x / (1.0 - f * rc * x);
            let (sampled, _) = albedos(&m, view(c), 20_000, 11);
            check(&format!("η {eta} t {t} cos {c}"), sampled, truth);
        }
    }
}

/// Both sides see the coating: a view from below reflects as the mirrored view from above,
/// and nothing crosses.
#[test]
fn both_sides_see_the_coating_and_nothing_crosses() {
    let m = coated(LayeredBase::Diffuse, 0.7, 1.5, 0.1);
    let w = wavelengths();
    let (wo, wi) = (view(0.7), Vec3::new(-0.3, 0.2, 0.8).normalize());
    let up = m.eval(wo, wi, &w, TransportMode::Radiance)[0];
    let down = m.eval(-wo, -wi, &w, TransportMode::Radiance)[0];
    assert!(up > 0.0 && up == down, "{up} {down}");
    assert_eq!(m.eval(wo, -wi, &w, TransportMode::Radiance)[0], 0.0);
}

/// With a rough coating, sampling and evaluation must estimate the same ∫ f·cos θ dω.
#[test]
fn rough_coatings_sample_what_they_evaluate() {
    for &(alpha, rho, eta, t, albedo) in &[
        (0.224f32, 0.5f32, 1.5f32, 0.01f32, 0.0f32),
        (0.1, 0.8, 1.5, 0.01, 0.0),
        (0.3, 0.3, 1.33, 0.3, 0.7),
    ] {
        let m = Material::Layered(Box::new(Layered {
            base: LayeredBase::Diffuse,
            reflectance: Spectrum::Constant(rho).into(),
            eta: Ior::Constant(eta),
            alpha: Some([alpha, alpha]),
            alpha_texture: None,
            thickness: t,
            albedo: Spectrum::Constant(albedo).into(),
            g: 0.3,
            max_depth: 10,
            n_samples: 1,
            pbrt_exit_weight: false,
        }));
        for &c in &[0.9f32, 0.5, 0.2] {
            let ((s, se_s), (e, se_e)) = albedos(&m, view(c), 400_000, 3);
            let z = (s - e) / (se_s * se_s + se_e * se_e).sqrt();
            println!(
                "α {alpha} ρ {rho} cos {c}: sampled {s:.5} ± {se_s:.5}, evaluated {e:.5} ± {se_e:.5} (z {z:.1})"
            );
            assert!(z.abs() < 5.0);
        }
    }
}

#[derive(serde::Deserialize)]
struct PbrtAlbedos {
    case: Vec<PbrtAlbedo>,
}

#[derive(serde::Deserialize)]
struct PbrtAlbedo {
    name: String,
    cos: f32,
    params: std::collections::BTreeMap<String, toml::Value>,
    sampled: f64,
    sampled_se: f64,
    evaluated: f64,
    evaluated_se: f64,
}

/// Directional albedos against pbrt-v4's own layered BSDF (`tests/data/pbrt_layered_albedo.toml`,
/// from `scripts/gen_pbrt_layered_albedo.py`): spectrace's sampler against pbrt-v4's sampler;
/// spectrace's f with pbrt-v4's exit weight against pbrt-v4's f (which is biased high); and
/// spectrace's own f against pbrt-v4's sampler, the unbiased figure.
#[test]
fn albedos_match_pbrt_v4s_own_bsdf() {
    let p = support::data_path("pbrt_layered_albedo.toml");
    let data: PbrtAlbedos = toml::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
    let table = |v: f32| Arc::new(PiecewiseLinear::new(vec![360.0, 830.0], vec![v; 2]).unwrap());
    let mut failures = Vec::new();
    for c in &data.case {
        let num = |k: &str| c.params[k].as_float().unwrap() as f32;
        let base = match c.params["base"].as_str().unwrap() {
            "diffuse" => LayeredBase::Diffuse,
            _ => LayeredBase::Conductor {
                ior: Some(ComplexIor {
                    n: table(num("n")),
                    k: table(num("k")),
                }),
                alpha: Some([num("conductor_alpha"); 2]),
            },
        };
        let layered = |pbrt_exit_weight: bool| {
            Material::Layered(Box::new(Layered {
                base: base.clone(),
                reflectance: Spectrum::Constant(
                    c.params
                        .get("rho")
                        .map_or(0.0, |v| v.as_float().unwrap() as f32),
                )
                .into(),
                eta: Ior::Constant(num("eta")),
                alpha: Some([num("alpha"); 2]),
                alpha_texture: None,
                thickness: num("thickness"),
                albedo: Spectrum::Constant(num("albedo")).into(),
                g: num("g"),
                max_depth: 10,
                n_samples: 1,
                pbrt_exit_weight,
            }))
        };
        let (sampled, own) = albedos(&layered(false), view(c.cos), 400_000, 5);
        let (_, pbrt_weight) = albedos(&layered(true), view(c.cos), 400_000, 6);
        for (what, (m, se), (r, rse)) in [
            ("sampled", sampled, (c.sampled, c.sampled_se)),
            (
                "f with pbrt-v4's weight",
                pbrt_weight,
                (c.evaluated, c.evaluated_se),
            ),
            ("f", own, (c.sampled, c.sampled_se)),
        ] {
            let z = (m - r) / (se * se + rse * rse).sqrt();
            let line = format!(
                "{} cos {}: {what} {m:.5} ± {se:.5} against pbrt-v4 {r:.5} ± {rse:.5} (z {z:+.1})",
                c.name, c.cos
            );
            println!("{line}");
            if z.abs() > 5.0 {
                failures.push(line);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
