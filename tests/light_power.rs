//! Each light's emitted power, integrated numerically over its sphere of directions or its
//! area, equals what the scene file states, within 0.1%. The integrals use only the light's
//! radiance/intensity as the renderer evaluates it, the CIE table and closed-form areas.

use std::f64::consts::PI;
use std::path::Path;

use glam::{Vec2, Vec3};
use spectrace::colour::cie::{K_M, cmf};
use spectrace::light::Light;
use spectrace::scene::Scene;
use spectrace::spectrum::SampledWavelengths;

const HEAD: &str = r#"
[camera]
eye = [0, 0, -10]
target = [0, 0, 0]
fov = "40 deg"
[film]
width = 8
height = 8
[materials.grey]
type = "diffuse"
reflectance = 0.5
"#;

fn scene(body: &str) -> Scene {
    let text = format!("{HEAD}\n{body}");
    let desc = spectrace::loader::load_str(&text, Path::new("inline.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"))
}

fn at(l: f32) -> SampledWavelengths<1> {
    SampledWavelengths {
        lambda: [l],
        pdf: [1.0],
    }
}

/// ∫ g(λ) dλ over 360–830 nm by the midpoint rule at 0.01 nm, with the photometric weight
/// K_m ȳ(λ) when `lumens`.
fn over_lambda(lumens: bool, g: impl Fn(f32) -> f64) -> f64 {
    let n = 47_000;
    let h = 0.01;
    (0..n)
        .map(|i| {
            let l = (360.0 + (i as f64 + 0.5) * h) as f32;
            let y = if lumens {
                K_M * cmf().y_bar(l) as f64
            } else {
                1.0
            };
            h * y * g(l)
        })
        .sum()
}

/// ∫ over the unit sphere of f(direction), midpoint rule in (cos θ, φ).
fn over_sphere(f: impl Fn(Vec3) -> f64, n_theta: usize, n_phi: usize) -> f64 {
    let mut acc = 0.0;
    let (dz, dphi) = (2.0 / n_theta as f64, 2.0 * PI / n_phi as f64);
    for i in 0..n_theta {
        let z = -1.0 + (i as f64 + 0.5) * dz;
        let r = (1.0 - z * z).sqrt();
        for j in 0..n_phi {
            let phi = (j as f64 + 0.5) * dphi;
            acc += f(Vec3::new(
                (r * phi.cos()) as f32,
                (r * phi.sin()) as f32,
                z as f32,
            )) * dz
                * dphi;
        }
    }
    acc
}

/// Intensity of a point-like light toward `dir`, per nm: li · r² at distance r.
fn intensity(s: &Scene, light: &Light, dir: Vec3, l: f32) -> f64 {
    let pos = match light {
        Light::Point(p) => p.position,
        Light::Spot(p) => p.position,
        _ => panic!("not point-like"),
    };
    let r = 3.0;
    match light.sample_li(&s.shapes, pos + dir * r, &at(l), Vec2::ZERO) {
        Some(ls) => ls.li[0] as f64 * (r * r) as f64,
        None => 0.0,
    }
}

fn assert_close(got: f64, want: f64, what: &str) {
    assert!(
        ((got - want) / want).abs() < 1e-3,
        "{what}: integrated {got}, stated {want}"
    );
}

#[test]
fn point_light_watts_and_lumens() {
    for (amount, lumens, want) in [("\"100 W\"", false, 100.0), ("\"800 lm\"", true, 800.0)] {
        for spectrum in [
            "\"blackbody:3000K\"",
            "\"cie-f11\"",
            "{ samples = [[500, 1], [600, 3]] }",
        ] {
            let s = scene(&format!(
                "[[shapes]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"grey\"\n[[lights]]\ntype = \"point\"\nposition = [5, 5, 5]\nspectrum = {spectrum}\npower = {amount}\n"
            ));
            let light = &s.lights[0];
            // isotropic: integrate over λ in one direction, then over the sphere in a few
            let per_dir = |d: Vec3| over_lambda(lumens, |l| intensity(&s, light, d, l));
            let total = over_sphere(per_dir, 4, 4);
            assert_close(total, want, &format!("point {amount} {spectrum}"));
        }
    }
}

