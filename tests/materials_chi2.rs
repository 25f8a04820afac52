//! χ² goodness of fit of every non-delta BSDF sampler against its own `pdf`, over incident
//! directions (normal, 45°, grazing 85°, from outside and inside for the dielectric) and hero
//! wavelengths. Family-wise significance 0.01 with the Šidák correction over all cases.

#[path = "support/chi2.rs"]
mod chi2;
mod support;

use std::sync::Arc;

use chi2::{Chi2Outcome, Grid, chi2_test, gamma_q, ln_gamma, sidak};
use glam::{Vec2, Vec3};
use spectrace::material::microfacet::Distribution;
use spectrace::material::{
    Lambert, Material, Phong, Plastic, RoughConductor, RoughDielectric, TransportMode,
};
use spectrace::spectrum::named::{Named, lookup};
use spectrace::spectrum::{PiecewiseLinear, SampledWavelengths, Spectrum};
use support::Rng;

const SAMPLES: usize = 1_000_000;

fn bk7() -> spectrace::spectrum::ior::Ior {
    match lookup("glass:N-BK7") {
        Ok(Named::Dielectric(g)) => g.ior,
        other => panic!("{other:?}"),
    }
}

fn gold() -> spectrace::spectrum::ior::ComplexIor {
    match lookup("metal:Au") {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    }
}

/// Direction at polar angle `theta_deg` from +z (or from −z if `below`), azimuth `phi` rad.
fn dir(theta_deg: f32, phi: f32, below: bool) -> Vec3 {
    let t = theta_deg.to_radians();
    let z = if below { -t.cos() } else { t.cos() };
    Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), z)
}

fn wavelengths(hero: f32) -> SampledWavelengths<4> {
    let mut lambda = [hero; 4];
    for (j, l) in lambda.iter_mut().enumerate().skip(1) {
        *l = 360.0 + (hero - 360.0 + 117.5 * j as f32) % 470.0;
    }
    SampledWavelengths {
        lambda,
        pdf: [1.0 / 470.0; 4],
    }
}

struct Case {
    name: String,
    material: Material,
    wo: Vec3,
    w: SampledWavelengths<4>,
    grid: Grid,
}

const COARSE: Grid = Grid {
    n_cos: 10,
    n_phi: 20,
    both_hemispheres: false,
};
const FINE: Grid = Grid {
    n_cos: 20,
    n_phi: 40,
    both_hemispheres: false,
};

fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    let angles = [0.0f32, 45.0, 85.0];
    let phi = 0.7;
    for &t in &angles {
        v.push(Case {
            name: format!("Lambert θo={t}"),
            material: Material::Diffuse(Lambert::new(Spectrum::Constant(0.8))),
            wo: dir(t, phi, false),
            w: wavelengths(550.0),
            grid: COARSE,
        });
    }
    for (n, grid) in [(1.0f32, COARSE), (10.0, COARSE), (100.0, FINE)] {
        for &t in &angles {
            let m = Phong::new(Spectrum::Constant(0.0), Spectrum::Constant(1.0), n).unwrap();
            v.push(Case {
                name: format!("Phong specular n={n} θo={t}"),
                material: Material::Phong(m),
                wo: dir(t, phi, false),
                w: wavelengths(500.0),
                grid,
            });
        }
    }
    // Mixed lobes with spectrally varying kd/ks: the lobe choice uses several wavelengths.
    let ramp = |a: f32, b: f32| {
        Spectrum::Piecewise(Arc::new(
            PiecewiseLinear::new(vec![360.0, 830.0], vec![a, b]).unwrap(),
        ))
    };
    for &t in &angles {
        let m = Phong::new(ramp(0.2, 0.6), ramp(0.7, 0.3), 20.0).unwrap();
        v.push(Case {
            name: format!("Phong mixed n=20 θo={t}"),
            material: Material::Phong(m),
            wo: dir(t, phi, false),
            w: wavelengths(600.0),
            grid: COARSE,
        });
    }
    let heroes = [450.0f32, 550.0, 650.0];
    let mut h = 0;
    for dist in [Distribution::Ggx, Distribution::Beckmann] {
        for alpha in [0.1f32, 0.5] {
            for below in [false, true] {
                for &t in &angles {
                    let grid = Grid {
                        both_hemispheres: true,
                        ..if alpha < 0.2 { FINE } else { COARSE }
                    };
                    v.push(Case {
                        name: format!(
                            "RoughDielectric {dist:?} BK7 α={alpha} θo={t} {} λ={}",
                            if below { "inside" } else { "outside" },
                            heroes[h % 3]
                        ),
                        material: Material::RoughDielectric(
                            RoughDielectric::new(bk7(), 1.0, alpha).with_distribution(dist),
                        ),
                        wo: dir(t, phi, below),
                        w: wavelengths(heroes[h % 3]),
                        grid,
                    });
                    h += 1;
                }
            }
        }
        for alpha in [0.1f32, 0.5] {
            for &t in &angles {
                v.push(Case {
                    name: format!("RoughConductor {dist:?} Au α={alpha} θo={t}"),
                    material: Material::RoughConductor(
                        RoughConductor::new(gold(), 1.0, alpha).with_distribution(dist),
                    ),
                    wo: dir(t, phi, false),
                    w: wavelengths(heroes[h % 3]),
                    grid: if alpha < 0.2 { FINE } else { COARSE },
                });
                h += 1;
            }
        }
    }
    // anisotropic lobes (α_u ≠ α_v), seen from an azimuth between the two axes
    for dist in [Distribution::Ggx, Distribution::Beckmann] {
        for &t in &angles {
            v.push(Case {
                name: format!("RoughConductor {dist:?} Au α=(0.08, 0.4) θo={t}"),
                material: Material::RoughConductor(
                    RoughConductor::new(gold(), 1.0, 0.1)
                        .with_distribution(dist)
                        .with_anisotropy(0.08, 0.4),
                ),
                wo: dir(t, phi, false),
                w: wavelengths(heroes[h % 3]),
                grid: FINE,
            });
            h += 1;
            v.push(Case {
                name: format!("RoughDielectric {dist:?} BK7 α=(0.5, 0.12) θo={t}"),
                material: Material::RoughDielectric(
                    RoughDielectric::new(bk7(), 1.0, 0.1)
                        .with_distribution(dist)
                        .with_anisotropy(0.5, 0.12),
                ),
                wo: dir(t, phi, h % 2 == 0),
                w: wavelengths(heroes[h % 3]),
                grid: Grid {
                    both_hemispheres: true,
                    ..FINE
                },
            });
            h += 1;
        }
    }
    // Mitsuba's `mask` (opacity 0.6) around a rough conductor: the straight-through lobe counts
    // as rejected, as many as the nested density (times 0.6) falls short of 1
    for &t in &angles {
        v.push(Case {
            name: format!("Mask 0.6 over RoughConductor θo={t}"),
            material: Material::Mask(Box::new(spectrace::material::Mask {
                opacity: Spectrum::Constant(0.6).into(),
                inner: Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.3)),
            })),
            wo: dir(t, phi, false),
            w: wavelengths(550.0),
            grid: COARSE,
        });
    }
    // Mitsuba's `blendbsdf`: a diffuse and a rough conductor (both with densities), and a
    // smooth dielectric with a diffuse one (the dielectric's delta lobes count as rejected)
    for &t in &angles {
        v.push(Case {
            name: format!("Blend 0.3 of Lambert and RoughConductor θo={t}"),
            material: Material::Blend(Box::new(spectrace::material::Blend {
                weight: Spectrum::Constant(0.3).into(),
                a: Material::Diffuse(Lambert::new(Spectrum::Constant(0.8))),
                b: Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.15)),
            })),
            wo: dir(t, phi, false),
            w: wavelengths(550.0),
            grid: FINE,
        });
        v.push(Case {
            name: format!("Blend 0.6 of Dielectric and Lambert θo={t}"),
            material: Material::Blend(Box::new(spectrace::material::Blend {
                weight: Spectrum::Constant(0.6).into(),
                a: Material::Dielectric(spectrace::material::Dielectric::new(bk7(), 1.0)),
                b: Material::Diffuse(Lambert::new(Spectrum::Constant(0.5))),
            })),
            wo: dir(t, phi, false),
            w: wavelengths(550.0),
            grid: COARSE,
        });
    }
    // Plastics (Mitsuba's `plastic` and `roughplastic`): the smooth coating's delta reflection
    // is not a direction with a density, so its samples count as rejected, as many as the
    // diffuse part's density falls short of 1
    for (rough, grid) in [
        (None, COARSE),
        (Some((0.1, Distribution::Beckmann)), FINE),
        (Some((0.3, Distribution::Ggx)), COARSE),
    ] {
        for &t in &angles {
            let m = Plastic::new(
                Spectrum::Constant(0.5).into(),
                0.5,
                1.0,
                1.49,
                1.000277,
                false,
                rough,
            )
            .unwrap();
            if rough.is_none() {
                // the same under a thin film (its spectral R, T and R_int; `coated.rs`)
                let film = spectrace::optics::thin_film::Coating {
                    layers: vec![spectrace::optics::thin_film::Layer {
                        index: spectrace::optics::thin_film::LayerIndex::Dielectric(
                            spectrace::spectrum::ior::Ior::Constant(2.35),
                        ),
                        thickness_nm: 120.0,
                    }],
                };
                v.push(Case {
                    name: format!("Plastic with a thin film θo={t}"),
                    material: Material::Plastic(m.clone().with_film(film, 1.000277, 1.49).unwrap()),
                    wo: dir(t, phi, false),
                    w: wavelengths(550.0),
                    grid: FINE,
                });
            }
            v.push(Case {
                name: format!("Plastic {rough:?} θo={t}"),
                material: Material::Plastic(m),
                wo: dir(t, phi, false),
                w: wavelengths(550.0),
                grid,
            });
        }
    }
    // Mitsuba's polarising plastic: its glossy lobe (Beckmann α = 0.06, the documentation
    // scenes') and GGX α = 0.3, beside the cosine-weighted diffuse part
    for (alpha, kind, grid) in [
        (0.06, Distribution::Beckmann, FINE),
        (0.3, Distribution::Ggx, COARSE),
    ] {
        for &t in &angles {
            let m = spectrace::material::PPlastic::new(
                Spectrum::Constant(0.3).into(),
                0.3,
                1.0,
                1.49,
                spectrace::material::microfacet::Microfacet::new(alpha, kind),
            );
            v.push(Case {
                name: format!("PPlastic {kind:?} α={alpha} θo={t}"),
                material: Material::PPlastic(m),
                wo: dir(t, phi, false),
                w: wavelengths(550.0),
                grid,
            });
        }
    }
    // Mitsuba's measured_polarized: GGX visible normals of alpha_sample (0.02, its gold
    // scenes', and 0.3) mixed with 10 % of the cosine-weighted hemisphere; the table's values
    // do not enter the density
    for (alpha, grid) in [(0.02, FINE), (0.3, COARSE)] {
        for &t in &angles {
            let m = spectrace::material::MeasuredPolarized {
                phi_d: vec![0.0],
                theta_d: vec![0.0],
                theta_h: vec![0.0],
                wavelengths: vec![550.0],
                m: std::sync::Arc::new(vec![0.1; 16]),
                sampling: spectrace::material::microfacet::Ggx::new(alpha),
                wavelength: None,
            };
            v.push(Case {
                name: format!("MeasuredPolarized α_sample={alpha} θo={t}"),
                material: Material::MeasuredPolarized(Box::new(m)),
                wo: dir(t, phi, false),
                w: wavelengths(550.0),
                grid,
            });
        }
    }
    v
}

