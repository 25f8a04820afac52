//! The light tracer (`light`) against closed forms and against the path tracer (`path`) on
//! scenes where light tracing needs care: shading normals (Veach 1997 §5.3), the pixel filter
//! and lights at infinity.
//!
//! Tolerances come from the measured noise: a check compares a mean over pixels and asserts the
//! difference stays within 4.5 standard errors estimated from the pixels' own scatter.

mod support;

use std::f64::consts::PI;
use std::path::PathBuf;

use support::render::{render_with, scene_from};

/// Mean and standard error of the mean.
fn mean_se(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

/// Writes `text` to a fresh file under Cargo's per-test temporary directory.
fn write_tmp(name: &str, text: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("light_tracer");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write file");
    path
}

// ---------------------------------------------------------------------------------------------
// Shading normals

/// sin and cos of the 25° tilt of the vertex normals (about the z axis, toward +x).
const TILT_SIN: f64 = 0.422_618_261_740_699_4;
const TILT_COS: f64 = 0.906_307_787_036_649_9;

/// A 10 m square in the plane y = 0 whose four vertex normals are all tilted 25° toward +x,
/// lit by a 100 W equal-energy point light at (2, 2, 0) (45° from the geometric normal at the
/// origin, 20° from the shading normal), seen from 5 m above.
fn tilted_scene(integrator: &str) -> spectrace::scene::Scene {
    let obj = write_tmp(
        "tilted_plane.obj",
        &format!(
            "v -5 0 -5\nv -5 0 5\nv 5 0 5\nv 5 0 -5\nvn {TILT_SIN} {TILT_COS} 0\nf 1//1 2//1 3//1 4//1\n"
        ),
    );
    scene_from(&format!(
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
type = "obj"
file = "{}"
material = "grey"
[[lights]]
type = "point"
position = [2, 2, 0]
spectrum = "cie-e"
power = "100 W"
"#,
        obj.display()
    ))
}

/// Band radiance of the tilted plane seen through the centre of pixel (px, py): a Lambertian
/// BRDF with shading normal ns integrates f·|ns·wi|, so L = ρ/π · I · (ns·wi) / r² with
/// I = 100 W / 4π.
fn tilted_closed_form(scene: &spectrace::scene::Scene, px: usize, py: usize) -> f64 {
    let ray = scene.camera.generate_ray(
        glam::Vec2::new(px as f32 + 0.5, py as f32 + 0.5),
        glam::Vec2::splat(0.5),
    );
    let t = -ray.o.y as f64 / ray.d.y as f64;
    let p = [
        ray.o.x as f64 + t * ray.d.x as f64,
        0.0,
        ray.o.z as f64 + t * ray.d.z as f64,
    ];
    let d = [2.0 - p[0], 2.0, -p[2]];
    let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let cos_s = (d[0] * TILT_SIN + d[1] * TILT_COS) / r2.sqrt();
    0.5 / PI * (100.0 / (4.0 * PI)) * cos_s.max(0.0) / r2
}

/// Each pixel of `kind` divided by the closed form: (mean, standard error) over the image.
fn tilted_ratio(kind: &str) -> (f64, f64) {
    let s = tilted_scene(kind);
    let (img, stats) = render_with(&s, |_| {});
    assert_eq!(stats.nan_samples + stats.inf_samples, 0);
    let ratios: Vec<f64> = (0..32 * 32)
        .map(|i| img.band[i] as f64 / tilted_closed_form(&s, i % 32, i / 32))
        .collect();
    mean_se(&ratios)
}

/// Light tracing with shading normals needs the adjoint BSDF (Veach 1997 §5.3): with vertex
/// normals tilted 25° and a light at 45°, `light` must render what `path` renders, and both the
/// closed form. Without the correction `light` reads |ns·wc|/|ng·wc| · |ng·wi|/|ns·wi| of the
/// truth, 0.906 · 0.707 / 0.940 = 0.68 at the image centre.
#[test]
fn shading_normals_light_matches_path() {
    let (lm, lse) = tilted_ratio("light");
    let (pm, pse) = tilted_ratio("path");
    // the pixel footprint differs from the centre value by < 0.3 % (see render_physics.rs)
    assert!(
        (pm - 1.0).abs() < 0.003 + 4.5 * pse,
        "path / closed form = {pm} ± {pse}"
    );
    let se = (lse / lm).hypot(pse / pm);
    eprintln!(
        "light/closed = {lm:.4} ± {lse:.4}, path/closed = {pm:.5} ± {pse:.5}, light/path = {:.4} ± {se:.4}",
        lm / pm
    );
    assert!(se < 0.01, "noise too high to decide: {se}");
    assert!(
        (lm / pm - 1.0).abs() < 4.5 * se,
        "light / path = {} (± {se}); light/closed = {lm} ± {lse}, path/closed = {pm} ± {pse}",
        lm / pm
    );
}
