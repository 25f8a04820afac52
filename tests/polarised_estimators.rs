//! Polarised light tracing and BDPT against the polarised path tracer (issue 28): three
//! estimators of the same Stokes image, which agree only if every scattering event's Mueller
//! matrix is applied in the same order, with the same frames, whichever way the path was
//! walked. (The path tracer itself is held to Mitsuba 3 in `polarised_reference.rs`; light
//! tracing cannot be held to those scenes, whose glossy reflections of an environment map it
//! almost never finds.)
//!
//! The scene: a point light and a lamp behind a linear polariser (polarised light arriving at
//! the next event, so that the light subpath's Stokes vector matters) over a diffuse floor,
//! a rough gold sphere (a conductor's Fresnel matrix, whose phase turns linear into elliptical
//! light: S3) and a frosted N-BK7 sphere (two rough dielectric events in a row, dispersive:
//! the hero alone), seen from above at an angle where both reflect the lights. Per 12 × 12 tile, the X, Y, Z of S0–S3 of each
//! estimator must agree with the path tracer's within 5 combined standard errors, each from
//! the spread of independently seeded renders.

mod support;

use spectrace::integrator::IntegratorKind;
use support::render::render_with;

const SCENE: &str = r#"
[camera]
eye = [0, 2.2, -3.2]
target = [0, 0.3, 0]
fov = "36 deg"

[film]
width = 48
height = 36

[integrator]
type = "path"
polarised = true
max_depth = 4

[materials.gold]
type = "conductor"
metal = "Au"
roughness = 0.2

[materials.frosted]
type = "dielectric"
ior = "N-BK7"
roughness = 0.2

[materials.floor]
type = "diffuse"
reflectance = 0.5

[materials.lamp]
type = "diffuse"
reflectance = 0

[materials.filter]
type = "polariser"
angle = "30 deg"

[[lights]]
type = "point"
position = [-1.2, 2.0, -0.5]
intensity = "100 cd"

[[shapes]]
type = "sphere"
center = [-0.6, 0.5, 0]
radius = 0.5
material = "gold"

[[shapes]]
type = "sphere"
center = [0.6, 0.5, 0]
radius = 0.5
material = "frosted"

# a lamp shining down through a polarising filter
[[shapes]]
type = "rectangle"
material = "lamp"
emission = { spectrum = "cie-d65", power = "20 W" }
transform = [{ scale = 0.3 }, { rotate = { axis = [1, 0, 0], angle = "90 deg" } }, { translate = [0.2, 2.4, 0.8] }]

[[shapes]]
type = "rectangle"
material = "filter"
transform = [{ scale = 0.6 }, { rotate = { axis = [1, 0, 0], angle = "90 deg" } }, { translate = [0.2, 2.3, 0.8] }]

[[shapes]]
type = "rectangle"
material = "floor"
transform = [{ scale = 4 }, { rotate = { axis = [1, 0, 0], angle = "-90 deg" } }]
"#;

const TILE: usize = 12;

/// Per seed, per tile, the X, Y, Z of S0, S1, S2, S3 (12 numbers).
fn tiles(integrator: IntegratorKind, seeds: u32, spp: u32) -> Vec<Vec<[f64; 12]>> {
    let desc = spectrace::loader::load_str(SCENE, std::path::Path::new("estimators.toml"))
        .expect("the scene");
    let scene = spectrace::build::build(&desc).expect("builds");
    assert!(scene.integrator.polarised);
    (0..seeds)
        .map(|seed| {
            let (img, stats) = render_with(&scene, |o| {
                o.spp = spp;
                o.seed = 7 + seed;
                o.integrator = integrator;
            });
            assert_eq!(stats.nan_samples + stats.inf_samples, 0);
            let (w, h) = (img.width, img.height);
            let mut out = vec![[0.0; 12]; (w / TILE) * (h / TILE)];
            for y in 0..h {
                for x in 0..w {
                    let (i, t) = (y * w + x, (y / TILE) * (w / TILE) + x / TILE);
                    for c in 0..3 {
                        out[t][c] += img.xyz[i][c] as f64;
                        for k in 0..3 {
                            out[t][3 * (k + 1) + c] += img.stokes[i][k][c] as f64;
                        }
                    }
                }
            }
            for t in &mut out {
                for v in t.iter_mut() {
                    *v /= (TILE * TILE) as f64;
                }
            }
            out
        })
        .collect()
}

/// Mean and standard error over seeds of every tile's every number.
fn stats(r: &[Vec<[f64; 12]>]) -> Vec<[(f64, f64); 12]> {
    let n = r.len() as f64;
    (0..r[0].len())
        .map(|t| {
            std::array::from_fn(|c| {
                let m = r.iter().map(|s| s[t][c]).sum::<f64>() / n;
                let v = r.iter().map(|s| (s[t][c] - m).powi(2)).sum::<f64>() / (n - 1.0);
                (m, (v / n).sqrt())
            })
        })
        .collect()
}

fn agree_with_path(integrator: IntegratorKind, seeds: u32, spp: u32) {
    let reference = stats(&tiles(IntegratorKind::Path, 16, 16));
    let ours = stats(&tiles(integrator, seeds, spp));
    let mut failures = Vec::new();
    let mut worst = 0.0f64;
    let mut polarised = 0;
    for (t, (a, b)) in ours.iter().zip(&reference).enumerate() {
        for c in 0..12 {
            let ((ma, sa), (mb, sb)) = (a[c], b[c]);
            // a floor for single-precision rounding, relative to S0
            let floor = 1e-6 * b[c % 3].0.abs();
            let se = (sa * sa + sb * sb + floor * floor).sqrt();
            let z = if se > 0.0 { (ma - mb) / se } else { 0.0 };
            worst = worst.max(z.abs());
            if c >= 3 && mb.abs() > 5.0 * sb && mb.abs() > 0.01 * b[c % 3].0 {
                polarised += 1;
            }
            if z.abs() > 5.0 {
                failures.push(format!(
                    "tile {t} S{}.{}: {ma:.5} vs path {mb:.5} (z {z:+.1})",
                    c / 3,
                    ["X", "Y", "Z"][c % 3]
                ));
            }
        }
    }
    println!(
        "{}: worst |z| {worst:.2}, {polarised} clearly polarised values",
        integrator.name()
    );
    // the test means something only if the image is polarised where it is compared
    assert!(
        polarised >= 12,
        "only {polarised} clearly nonzero S1–S3 values"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn polarised_light_tracing_agrees_with_path() {
    agree_with_path(IntegratorKind::Light, 16, 16);
}

#[test]
fn polarised_bdpt_agrees_with_path() {
    agree_with_path(IntegratorKind::Bdpt, 16, 8);
}
