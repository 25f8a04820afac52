//! Rendered images against closed-form radiometry (`../shared/PHYSICS.md`, "Lights").

mod support;

use std::f64::consts::PI;

use spectrace::loader::desc::IntegratorKind;
use support::render::{mean, render_with, scene_from};

const CIE_Y_INTEGRAL: f64 = 106.856895;
const K_M: f64 = 683.002;

/// A closed sphere of albedo ρ emitting Le everywhere, camera inside: L = Le/(1 − ρ), for
/// camera paths (`path`) and light paths (`light`). The 1 % tolerance is at least 4σ of each
/// estimate: measured over seeds 0–10 with `spectrace render --seed`, the image mean at ρ = 0.8
/// has σ ≈ 0.2 % for `path` at 256 spp and σ ≈ 0.66 % for `light` at 256 light paths per
/// pixel, so the light tracer runs 2048 (σ ≈ 0.23 %).
#[test]
fn furnace_path_and_light() {
    for (integrator, rho) in [("path", 0.5), ("path", 0.8), ("light", 0.5), ("light", 0.8)] {
        let spp = if integrator == "light" { 2048 } else { 256 };
        let s = scene_from(&support::render::furnace_toml(integrator, rho, spp));
        let (img, stats) = render_with(&s, |_| {});
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        let got = mean(img.band.iter().copied());
        let want = 1.0 / (1.0 - rho);
        assert!(
            (got / want - 1.0).abs() < 0.01,
            "ρ = {rho}: L = {got}, want {want}"
        );
    }
}

fn radiometry_scene(integrator: &str) -> spectrace::scene::Scene {
    scene_from(&support::render::point_over_plane_toml(integrator))
}

/// A 100 W point light 2 m above a ρ = 0.5 Lambertian plane: L = ρ/π · I cos θ / r² with
/// I = Φ/(4π), and Y = K_m ∫ L ȳ dλ for the equal-energy spectrum.
#[test]
fn point_light_over_plane() {
    for kind in ["path", "whitted"] {
        let s = radiometry_scene(kind);
        let (img, _) = render_with(&s, |_| {});
        for (px, py) in [(16, 16), (4, 16), (20, 27), (30, 2), (9, 9)] {
            // the plane point seen through the pixel centre
            let (r2, cos) = support::render::plane_point(&s, px, py);
            let l_band = 0.5 / PI * (100.0 / (4.0 * PI)) * cos / r2;
            let y = l_band * K_M * CIE_Y_INTEGRAL / 470.0;
            let i = py * 32 + px;
            let (gl, gy) = (img.band[i] as f64, img.xyz[i][1] as f64);
            // the pixel averages L over its footprint; at 32×32 that differs from the centre
            // value by < 0.3 %; 256 stratified samples bound the spectral noise
            assert!(
                (gl / l_band - 1.0).abs() < 0.01,
                "{kind} pixel ({px},{py}): L = {gl}, want {l_band}"
            );
            assert!(
                (gy / y - 1.0).abs() < 0.01,
                "{kind} pixel ({px},{py}): Y = {gy}, want {y}"
            );
        }
    }
}

fn emitter_scene(emission: &str) -> spectrace::scene::Scene {
    scene_from(&format!(
        r#"
[camera]
eye = [0, 0, -1]
target = [0, 0, 0]
fov = "20 deg"
[film]
width = 16
height = 16
spp = 64
[integrator]
max_depth = 1
[[shapes]]
type = "rectangle"
transform = [{{ scale = 5 }}, {{ rotate = {{ axis = [0, 1, 0], angle = "180 deg" }} }}]
emission = {{ {emission} }}
"#
    ))
}

/// An emitter declared as 100 cd/m² reads 100 cd/m² in Y within 0.5 %.
#[test]
fn luminance_calibration() {
    for spectrum in ["cie-d65", "cie-f11", "blackbody:2700K"] {
        let s = emitter_scene(&format!(
            "spectrum = \"{spectrum}\", luminance = \"100 cd/m^2\""
        ));
        let (img, _) = render_with(&s, |_| {});
        let y = mean(img.xyz.iter().map(|p| p[1]));
        assert!((y / 100.0 - 1.0).abs() < 0.005, "{spectrum}: Y = {y} cd/m²");
    }
}

