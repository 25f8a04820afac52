//! Rendering helpers for the integration tests.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use spectrace::film::Image;
use spectrace::render::{RenderOptions, RenderStats, render};
use spectrace::scene::Scene;

/// Loads and builds a scene from TOML text (relative paths resolve against `scenes/`).
pub fn scene_from(text: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.toml");
    let desc = spectrace::loader::load_str(text, &path).unwrap_or_else(|e| panic!("{e}"));
    spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"))
}

/// Renders with the scene's settings, overridden by `f`.
pub fn render_with(scene: &Scene, f: impl FnOnce(&mut RenderOptions)) -> (Image, RenderStats) {
    let mut o = RenderOptions::from_scene(scene);
    f(&mut o);
    let cancel = AtomicBool::new(false);
    let (film, stats) = render(scene, &o, &cancel, &|_, _| {}).expect("render starts");
    (film.image(), stats)
}

/// Light tracing and BDPT refuse to render `scene` (a camera whose importance is not
/// modelled), with an error containing `needle`.
#[allow(dead_code)]
pub fn assert_light_and_bdpt_refuse(scene: &Scene, needle: &str) {
    for kind in [
        spectrace::integrator::IntegratorKind::Light,
        spectrace::integrator::IntegratorKind::Bdpt,
    ] {
        let mut o = RenderOptions::from_scene(scene);
        o.integrator = kind;
        let cancel = AtomicBool::new(false);
        let e = render(scene, &o, &cancel, &|_, _| {}).expect_err("refused");
        assert!(e.to_string().contains(needle), "{e}");
    }
}

/// Mean of a per-pixel quantity over the image.
pub fn mean(v: impl Iterator<Item = f32>) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for x in v {
        s += x as f64;
        n += 1;
    }
    s / n as f64
}

/// The white furnace, TOML: a closed sphere of albedo `rho` emitting 1 W·m⁻²·sr⁻¹ everywhere
/// (both sides), the camera inside, 16×16 pixels at `spp`, `integrator` with 1000 bounces; every
/// pixel converges to L = Le/(1 − ρ).
pub fn furnace_toml(integrator: &str, rho: f64, spp: u32) -> String {
    format!(
        r#"
[camera]
eye = [0, 0, 0]
target = [0, 0, 1]
fov = "90 deg"
[film]
width = 16
height = 16
spp = {spp}
[integrator]
type = "{integrator}"
max_depth = 1000
[materials.m]
type = "diffuse"
reflectance = {rho}
[[shapes]]
type = "sphere"
radius = 1
material = "m"
two_sided = true
emission = {{ radiance = "1 W/m^2/sr", two_sided = true }}
"#
    )
}

/// The point-light-over-plane scene, TOML: a 100 W equal-energy point light 2 m above a
/// ρ = 0.5 Lambertian plane (the 20 m square y = 0), seen from 5 m above through a 60° view at
/// 32×32 pixels with a box filter, 256 spp, rendered by `integrator` at one bounce.
pub fn point_over_plane_toml(integrator: &str) -> String {
    format!(
        r#"
[camera]
eye = [0, 5, 0]
target = [0, 0, 0]
up = [0, 0, -1]
fov = "60 deg"
[film]
width = 32
height = 32
spp = 256
filter = "box"
[integrator]
type = "{integrator}"
max_depth = 1
[materials.grey]
type = "diffuse"
reflectance = 0.5
[[shapes]]
type = "rectangle"
material = "grey"
transform = [{{ scale = 10 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}]
[[lights]]
type = "point"
position = [0, 2, 0]
spectrum = "cie-e"
power = "100 W"
"#
    )
}

/// For the point-light-over-plane scenes (light 2 m above the origin of the plane y = 0): the
/// squared distance r² (m²) from the light to the plane point seen through the centre of pixel
/// (px, py), and the cosine of incidence there.
pub fn plane_point(scene: &Scene, px: usize, py: usize) -> (f64, f64) {
    let ray = scene.camera.generate_ray(
        glam::Vec2::new(px as f32 + 0.5, py as f32 + 0.5),
        glam::Vec2::splat(0.5),
    );
    let t = -ray.o.y as f64 / ray.d.y as f64;
    let (x, z) = (
        ray.o.x as f64 + t * ray.d.x as f64,
        ray.o.z as f64 + t * ray.d.z as f64,
    );
    let r2 = x * x + z * z + 4.0;
    (r2, 2.0 / r2.sqrt())
}

/// Loads and builds a scene file.
pub fn scene_at(path: &Path) -> Scene {
    let desc = spectrace::loader::load(path).unwrap_or_else(|e| panic!("{e}"));
    spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"))
}

/// Every meter point's reading, `samples` per point, 2 threads, seed `seed`.
pub fn measure(scene: &Scene, samples: u32, seed: u32) -> Vec<spectrace::render::measure::Reading> {
    let points: Vec<_> = scene
        .meters
        .iter()
        .flat_map(|m| m.points.iter().copied())
        .collect();
    let opts = spectrace::render::measure::MeasureOptions {
        samples,
        threads: Some(2),
        seed,
        max_depth: scene.integrator.max_depth,
        spectral_bins: 0,
    };
    let cancel = AtomicBool::new(false);
    spectrace::render::measure::measure(scene, &points, &opts, &cancel, &|_| {})
        .expect("measure starts")
        .into_iter()
        .map(|r| r.expect("complete"))
        .collect()
}

/// TOML: a black 60 m floor (y = 0) seen by an 8 × 8 camera, then `rest` (the meters and
/// lights of a measurement).
pub fn black_floor(rest: &str) -> String {
    format!(
        r#"
[camera]
eye = [0, 5, 5]
target = [0, 0, 0]
fov = "40 deg"
[film]
width = 8
height = 8
spp = 1
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "rectangle"
material = "black"
transform = [{{ scale = 30 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}]
{rest}
"#
    )
}

/// Asserts that the MIS-weighted images of every bdpt strategy (s, t) with
/// s + t − 2 ≤ `max_depth` sum to the full render of `scene`: the same random numbers feed
/// each, so they agree to rounding (1e-4 relative).
pub fn assert_strategies_sum_to_full(scene: &Scene, max_depth: u32) {
    use spectrace::integrator::bdpt::Strategy;
    let (full, _) = render_with(scene, |_| {});
    let mut sum = vec![0.0f64; full.band.len()];
    for len in 2..=max_depth + 2 {
        for t in 1..=len {
            let sv = len - t;
            if (sv, t) == (1, 1) {
                continue;
            }
            let (img, _) = render_with(scene, |o| {
                o.strategy = Some(Strategy {
                    s: sv,
                    t,
                    weighted: true,
                });
            });
            for (a, b) in sum.iter_mut().zip(&img.band) {
                *a += *b as f64;
            }
        }
    }
    let total: f64 = full.band.iter().map(|&v| v as f64).sum();
    assert!(total > 0.0);
    for (i, (a, b)) in sum.iter().zip(&full.band).enumerate() {
        assert!(
            (a - *b as f64).abs() <= 1e-4 * (*b as f64).abs() + 1e-6 * total / sum.len() as f64,
            "pixel {i}: Σ strategies {a}, full {b}"
        );
    }
}
