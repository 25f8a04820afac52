//! Test cases of CIE 171:2006 ("Test cases to assess the accuracy of lighting computer
//! programs") that have analytical answers and that spectrace's features can express, each
//! with its closed form, in the standard's spirit: the geometry here is chosen for the test
//! (the standard's own dimensions are not reproduced), the closed forms are derived or cited in
//! each test, and every case is measured with `[[sensors]]` (hemispherical integration).
//! The README's table lists each case, its closed form and the measured error
//! (`cargo test --release --test cie171 -- --nocapture` prints them).

mod support;

use std::f64::consts::PI;

use support::render::{measure, scene_from};

fn report(case: &str, got: f64, want: f64, tol: f64) {
    let rel = got / want - 1.0;
    eprintln!(
        "{case}: {got:.6} vs closed form {want:.6} ({:+.3} %)",
        rel * 100.0
    );
    assert!(rel.abs() < tol, "{case}: {got} vs {want}");
}

/// §5.2-type: a point source of intensity I above a plane: E = I cos³θ / h².
#[test]
fn point_source_illuminance() {
    let scene = scene_from(&support::render::black_floor(
        "[[lights]]\ntype = \"point\"\nposition = [0, 2.5, 0]\nspectrum = \"cie-a\"\nintensity = \"800 cd\"\n\
         [[sensors]]\ntype = \"grid\"\ncorner = [0, 0, 0]\nedge_u = [0, 0, 4]\nedge_v = [4, 0, 0]\ncount = [4, 4]\n",
    ));
    let r = measure(&scene, 1024, 0);
    let mut worst: f64 = 0.0;
    for (p, x) in scene.meters[0].points.iter().zip(&r) {
        let d2 = (p.p.x * p.p.x + p.p.z * p.p.z) as f64 + 6.25;
        let cos = 2.5 / d2.sqrt();
        let want = 800.0 * cos / d2;
        worst = worst.max((x.illuminance_lx / want - 1.0).abs());
        assert!((x.illuminance_lx / want - 1.0).abs() < 0.005);
    }
    eprintln!("point source: worst {:.4} % over 16 points", worst * 100.0);
}

/// §5.3-type: a Lambertian disk source of luminance L, radius R, facing down at height h:
/// on its axis E = π L R² / (R² + h²) (the disk's configuration factor).
#[test]
fn area_source_illuminance() {
    let (l, r, h) = (5000.0, 0.3, 1.2);
    let scene = scene_from(&support::render::black_floor(&format!(
        "[[shapes]]\ntype = \"disk\"\ntransform = [{{ scale = {r} }}, {{ rotate = {{ axis = [1, 0, 0], angle = \"90 deg\" }} }}, {{ translate = [0, {h}, 0] }}]\nemission = {{ spectrum = \"cie-d65\", luminance = \"{l} cd/m^2\" }}\n\
         [[sensors]]\ntype = \"point\"\nposition = [0, 0, 0]\nnormal = [0, 1, 0]\n"
    )));
    let x = &measure(&scene, 65536, 0)[0];
    report(
        "disk source on its axis",
        x.illuminance_lx,
        PI * l * r * r / (r * r + h * h),
        0.005,
    );
}

/// §5.6-type (diffuse interreflection): inside a sphere of reflectance ρ lit by a source of
/// flux Φ at its centre, the illuminance of the wall is Φ/(4πR²)·1/(1 − ρ) (direct plus the
/// uniform reflected part ρΦ/(A(1 − ρ)), exact for a sphere).
#[test]
fn integrating_sphere() {
    let (phi, rho, radius) = (1000.0, 0.8, 1.5);
    let scene = scene_from(&format!(
        r#"
[camera]
eye = [0, 0, 0]
target = [0, 0, 1]
fov = "60 deg"
[film]
width = 8
height = 8
spp = 1
[integrator]
max_depth = 200
[materials.wall]
type = "diffuse"
reflectance = {rho}
[[shapes]]
type = "sphere"
radius = {radius}
material = "wall"
two_sided = true
[[lights]]
type = "point"
position = [0, 0, 0]
spectrum = "cie-e"
power = "{phi} lm"
[[sensors]]
type = "point"
position = [0, -{inner}, 0]
normal = [0, 1, 0]
[[sensors]]
type = "point"
position = [{inner}, 0, 0]
normal = [-1, 0, 0]
"#,
        inner = radius * 0.999
    ));
    let want = phi / (4.0 * PI * radius * radius) / (1.0 - rho);
    for x in measure(&scene, 1 << 18, 0) {
        eprintln!("standard error {:.3} %", x.illuminance_se_lx / want * 100.0);
        report("integrating sphere, ρ = 0.8", x.illuminance_lx, want, 0.005);
    }
}

