//! A colour unit test written with `spectrace::api`: the 24 ColorChecker patches (N. Ohta's
//! measured reflectances) lit by a uniform D65 sky of 100 cd/m² are rendered, and each patch's
//! CIELAB colour must be within ΔE00 0.5 of colour-science's (ASTM E308 integration,
//! `tests/data/colorchecker_d65.csv`). A Lambertian patch under a uniform sky reflects
//! L(λ) = ρ(λ)·L_sky(λ), so the perfect reflector's Y is 100 cd/m²: the Lab white.
//! Run: `cargo run --release --example api_colorchecker_delta_e`.

use spectrace::api::{Camera, Light, Material, Options, Scene, Shape, Spectrum, metres, render};
use spectrace::colour::lab::{delta_e_2000, xyz_to_lab};
use spectrace::units::{Length, Luminance, length::meter, luminance::candela_per_square_meter};

/// (name, L, a, b) of every patch, from the colour-science table.
fn reference() -> Vec<(String, [f64; 3])> {
    let text = include_str!("../tests/data/colorchecker_d65.csv");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (name, l, a, b) = (col("name"), col("L"), col("a"), col("b"));
    lines
        .map(|row| {
            let f: Vec<&str> = row.split(',').collect();
            let num = |i: usize| f[i].trim().parse::<f64>().unwrap();
            (f[name].to_string(), [num(l), num(a), num(b)])
        })
        .collect()
}

fn check() -> Result<(), spectrace::Error> {
    let patches = reference();
    // a 6 × 4 chart of 0.9 m patches, 1 m apart, seen face-on at 10 px per metre
    let mut builder = Scene::builder()
        .camera(Camera::orthographic(
            metres([0.0, 0.0, 10.0]),
            metres([0.0; 3]),
            Length::new::<meter>(6.0),
        ))
        .film(60, 40)
        .light(
            Light::environment(Luminance::new::<candela_per_square_meter>(100.0))
                .spectrum(Spectrum::named("cie-d65")?),
        );
    for (i, (name, _)) in patches.iter().enumerate() {
        let (col, row) = ((i % 6) as f64, (i / 6) as f64);
        builder = builder
            .material(
                name,
                Material::diffuse(Spectrum::named(&format!("colorchecker:{name}"))?),
            )
            .shape(
                Shape::rectangle()
                    .scale(0.45)
                    .translate(metres([col - 2.5, 1.5 - row, 0.0]))
                    .material(name),
            );
    }
    let image = render(
        &builder.build()?,
        &Options {
            spp: Some(256),
            ..Options::default()
        },
    )?;
    // the white: Y = 100 cd/m² at D65's chromaticity (CIE 15: x = 0.3127, y = 0.3290)
    let (x, y) = (0.3127, 0.3290);
    let white = [100.0 * x / y, 100.0, 100.0 * (1.0 - x - y) / y];
    let mut worst: f64 = 0.0;
    for (i, (name, lab_ref)) in patches.iter().enumerate() {
        // the mean XYZ of the 5 × 5 pixels at the patch's centre (clear of its edges)
        let (x0, y0) = ((i % 6) * 10 + 3, (i / 6) * 10 + 3);
        let mut xyz = [0.0; 3];
        for py in y0..y0 + 5 {
            for px in x0..x0 + 5 {
                for (c, v) in image.xyz(px, py).iter().enumerate() {
                    xyz[c] += v.get::<candela_per_square_meter>() / 25.0;
                }
            }
        }
        let de = delta_e_2000(xyz_to_lab(xyz, white), *lab_ref);
        println!("{name:<16} ΔE00 {de:.3}");
        worst = worst.max(de);
        assert!(de < 0.5, "{name}: ΔE00 = {de}");
    }
    println!("worst ΔE00 {worst:.3}");
    Ok(())
}

fn main() -> Result<(), spectrace::Error> {
    check()
}

// `cargo test` runs this example as a test too (`test = true` in Cargo.toml)
#[test]
fn example_check_passes() {
    check().unwrap();
}
