//! The README's ten-line library test (section "Rust library API"), verbatim, and a check that
//! the README still shows exactly this code.

use spectrace::units::{
    LuminousFlux, luminance::candela_per_square_meter as cd_m2, luminous_flux::lumen,
};
use spectrace::*;

#[rustfmt::skip]
// README begin
#[test]
fn grey_floor_under_an_800_lm_lamp() -> Result<(), Error> {
    let scene = Scene::builder()
        .camera(Camera::perspective(metres([0.0, 1.0, 0.0]), metres([0.0; 3]), degrees(2.0)).up([0.0, 0.0, 1.0]))
        .film(16, 16)
        .material("grey", Material::diffuse(0.18))
        .shape(Shape::rectangle().scale(10.0).rotate([1.0, 0.0, 0.0], degrees(-90.0)).material("grey"))
        .light(Light::point(metres([0.0, 2.0, 0.0]), LuminousFlux::new::<lumen>(800.0)).spectrum(Spectrum::named("cie-a")?))
        .build()?;
    let image = render(&scene, &Options { spp: Some(64), ..Options::default() })?;
    let l = image.mean_luminance(Region::all(&image)); // cd/m², with its standard error
    let expected = 0.18 * 800.0 / (4.0 * std::f64::consts::PI.powi(2) * 4.0); // L = ρΦ/(4π²h²)
    println!("{:.5} ± {:.5} cd/m², closed form {expected:.5}", l.value.get::<cd_m2>(), l.standard_error.get::<cd_m2>());
    assert!((l.value.get::<cd_m2>() - expected).abs() < 3.0 * l.standard_error.get::<cd_m2>());
    Ok(())
}
// README end

#[test]
fn the_readme_shows_this_test() {
    let me = include_str!("readme_api.rs");
    let code = me.split("// README begin\n").nth(1).unwrap();
    let code = code.split("// README end").next().unwrap();
    let readme = include_str!("../README.md");
    assert!(
        readme.contains(code),
        "README.md's Rust example differs from tests/readme_api.rs"
    );
}
