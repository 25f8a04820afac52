//! pbrt-v4 reference scenes (`tests/reference/pbrt/<name>/scene.pbrt`, each with pbrt-v4's own
//! renders in `refs.toml` from `scripts/gen_pbrt_reference.py`): spectrace reads the scene
//! unchanged, renders it with two seeds at the scene's sample count, and every 8 × 8 block's
//! mean Y must lie within 5 standard errors of pbrt-v4's (both renderers' noise, measured from
//! their seeds' differences). `compare.toml` in a folder may ask for pbrt-v4's layered exit
//! weight (`pbrt_exit_weight`), for scenes where pbrt-v4's layered f is biased, or say that
//! the film has a pixel sensor (`sensor`): then pbrt-v4's R, G and B blocks are compared with
//! spectrace's `sensor.wb.R/G/B` channels (5 nm spectral bins for a camera's curves, as the
//! command line renders them).

mod support;

use std::path::Path;

use spectrace::colour::cie::K_M;
use spectrace::loader::desc::MaterialKind;

#[derive(serde::Deserialize)]
struct Refs {
    width: usize,
    height: usize,
    block: usize,
    mean: Vec<f64>,
    stderr: Vec<f64>,
}

#[derive(serde::Deserialize, Default)]
struct Compare {
    #[serde(default)]
    pbrt_exit_weight: bool,
    #[serde(default)]
    sensor: bool,
}

/// Per block: the mean Y (pbrt-v4's scale) of two seeds and its standard error.
fn blocks(a: &[f64], b: &[f64], w: usize, h: usize, k: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut mean, mut se) = (Vec::new(), Vec::new());
    for by in (0..h).step_by(k) {
        for bx in (0..w).step_by(k) {
            let (mut s, mut d2, mut n) = (0.0, 0.0, 0.0);
            for y in by..(by + k).min(h) {
                for x in bx..(bx + k).min(w) {
                    let (p, q) = (a[y * w + x], b[y * w + x]);
                    s += p + q;
                    d2 += (p - q) * (p - q);
                    n += 1.0;
                }
            }
            mean.push(s / (2.0 * n));
            se.push(d2.sqrt() / (2.0 * n));
        }
    }
    (mean, se)
}

/// The scene's pixel sensor's pbrt-v4 image: its R, G and B (`sensor.wb.*`) one above the
/// other.
fn sensor_rgb(scene: &spectrace::scene::Scene, seed: u32) -> Vec<f64> {
    let sensor = scene.camera_sensor.as_ref().expect("the film has a sensor");
    let bins = if sensor.curves.is_some() { 94 } else { 0 };
    let (img, _) = support::render::render_with(scene, |o| {
        o.seed = seed;
        o.spectral_bins = bins;
    });
    let cos = vec![1.0f32; img.width * img.height];
    let (ch, _) = spectrace::output::sensor_channels(&img, sensor, &cos);
    ["R", "G", "B"]
        .iter()
        .flat_map(|c| {
            let name = format!("sensor.wb.{c}");
            let (_, v) = ch.iter().find(|(n, _)| *n == name).expect("wb channel");
            v.iter().map(|&x| x as f64).collect::<Vec<_>>()
        })
        .collect()
}

/// The scene's Y images (pbrt-v4's scale) for seeds 1 and 2, or with `cmp.sensor` its sensor's
/// R, G, B images.
fn render(path: &Path, cmp: &Compare) -> (Vec<f64>, Vec<f64>, u32) {
    let pbrt_exit_weight = cmp.pbrt_exit_weight;
    let mut desc = spectrace::loader::pbrt::load(path).unwrap_or_else(|e| panic!("{e}"));
    fn set(k: &mut MaterialKind, on: bool) {
        match k {
            MaterialKind::Layered(l) => l.pbrt_exit_weight = on,
            MaterialKind::NormalMap { inner, .. } | MaterialKind::BumpMap { inner, .. } => {
                set(inner, on)
            }
            _ => {}
        }
    }
    for m in &mut desc.materials {
        set(&mut m.kind, pbrt_exit_weight);
    }
    let spp = desc.film.spp;
    let scene = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
    if cmp.sensor {
        return (sensor_rgb(&scene, 1), sensor_rgb(&scene, 2), spp);
    }
    let y = |seed: u32| -> Vec<f64> {
        let (img, _) = support::render::render_with(&scene, |o| o.seed = seed);
        img.xyz.iter().map(|p| p[1] as f64 / K_M).collect()
    };
    (y(1), y(2), spp)
}

#[test]
fn reference_scenes_match_pbrt_v4() {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/pbrt");
    let mut names: Vec<_> = std::fs::read_dir(&base)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().join("refs.toml").is_file())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        // PBRT_REF_ONLY=name,… runs only those scenes (when working on one)
        .filter(|n| std::env::var("PBRT_REF_ONLY").map_or(true, |o| o.split(',').any(|x| x == n)))
        .collect();
    names.sort();
    assert!(!names.is_empty());
    let mut failures = Vec::new();
    for name in names {
        let dir = base.join(&name);
        let refs: Refs =
            toml::from_str(&std::fs::read_to_string(dir.join("refs.toml")).unwrap()).unwrap();
        let cmp: Compare = std::fs::read_to_string(dir.join("compare.toml"))
            .map(|t| toml::from_str(&t).unwrap())
            .unwrap_or_default();
        let (a, b, spp) = render(&dir.join("scene.pbrt"), &cmp);
        let rows = if cmp.sensor { 3 } else { 1 } * refs.height;
        let (mean, se) = blocks(&a, &b, refs.width, rows, refs.block);
        assert_eq!(mean.len(), refs.mean.len(), "{name}: block count");
        let (mut worst, mut at) = (0.0f64, 0);
        for i in 0..mean.len() {
            let z = (mean[i] - refs.mean[i])
                / (se[i].powi(2) + refs.stderr[i].powi(2)).sqrt().max(1e-12);
            if z.abs() > worst.abs() {
                (worst, at) = (z, i);
            }
        }
        if std::env::var("PBRT_REF_BLOCKS").is_ok() {
            for i in 0..mean.len() {
                let z = (mean[i] - refs.mean[i]) / (se[i].powi(2) + refs.stderr[i].powi(2)).sqrt();
                println!(
                    "  block {i}: {:.5} vs {:.5} (z {z:+.1})",
                    mean[i], refs.mean[i]
                );
            }
        }
        let total = |v: &[f64]| v.iter().sum::<f64>();
        println!(
            "{name} ({spp} spp): {} sum ratio {:.4}; worst block {at}: spectrace {:.5} ± {:.5}, pbrt-v4 {:.5} ± {:.5} (z {worst:+.2})",
            if cmp.sensor { "sensor R+G+B" } else { "Y" },
            total(&mean) / total(&refs.mean),
            mean[at],
            se[at],
            refs.mean[at],
            refs.stderr[at]
        );
        if worst.abs() > 5.0 {
            failures.push(format!("{name}: block {at} z {worst:.2}"));
        }
        if cmp.pbrt_exit_weight {
            let own = Compare {
                pbrt_exit_weight: false,
                sensor: false,
            };
            let (a2, b2, _) = render(&dir.join("scene.pbrt"), &own);
            let (own, _) = blocks(&a2, &b2, refs.width, refs.height, refs.block);
            println!(
                "{name}: with spectrace's own exit weight, Y sum ratio {:.4} (pbrt-v4's layered bias)",
                total(&own) / total(&refs.mean)
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
