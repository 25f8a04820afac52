//! Illuminance meters (`[[sensors]]`, `spectrace measure`) against closed forms: a point light
//! over a grid (E = I cos θ / d²), a square Lambertian emitter over a grid (the rectangle's
//! configuration factor, by corner superposition), the reported standard error covering the
//! true error at the rate its t distribution states, and the CLI's CSV.

mod support;

use std::f64::consts::PI;

use support::cli::{spectrace, tmpdir};
use support::render::{measure, scene_from};

const FLOOR: &str = r#"
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
transform = [{ scale = 20 }, { rotate = { axis = [1, 0, 0], angle = "-90 deg" } }]
[[sensors]]
type = "grid"
name = "floor"
corner = [-2, 0, -1.5]
edge_u = [0, 0, 3]
edge_v = [4, 0, 0]
count = [8, 8]
"#;

#[test]
fn point_light_over_a_grid() {
    let scene = scene_from(&format!(
        "{FLOOR}\n[[lights]]\ntype = \"point\"\nposition = [0.3, 2, -0.2]\nspectrum = \"cie-d65\"\nintensity = \"1000 cd\"\n"
    ));
    let m = &scene.meters[0];
    assert_eq!(m.points.len(), 64);
    // cell centres, normal from edge_u × edge_v = ẑ × x̂ = +y
    assert!((m.points[0].p - glam::Vec3::new(-1.75, 0.0, -1.3125)).length() < 1e-6);
    assert!((m.points[0].n - glam::Vec3::Y).length() < 1e-6);
    let r = measure(&scene, 1024, 0);
    for (p, x) in m.points.iter().zip(&r) {
        let (dx, dz) = (p.p.x as f64 - 0.3, p.p.z as f64 + 0.2);
        let d2 = dx * dx + dz * dz + 4.0;
        let truth = 1000.0 * (2.0 / d2.sqrt()) / d2;
        let rel = x.illuminance_lx / truth - 1.0;
        assert!(
            rel.abs() < 0.005,
            "{:?}: {} vs {truth} lx",
            p.p,
            x.illuminance_lx
        );
    }
}

/// ∫ cos θ dω of the rectangle [0, a] × [0, b] at height h seen from below its corner (0, 0):
/// the configuration factor of a parallel rectangle times π (Howell's catalogue, C-11).
fn corner(a: f64, b: f64, h: f64) -> f64 {
    let sgn = a.signum() * b.signum();
    let (x, y) = (a.abs() / h, b.abs() / h);
    if x == 0.0 || y == 0.0 {
        return 0.0;
    }
    sgn * 0.5
        * (x / (1.0 + x * x).sqrt() * (y / (1.0 + x * x).sqrt()).atan()
            + y / (1.0 + y * y).sqrt() * (x / (1.0 + y * y).sqrt()).atan())
}

/// E below a Lambertian square [x0, x1] × [z0, z1] at height h, radiance L: corner sums.
fn under_rect(l: f64, px: f64, pz: f64, (x0, x1, z0, z1): (f64, f64, f64, f64), h: f64) -> f64 {
    let (a0, a1, b0, b1) = (x0 - px, x1 - px, z0 - pz, z1 - pz);
    l * (corner(a1, b1, h) - corner(a0, b1, h) - corner(a1, b0, h) + corner(a0, b0, h))
}

#[test]
fn square_area_light_over_a_grid_and_its_standard_error() {
    // a 1 m square emitter facing down at 2 m, 100 W/m²/sr band radiance, equal energy
    let scene = scene_from(&format!(
        "{FLOOR}\n[[shapes]]\ntype = \"rectangle\"\ntransform = [{{ scale = 0.5 }}, {{ rotate = {{ axis = [1, 0, 0], angle = \"90 deg\" }} }}, {{ translate = [0, 2, 0] }}]\nemission = {{ spectrum = \"cie-e\", radiance = \"100 W/m^2/sr\" }}\n"
    ));
    let m = &scene.meters[0];
    let l_band = 100.0;
    // well converged: within 0.5 % of the closed form (irradiance over the band, W/m²)
    let r = measure(&scene, 4096, 0);
    for (p, x) in m.points.iter().zip(&r) {
        let truth = under_rect(
            l_band,
            p.p.x as f64,
            p.p.z as f64,
            (-0.5, 0.5, -0.5, 0.5),
            2.0,
        );
        let rel = x.irradiance_w_m2 / truth - 1.0;
        assert!(
            rel.abs() < 0.005,
            "{:?}: {} vs {truth} W/m²",
            p.p,
            x.irradiance_w_m2
        );
    }
    // few samples: the error in standard errors follows Student's t with 15 degrees of freedom,
    // P(|t| < 1) = 0.661, P(|t| < 2) = 0.936; over 64 points × 4 seeds = 256 readings
    let (mut within1, mut within2, mut n) = (0, 0, 0);
    for seed in 1..5 {
        let r = measure(&scene, 64, seed);
        for (p, x) in m.points.iter().zip(&r) {
            let truth = under_rect(
                l_band,
                p.p.x as f64,
                p.p.z as f64,
                (-0.5, 0.5, -0.5, 0.5),
                2.0,
            );
            let t = (x.irradiance_w_m2 - truth).abs() / x.irradiance_se_w_m2;
            within1 += (t < 1.0) as usize;
            within2 += (t < 2.0) as usize;
            n += 1;
        }
    }
    let (f1, f2) = (within1 as f64 / n as f64, within2 as f64 / n as f64);
    eprintln!("within 1 se: {f1:.3} (t: 0.661), within 2 se: {f2:.3} (t: 0.936)");
    // binomial standard deviations at n = 256: 0.030 and 0.015; allow 4 of them
    assert!((f1 - 0.661).abs() < 0.12, "{f1}");
    assert!((f2 - 0.936).abs() < 0.06, "{f2}");
}