fn run(m: &Material, wo: Vec3, w: &SampledWavelengths<4>, grid: Grid, seed: u64) -> Chi2Outcome {
    let mut rng = Rng::new(seed);
    let mode = TransportMode::Radiance;
    chi2_test(
        grid,
        SAMPLES,
        || {
            let uc = rng.uniform();
            let u = Vec2::new(rng.uniform(), rng.uniform());
            m.sample(wo, w, uc, u, mode)
                .filter(|s| !s.specular)
                .map(|s| s.wi)
        },
        |d| m.pdf(wo, d, w, mode) as f64,
    )
}

#[test]
fn chi2_every_sampler_matches_its_pdf() {
    let cases = cases();
    let level = sidak(0.01, cases.len());
    let mut failures = Vec::new();
    let mut p_min = f64::INFINITY;
    let mut p_max: f64 = 0.0;
    for (k, c) in cases.iter().enumerate() {
        let r = run(&c.material, c.wo, &c.w, c.grid, 0x5EED_0000 + k as u64);
        println!(
            "{:<55} χ²={:>9.2} dof={:>4} p={:.4} ∫pdf={:.5} rejected={}",
            c.name, r.chi2, r.dof, r.p_value, r.integral, r.rejected
        );
        p_min = p_min.min(r.p_value);
        p_max = p_max.max(r.p_value);
        if r.p_value < level || r.in_empty_cells > 0 || r.integral > 1.0 + 1e-3 {
            failures.push(format!("{}: {r:?}", c.name));
        }
    }
    println!(
        "{} cases, per-case level {level:.2e}, p in [{p_min:.4}, {p_max:.4}]",
        cases.len()
    );
    assert!(failures.is_empty(), "χ² failures:\n{}", failures.join("\n"));
}

