//! False-colour PNGs read back against closed forms: under a 100 W point light 2 m above a
//! ρ = 0.5 Lambertian plane, the colour of a pixel decodes (through the viridis table and the
//! legend's scale) to the closed-form luminance L = ρ/π · E or illuminance E = I cos θ / r².

mod support;

use std::f64::consts::PI;

use spectrace::falsecolour::VIRIDIS;
use support::cli::{spectrace, tmpdir};
use support::render::scene_from;

const K_M: f64 = 683.002;
const CIE_Y_INTEGRAL: f64 = 106.856895;

/// The viridis index of an 8-bit colour (exact match), or panics.
fn index(c: [u8; 3]) -> usize {
    VIRIDIS
        .iter()
        .position(|&v| v == c)
        .unwrap_or_else(|| panic!("{c:?} is not a viridis colour"))
}

fn pixel(png: &std::path::Path, x: usize, y: usize) -> [u8; 3] {
    let img = spectrace::image_io::read_rgb(png).expect("png reads");
    let p = img.rgb[y * img.width + x];
    p.map(|v| (v * 255.0).round() as u8)
}

#[test]
fn false_colour_pixels_decode_to_the_closed_form() {
    let dir = tmpdir("false-colour");
    let toml = support::render::point_over_plane_toml("path");
    std::fs::write(dir.join("p.toml"), &toml).unwrap();
    let scene = scene_from(&toml);
    // E_v = I_v cos θ / r², I_v = 100 W/(4π) · K_m ∫ȳ / 470 nm (equal energy over 360–830 nm)
    let iv = 100.0 / (4.0 * PI) * K_M * CIE_Y_INTEGRAL / 470.0;
    for (kind, scale, max) in [
        ("luminance", "linear", 200.0),
        ("illuminance", "linear", 1500.0),
        ("illuminance", "log", 1000.0),
    ] {
        let (ok, err) = spectrace(
            &dir,
            &[
                "render",
                "p.toml",
                "-o",
                "p.exr",
                "--quiet",
                "--spp",
                "64",
                "--false-colour",
                kind,
                "--false-colour-scale",
                scale,
                "--false-colour-max",
                &max.to_string(),
                "--false-colour-decades",
                "2",
            ],
        );
        assert!(ok, "{err}");
        let png = dir.join("p.false.png");
        for (px, py) in [(16, 16), (4, 16), (20, 27), (9, 9)] {
            let (r2, cos) = support::render::plane_point(&scene, px, py);
            let e = iv * cos / r2;
            let truth = if kind == "luminance" { 0.5 / PI * e } else { e };
            let k = index(pixel(&png, px, py)) as f64 / 255.0;
            let got = if scale == "linear" {
                k * max
            } else {
                max / 100.0 * 100f64.powf(k)
            };
            // one colour step is 1/255 of the scale (linear) or of its two decades (log);
            // allow two steps and 1 % for noise and the pixel's footprint
            let step = if scale == "linear" {
                max / 255.0
            } else {
                truth * (100f64.powf(1.0 / 255.0) - 1.0)
            };
            assert!(
                (got - truth).abs() < 2.0 * step + 0.01 * truth,
                "{kind} {scale} ({px},{py}): {got} vs {truth}"
            );
        }
    }
    // errors: a false-colour PNG without a kind; a non-positive top
    let (ok, err) = spectrace(
        &dir,
        &[
            "render",
            "p.toml",
            "-o",
            "q.exr",
            "--false-colour-png",
            "x.png",
        ],
    );
    assert!(
        !ok && err.contains("--false-colour-png needs --false-colour"),
        "{err}"
    );
    let (ok, err) = spectrace(
        &dir,
        &[
            "render",
            "p.toml",
            "-o",
            "q.exr",
            "--false-colour",
            "luminance",
            "--false-colour-max",
            "0",
        ],
    );
    assert!(
        !ok && err.contains("--false-colour-max must be a positive number"),
        "{err}"
    );
}
