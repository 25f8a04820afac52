//! The light tracer (`light`) against closed forms and against the path tracer (`path`) on
//! scenes where light tracing needs care: shading normals (Veach 1997 §5.3), the pixel filter
//! and lights at infinity.
//!
//! Tolerances come from the measured noise: a check compares a mean over pixels and asserts the
//! difference stays within 4.5 standard errors estimated from the pixels' own scatter.

mod support;

use std::f64::consts::PI;
use std::path::PathBuf;

use support::render::{mean, render_with, scene_from};

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
    let centre: Vec<f64> = (0..64)
        .map(|k| ratios[(12 + k / 8) * 32 + 12 + k % 8])
        .collect();
    let (c, c_se) = mean_se(&centre);
    eprintln!("{kind}/closed over the central 8 × 8 pixels: {c:.4} ± {c_se:.4}");
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
    // bdpt's light subpaths carry the same correction (and its camera subpaths need none)
    let (bm, bse) = tilted_ratio("bdpt");
    let se = (bse / bm).hypot(pse / pm);
    eprintln!(
        "bdpt/closed = {bm:.4} ± {bse:.4}, bdpt/path = {:.4} ± {se:.4}",
        bm / pm
    );
    assert!(se < 0.01, "noise too high to decide: {se}");
    assert!(
        (bm / pm - 1.0).abs() < 4.5 * se,
        "bdpt / path = {} (± {se}); bdpt/closed = {bm} ± {bse}",
        bm / pm
    );
}

// ---------------------------------------------------------------------------------------------
// Lights at infinity

/// A 6 m square (`rectangle` is [−1, 1]², scaled by 3) of albedo 0.5 in the plane y = 0 that fills the view of a camera 5 m above it,
/// lit by `light` (TOML of one `[[lights]]` entry) and `extra` shapes.
fn plane_under_sky(integrator: &str, light: &str, extra: &str, filter: &str) -> String {
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
filter = {filter}
[integrator]
type = "{integrator}"
max_depth = 1
[materials.grey]
type = "diffuse"
reflectance = 0.5
[[shapes]]
type = "rectangle"
material = "grey"
transform = [{{ scale = 3 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}]
{extra}
[[lights]]
{light}
"#
    )
}

/// A uniform environment of radiance L over a Lambertian plane that sees only the sky above
/// it: E = π L, so the plane's radiance is ρ L = 0.5 W·m⁻²·sr⁻¹ for L = 1 W·m⁻²·sr⁻¹
/// (equal-energy spectrum, band radiance). Light tracing must trace it; before, it skipped
/// environment lights and rendered black.
#[test]
fn environment_light_traced() {
    let env = r#"type = "environment"
spectrum = "cie-e"
radiance = "1 W/m^2/sr""#;
    for kind in ["light", "path", "bdpt"] {
        let s = scene_from(&plane_under_sky(kind, env, "", "\"box\""));
        // about 1 particle in 9 reaches the visible plane: 1024 paths per pixel
        let spp = if kind == "light" { 1024 } else { 64 };
        let (img, stats) = render_with(&s, |o| o.spp = spp);
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        // band radiance over the scene's wavelength range: ρ L = 0.5 W·m⁻²·sr⁻¹
        let v: Vec<f64> = img.band.iter().map(|&b| b as f64 / 0.5).collect();
        let (m, se) = mean_se(&v);
        eprintln!("{kind}: plane / (ρ L_env) = {m:.4} ± {se:.4}");
        assert!(se < 0.01, "{kind}: noise too high to decide: {se}");
        assert!(
            (m - 1.0).abs() < 4.5 * se + 1e-4,
            "{kind}: plane radiance / ρ L_env = {m} ± {se}"
        );
    }
}

/// Per-column statistics of an image whose content is constant along columns (an edge along
/// the image's vertical axis), over the rows `rows`: (mean, standard deviation of one pixel).
fn column_stats(v: &[f32], width: usize, rows: std::ops::Range<usize>) -> Vec<(f64, f64)> {
    (0..width)
        .map(|x| {
            let col: Vec<f64> = rows.clone().map(|y| v[y * width + x] as f64).collect();
            let (m, se) = mean_se(&col);
            (m, se * (col.len() as f64).sqrt())
        })
        .collect()
}