#[test]
fn spot_light_power_includes_the_falloff() {
    // the native smoothstep in cos θ, and Mitsuba's falloff linear in θ (with a wide ramp,
    // where the two differ by 14.6 % in power)
    for (falloff, start) in [("", "20 deg"), ("falloff = \"linear\"\n", "10 deg")] {
        for (amount, lumens, want) in [("\"50 W\"", false, 50.0), ("\"1000 lm\"", true, 1000.0)] {
            spot_power(falloff, start, amount, lumens, want);
        }
    }
}

fn spot_power(falloff: &str, start: &str, amount: &str, lumens: bool, want: f64) {
    {
        let s = scene(&format!(
            "[[shapes]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"grey\"\n[[lights]]\ntype = \"spot\"\nposition = [0, 5, 0]\ntarget = [0, 0, 0]\nspectrum = \"cie-d65\"\ncone_angle = \"30 deg\"\nfalloff_start = \"{start}\"\n{falloff}power = {amount}\n"
        ));
        let light = &s.lights[0];
        // ∫ dλ first at the axis, then the angular profile relative to the axis
        let axis = Vec3::new(0.0, -1.0, 0.0);
        let on_axis = over_lambda(lumens, |l| intensity(&s, light, axis, l));
        let i550 = intensity(&s, light, axis, 550.0);
        // the sphere grid's pole on the spot's axis (−y): (x, y, z) ↦ (x, −z, y)
        let profile = over_sphere(
            |d| intensity(&s, light, Vec3::new(d.x, -d.z, d.y), 550.0) / i550,
            4000,
            8,
        );
        assert_close(
            on_axis * profile,
            want,
            &format!("spot {amount} {falloff} {start}"),
        );
    }
}

/// ∫ L(ω) |cos θ| dω over the sphere around normal `n` for an area light at wavelength `l`.
fn exitance(light: &Light, n: Vec3, l: f32) -> f64 {
    over_sphere(
        |d| light.emitted(n, d, glam::Vec2::ZERO, &at(l))[0] as f64 * (d.dot(n).abs() as f64),
        400,
        16,
    )
}

#[test]
fn area_light_power_radiance_and_luminance() {
    // a 1 m × 1 m rectangle (object square [-1,1]² scaled by 0.5) and a sphere of radius 0.3 m
    let rect_area = 1.0;
    let sphere_area = 4.0 * PI * 0.09;
    for (shape, area) in [
        (
            "type = \"rectangle\"\ntransform = [{ scale = 0.5 }]",
            rect_area,
        ),
        ("type = \"sphere\"\nradius = 0.3", sphere_area),
    ] {
        for (emission, lumens, want, per_area) in [
            ("power = \"60 W\"", false, 60.0, false),
            ("power = \"60 W\", two_sided = true", false, 60.0, false),
            ("power = \"900 lm\"", true, 900.0, false),
            ("radiance = \"10 W/m^2/sr\"", false, 10.0, true),
            ("luminance = \"100 cd/m^2\"", true, 100.0, true),
        ] {
            let s = scene(&format!(
                "[[shapes]]\n{shape}\nemission = {{ spectrum = \"cie-a\", {emission} }}\n[[lights]]\ntype = \"point\"\nposition = [5, 5, 5]\npower = \"1 W\"\n"
            ));
            let light = s
                .lights
                .iter()
                .find(|l| matches!(l, Light::Area(_)))
                .expect("area light");
            let n = Vec3::Z;
            if per_area {
                // radiance along the normal, integrated over λ
                let got = over_lambda(lumens, |l| {
                    light.emitted(n, n, glam::Vec2::ZERO, &at(l))[0] as f64
                });
                assert_close(got, want, &format!("{shape}: {emission}"));
            } else {
                // exitance at 550 nm gives the angular integral; scale by the λ integral
                let m550 = exitance(light, n, 550.0);
                let l550 = light.emitted(n, n, glam::Vec2::ZERO, &at(550.0))[0] as f64;
                let band = over_lambda(lumens, |l| {
                    light.emitted(n, n, glam::Vec2::ZERO, &at(l))[0] as f64
                });
                assert_close(
                    m550 / l550 * band * area,
                    want,
                    &format!("{shape}: {emission}"),
                );
            }
        }
    }
}

