//! Normal and bump maps (Mitsuba's `normalmap`, `bumpmap`) against closed forms: a plane lit by
//! a directional light, seen from above, with a diffuse material whose shading normal a map
//! tilts. The ratio to the same plane without the map is, per pixel,
//! cos(n′, l)·G₁(l) / cos(n, l): the Lambert cosine about the perturbed normal n′, times the
//! bump-terminator shadowing G₁ of Conty Estevez et al. 2019 (which Mitsuba 3.9.1 applies; the
//! unit test of `material::perturb::shadowing` checks it against Mitsuba's own values).

mod support;

use std::path::PathBuf;

use glam::Vec3;
use support::render::{mean, render_with, scene_from};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("spectrace-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// G₁ of the paper, written out here from its definition (not the crate's function).
fn g1(cos_d: f64, cos_i: f64) -> f64 {
    let tan2_d = (1.0 - cos_d * cos_d) / (cos_d * cos_d);
    let a2 = (tan2_d / 8.0).clamp(0.0, 1.0);
    let tan2_i = (1.0 - cos_i * cos_i) / (cos_i * cos_i);
    2.0 / (1.0 + (1.0 + a2 * tan2_i).sqrt())
}

/// A rectangle (normal +z, uv = ((x + 1)/2, (y + 1)/2)) seen from 5 m above through a 4°
/// field of view, lit by a directional light arriving from `l` (unit, toward the light), with
/// material `m` (TOML tables naming the rectangle's material "top").
fn plane(materials: &str, l: Vec3) -> f64 {
    plane_with(materials, l, "path", 16)
}

/// [`plane`] rendered by `integrator` at `spp`.
fn plane_with(materials: &str, l: Vec3, integrator: &str, spp: u32) -> f64 {
    let s = scene_from(&format!(
        r#"
[camera]
eye = [0, 0, 5]
target = [0, 0, 0]
up = [0, 1, 0]
fov = "4 deg"
[film]
width = 8
height = 8
spp = {spp}
[integrator]
type = "{integrator}"
max_depth = 1
{materials}
[[shapes]]
type = "rectangle"
material = "top"
[[lights]]
type = "directional"
direction = [{}, {}, {}]
spectrum = "cie-e"
irradiance = "100 W/m^2"
"#,
        -l.x, -l.y, -l.z
    ));
    let (img, stats) = render_with(&s, |_| {});
    assert_eq!(stats.nan_samples + stats.inf_samples, 0);
    mean(img.band.iter().copied())
}

const PAINT: &str = "[materials.paint]\ntype = \"diffuse\"\nreflectance = 0.5\n";

/// A normal map of one texel tilting the normal 30° toward +x (the rectangle's ∂p/∂u), stored
/// as (n + 1)/2 in bytes, written into the folder `name`: the materials with the map over
/// `PAINT` and without it (both named "top"), and the map's normal as the renderer decodes it.
fn tilted_map(name: &str) -> (String, String, Vec3) {
    let d = dir(name);
    let t = 30f64.to_radians();
    let bytes = [t.sin(), 0.0, t.cos()].map(|c| ((c + 1.0) / 2.0 * 255.0).round() as u8);
    let png = d.join("n.png");
    spectrace::image_io::write_png_srgb8(&png, 1, 1, &[bytes]).unwrap();
    let n = Vec3::from(bytes.map(|b| b as f32 / 255.0 * 2.0 - 1.0)).normalize();
    let mapped = format!(
        "{PAINT}[materials.top]\ntype = \"normal_map\"\nmap = {{ image = \"{}\" }}\nmaterial = \"paint\"\n",
        png.display()
    );
    let plain = PAINT.replace("paint", "top");
    (mapped, plain, n)
}

#[test]
fn constant_normal_map_tilts_the_lambert_cosine() {
    let (mapped, plain, n) = tilted_map("normalmap");
    for deg in [0.0f32, 40.0, -40.0, 75.0] {
        let a = deg.to_radians();
        let l = Vec3::new(a.sin(), 0.0, a.cos());
        let want = (n.dot(l).max(0.0) as f64) * g1(n.z as f64, l.z as f64) / l.z as f64;
        let got = plane(&mapped, l) / plane(&plain, l);
        println!("light at {deg}°: ratio {got:.5}, closed form {want:.5}");
        assert!(
            (got - want).abs() < 2e-3 * want.max(0.1),
            "light at {deg}°: {got} vs {want}"
        );
    }
}

#[test]
fn linear_height_ramp_tilts_like_its_gradient() {
    let d = dir("bumpmap");
    // heights 0, 1, 2, 3 across 4 texels: dh/du = 4 between the texel centres (u in [1/8, 7/8])
    let exr = d.join("h.exr");
    spectrace::image_io::write_exr(
        &exr,
        4,
        1,
        &[spectrace::image_io::Channel {
            name: "Y",
            data: &[0.0, 1.0, 2.0, 3.0],
        }],
        &[],
    )
    .unwrap();
    let scale = 0.25;
    // ∂p/∂u = 2 x̂, ∂p/∂v = 2 ŷ on the unit rectangle; the bump adds scale·dh/du = scale·4
    // along the normal to ∂p/∂u, and n′ ∝ ∂p/∂u′ × ∂p/∂v′
    let du = Vec3::new(2.0, 0.0, scale * 4.0);
    let dv = Vec3::new(0.0, 2.0, 0.0);
    let n = du.cross(dv).normalize();
    let mapped = format!(
        "{PAINT}[materials.top]\ntype = \"bump_map\"\nheight = {{ image = \"{}\", wrap = \"clamp\" }}\nscale = {scale}\nmaterial = \"paint\"\n",
        exr.display()
    );
    let plain = PAINT.replace("paint", "top");
    for deg in [0.0f32, 35.0, -35.0] {
        let a = deg.to_radians();
        let l = Vec3::new(a.sin(), 0.0, a.cos());
        let want = (n.dot(l).max(0.0) as f64) * g1(n.z as f64, l.z as f64) / l.z as f64;
        let got = plane(&mapped, l) / plane(&plain, l);
        println!("light at {deg}°: ratio {got:.5}, closed form {want:.5} (n′ = {n})");
        assert!(
            (got - want).abs() < 2e-3 * want.max(0.1),
            "light at {deg}°: {got} vs {want}"
        );
    }
}

/// Particles see the same tilted normal: light tracing and `bdpt` (whose t = 1 strategies carry
/// particles) evaluate the map's adjoint (the cosine ratio and shadowing on the light's side,
/// not the camera's), so the same closed form holds within 1 % (measured: to 5 digits, the same
/// particles lighting both planes). Evaluating the map for particles as for camera paths makes
/// the ratio cos θ′ of the view, 0.867 for every light direction here (measured).
#[test]
fn particles_see_the_same_tilted_normal() {
    let (mapped, plain, n) = tilted_map("normalmap-particles");
    for integrator in ["light", "bdpt"] {
        for deg in [40.0f32, -40.0] {
            let a = deg.to_radians();
            let l = Vec3::new(a.sin(), 0.0, a.cos());
            let want = (n.dot(l).max(0.0) as f64) * g1(n.z as f64, l.z as f64) / l.z as f64;
            let got =
                plane_with(&mapped, l, integrator, 4096) / plane_with(&plain, l, integrator, 4096);
            println!("{integrator}, light at {deg}°: ratio {got:.5}, closed form {want:.5}");
            assert!(
                (got / want - 1.0).abs() < 0.01,
                "{integrator}, light at {deg}°: {got} vs {want}"
            );
        }
    }
}