/// The test has power: a sampler checked against a slightly different density is rejected.
#[test]
fn chi2_rejects_a_mismatched_pdf() {
    let mut rng = Rng::new(7);
    let w = wavelengths(550.0);
    let wo = dir(45.0, 0.3, false);
    let sampled = Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.5));
    let claimed = Material::RoughConductor(RoughConductor::new(gold(), 1.0, 0.55));
    let mode = TransportMode::Radiance;
    let r = chi2_test(
        COARSE,
        SAMPLES,
        || {
            let u = Vec2::new(rng.uniform(), rng.uniform());
            sampled.sample(wo, &w, 0.5, u, mode).map(|s| s.wi)
        },
        |d| claimed.pdf(wo, d, &w, mode) as f64,
    );
    assert!(r.p_value < 1e-6, "{r:?}");
    // Phong sampled with exponent 10 but claiming the density of exponent 11.
    let sampled = Material::Phong(
        Phong::new(Spectrum::Constant(0.0), Spectrum::Constant(1.0), 10.0).unwrap(),
    );
    let claimed = Material::Phong(
        Phong::new(Spectrum::Constant(0.0), Spectrum::Constant(1.0), 11.0).unwrap(),
    );
    let r = chi2_test(
        COARSE,
        SAMPLES,
        || {
            let u = Vec2::new(rng.uniform(), rng.uniform());
            sampled.sample(wo, &w, 0.5, u, mode).map(|s| s.wi)
        },
        |d| claimed.pdf(wo, d, &w, mode) as f64,
    );
    assert!(r.p_value < 1e-6, "{r:?}");
}

/// The p-value machinery against tabulated values.
#[test]
fn incomplete_gamma_matches_tables() {
    // ln Γ at integers and half-integers.
    assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
    assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
    assert!((ln_gamma(10.5) - 1_133_278.388_7f64.ln()).abs() < 1e-9);
    // Q(1, x) = e^{−x}.
    for x in [0.1, 1.0, 3.0, 10.0, 50.0] {
        let e = f64::exp(-x);
        assert!((gamma_q(1.0, x) - e).abs() / e < 1e-10, "Q(1, {x})");
    }
    // χ² upper 1 % critical values (NIST/SEMATECH e-Handbook, table 1.3.6.7.4).
    for (dof, crit) in [(1.0, 6.635), (2.0, 9.210), (10.0, 23.209), (100.0, 135.807)] {
        let p = gamma_q(0.5 * dof, 0.5 * crit);
        assert!((p - 0.01).abs() < 2e-5, "dof {dof}: p = {p}");
    }
    // and the 5 % ones
    for (dof, crit) in [(5.0, 11.070), (30.0, 43.773), (50.0, 67.505)] {
        let p = gamma_q(0.5 * dof, 0.5 * crit);
        assert!((p - 0.05).abs() < 1e-4, "dof {dof}: p = {p}");
    }
    assert!((sidak(0.01, 1) - 0.01).abs() < 1e-15);
    assert!((1.0 - (1.0 - sidak(0.01, 40)).powi(40) - 0.01).abs() < 1e-12);
}