/// A blackbody emitter (absolute Planck radiance, scale 1) has L = ∫ Planck dλ over 360–830 nm.
#[test]
fn blackbody_band_radiance() {
    let t = 3000.0f64;
    let (h, c, k) = (6.626_070_15e-34, 299_792_458.0, 1.380_649e-23);
    let planck = |l_nm: f64| {
        let l = l_nm * 1e-9;
        2.0 * h * c * c / l.powi(5) / ((h * c / (l * k * t)).exp() - 1.0) * 1e-9
    };
    let n = 47_000;
    let want: f64 = (0..n)
        .map(|i| planck(360.0 + (i as f64 + 0.5) * 0.01) * 0.01)
        .sum();
    let s = emitter_scene("spectrum = { blackbody = \"3000 K\" }, scale = 1");
    let (img, _) = render_with(&s, |_| {});
    let got = mean(img.band.iter().copied());
    assert!(
        (got / want - 1.0).abs() < 0.005,
        "L = {got}, ∫Planck = {want}"
    );
}

/// The same seed gives the same image with 1 thread and with 2.
#[test]
fn deterministic_across_thread_counts() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.toml");
    let desc = spectrace::loader::load(&path).unwrap();
    let mut s = spectrace::build::build(&desc).unwrap();
    s.film.width = 48;
    s.film.height = 48;
    let cam = spectrace::geometry::Camera::perspective_focal(
        spectrace::geometry::Transform::look_at(
            glam::Vec3::new(0.278, 0.273, -0.8),
            glam::Vec3::new(0.278, 0.273, 0.0),
            glam::Vec3::Y,
        )
        .unwrap(),
        0.035,
        0.025,
        48,
        48,
    )
    .unwrap();
    s.camera = cam;
    let (a, _) = render_with(&s, |o| {
        o.spp = 8;
        o.threads = Some(1);
        o.seed = 42;
    });
    let (b, _) = render_with(&s, |o| {
        o.spp = 8;
        o.threads = Some(2);
        o.seed = 42;
    });
    assert_eq!(a.xyz, b.xyz);
    assert_eq!(a.band, b.band);
    let (c, _) = render_with(&s, |o| {
        o.spp = 8;
        o.threads = Some(2);
        o.seed = 43;
    });
    assert_ne!(a.xyz, c.xyz, "a different seed gives a different image");
    let _ = IntegratorKind::Path;
}

/// The `whitted` integrator traces a smooth plastic's coating as a mirror of weight F: a black
/// base (ρ = 0, index 1.49) seen head-on under a uniform sky reflects exactly F(0) =
/// ((1.49 − 1)/(1.49 + 1))² of the sky, pixel by pixel against the sky seen directly with the
/// same seed (the same wavelengths).
#[test]
fn whitted_reflects_a_smooth_plastic_coating() {
    let scene = |with_plastic: bool| {
        let shape = if with_plastic {
            r#"
[materials.coat]
type = "plastic"
reflectance = 0
ior = 1.49

[[shapes]]
type = "rectangle"
material = "coat"
transform = [{ scale = 10 }]
"#
        } else {
            ""
        };
        support::render::scene_from(&format!(
            r#"
[camera]
type = "orthographic"
eye = [0, 0, 1]
target = [0, 0, 0]
up = [0, 1, 0]
view_width = "1 m"

[film]
width = 4
height = 4
spp = 4

[integrator]
type = "whitted"
max_depth = 2
{shape}
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#
        ))
    };
    let (coat, _) = support::render::render_with(&scene(true), |_| {});
    // the camera looks down −z: the sky straight behind the camera is what the mirror shows
    let (sky, _) = support::render::render_with(&scene(false), |_| {});
    let f = ((1.49f64 - 1.0) / (1.49 + 1.0)).powi(2);
    for (c, s) in coat.band.iter().zip(&sky.band) {
        assert!(
            ((c / s) as f64 / f - 1.0).abs() < 1e-4,
            "{c} / {s} vs F = {f}"
        );
    }
}

