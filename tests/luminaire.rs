//! Luminaires from IES LM-63 and EULUMDAT files against the closed forms their tables were
//! written from: illuminance E = I(γ, C)·cos θ / d² at measured angles for every symmetry
//! type of both formats, a luminaire aimed sideways with its C0 plane turned, the total flux
//! integrated from meters on a sphere against the closed form and the file's declared lumens,
//! `path`, `light` and `bdpt` agreeing on a lit floor, and located errors for bad files.

mod support;

use std::f64::consts::PI;
use std::path::Path;

use glam::Vec3;
use spectrace::loader::desc::IntegratorKind;
use spectrace::scene::{Meter, MeterPoint};
use support::cli::tmpdir;
use support::photometric::{ies, ldt};
use support::render::{mean, measure, render_with, scene_at};

type Dist = fn(f64, f64) -> f64;

/// I(γ, C), cd: linear in γ (so the table is exact between its angles too) times g(C).
fn radial(g: f64) -> f64 {
    1000.0 * (1.0 - g / 180.0)
}
fn axial(g: f64, _c: f64) -> f64 {
    radial(g)
}
fn quadrant(g: f64, c: f64) -> f64 {
    radial(g) * (1.0 + 0.5 * c.to_radians().cos().powi(2))
}
fn bilateral_0_180(g: f64, c: f64) -> f64 {
    let c = c.to_radians();
    radial(g) * (1.0 + 0.5 * c.cos() + 0.2 * (2.0 * c).cos())
}
fn bilateral_90_270(g: f64, c: f64) -> f64 {
    radial(g) * (1.0 + 0.5 * c.to_radians().sin())
}
fn full(g: f64, c: f64) -> f64 {
    let c = c.to_radians();
    radial(g) * (1.0 + 0.5 * c.cos() + 0.3 * c.sin())
}

fn steps(from: f64, to: f64, step: f64) -> Vec<f64> {
    let n = ((to - from) / step).round() as usize;
    (0..=n).map(|k| from + k as f64 * step).collect()
}

