//! Camera sensors against the exposure formula and published data: a flat 100 cd/m² field at
//! ISO 100, 1/100 s, f/4 gives H = (π/4)·L·t·cos⁴θ/N² at the centre and the corners; a grey
//! card under D65 (or CIE A) white-balances to neutral for both adaptations; each camera's
//! curves peak at 1 and integrate to what their file's source states.

mod support;

use std::f64::consts::PI;

use support::cli::{spectrace, tmpdir};

fn channel(img: &spectrace::image_io::ExrImage, name: &str) -> Vec<f32> {
    img.channel(name)
        .unwrap_or_else(|| panic!("no channel {name}"))
        .to_vec()
}

const FIELD: &str = r#"
[camera]
eye = [0, 0, 0]
target = [0, 0, 1]
fov = "60 deg"
[film]
width = 33
height = 33
spp = 64
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "sphere"
radius = 10
material = "black"
two_sided = true
emission = { spectrum = "cie-d65", luminance = "100 cd/m^2", two_sided = true }
[camera.sensor]
curves = "cie-1931"
iso = 100
shutter = "1/100 s"
f_number = 4
"#;

#[test]
fn flat_field_exposure_follows_the_formula() {
    let dir = tmpdir("sensor-field");
    std::fs::write(dir.join("f.toml"), FIELD).unwrap();
    let (ok, err) = spectrace(&dir, &["render", "f.toml", "-o", "f.exr", "--quiet"]);
    assert!(ok, "{err}");
    let img = spectrace::image_io::read_exr(&dir.join("f.exr")).unwrap();
    let h = channel(&img, "sensor.H");
    let g = channel(&img, "sensor.G");
    let y = channel(&img, "Y");
    // the pixel (x, y) centre is at tan θ = |(x + ½ − 16.5, y + ½ − 16.5)|·tan 30° / 16.5
    let h0 = PI / 4.0 * 100.0 * 0.01 / 16.0;
    for (px, py) in [(16usize, 16usize), (0, 0), (32, 0), (5, 20)] {
        let (dx, dy) = (px as f64 + 0.5 - 16.5, py as f64 + 0.5 - 16.5);
        let t = (dx * dx + dy * dy).sqrt() * (PI / 6.0).tan() / 16.5;
        let cos4 = (1.0 / (1.0 + t * t)).powi(2);
        let i = py * 33 + px;
        // the pixel's luminance is 100 cd/m² up to the wavelength sampling's noise
        let want = h0 * cos4 * y[i] as f64 / 100.0;
        assert!((y[i] as f64 / 100.0 - 1.0).abs() < 0.01, "Y {}", y[i]);
        assert!(
            (h[i] as f64 / want - 1.0).abs() < 1e-4,
            "({px},{py}): H {} vs {want} lx·s",
            h[i]
        );
        // the CIE sensor's raw G: 0.18 · ISO/10 · H_v
        assert!(
            (g[i] as f64 / (1.8 * h[i] as f64) - 1.0).abs() < 1e-4,
            "G {}",
            g[i]
        );
    }
    let units = img
        .attributes
        .iter()
        .find(|(n, _)| n == "spectrace:sensor")
        .map(|(_, v)| format!("{v:?}"))
        .unwrap();
    assert!(
        units.contains("lx.s") && units.contains("ISO 100"),
        "{units}"
    );
}