#[test]
fn measure_writes_a_csv() {
    let dir = tmpdir("measure-cli");
    let scene = format!(
        "{FLOOR}\n[[sensors]]\ntype = \"point\"\nname = \"desk\"\nposition = [0, 0.75, 0]\nnormal = [0, 1, 0]\n[[lights]]\ntype = \"point\"\nposition = [0, 2.75, 0]\nspectrum = \"cie-a\"\nintensity = \"400 cd\"\n"
    );
    std::fs::write(dir.join("s.toml"), scene).unwrap();
    let (ok, err) = spectrace(
        &dir,
        &[
            "measure",
            "s.toml",
            "-o",
            "m.csv",
            "--samples",
            "256",
            "--spectral",
            "--quiet",
        ],
    );
    assert!(ok, "{err}");
    assert!(err.contains("desk: "), "{err}");
    let csv = std::fs::read_to_string(dir.join("m.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(&header[..4], &["sensor", "i", "j", "x_m"]);
    assert_eq!(header[9], "illuminance_lx");
    // 10 nm bins over 360–830 nm
    assert_eq!(header.len(), 13 + 47);
    assert_eq!(header[13], "E_365nm_W_m2_nm");
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 65);
    let desk = rows.iter().find(|r| r[0] == "desk").unwrap();
    let e: f64 = desk[9].parse().unwrap();
    assert!(
        (e / 100.0 - 1.0).abs() < 0.005,
        "400 cd at 2 m: 100 lx, read {e}"
    );
    // the spectral columns integrate to the irradiance column (10 nm bins)
    let band: f64 = desk[11].parse().unwrap();
    let sum: f64 = desk[13..]
        .iter()
        .map(|v| v.parse::<f64>().unwrap() * 10.0)
        .sum();
    assert!((sum / band - 1.0).abs() < 1e-6, "{sum} vs {band}");
    let _ = PI;

    // errors: no sensors, bad sensor fields
    std::fs::write(
        dir.join("none.toml"),
        FLOOR.split("[[sensors]]").next().unwrap().to_string()
            + "[[lights]]\ntype = \"point\"\nposition = [0, 2, 0]\npower = \"1 W\"\n",
    )
    .unwrap();
    let (ok, err) = spectrace(&dir, &["measure", "none.toml", "-o", "n.csv"]);
    assert!(
        !ok && err.contains("the scene has no [[sensors]] to measure"),
        "{err}"
    );
    for (bad, want) in [
        (
            "edge_v = [4, 0, 0]",
            "edge_v = [0, 0, 6]",
            "sensors[0].edge_v: the grid's edges are zero or parallel",
        ),
        (
            "count = [8, 8]",
            "count = [0, 8]",
            "sensors[0].count: expected [nu, nv]",
        ),
        (
            "name = \"floor\"",
            "name = \"a,b\"",
            "sensors[0].name: a sensor name must not",
        ),
        (
            "type = \"grid\"",
            "type = \"cube\"",
            "sensors[0].type: unknown sensor type \"cube\"",
        ),
    ]
    .map(|(a, b, c)| ((a, b), c))
    {
        let text = FLOOR.replace(bad.0, bad.1)
            + "[[lights]]\ntype = \"point\"\nposition = [0, 2, 0]\npower = \"1 W\"\n";
        std::fs::write(dir.join("bad.toml"), text).unwrap();
        let (ok, err) = spectrace(&dir, &["measure", "bad.toml", "-o", "b.csv"]);
        assert!(!ok && err.contains(want), "want {want:?}: {err}");
        assert!(err.contains("bad.toml:"), "{err}");
    }
    assert!(!dir.join("b.csv").exists());
    // a missing output folder is found before measuring
    let (ok, err) = spectrace(&dir, &["measure", "s.toml", "-o", "nowhere/m.csv"]);
    assert!(
        !ok && err.contains("folder nowhere does not exist"),
        "{err}"
    );
}
