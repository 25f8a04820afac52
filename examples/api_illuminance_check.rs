//! A radiometric unit test written with `spectrace::api`: the illuminance a 1000 lm isotropic
//! lamp 2 m above a work plane gives there, against the inverse-square cosine law
//! E = I·cos³θ / h² with I = Φ/4π, at the nadir and 1 m and 2 m to the side.
//! Run: `cargo run --release --example api_illuminance_check`.

use spectrace::api::{
    Camera, Light, Material, MeasureOptions, Meter, Scene, Shape, degrees, measure, metres,
};
use spectrace::units::{LuminousFlux, illuminance::lux, luminous_flux::lumen};

fn check() -> Result<(), spectrace::Error> {
    let (flux, h) = (1000.0, 2.0);
    let mut builder = Scene::builder()
        .camera(Camera::perspective(
            metres([0.0, 1.0, -4.0]),
            metres([0.0; 3]),
            degrees(40.0),
        ))
        // a black floor just below the meters: no light comes back up
        .material("black", Material::diffuse(0.0))
        .shape(
            Shape::rectangle()
                .scale(10.0)
                .rotate([1.0, 0.0, 0.0], degrees(-90.0))
                .translate(metres([0.0, -0.01, 0.0]))
                .material("black"),
        )
        .light(
            Light::point(metres([0.0, h, 0.0]), LuminousFlux::new::<lumen>(flux))
                .spectrum(spectrace::Spectrum::named("cie-d:4000K")?),
        );
    let offsets = [0.0, 1.0, 2.0];
    for d in offsets {
        builder = builder.meter(Meter::point(
            &format!("{d} m"),
            metres([d, 0.0, 0.0]),
            [0.0, 1.0, 0.0],
        ));
    }
    let readings = measure(&builder.build()?, &MeasureOptions::default())?;
    for (r, d) in readings.iter().zip(offsets) {
        let cos = h / (h * h + d * d).sqrt();
        let expected = flux / (4.0 * std::f64::consts::PI) * cos.powi(3) / (h * h);
        let (e, se) = (
            r.illuminance.value.get::<lux>(),
            r.illuminance.standard_error.get::<lux>(),
        );
        println!(
            "{}: {e:.5} lx ± {se:.5} (closed form {expected:.5} lx)",
            r.meter
        );
        assert!(
            (e - expected).abs() < 3.0 * se + 1e-4 * expected,
            "{}: {e} lx, expected {expected} lx",
            r.meter
        );
    }
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
