//! Daylight against published and closed-form values: NOAA's solar position against NREL's SPA
//! (pvlib, `tests/data/solar_position_spa.csv`), the CIE overcast sky's horizontal illuminance
//! E_h = (7π/9)·L_z, the CIE clear sky's E_h/L_z from an independent quadrature
//! (`tests/data/cie_sky_vectors.csv`), a sky set by its horizontal illuminance, and the daylight
//! factor under a square roof opening against the configuration-factor closed form.

mod support;

use std::f64::consts::PI;

use spectrace::daylight::solar::{UtcTime, sun_position};
use support::Csv;
use support::render::{measure, scene_from};

#[test]
fn noaa_solar_position_matches_spa() {
    let csv = Csv::read("solar_position_spa.csv");
    let col = |n: &str| csv.columns.iter().position(|c| c == n).unwrap();
    let (t, lat, lon, z, a) = (
        col("utc"),
        col("lat"),
        col("lon"),
        col("apparent_zenith_deg"),
        col("azimuth_deg"),
    );
    let mut worst: f64 = 0.0;
    for row in &csv.rows {
        let f = |i: usize| row[i].parse::<f64>().unwrap();
        let s = sun_position(f(lat), f(lon), UtcTime::parse(&row[t]).unwrap());
        let dz = s.zenith - f(z);
        let mut da = s.azimuth - f(a);
        da -= 360.0 * (da / 360.0).round();
        worst = worst.max(dz.abs()).max(da.abs());
        // NOAA's stated accuracy is 0.01°; its refraction is a sea-level standard atmosphere
        assert!(
            dz.abs() < 0.02 && da.abs() < 0.02,
            "{}: Δzenith {dz}°, Δazimuth {da}°",
            row[t]
        );
    }
    eprintln!("worst NOAA − SPA: {worst:.4}°");
}

/// A meter on an unobstructed horizontal plane under `sky` (TOML keys).
fn horizontal(sky: &str, samples: u32) -> spectrace::render::measure::Reading {
    let scene = scene_from(&format!(
        r#"
[camera]
eye = [0, 1, 5]
target = [0, 1, 0]
fov = "60 deg"
[film]
width = 8
height = 8
spp = 1
[[lights]]
type = "sky"
{sky}
[[sensors]]
type = "point"
position = [0, 0, 0]
normal = [0, 1, 0]
"#
    ));
    measure(&scene, samples, 0).remove(0)
}

#[test]
fn overcast_sky_horizontal_illuminance_is_7pi_over_9_lz() {
    let r = horizontal(
        "model = \"cie-overcast\"\nluminance = \"10000 cd/m^2\"",
        16384,
    );
    let truth = 7.0 * PI / 9.0 * 10_000.0;
    let rel = r.illuminance_lx / truth - 1.0;
    eprintln!(
        "overcast: {} lx vs {truth} lx ({:+.4} %)",
        r.illuminance_lx,
        rel * 100.0
    );
    assert!(rel.abs() < 0.005, "{} lx vs {truth} lx", r.illuminance_lx);
}

#[test]
fn cie_general_skies_match_independent_quadrature() {
    let csv = Csv::read("cie_sky_vectors.csv");
    let mut n = 0;
    for row in csv.rows.iter().filter(|r| r[0] == "Eh") {
        let (ty, elev, value) = (&row[1], &row[2], row[5].parse::<f64>().unwrap());
        let r = horizontal(
            &format!(
                "model = \"cie-{ty}\"\nluminance = \"1000 cd/m^2\"\nsun_elevation = \"{elev} deg\"\nsun_azimuth = \"120 deg\""
            ),
            16384,
        );
        let truth = value * 1000.0;
        let rel = r.illuminance_lx / truth - 1.0;
        eprintln!("type {ty} at {elev}°: {:+.4} %", rel * 100.0);
        assert!(
            rel.abs() < 0.005,
            "type {ty}, sun at {elev}°: {} vs {truth} lx",
            r.illuminance_lx
        );
        n += 1;
    }
    assert_eq!(n, 6);
}

