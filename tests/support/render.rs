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
    spectrace::scene::build(&desc).unwrap_or_else(|e| panic!("{e}"))
}

/// Renders with the scene's settings, overridden by `f`.
pub fn render_with(scene: &Scene, f: impl FnOnce(&mut RenderOptions)) -> (Image, RenderStats) {
    let mut o = RenderOptions::from_scene(scene);
    f(&mut o);
    let cancel = AtomicBool::new(false);
    let (film, stats) = render(scene, &o, &cancel, &|_, _| {}).expect("render starts");
    (film.image(), stats)
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