/// A black floor (y = 0) under a luminaire 2 m up aiming down, with `extra` TOML for the light.
fn scene_text(file: &str, extra: &str) -> String {
    format!(
        r#"
[camera]
eye = [0, 5, 5]
target = [0, 0, 0]
fov = "40 deg"
[film]
width = 16
height = 16
spp = 1
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "rectangle"
material = "black"
transform = [{{ scale = 50 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}]
[[lights]]
type = "luminaire"
file = "{file}"
position = [0, 2, 0]
target = [0, 0, 0]
{extra}
"#
    )
}

/// World direction of (γ, C) for a luminaire aiming down (−y) with C0 along +x: the
/// photometric frame's y (C90) is up × x = −z.
fn down_dir(g: f64, c: f64) -> Vec3 {
    let (g, c) = (g.to_radians(), c.to_radians());
    Vec3::new(
        (g.sin() * c.cos()) as f32,
        -g.cos() as f32,
        (-g.sin() * c.sin()) as f32,
    )
}

/// Meters on the floor where the directions (γ, C) from the luminaire land, facing up; the
/// truth E = I·cos γ/d² with d = 2 m / cos γ.
fn check_floor(file: &Path, dist: Dist, gammas: &[f64], label: &str) {
    let text = scene_text(&file.file_name().unwrap().to_string_lossy(), "");
    let path = file.with_extension("toml");
    std::fs::write(&path, text).unwrap();
    let mut scene = scene_at(&path);
    let mut angles = Vec::new();
    let mut points = Vec::new();
    for &g in gammas {
        for k in 0..24 {
            let c = 15.0 * k as f64;
            let d = down_dir(g, c);
            let t = 2.0 / g.to_radians().cos() as f32;
            points.push(MeterPoint {
                p: Vec3::new(0.0, 2.0, 0.0) + d * t,
                n: Vec3::Y,
            });
            angles.push((g, c));
        }
    }
    scene.meters = vec![Meter {
        name: "floor".into(),
        grid: [points.len() as u32, 1],
        points,
    }];
    let r = measure(&scene, 1024, 1);
    let mut worst = 0.0f64;
    for (reading, &(g, c)) in r.iter().zip(&angles) {
        let cos = g.to_radians().cos();
        let truth = dist(g, c) * cos * cos * cos / 4.0;
        let rel = reading.illuminance_lx / truth - 1.0;
        worst = worst.max(rel.abs());
        assert!(
            rel.abs() < 0.005,
            "{label}: γ {g}°, C {c}°: {} lx, closed form {truth} lx ({:+.3} %)",
            reading.illuminance_lx,
            rel * 100.0
        );
    }
    eprintln!("{label}: worst illuminance error {:.4} %", worst * 100.0);
}

#[test]
fn illuminance_under_every_ies_symmetry_equals_the_file() {
    let dir = tmpdir("ies-symmetry");
    let v = steps(0.0, 90.0, 5.0);
    let cases: [(&str, Vec<f64>, Dist); 5] = [
        ("axial", vec![0.0], axial),
        ("quadrant", steps(0.0, 90.0, 15.0), quadrant),
        ("bilateral-0-180", steps(0.0, 180.0, 15.0), bilateral_0_180),
        (
            "bilateral-90-270",
            steps(90.0, 270.0, 15.0),
            bilateral_90_270,
        ),
        ("full", steps(0.0, 360.0, 15.0), full),
    ];
    for (name, h, dist) in cases {
        let file = dir.join(format!("{name}.ies"));
        std::fs::write(&file, ies(&v, &h, &dist)).unwrap();
        check_floor(
            &file,
            dist,
            &[10.0, 25.0, 40.0, 55.0],
            &format!("IES {name}"),
        );
    }
}

#[test]
fn illuminance_under_every_eulumdat_symmetry_equals_the_file() {
    let dir = tmpdir("ldt-symmetry");
    let g = steps(0.0, 90.0, 5.0);
    let cases: [(u32, Dist); 5] = [
        (0, full),
        (1, axial),
        (2, bilateral_0_180),
        (3, bilateral_90_270),
        (4, quadrant),
    ];
    for (isym, dist) in cases {
        let file = dir.join(format!("isym{isym}.ldt"));
        std::fs::write(&file, ldt(isym, 24, 15.0, &g, 2000.0, 80.0, &dist)).unwrap();
        check_floor(
            &file,
            dist,
            &[10.0, 25.0, 40.0, 55.0],
            &format!("LDT Isym {isym}"),
        );
    }
}

/// A luminaire aimed along +x (a wall washer) with its C0 plane turned up (+y): the direction
/// (γ, C) is cos γ·x̂ + sin γ (cos C·ŷ + sin C·(up × C0 = −x̂ × ŷ … )), measured by meters that
/// face the luminaire, E = I/d².
#[test]
fn aim_and_c0_orient_the_distribution() {
    let dir = tmpdir("ies-aim");
    let file = dir.join("full.ies");
    std::fs::write(
        &file,
        ies(&steps(0.0, 90.0, 5.0), &steps(0.0, 360.0, 15.0), &full),
    )
    .unwrap();
    let text = scene_text("full.ies", "c0 = [0, 1, 0]").replace(
        "position = [0, 2, 0]\ntarget = [0, 0, 0]",
        "position = [0, 2, 0]\ntarget = [3, 2, 0]",
    );
    let path = dir.join("aim.toml");
    std::fs::write(&path, text).unwrap();
    let mut scene = scene_at(&path);
    // photometric frame: up = −x (away from the target), x = +y (C0), y = up × x = −x × y = −z
    let (up, x, y) = (-Vec3::X, Vec3::Y, -Vec3::Z);
    let mut angles = Vec::new();
    let mut points = Vec::new();
    for g in [15.0f64, 30.0, 45.0] {
        for k in 0..24 {
            let c = 15.0 * k as f64;
            let (gr, cr) = (g.to_radians() as f32, c.to_radians() as f32);
            let d = -up * gr.cos() + (x * cr.cos() + y * cr.sin()) * gr.sin();
            points.push(MeterPoint {
                p: Vec3::new(0.0, 2.0, 0.0) + d * 1.5,
                n: -d,
            });
            angles.push((g, c));
        }
    }
    scene.meters = vec![Meter {
        name: "ring".into(),
        grid: [points.len() as u32, 1],
        points,
    }];
    for (r, &(g, c)) in measure(&scene, 256, 2).iter().zip(&angles) {
        let truth = full(g, c) / (1.5 * 1.5);
        let rel = r.illuminance_lx / truth - 1.0;
        assert!(
            rel.abs() < 0.005,
            "γ {g}°, C {c}°: {} vs {truth} lx",
            r.illuminance_lx
        );
    }
}

/// The flux through a sphere of meters around the luminaire, ∮ E dA, equals the closed form of
/// the table's distribution and the lumens the file declares (light output ratio × lamp flux).
#[test]
fn total_flux_equals_the_closed_form_and_the_declared_lumens() {
    let dir = tmpdir("ldt-flux");
    // I = 1000 (1 − γ/90°)(1 + 0.5·C/90°) in the quadrant, zero above the horizon:
    // Φ = 1.25 · 1000 · 2π ∫₀^{π/2} (1 − 2γ/π) sin γ dγ = 1.25 · 1000 · (2π − 4) lm
    let dist = |g: f64, c: f64| 1000.0 * (1.0 - g / 90.0) * (1.0 + 0.5 * c / 90.0);
    let phi = 1.25 * 1000.0 * (2.0 * PI - 4.0);
    let lamp = 3000.0;
    let lor = (phi / lamp * 100.0 * 1e6).round() / 1e6;
    let file = dir.join("flux.ldt");
    std::fs::write(
        &file,
        ldt(4, 24, 15.0, &steps(0.0, 90.0, 5.0), lamp, lor, &dist),
    )
    .unwrap();
    let declared = lor / 100.0 * lamp;
    assert!((declared / phi - 1.0).abs() < 1e-6);
    // the luminaire at the centre of a black sphere of radius 5 m, meters on a sphere of 1 m
    let text = scene_text("flux.ldt", "").replace(
        "type = \"rectangle\"\nmaterial = \"black\"\ntransform = [{ scale = 50 }, { rotate = { axis = [1, 0, 0], angle = \"-90 deg\" } }]",
        "type = \"sphere\"\nmaterial = \"black\"\nradius = 5\ntwo_sided = true",
    );
    let path = dir.join("flux.toml");
    std::fs::write(&path, text).unwrap();
    let mut scene = scene_at(&path);
    let centre = Vec3::new(0.0, 2.0, 0.0);
    let (nt, nc) = (90usize, 48usize);
    let mut points = Vec::new();
    for i in 0..nt {
        let cos = 1.0 - 2.0 * (i as f64 + 0.5) / nt as f64;
        let sin = (1.0 - cos * cos).sqrt();
        for j in 0..nc {
            let phi = 2.0 * PI * (j as f64 + 0.5) / nc as f64;
            let d = Vec3::new(
                (sin * phi.cos()) as f32,
                cos as f32,
                (sin * phi.sin()) as f32,
            );
            points.push(MeterPoint {
                p: centre + d,
                n: -d,
            });
        }
    }
    scene.meters = vec![Meter {
        name: "sphere".into(),
        grid: [nc as u32, nt as u32],
        points,
    }];
    let r = measure(&scene, 64, 3);
    let cell = 4.0 * PI / (nt * nc) as f64;
    let flux: f64 = r.iter().map(|x| x.illuminance_lx * cell).sum();
    let rel = flux / declared - 1.0;
    eprintln!(
        "flux {flux:.3} lm, declared {declared:.3} lm, closed form {phi:.3} lm ({:+.4} %)",
        rel * 100.0
    );
    assert!(rel.abs() < 0.005, "{flux} lm vs {declared} lm");
}

/// A grey floor lit by an asymmetric, tilted luminaire: `light` (particles from `sample_le`)
/// and `bdpt` agree with `path` (light samples from `sample_li`) on the image's mean luminance
/// and on each quarter of it.
#[test]
fn path_light_and_bdpt_agree() {
    let dir = tmpdir("ies-integrators");
    std::fs::write(
        dir.join("full.ies"),
        ies(&steps(0.0, 180.0, 5.0), &steps(0.0, 360.0, 15.0), &full),
    )
    .unwrap();
    let text = scene_text("full.ies", "")
        .replace("reflectance = 0", "reflectance = 0.5")
        .replace("target = [0, 0, 0]\n\n", "target = [1, 0, 0.5]\n")
        .replace(
            "width = 16\nheight = 16\nspp = 1",
            "width = 32\nheight = 32\nspp = 64",
        )
        .replace("eye = [0, 5, 5]", "eye = [0, 6, 0.01]");
    let path = dir.join("floor.toml");
    std::fs::write(&path, text).unwrap();
    let scene = scene_at(&path);
    let quarters = |img: &spectrace::film::Image| -> [f64; 4] {
        let mut q = [0.0; 4];
        for y in 0..img.height {
            for x in 0..img.width {
                let k = (y * 2 / img.height) * 2 + x * 2 / img.width;
                q[k] += img.xyz[y * img.width + x][1] as f64 / (img.width * img.height / 4) as f64;
            }
        }
        q
    };
    let (p, _) = render_with(&scene, |o| {
        o.integrator = IntegratorKind::Path;
        o.max_depth = 1;
    });
    let qp = quarters(&p);
    for kind in [IntegratorKind::Light, IntegratorKind::Bdpt] {
        let (img, _) = render_with(&scene, |o| {
            o.integrator = kind;
            o.max_depth = 1;
        });
        let (a, b) = (
            mean(img.xyz.iter().map(|v| v[1])),
            mean(p.xyz.iter().map(|v| v[1])),
        );
        assert!(
            (a / b - 1.0).abs() < 0.01,
            "{kind:?}: mean Y {a} vs path {b}"
        );
        for (k, (x, y)) in quarters(&img).iter().zip(qp).enumerate() {
            assert!(
                (x / y - 1.0).abs() < 0.02,
                "{kind:?}: quarter {k}: {x} vs path {y}"
            );
        }
    }
}

#[test]
fn bad_files_give_located_errors() {
    let dir = tmpdir("ies-bad");
    let good = ies(&[0.0, 45.0, 90.0], &[0.0], &axial);
    let cases = [
        (
            good.replace("1 1 10\n", "1 1\n"),
            "bad.ies:8:1: vertical angles[2]",
        ),
        (good.replace(" 1 2 0.1", " 3 2 0.1"), "bad.ies:5:"),
        (
            good.replace("TILT=NONE", "TILT=missing.tilt"),
            "cannot read the tilt file",
        ),
        (good.replace("\n0\n", "\n45\n"), "horizontal angles: type C"),
    ];
    for (text, want) in cases {
        std::fs::write(dir.join("bad.ies"), text).unwrap();
        let toml = scene_text("bad.ies", "");
        let path = dir.join("bad.toml");
        std::fs::write(&path, toml).unwrap();
        let e = spectrace::loader::load(&path).unwrap_err().to_string();
        assert!(e.contains(want), "want {want:?} in: {e}");
    }
    // the scene's own fields
    std::fs::write(dir.join("ok.ies"), &good).unwrap();
    for (extra, want) in [
        (
            "c0 = [0, 1, 0]",
            "lights[0].c0: the C0 direction must not be zero or along the nadir",
        ),
        (
            "tilt = \"200 deg\"",
            "lights[0].tilt: expected a tilt from 0 to 180 deg",
        ),
        (
            "power = \"100 lm\"\nscale = 2",
            "lights[0].scale: give power or scale, not both",
        ),
        ("radius = 1", "radius"),
    ] {
        let path = dir.join("fields.toml");
        std::fs::write(&path, scene_text("ok.ies", extra)).unwrap();
        let e = spectrace::loader::load(&path).unwrap_err().to_string();
        assert!(e.contains(want), "want {want:?} in: {e}");
    }
    let path = dir.join("nofile.toml");
    std::fs::write(&path, scene_text("nothere.ies", "")).unwrap();
    let e = spectrace::loader::load(&path).unwrap_err().to_string();
    assert!(
        e.contains("lights[0].file: photometric file not found"),
        "{e}"
    );
}

/// `power` rescales the distribution to a total flux; the tilt table multiplies at `tilt`.
#[test]
fn power_and_tilt_scale_the_file() {
    let dir = tmpdir("ies-power");
    let v = steps(0.0, 180.0, 5.0);
    let text = ies(&v, &[0.0], &axial);
    std::fs::write(dir.join("a.ies"), &text).unwrap();
    std::fs::write(
        dir.join("t.ies"),
        text.replace("TILT=NONE", "TILT=INCLUDE\n1\n3\n0 30 90\n1 0.8 0.5"),
    )
    .unwrap();
    // the axial distribution's flux: 2π ∫ 1000 (1 − γ/π) sin γ dγ = 2π · 1000 · (2 − 1) = 2000π lm
    let flux = 2000.0 * PI;
    let at = |file: &str, extra: &str| {
        let path = dir.join("p.toml");
        std::fs::write(&path, scene_text(file, extra)).unwrap();
        let mut scene = scene_at(&path);
        scene.meters = vec![Meter {
            name: "m".into(),
            grid: [1, 1],
            points: vec![MeterPoint {
                p: Vec3::ZERO,
                n: Vec3::Y,
            }],
        }];
        measure(&scene, 256, 4)[0].illuminance_lx
    };
    let base = at("a.ies", "");
    assert!(
        (base / 250.0 - 1.0).abs() < 0.005,
        "{base} lx, 1000 cd at 2 m is 250 lx"
    );
    let p = at("a.ies", "power = \"1000 lm\"");
    assert!((p / (base * 1000.0 / flux) - 1.0).abs() < 0.005, "{p} lx");
    let t = at("t.ies", "tilt = \"15 deg\"");
    assert!((t / (base * 0.9) - 1.0).abs() < 0.005, "{t} lx");
}
