//! A radiometric unit test written with `spectrace::api`, as a user's test suite would hold it:
//! a flat field of 100 cd/m² of D65 must read 100 cd/m² within 3 standard errors.
//! Run: `cargo run --release --example api_exposure_check`.

use spectrace::api::{Options, Region, Scene, render};
use spectrace::units::luminance::candela_per_square_meter;

fn check() -> Result<(), spectrace::Error> {
    let scene = Scene::from_toml(
        r#"
        [camera]
        eye = [0, 0, 0]
        target = [0, 0, 1]
        fov = "40 deg"
        [film]
        width = 16
        height = 16
        [materials.black]
        type = "diffuse"
        reflectance = 0
        [[shapes]]
        type = "sphere"
        radius = 1
        material = "black"
        two_sided = true
        emission = { spectrum = "cie-d65", luminance = "100 cd/m^2", two_sided = true }
        "#,
    )?;
    let image = render(
        &scene,
        &Options {
            spp: Some(64),
            ..Options::default()
        },
    )?;
    let l = image.mean_luminance(Region::all(&image));
    let (v, se) = (
        l.value.get::<candela_per_square_meter>(),
        l.standard_error.get::<candela_per_square_meter>(),
    );
    println!("mean luminance {v:.4} cd/m² ± {se:.4} (standard error)");
    assert!((v - 100.0).abs() < 3.0 * se + 1e-9, "expected 100 cd/m²");
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