#[test]
fn a_sky_set_by_its_horizontal_illuminance() {
    let r = horizontal(
        "model = \"cie-12\"\nirradiance = \"20000 lx\"\nlatitude = 52.0\nlongitude = 4.36\ntime = \"2026-06-21T14:00:00+02:00\"",
        16384,
    );
    assert!(
        (r.illuminance_lx / 20_000.0 - 1.0).abs() < 0.005,
        "{}",
        r.illuminance_lx
    );
}

/// The sky component under a 1 m × 1 m hole in the ceiling of a black room, 3 m above the
/// meter: DF = 3(P + 2Q)/(7π) under the overcast sky, with P = ∫ cos θ dω and Q = ∫ cos² θ dω
/// over the hole (four corner rectangles of A = B = 0.5 m at h = 3 m:
/// P_c = ½[X/√(1+X²)·atan(Y/√(1+X²)) + Y/√(1+Y²)·atan(X/√(1+Y²))],
/// Q_c = ⅓[atan(AB/(hD)) + (ABh/D)(1/(A²+h²) + 1/(B²+h²))], D = √(A²+B²+h²)).
#[test]
fn daylight_factor_under_a_roof_opening() {
    let (a, b, h): (f64, f64, f64) = (0.5, 0.5, 3.0);
    let (x, y) = (a / h, b / h);
    let pc = 0.5
        * (x / (1.0 + x * x).sqrt() * (y / (1.0 + x * x).sqrt()).atan()
            + y / (1.0 + y * y).sqrt() * (x / (1.0 + y * y).sqrt()).atan());
    let d = (a * a + b * b + h * h).sqrt();
    let qc = ((a * b / (h * d)).atan()
        + a * b * h / d * (1.0 / (a * a + h * h) + 1.0 / (b * b + h * h)))
        / 3.0;
    let df = 3.0 * (4.0 * pc + 8.0 * qc) / (7.0 * PI);
    assert!((df - 0.0435898).abs() < 1e-6, "{df}");
    // the room: 6 m × 6 m × 3 m, black, the ceiling's hole [-0.5, 0.5]² at its centre
    let scene = scene_from(
        r#"
[camera]
eye = [2, 1.5, 2]
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
vertices = [[-3, 0, -3], [3, 0, -3], [3, 0, 3], [-3, 0, 3],
            [-3, 3, -3], [3, 3, -3], [3, 3, 3], [-3, 3, 3],
            [-0.5, 3, -0.5], [0.5, 3, -0.5], [0.5, 3, 0.5], [-0.5, 3, 0.5]]
faces = [[0, 1, 2], [0, 2, 3],
         [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7],
         [4, 5, 9], [4, 9, 8], [5, 6, 10], [5, 10, 9], [6, 7, 11], [6, 11, 10], [7, 4, 8], [7, 8, 11]]
[[lights]]
type = "sky"
model = "cie-overcast"
luminance = "10000 cd/m^2"
[[sensors]]
type = "point"
position = [0, 0, 0]
normal = [0, 1, 0]
"#,
    );
    let r = measure(&scene, 1 << 20, 0).remove(0);
    let eh = 7.0 * PI / 9.0 * 10_000.0;
    let got = r.illuminance_lx / eh;
    let rel = got / df - 1.0;
    eprintln!(
        "daylight factor {got:.6} vs {df:.6} ({:+.3} %, standard error {:.3} %)",
        rel * 100.0,
        r.illuminance_se_lx / eh / df * 100.0
    );
    assert!(rel.abs() < 0.005, "DF {got} vs closed form {df}");
}