/// Compares `light` with `path` pixel by pixel where the content is constant along columns:
/// every pixel of `rows` within 5 σ (σ from each column's own scatter, both integrators), and
/// every column mean within 4.5 standard errors. Returns the worst column deviation in
/// standard errors, and prints the column profiles.
fn compare_columns(light: &[f32], path: &[f32], width: usize, rows: std::ops::Range<usize>) -> f64 {
    let n = rows.len() as f64;
    let (cl, cp) = (
        column_stats(light, width, rows.clone()),
        column_stats(path, width, rows.clone()),
    );
    let mut worst: f64 = 0.0;
    let mut failures = Vec::new();
    for x in 0..width {
        let ((ml, sl), (mp, sp)) = (cl[x], cp[x]);
        let sigma = sl.hypot(sp);
        eprintln!("column {x:2}: light {ml:.4} ± {sl:.4}, path {mp:.4} ± {sp:.4}");
        let z = if sigma > 0.0 {
            (ml - mp).abs() / (sigma / n.sqrt())
        } else if ml == mp {
            0.0
        } else {
            f64::INFINITY
        };
        worst = worst.max(z);
        if z > 4.5 {
            failures.push(format!("column {x}: light {ml} vs path {mp} ({z:.1} SE)"));
        }
        for y in rows.clone() {
            let (a, b) = (light[y * width + x] as f64, path[y * width + x] as f64);
            if (a - b).abs() > 5.0 * sigma {
                failures.push(format!(
                    "pixel ({x}, {y}): light {a} vs path {b} (σ {sigma})"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    worst
}

/// A sun of 20° angular diameter (E⊥ = 100 W/m², equal-energy) at 45° over the plane, behind a
/// black wall 1 m high along the z axis: the wall's shadow has a penumbra from x = −tan 35° to
/// −tan 55° (−0.70 to −1.43 m, about 4 pixels) that light tracing renders only if it samples
/// the disk's directions; before, it traced the sun as collimated and drew a sharp shadow. The
/// lit plane has the closed form L = ρ/π · E⊥ cos 45° (the disk integral of cos θ is exact:
/// ∫_cone n·ω dω = n·a · π sin²α).
#[test]
fn sun_disk_penumbra_light_matches_path() {
    let sun = r#"type = "directional"
direction = [-1, -1, 0]
angular_diameter = "20 deg"
spectrum = "cie-e"
irradiance = "100 W/m^2""#;
    let wall = r#"[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "rectangle"
material = "black"
transform = [{ scale = [3, 0.5, 1] }, { rotate = { axis = [0, 1, 0], angle = "90 deg" } }, { translate = [0, 0.5, 0] }]
"#;
    let render = |kind: &str, spp: u32| {
        let s = scene_from(&plane_under_sky(kind, sun, wall, "\"box\""));
        let (img, stats) = render_with(&s, |o| o.spp = spp);
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        img
    };
    let (light, path) = (render("light", 1024), render("path", 64));
    let lit = 0.5 / PI * 100.0 * std::f64::consts::FRAC_1_SQRT_2;
    // rows 4..28: the wall ends at z = ±3 m, whose own penumbra stays outside them
    let cols = column_stats(&path.band, 32, 4..28);
    let (m, _) = cols[31];
    assert!(
        (m / lit - 1.0).abs() < 0.01,
        "path: lit plane {m}, closed form {lit}"
    );
    let worst = compare_columns(&light.band, &path.band, 32, 4..28);
    eprintln!("worst column deviation {worst:.2} standard errors");
    // bdpt samples the disk from both ends (its light subpaths and its light sampling)
    let bdpt = render("bdpt", 256);
    let worst = compare_columns(&bdpt.band, &path.band, 32, 4..28);
    eprintln!("bdpt: worst column deviation {worst:.2} standard errors");
}

// ---------------------------------------------------------------------------------------------
// Pixel filter

/// The half x < 0 of the plane lit by a collimated 100 W/m² beam straight down, black beyond,
/// seen from 5 m above with a Gaussian filter (σ = 0.5 px): the edge x = 0 falls on the
/// boundary between columns 15 and 16. The path tracer importance-samples the filter, so a
/// pixel is ∫ L(x) f(x − centre) dx / ∫ f and the columns next to the edge read about 0.84 and
/// 0.16 of the lit value; the light tracer must splat each connection with the same weights.
/// Before, it splatted into the one pixel it landed in: a box-filtered edge (1 and 0).
#[test]
fn gaussian_filter_edge_light_matches_path() {
    let scene = |kind: &str| {
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
filter = "gaussian"
[integrator]
type = "{kind}"
max_depth = 1
[materials.grey]
type = "diffuse"
reflectance = 0.5
[[shapes]]
type = "rectangle"
material = "grey"
transform = [{{ scale = [1.5, 3, 1] }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}, {{ translate = [-1.5, 0, 0] }}]
[[lights]]
type = "directional"
direction = [0, -1, 0]
spectrum = "cie-e"
irradiance = "100 W/m^2"
"#
        ))
    };
    let render = |kind: &str, spp: u32| {
        let s = scene(kind);
        let (img, stats) = render_with(&s, |o| o.spp = spp);
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        img
    };
    let (light, path) = (render("light", 256), render("path", 64));
    let lit = 0.5 / PI * 100.0;
    // rows 4..28 stay 1.5 px clear of the plane's ends at z = ±3 m
    let cols = column_stats(&path.band, 32, 4..28);
    // (column 3: the filter of columns 0 and 1 reaches past the plane's end at x = −3 m)
    assert!(
        (cols[3].0 / lit - 1.0).abs() < 1e-3,
        "path: lit plane {}",
        cols[3].0
    );
    // the reconstruction the path tracer realises: a Gaussian, not a box
    let (a, b) = (cols[15].0 / lit, cols[16].0 / lit);
    assert!(a < 0.9 && b > 0.1, "path edge columns {a}, {b}");
    let worst = compare_columns(&light.band, &path.band, 32, 4..28);
    eprintln!("worst column deviation {worst:.2} standard errors");
    // bdpt's t = 1 splats and its camera samples must reconstruct alike
    let bdpt = render("bdpt", 256);
    let worst = compare_columns(&bdpt.band, &path.band, 32, 4..28);
    eprintln!("bdpt: worst column deviation {worst:.2} standard errors");
}

/// Light tracing gives the same image with 1 thread and with 2, filter splats and lights at
/// infinity included (a sun disk and an environment over the Gaussian-filtered plane).
#[test]
fn light_tracing_deterministic_across_thread_counts() {
    let s = scene_from(&plane_under_sky(
        "light",
        "type = \"environment\"\nspectrum = \"cie-e\"\nradiance = \"1 W/m^2/sr\"\n[[lights]]\ntype = \"directional\"\ndirection = [-1, -1, 0]\nangular_diameter = \"20 deg\"\nirradiance = \"100 W/m^2\"",
        "",
        "\"gaussian\"",
    ));
    let (a, _) = render_with(&s, |o| {
        o.spp = 8;
        o.threads = Some(1);
        o.seed = 7;
    });
    let (b, _) = render_with(&s, |o| {
        o.spp = 8;
        o.threads = Some(2);
        o.seed = 7;
    });
    assert_eq!(a.xyz, b.xyz);
    assert_eq!(a.band, b.band);
    assert!(a.band.iter().any(|&v| v > 0.0));
}

/// The sky and a sun disk seen directly: a camera 5 m above the plane looks toward a sun of 20°
/// angular diameter (E⊥ = 100 W/m², so the disk's radiance is E⊥/(π sin² 10°)) in a uniform
/// sky of 1 W·m⁻²·sr⁻¹. Particles from infinity never reach a pinhole, so light tracing adds
/// these along camera rays; before, it rendered them black. The centre pixel reads sky + disk,
/// a corner pixel the sky alone, and `light` matches `path` pixel by pixel at the disk's edge.
#[test]
fn sky_and_sun_seen_directly() {
    let lights = "type = \"environment\"\nspectrum = \"cie-e\"\nradiance = \"1 W/m^2/sr\"\n[[lights]]\ntype = \"directional\"\ndirection = [-1, -1, 0]\nangular_diameter = \"20 deg\"\nspectrum = \"cie-e\"\nirradiance = \"100 W/m^2\"";
    let text = |kind: &str| {
        plane_under_sky(kind, lights, "", "\"gaussian\"")
            .replace("target = [0, 0, 0]", "target = [1, 6, 0]")
    };
    let (light, _) = render_with(&scene_from(&text("light")), |o| o.spp = 64);
    let (path, _) = render_with(&scene_from(&text("path")), |o| o.spp = 64);
    let sin2 = (10f64.to_radians()).sin().powi(2);
    let disk = 100.0 / (PI * sin2);
    // the 5 × 5 pixels at the centre lie inside the disk (radius ≈ 5 px), the 4 × 4 at a
    // corner see only sky; spectral sampling is the only noise there
    let block = |x0: usize, y0: usize, n: usize, want: f64| {
        let v: Vec<f64> = (0..n * n)
            .map(|k| light.band[(y0 + k / n) * 32 + x0 + k % n] as f64 / want)
            .collect();
        mean_se(&v)
    };
    let (c, c_se) = block(14, 14, 5, 1.0 + disk);
    let (k, k_se) = block(0, 0, 4, 1.0);
    eprintln!("light / closed form: sun disk {c:.5} ± {c_se:.5}, sky {k:.5} ± {k_se:.5}");
    assert!((c - 1.0).abs() < 4.5 * c_se + 1e-4, "disk {c} ± {c_se}");
    assert!((k - 1.0).abs() < 4.5 * k_se + 1e-4, "sky {k} ± {k_se}");
    // per pixel: both average the same filter over the disk's edge with 64 samples; the
    // difference of two such means is within 5 σ, σ² = Var(one sample)·2/64 ≤ (disk/2)²·2/64
    let sigma = disk / 2.0 * (2.0f64 / 64.0).sqrt();
    let mut worst: f64 = 0.0;
    for i in 0..32 * 32 {
        let (a, b) = (light.band[i] as f64, path.band[i] as f64);
        worst = worst.max((a - b).abs() / sigma);
        assert!(
            (a - b).abs() < 5.0 * sigma,
            "pixel {i}: light {a}, path {b}"
        );
    }
    let (ml, mp) = (
        light.band.iter().map(|&v| v as f64).sum::<f64>(),
        path.band.iter().map(|&v| v as f64).sum::<f64>(),
    );
    eprintln!("worst pixel {worst:.2} σ; image sums light {ml:.1}, path {mp:.1}");
}

/// Mitsuba's `projector` with a uniform irradiance v lights a plane at distance d facing it
/// with E = π·scale·v/d² everywhere inside its image (the intensity π·scale·v/cos³θ falls off
/// exactly as the plane recedes), so a white diffuse plane has L = E/π = scale·v/4 at d = 2:
/// checked for camera paths (`path`) and for particles from the projector (`light`, its image
/// sampled uniformly on the plane z = 1). A bare number v is an emission, Mitsuba's D65 × v
/// (the CIE D65 table / 98.997, so that its Y matches a flat v), as Mitsuba 3.9.1 renders it
/// (`tests/mitsuba_data_plugins.rs`).
#[test]
fn projector_lights_a_facing_plane_uniformly() {
    let dir = std::env::temp_dir().join(format!("spectrace-projector-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("projector.xml");
    std::fs::write(
        &path,
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective"><float name="fov" value="20"/>
    <transform name="to_world"><lookat origin="0.2,0,3" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film>
  </sensor>
  <emitter type="projector">
    <transform name="to_world"><lookat origin="0,0,2" target="0,0,0" up="0,1,0"/></transform>
    <float name="fov" value="60"/>
    <float name="scale" value="2"/>
    <float name="irradiance" value="0.5"/>
  </emitter>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
    <bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></shape>
</scene>"#,
    )
    .unwrap();
    let desc = spectrace::loader::load_any(&path, &[]).unwrap();
    let scene = spectrace::build::build(&desc).unwrap();
    // `band` integrates the spectral radiance (Mitsuba's D65 × v) over the simulated range
    let Ok(spectrace::spectrum::named::Named::Curve { spectrum: d65, .. }) =
        spectrace::spectrum::named::lookup("cie-d65")
    else {
        panic!("cie-d65 is a named curve")
    };
    let w = scene.wavelengths;
    let want = 2.0 * 0.5 / 4.0 * d65.integrate(w.min_nm, w.max_nm, 0.5) / 98.99741751876255;
    for (kind, spp) in [
        (spectrace::loader::desc::IntegratorKind::Path, 64),
        (spectrace::loader::desc::IntegratorKind::Light, 1024),
    ] {
        let (img, _) = render_with(&scene, |o| {
            o.integrator = kind;
            o.spp = spp;
        });
        let got = mean(img.band.iter().copied());
        println!("{kind:?}: L = {got}, want {want}");
        assert!((got / want - 1.0).abs() < 0.01, "{kind:?}: {got} vs {want}");
    }
}