#[test]
fn directional_and_environment() {
    let s = scene(
        "[[shapes]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"grey\"\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0, -1, 0]\nspectrum = \"blackbody:5778K\"\nirradiance = \"1000 W/m^2\"\n\
         [[lights]]\ntype = \"sun\"\ndirection = [0, -1, 0]\nangular_diameter = \"0.53 deg\"\nspectrum = \"blackbody:5778K\"\nirradiance = \"100000 lx\"\n\
         [[lights]]\ntype = \"environment\"\nspectrum = \"cie-d65\"\nluminance = \"5 cd/m^2\"\n",
    );
    let p = Vec3::ZERO;
    let e = over_lambda(false, |l| {
        s.lights[0]
            .sample_li(&s.shapes, p, &at(l), Vec2::ZERO)
            .map_or(0.0, |x| x.li[0] as f64)
    });
    assert_close(e, 1000.0, "directional irradiance");
    // the sun disk: uniform radiance inside the 0.265° half-angle, none outside, so
    // E⊥ = L · ∫_cone cos θ dω = L · π sin²α (closed form), integrated over λ with K_m ȳ.
    let sun = &s.lights[1];
    let up = Vec3::Y;
    let alpha = (0.53f64 / 2.0).to_radians();
    let dir = |t: f64| Vec3::new(t.sin() as f32, t.cos() as f32, 0.0);
    let centre = sun.escaped(up, &at(550.0))[0];
    for k in 0..50 {
        let t = 0.98 * alpha * k as f64 / 49.0;
        assert_eq!(
            sun.escaped(dir(t), &at(550.0))[0],
            centre,
            "not uniform at {t} rad"
        );
    }
    assert_eq!(
        sun.escaped(dir(1.05 * alpha), &at(550.0))[0],
        0.0,
        "light outside the disk"
    );
    let lum = over_lambda(true, |l| sun.escaped(up, &at(l))[0] as f64);
    assert_close(lum * PI * alpha.sin().powi(2), 100_000.0, "sun illuminance");
    let env = over_lambda(true, |l| s.lights[2].escaped(Vec3::X, &at(l))[0] as f64);
    assert_close(env, 5.0, "environment luminance");
}

/// One row of `tests/data/illuminant_integrals.csv` (colour-science tables, exact integrals).
struct IlluminantIntegral {
    name: String,
    lo: f64,
    hi: f64,
    /// ∫ S dλ over [lo, hi], S's unit × nm.
    band: f64,
    /// ∫ S ȳ dλ over [lo, hi] ∩ 360–830 nm.
    luminous: f64,
}

fn illuminant_integrals() -> Vec<IlluminantIntegral> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/illuminant_integrals.csv"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("illuminant"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let x = |i: usize| f[i].parse::<f64>().unwrap_or_else(|e| panic!("{l}: {e}"));
            IlluminantIntegral {
                name: f[0].to_string(),
                lo: x(1),
                hi: x(2),
                band: x(3),
                luminous: x(4),
            }
        })
        .collect()
}

/// CIE standard illuminant A by its defining formula (CIE 015:2018 eq. 4.1): Planck's law with
/// c₂ = 1.435e7 nm·K at 2848 K (2856 K on ITS-90), normalised to 100 at 560 nm.
fn cie_a(l: f64) -> f64 {
    let c2: f64 = 1.435e7 / 2848.0;
    100.0 * (560.0 / l).powi(5) * (c2 / 560.0).exp_m1() / (c2 / l).exp_m1()
}

/// (∫ S dλ, ∫ S ȳ dλ) of CIE A over [lo, hi], by Simpson's rule at 0.005 nm on the formula
/// (ȳ from the CIE 1931 table, zero outside 360–830 nm).
fn cie_a_integrals(lo: f64, hi: f64) -> (f64, f64) {
    let n = ((hi - lo) / 0.005).round() as usize; // even for the ranges used here
    let h = (hi - lo) / n as f64;
    let (mut band, mut lum) = (0.0, 0.0);
    for i in 0..=n {
        let l = lo + i as f64 * h;
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let s = cie_a(l);
        band += w * s;
        lum += w * s * cmf().y_bar(l as f32) as f64;
    }
    (band * h / 3.0, lum * h / 3.0)
}