/// `cie-d:<T>K` against colour-science's D series at the same CCTs (10 nm points), and the
/// LED illuminants' chromaticities against colour-science's integration.
#[test]
fn daylight_of_a_cct_and_led_illuminants() {
    use spectrace::spectrum::named::{Named, lookup};
    let csv = Csv::read("cie_daylight_cct.csv");
    for (c, name) in csv.columns.iter().enumerate().skip(1) {
        let t = &name[1..];
        let Ok(Named::Curve { spectrum, .. }) = lookup(&format!("cie-d:{t}K")) else {
            panic!("cie-d:{t}K")
        };
        for row in &csv.rows {
            let (l, v): (f32, f64) = (row[0].parse().unwrap(), row[c].parse().unwrap());
            let got = spectrum.eval(l) as f64;
            assert!(
                (got - v).abs() < 1e-4 * v.max(1.0),
                "{t} K at {l} nm: {got} vs {v}"
            );
        }
    }
    let csv = Csv::read("cie_led_xy.csv");
    for row in &csv.rows {
        let Ok(Named::Curve { spectrum, .. }) = lookup(&row[0]) else {
            panic!("{}", row[0])
        };
        let xyz = spectrace::colour::cie::integrate_xyz(|l| spectrum.eval(l) as f64);
        let xy = spectrace::colour::cie::xyz_to_xy(xyz);
        let (x, y): (f64, f64) = (row[1].parse().unwrap(), row[2].parse().unwrap());
        assert!(
            (xy[0] - x).abs() < 5e-4 && (xy[1] - y).abs() < 5e-4,
            "{}: {xy:?} vs ({x}, {y})",
            row[0]
        );
    }
}

/// A sun placed by time and place: on a horizontal plane E = E_n·cos Z, with Z from NREL's SPA
/// (`solar_position_spa.csv`, Greenwich at noon on the 2024 June solstice: 28.0357°); the sky's
/// and the sun's keys are checked.
#[test]
fn a_sun_placed_by_time_and_place() {
    let sun = "type = \"sun\"\nirradiance = \"100000 lx\"\nlatitude = 51.4779\nlongitude = -0.0015\ntime = \"2024-06-21T13:00:00+01:00\"";
    let scene = scene_from(&format!(
        r#"
[camera]
eye = [0, 1, 5]
target = [0, 1, 0]
fov = "60 deg"
[film]
width = 8
height = 8
spp = 1
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "sphere"
radius = 0.1
material = "black"
transform = [{{ translate = [0, -5, 0] }}]
[[lights]]
{sun}
[[sensors]]
type = "point"
position = [0, 0, 0]
normal = [0, 1, 0]
"#
    ));
    let e = measure(&scene, 1024, 0)[0].illuminance_lx;
    let want = 100_000.0 * 28.0357f64.to_radians().cos();
    assert!((e / want - 1.0).abs() < 0.001, "{e} vs {want} lx");
    // errors: direction and time together; a time without a zone; the sun below the horizon
    // a direction with the sun's place (here a latitude alone) is refused
    let text = "[camera]\neye = [0, 1, 5]\ntarget = [0, 1, 0]\nfov = \"40 deg\"\n[[lights]]\ntype = \"sun\"\nirradiance = \"1 lx\"\ndirection = [0, -1, 0]\nlatitude = 50\n";
    let e = spectrace::loader::load_str(text, std::path::Path::new("s.toml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("give the direction, or the sun's place"), "{e}");
    let extra = "direction = [0, -1, 0]";
    let text = format!(
        "[camera]\neye = [0, 1, 5]\ntarget = [0, 1, 0]\nfov = \"40 deg\"\n[[lights]]\n{sun}\n{extra}\n"
    );
    let e = spectrace::loader::load_str(&text, std::path::Path::new("s.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("give the direction, or the sun's place and time"),
        "{e}"
    );
    for (from, to, want) in [
        (
            "13:00:00+01:00",
            "13:00:00",
            "expected an ISO 8601 time with a zone",
        ),
        (
            "2024-06-21T13:00:00+01:00",
            "2024-12-21T23:00:00Z",
            "the sun is below the horizon then",
        ),
    ] {
        let text = format!(
            "[camera]\neye = [0, 1, 5]\ntarget = [0, 1, 0]\nfov = \"40 deg\"\n[[lights]]\n{}\n",
            sun.replace(from, to)
        );
        let e = spectrace::loader::load_str(&text, std::path::Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains(want) && e.contains("lights[0].time"), "{e}");
    }
}
