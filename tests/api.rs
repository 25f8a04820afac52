//! The library API (`spectrace::api`) as a user's radiometric test uses it: a closed-form
//! luminance per pixel, the region mean within its standard error over several seeds, spectral
//! radiance per bin, and located errors.

mod support;

use std::f64::consts::PI;

use spectrace::api::{Options, Region, Scene, render};
use spectrace::units::Length;
use spectrace::units::length::nanometer;
use spectrace::units::luminance::candela_per_square_meter;
use spectrace::units::spectral_radiance::watt_per_square_meter_steradian_nanometer;

const K_M: f64 = 683.002;
const CIE_Y_INTEGRAL: f64 = 106.856895;

#[test]
fn luminance_of_a_plane_under_a_point_light() {
    let scene = Scene::from_toml(&support::render::point_over_plane_toml("path")).unwrap();
    let img = render(
        &scene,
        &Options {
            spp: Some(256),
            ..Default::default()
        },
    )
    .unwrap();
    let inner = scene.inner();
    for (px, py) in [(16, 16), (4, 16), (20, 27)] {
        let (r2, cos) = support::render::plane_point(inner, px, py);
        let l_band = 0.5 / PI * (100.0 / (4.0 * PI)) * cos / r2;
        let y = l_band * K_M * CIE_Y_INTEGRAL / 470.0;
        let got = img.luminance(px, py).get::<candela_per_square_meter>();
        assert!(
            (got / y - 1.0).abs() < 0.01,
            "({px},{py}): {got} vs {y} cd/m²"
        );
    }
}

/// A uniform 100 cd/m² field: the region mean lies within 2 standard errors for most seeds,
/// and the standard error is small (the per-pixel variance of a scrambled Sobol mean is at
/// most the independent samples' one, so the bound is conservative).
#[test]
fn region_mean_and_standard_error() {
    let scene = Scene::from_toml(
        r#"
[camera]
eye = [0, 0, 0]
target = [0, 0, 1]
fov = "40 deg"
[film]
width = 8
height = 8
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "sphere"
radius = 1
material = "black"
two_sided = true
emission = { spectrum = "cie-a", luminance = "100 cd/m^2", two_sided = true }
"#,
    )
    .unwrap();
    let mut covered = 0;
    for seed in 0..8 {
        let img = render(
            &scene,
            &Options {
                spp: Some(16),
                seed,
                ..Default::default()
            },
        )
        .unwrap();
        let e = img.mean_luminance(Region::all(&img));
        let (v, se) = (
            e.value.get::<candela_per_square_meter>(),
            e.standard_error.get::<candela_per_square_meter>(),
        );
        assert!(se > 0.0 && se < 1.0, "se {se}");
        covered += ((v - 100.0).abs() < 2.0 * se) as usize;
    }
    assert!(covered >= 7, "{covered} of 8 within 2 standard errors");
}

#[test]
fn spectral_radiance_and_errors() {
    // the furnace: L = Le/(1 − ρ) = 2/470 W·m⁻²·sr⁻¹·nm⁻¹ at every wavelength
    let scene = Scene::from_toml(&support::render::furnace_toml("path", 0.5, 64)).unwrap();
    let img = render(
        &scene,
        &Options {
            spectral_bins: Some(47),
            ..Default::default()
        },
    )
    .unwrap();
    let at = |nm: f64| {
        let mut s = 0.0;
        for y in 0..img.height() {
            for x in 0..img.width() {
                s += img
                    .spectral_radiance(x, y, Length::new::<nanometer>(nm))
                    .unwrap()
                    .get::<watt_per_square_meter_steradian_nanometer>();
            }
        }
        s / (img.width() * img.height()) as f64
    };
    for nm in [450.0, 555.0, 650.0] {
        assert!(
            (at(nm) / (2.0 / 470.0) - 1.0).abs() < 0.02,
            "{nm} nm: {}",
            at(nm)
        );
    }
    assert!(
        img.spectral_radiance(0, 0, Length::new::<nanometer>(900.0))
            .is_none()
    );
    let e = Scene::from_toml("[camera]\neye = [0, 0, 0]\n")
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("camera"), "{e}");
}