/// ∫ g(λ) dλ over [lo, hi] by the midpoint rule at 0.01 nm, with K_m ȳ(λ) when `lumens`.
fn over_range(lo: f64, hi: f64, lumens: bool, g: impl Fn(f32) -> f64) -> f64 {
    let h = 0.01;
    let n = ((hi - lo) / h).round() as usize;
    (0..n)
        .map(|i| {
            let l = (lo + (i as f64 + 0.5) * h) as f32;
            let y = if lumens {
                K_M * cmf().y_bar(l) as f64
            } else {
                1.0
            };
            h * y * g(l)
        })
        .sum()
}

/// Every named CIE illuminant over its whole defined range (A: Planck's law at any wavelength;
/// D65, D50: the CIE tables to 830 nm), for several scene wavelength ranges. A light given in
/// cd/m² must have the band radiance 100 cd/m² × ∫S dλ / (K_m ∫S ȳ dλ), and a light given in
/// watts the lumens 100 W × K_m ∫S ȳ dλ / ∫S dλ, both integrals over the scene's range and from
/// independent truth: the CIE A formula integrated here, and colour-science's CIE tables
/// integrated exactly by `scripts/gen_spectra.py` (`tests/data/illuminant_integrals.csv`).
#[test]
fn named_illuminants_band_radiance_and_lumens_over_the_range() {
    let rows = illuminant_integrals();
    assert!(rows.len() >= 18, "{} rows", rows.len());
    let (mut worst, mut failures): (Vec<String>, Vec<String>) = (Vec::new(), Vec::new());
    for r in &rows {
        let (band, luminous) = if r.name == "cie-a" {
            let (b, l) = cie_a_integrals(r.lo, r.hi);
            // the generator's integral of the same formula, as a cross-check of the data file
            assert!(
                (b / r.band - 1.0).abs() < 1e-6,
                "{}: {b} vs {}",
                r.name,
                r.band
            );
            assert!(
                (l / r.luminous - 1.0).abs() < 1e-6,
                "{}: {l} vs {}",
                r.name,
                r.luminous
            );
            (b, l)
        } else {
            (r.band, r.luminous)
        };
        let s = scene(&format!(
            "[scene]\nwavelength_range = [{}, {}]\n\
             [[shapes]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"grey\"\n\
             [[lights]]\ntype = \"environment\"\nspectrum = \"{name}\"\nluminance = \"100 cd/m^2\"\n\
             [[lights]]\ntype = \"point\"\nposition = [5, 5, 5]\nspectrum = \"{name}\"\npower = \"100 W\"\n",
            r.lo,
            r.hi,
            name = r.name
        ));
        let what = format!("{} over {}–{} nm", r.name, r.lo, r.hi);
        // band radiance of the 100 cd/m² environment
        let got = over_range(r.lo, r.hi, false, |l| {
            s.lights[0].escaped(Vec3::X, &at(l))[0] as f64
        });
        let want = 100.0 * band / (K_M * luminous);
        worst.push(format!("{what}: band radiance {:.4}", got / want));
        // lumens of the 100 W point light: 4π ∫ I K_m ȳ dλ
        let lm = 4.0
            * PI
            * over_range(r.lo, r.hi, true, |l| {
                intensity(&s, &s.lights[1], Vec3::Y, l)
            });
        let want_lm = 100.0 * K_M * luminous / band;
        worst.push(format!("{what}: lumens {:.4}", lm / want_lm));
        if ((got - want) / want).abs() > 1e-3 || ((lm - want_lm) / want_lm).abs() > 1e-3 {
            failures.push(format!(
                "{what}: band radiance {got:.6} W/m²/sr, closed form {want:.6} (ratio {:.4}); \
                 lumens {lm:.1}, closed form {want_lm:.1} (ratio {:.4})",
                got / want,
                lm / want_lm
            ));
        }
    }
    eprintln!("{}", worst.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