/// §5.9-type: the sky component under an unglazed horizontal roof opening (a × b at height h
/// above the point, centred): under the uniform sky SC = P/π, under the CIE overcast sky
/// 3(P + 2Q)/(7π), P = ∫ cos θ dω and Q = ∫ cos²θ dω over the opening (corner sums; see
/// `tests/daylight.rs`).
#[test]
fn sky_component_roof_opening() {
    let (a, b, h): (f64, f64, f64) = (0.75, 0.5, 2.0);
    let pc = |a: f64, b: f64| {
        let (x, y) = (a / h, b / h);
        0.5 * (x / (1.0 + x * x).sqrt() * (y / (1.0 + x * x).sqrt()).atan()
            + y / (1.0 + y * y).sqrt() * (x / (1.0 + y * y).sqrt()).atan())
    };
    let qc = |a: f64, b: f64| {
        let d = (a * a + b * b + h * h).sqrt();
        ((a * b / (h * d)).atan() + a * b * h / d * (1.0 / (a * a + h * h) + 1.0 / (b * b + h * h)))
            / 3.0
    };
    let (p, q) = (4.0 * pc(a, b), 4.0 * qc(a, b));
    for (model, want, eh) in [
        ("cie-5", p / PI, PI),
        (
            "cie-overcast",
            3.0 * (p + 2.0 * q) / (7.0 * PI),
            7.0 * PI / 9.0,
        ),
    ] {
        let scene = scene_from(&room_with(
            &format!("[-{a}, {h}, -{b}], [{a}, {h}, -{b}], [{a}, {h}, {b}], [-{a}, {h}, {b}]"),
            "roof",
            h,
            model,
        ));
        let x = &measure(&scene, 1 << 20, 0)[0];
        report(
            &format!("roof opening, {model}"),
            x.illuminance_lx / (eh * 1000.0),
            want,
            0.005,
        );
    }
}

/// §5.11-type: the sky component in front of an unglazed vertical opening (width w centred,
/// from the floor to height b, in a wall at distance c) under the uniform sky: SC = P/π with
/// P = 2·½[atan(a/c) − c/√(c² + b²)·atan(a/√(c² + b²))], a = w/2 (∫ cos θ dω of the opening
/// from a horizontal element, integrated in closed form).
#[test]
fn sky_component_facade_opening() {
    let (w, b, c): (f64, f64, f64) = (1.2, 1.5, 2.0);
    let a = w / 2.0;
    let e = (c * c + b * b).sqrt();
    let p = (a / c).atan() - c / e * (a / e).atan();
    let scene = scene_from(&room_with(
        &format!("[-{a}, 0, {c}], [{a}, 0, {c}], [{a}, {b}, {c}], [-{a}, {b}, {c}]"),
        "facade",
        3.0,
        "cie-5",
    ));
    let x = &measure(&scene, 1 << 20, 0)[0];
    report(
        "facade opening, uniform sky",
        x.illuminance_lx / (PI * 1000.0),
        p / PI,
        0.005,
    );
}

/// A black room 6 m wide and deep around the meter at the origin (facing up), open only through
/// the quadrilateral `hole` (4 corners) in its ceiling at `height` (`which` = "roof") or in its
/// wall z = c (`which` = "facade"), under a sky of zenith luminance 1000 cd/m².
fn room_with(hole: &str, which: &str, height: f64, model: &str) -> String {
    // the room's faces, leaving out the face holding the hole, which is a frame around it
    let (lo, hi) = (-3.0, 3.0);
    let mut v: Vec<[f64; 3]> = vec![
        [lo, 0.0, lo],
        [hi, 0.0, lo],
        [hi, 0.0, hi],
        [lo, 0.0, hi],
        [lo, height, lo],
        [hi, height, lo],
        [hi, height, hi],
        [lo, height, hi],
    ];
    let hole_v: Vec<[f64; 3]> = hole
        .split("], [")
        .map(|s| {
            let n: Vec<f64> = s
                .trim_matches(|c| c == '[' || c == ']')
                .split(',')
                .map(|x| x.trim().parse().unwrap())
                .collect();
            [n[0], n[1], n[2]]
        })
        .collect();
    let mut f: Vec<[usize; 3]> = vec![[0, 1, 2], [0, 2, 3]];
    let (outer, zc): ([usize; 4], f64) = if which == "roof" {
        // walls
        f.extend([
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ]);
        ([4, 5, 6, 7], 0.0)
    } else {
        // the facade wall is the plane z = c: the room runs from z = −3 to c
        let c = hole_v[0][2];
        v[2][2] = c;
        v[3][2] = c;
        v[6][2] = c;
        v[7][2] = c;
        f.extend([
            [4, 5, 6],
            [4, 6, 7],
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [3, 0, 4],
            [3, 4, 7],
        ]);
        ([3, 2, 6, 7], c)
    };
    let _ = zc;
    let base = v.len();
    v.extend(hole_v);
    // a frame between the outer quadrilateral and the hole (corresponding corners)
    for k in 0..4 {
        let (o0, o1) = (outer[k], outer[(k + 1) % 4]);
        let (h0, h1) = (base + k, base + (k + 1) % 4);
        f.push([o0, o1, h1]);
        f.push([o0, h1, h0]);
    }
    let verts: Vec<String> = v
        .iter()
        .map(|p| format!("[{}, {}, {}]", p[0], p[1], p[2]))
        .collect();
    let faces: Vec<String> = f
        .iter()
        .map(|t| format!("[{}, {}, {}]", t[0], t[1], t[2]))
        .collect();
    format!(
        r#"
[camera]
eye = [1, 1, 1]
target = [0, 0, 0]
fov = "60 deg"
[film]
width = 8
height = 8
spp = 1
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "mesh"
material = "black"
two_sided = true
vertices = [{}]
faces = [{}]
[[lights]]
type = "sky"
model = "{model}"
luminance = "1000 cd/m^2"
[[sensors]]
type = "point"
position = [0, 0, 0]
normal = [0, 1, 0]
"#,
        verts.join(", "),
        faces.join(", ")
    )
}