/// A blend (Mitsuba's `blendbsdf`) of a perfect mirror (weight 1 − w) and a Lambertian ρ (weight
/// w) on a convex sphere under a uniform sky L: every ray reflected from the sphere sees the
/// sky, so every pixel is ((1 − w)·1 + w·ρ)·L. This checks the blend's delta lobe against its
/// smooth one in the path tracer (the mirror chosen with probability 1 − w keeps its own
/// weight; the diffuse part is light-sampled and BSDF-sampled with MIS). Mitsuba 3.9.1 renders
/// the mirror part 0.4 as 0.27 here (it divides by a probability plus a density), which is why
/// this case is checked against the closed form rather than against Mitsuba. Tolerance 1 %: the
/// image mean's σ is about 0.15 % at 256 spp (from the per-sample spread of a two-valued
/// estimate, mirror 1 with probability 1 − w and about ρ otherwise, over 65 536 samples).
#[test]
fn blend_of_mirror_and_diffuse_under_uniform_sky() {
    for (w, rho) in [(0.6, 0.5), (0.25, 0.9), (1.0, 0.3), (0.0, 0.3)] {
        let s = scene_from(&format!(
            r#"
[camera]
eye = [0, 0, 5]
target = [0, 0, 0]
fov = "10 deg"
[film]
width = 16
height = 16
spp = 256
[materials.mirror]
type = "conductor"
eta = 0.0
k = 1.0
[materials.paint]
type = "diffuse"
reflectance = {rho}
[materials.m]
type = "blend"
weight = {w}
materials = ["mirror", "paint"]
[[shapes]]
type = "sphere"
radius = 1
material = "m"
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#
        ));
        let (img, stats) = render_with(&s, |_| {});
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        let got = mean(img.band.iter().copied());
        let want = (1.0 - w) + w * rho;
        println!("w = {w}, ρ = {rho}: L = {got}, want {want}");
        assert!(
            (got / want - 1.0).abs() < 0.01,
            "w = {w}, ρ = {rho}: L = {got}, want {want}"
        );
    }
}

/// TOML `specular_reflectance` on a perfect mirror sphere under a uniform sky scales what it
/// reflects: L = factor·L_sky exactly (the mirror's F = 1); and a roughness given as a
/// checkerboard of two equal values renders as that constant roughness does.
#[test]
fn specular_factor_and_textured_roughness_in_toml() {
    let scene = |material: &str| {
        scene_from(&format!(
            r#"
[camera]
eye = [0, 0, 5]
target = [0, 0, 0]
fov = "10 deg"
[film]
width = 8
height = 8
spp = 64
[materials.m]
{material}
[[shapes]]
type = "sphere"
radius = 1
material = "m"
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#
        ))
    };
    for k in [0.5, 0.25] {
        let (img, _) = render_with(
            &scene(&format!(
                "type = \"conductor\"\neta = 0.0\nk = 1.0\nspecular_reflectance = {k}"
            )),
            |_| {},
        );
        let got = mean(img.band.iter().copied());
        println!("specular_reflectance {k}: L = {got}");
        assert!((got - k).abs() < 1e-4, "specular_reflectance {k}: {got}");
    }
    let rough = |r: &str| {
        let (img, _) = render_with(
            &scene(&format!(
                "type = \"conductor\"\nmetal = \"Au\"\nroughness = {r}"
            )),
            |_| {},
        );
        mean(img.band.iter().copied())
    };
    let (a, b) = (rough("0.3"), rough("{ checkerboard = [0.3, 0.3] }"));
    println!("roughness 0.3: {a}, as a texture: {b}");
    assert!((a / b - 1.0).abs() < 1e-5, "{a} vs {b}");
}