/// A grey card (ρ = 0.5) filling the view under a light of `light` spectrum, seen by `curves`
/// balanced to `wb` by `adaptation`: the balanced channels are equal.
fn grey_card(curves: &str, light: &str, wb: &str, adaptation: &str) -> [f64; 3] {
    let dir = tmpdir(&format!("sensor-grey-{curves}-{adaptation}"));
    let scene = format!(
        r#"
[camera]
eye = [0, 0, -1]
target = [0, 0, 0]
fov = "20 deg"
[film]
width = 16
height = 16
spp = 256
[integrator]
max_depth = 1
[materials.grey]
type = "diffuse"
reflectance = 0.5
[[shapes]]
type = "rectangle"
material = "grey"
transform = [{{ scale = 2 }}, {{ rotate = {{ axis = [0, 1, 0], angle = "180 deg" }} }}]
[[lights]]
type = "point"
position = [0, 0, -2]
spectrum = "{light}"
intensity = "1000 cd"
[camera.sensor]
curves = "{curves}"
iso = 400
shutter = "1/50 s"
f_number = 2.8
white_balance = "{wb}"
adaptation = "{adaptation}"
"#
    );
    std::fs::write(dir.join("g.toml"), scene).unwrap();
    let (ok, err) = spectrace(&dir, &["render", "g.toml", "-o", "g.exr", "--quiet"]);
    assert!(ok, "{err}");
    let img = spectrace::image_io::read_exr(&dir.join("g.exr")).unwrap();
    let mean = |c: &str| {
        let v = channel(&img, c);
        v.iter().map(|&x| x as f64).sum::<f64>() / v.len() as f64
    };
    [
        mean("sensor.wb.R"),
        mean("sensor.wb.G"),
        mean("sensor.wb.B"),
    ]
}

#[test]
fn a_grey_card_white_balances_to_neutral() {
    for (curves, light, wb, adaptation) in [
        ("nikon-d5100", "cie-d65", "cie-d65", "von-kries"),
        ("sigma-sd-merrill", "cie-a", "cie-a", "von-kries"),
        ("cie-1931", "cie-a", "cie-a", "bradford"),
        ("nikon-d5100", "cie-a", "cie-a", "bradford"),
    ] {
        let [r, g, b] = grey_card(curves, light, wb, adaptation);
        eprintln!("{curves} {adaptation}: {r} {g} {b}");
        assert!(g > 0.0);
        assert!(
            (r / g - 1.0).abs() < 0.005 && (b / g - 1.0).abs() < 0.005,
            "{curves} {adaptation}: {r} {g} {b}"
        );
    }
}

#[test]
fn camera_curves_match_their_source() {
    for file in ["nikon_d5100.csv", "sigma_sd_merrill.csv"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("spectra/cameras")
            .join(file);
        let text = std::fs::read_to_string(&path).unwrap();
        // the stated integrals (trapezoids of the published table)
        let line = text
            .lines()
            .find(|l| l.starts_with("# integral_nm:"))
            .unwrap();
        let stated: Vec<f64> = line
            .split_whitespace()
            .filter_map(|t| t.split_once('=').map(|(_, v)| v.parse().unwrap()))
            .collect();
        let curves = spectrace::sensor::curves_from_text(&text, file).unwrap();
        for (k, c) in curves.iter().enumerate() {
            let integral = c.integrate(300.0, 900.0, 0.5);
            assert!(
                (integral / stated[k] - 1.0).abs() < 1e-4,
                "{file} channel {k}: {integral} vs {}",
                stated[k]
            );
            let peak = (3000..9000)
                .map(|i| c.eval(i as f32 / 10.0))
                .fold(0.0f32, f32::max);
            assert!(
                (peak - 1.0).abs() < 1e-6,
                "{file} channel {k} peaks at {peak}"
            );
        }
    }
    // unknown sensors name the known ones
    let dir = tmpdir("sensor-unknown");
    std::fs::write(dir.join("u.toml"), FIELD.replace("cie-1931", "canon-5d")).unwrap();
    let (ok, err) = spectrace(&dir, &["render", "u.toml", "-o", "u.exr"]);
    assert!(
        !ok && err.contains("camera.sensor.curves: unknown sensor \"canon-5d\""),
        "{err}"
    );
    std::fs::write(
        dir.join("s.toml"),
        FIELD.replace("shutter = \"1/100 s\"", "shutter = \"soon\""),
    )
    .unwrap();
    let (ok, err) = spectrace(&dir, &["render", "s.toml", "-o", "s.exr"]);
    assert!(
        !ok && err.contains("camera.sensor.shutter: expected a positive time"),
        "{err}"
    );
}