#[test]
fn builder_is_the_toml_format() {
    // the builder's scene and the same scene written by hand render the same pixels, bit for bit
    use spectrace::api::{Camera, Light, Material, Shape, Spectrum, degrees, metres};
    use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    let built = Scene::builder()
        .camera(
            Camera::perspective(metres([0.0, 1.0, 0.0]), metres([0.0; 3]), degrees(30.0))
                .up([0.0, 0.0, 1.0]),
        )
        .film(8, 8)
        .material("grey", Material::diffuse(0.18))
        .shape(
            Shape::rectangle()
                .scale(10.0)
                .rotate([1.0, 0.0, 0.0], degrees(-90.0))
                .material("grey"),
        )
        .light(
            Light::point(metres([0.0, 2.0, 0.0]), LuminousFlux::new::<lumen>(800.0))
                .spectrum(Spectrum::named("cie-a").unwrap()),
        )
        .build()
        .unwrap();
    let written = Scene::from_toml(
        r#"
        [camera]
        eye = [0, 1, 0]
        target = [0, 0, 0]
        up = [0, 0, 1]
        fov = "30 deg"
        [film]
        width = 8
        height = 8
        [materials.grey]
        type = "diffuse"
        reflectance = 0.18
        [[shapes]]
        type = "rectangle"
        material = "grey"
        transform = [{ scale = 10 }, { rotate = { axis = [1, 0, 0], angle = "-90 deg" } }]
        [[lights]]
        type = "point"
        position = [0, 2, 0]
        power = "800 lm"
        spectrum = "cie-a"
        "#,
    )
    .unwrap();
    let o = Options {
        spp: Some(4),
        ..Default::default()
    };
    let (a, b) = (render(&built, &o).unwrap(), render(&written, &o).unwrap());
    assert_eq!(a.xyz_cd_m2(), b.xyz_cd_m2());
    // and the closed form: L = ρΦ/(4π²h²) straight below the light (cos³θ ≈ 0.9992 at this pixel)
    let l = a.luminance(4, 4).get::<candela_per_square_meter>();
    let want = 0.18 * 800.0 / (4.0 * PI * PI * 4.0);
    assert!((l / want - 1.0).abs() < 0.01, "{l} vs {want}");
}

#[test]
fn builder_errors_name_the_field() {
    use spectrace::api::{Camera, Light, Material, Shape, degrees, metres};
    use spectrace::units::{Power, power::watt};
    let e = Scene::builder()
        .camera(Camera::perspective(
            metres([0.0, 0.0, -1.0]),
            metres([0.0; 3]),
            degrees(30.0),
        ))
        .material("m", Material::diffuse(0.5))
        .shape(Shape::sphere(metres([0.0; 3]), metres([1.0; 3])[0]).material("nope"))
        .light(Light::point(metres([0.0; 3]), Power::new::<watt>(1.0)))
        .build()
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("scene builder:") && e.contains("shapes[0].material") && e.contains("nope"),
        "{e}"
    );
    let e = spectrace::Spectrum::named("colorchecker:rde").unwrap_err();
    assert!(e.to_string().contains("colorchecker:red"), "{e}");
}

#[test]
fn out_of_range_options_and_lookups_are_errors() {
    use spectrace::api::{Error, Ior, MeasureOptions, measure, spectrum};
    use std::time::Duration;
    let scene = Scene::from_toml(&support::render::furnace_toml("path", 0.5, 1)).unwrap();
    let bad = [
        (
            Options {
                spp: Some(0),
                ..Default::default()
            },
            "spp must be at least 1",
        ),
        (
            Options {
                spp: Some((1 << 24) + 1),
                ..Default::default()
            },
            "spp must be at most",
        ),
        (
            Options {
                threads: Some(0),
                ..Default::default()
            },
            "threads must be at least 1",
        ),
        (
            Options {
                spectral_bins: Some(1001),
                ..Default::default()
            },
            "spectral_bins must be at most 1000",
        ),
        (
            Options {
                time_limit: Some(Duration::ZERO),
                ..Default::default()
            },
            "time_limit",
        ),
        (
            Options {
                target_error: Some(1.0),
                ..Default::default()
            },
            "target_error 1",
        ),
        (
            Options {
                target_error: Some(f64::NAN),
                ..Default::default()
            },
            "target_error NaN",
        ),
    ];
    for (o, want) in bad {
        match render(&scene, &o) {
            Err(Error::Options(m)) => assert!(m.contains(want), "{m} (expected {want})"),
            other => panic!("{o:?}: {:?}", other.map(|_| ())),
        }
    }
    for o in [
        MeasureOptions {
            samples: 0,
            ..Default::default()
        },
        MeasureOptions {
            threads: Some(0),
            ..Default::default()
        },
    ] {
        assert!(
            matches!(measure(&scene, &o), Err(Error::Options(_))),
            "{o:?}"
        );
    }
    let e = Ior::glass("N-BK8").unwrap_err().to_string();
    assert!(e.contains("N-BK7"), "{e}");
    let e = spectrum("cie-d65", &[Length::new::<nanometer>(-5.0)]).unwrap_err();
    assert!(matches!(e, Error::Options(_)), "{e}");
}
