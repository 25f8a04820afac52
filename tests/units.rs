//! Quantity strings and radiant ↔ luminous conversions.

use spectrace::spectrum::photometry::{
    luminous_efficacy, luminous_flux_monochromatic, radiant_power_monochromatic, radiant_power_of,
};
use spectrace::units::parse::{Dimension, QuantityError, parse, parse_any};
use spectrace::units::*;

#[test]
fn issue_examples_parse_to_si() {
    let cases: [(&str, Dimension, f64); 10] = [
        ("100 W", Dimension::Power, 100.0),
        ("550 nm", Dimension::Length, 550e-9),
        ("0.55 um", Dimension::Length, 0.55e-6),
        ("6500 K", Dimension::Temperature, 6500.0),
        ("1200 lm", Dimension::LuminousFlux, 1200.0),
        ("45 deg", Dimension::Angle, std::f64::consts::FRAC_PI_4),
        ("2.5 mm", Dimension::Length, 2.5e-3),
        ("800 cd/m^2", Dimension::Luminance, 800.0),
        ("3 W/sr", Dimension::RadiantIntensity, 3.0),
        ("10 lx", Dimension::Illuminance, 10.0),
    ];
    for (s, dim, si) in cases {
        let q = parse_any(s, dim).unwrap();
        assert_eq!(q.dimension, dim, "{s}");
        assert!(
            (q.si - si).abs() <= 1e-12 * si.abs(),
            "{s}: {} vs {si}",
            q.si
        );
    }
    let p: Power = parse("100 W").unwrap();
    assert_eq!(p.get::<power::watt>(), 100.0);
    let l: Luminance = parse("800 cd/m^2").unwrap();
    assert_eq!(l.get::<luminance::candela_per_square_meter>(), 800.0);
    let l: Length = parse("550nm").unwrap();
    assert!((l.get::<length::nanometer>() - 550.0).abs() < 1e-9);
    let r: SpectralRadiance = parse("0.5 W/m^2/sr/nm").unwrap();
    assert!(
        (r.get::<spectral_radiance::watt_per_square_meter_steradian_nanometer>() - 0.5).abs()
            < 1e-12
    );
}

#[test]
fn wrong_dimension_is_rejected_with_both_dimensions_named() {
    let e = parse::<Power>("100 nm").unwrap_err();
    assert!(matches!(
        e,
        QuantityError::WrongDimension {
            expected: Dimension::Power,
            found: Dimension::Length,
            ..
        }
    ));
    let msg = e.to_string();
    assert!(
        msg.contains("\"100 nm\"") && msg.contains("length") && msg.contains("radiant power"),
        "{msg}"
    );
    assert!(
        parse::<Radiance>("10 W/m^2").is_err(),
        "irradiance is not radiance"
    );
    assert!(
        parse::<LuminousFlux>("10 cd").is_err(),
        "candela is not lumen"
    );
    assert!(
        parse::<Illuminance>("10 cd/m^2").is_err(),
        "luminance is not illuminance"
    );
    assert!(
        parse::<RadiantIntensity>("3 W").is_err(),
        "power is not intensity"
    );
}

#[test]
fn missing_unknown_and_non_finite_are_rejected() {
    assert!(matches!(
        parse::<Power>("100"),
        Err(QuantityError::MissingUnit { .. })
    ));
    assert!(matches!(
        parse::<Power>("100 parsecs"),
        Err(QuantityError::UnknownUnit { .. })
    ));
    assert!(matches!(
        parse::<Power>("NaN W"),
        Err(QuantityError::NonFinite { .. })
    ));
    assert!(matches!(
        parse::<Power>("inf W"),
        Err(QuantityError::NonFinite { .. })
    ));
    assert!(matches!(
        parse::<Power>("1e999 W"),
        Err(QuantityError::NonFinite { .. })
    ));
    assert!(matches!(
        parse::<Power>("W"),
        Err(QuantityError::NoNumber { .. })
    ));
    assert!(matches!(
        parse::<Power>(""),
        Err(QuantityError::Empty { .. })
    ));
    assert!(matches!(
        parse::<Power>("1.2.3 W"),
        Err(QuantityError::NoNumber { .. })
    ));
    let msg = parse::<Power>("100 parsecs").unwrap_err().to_string();
    assert!(
        msg.contains("parsecs") && msg.contains("radiant power"),
        "{msg}"
    );
}

#[test]
fn one_lumen_at_555_nm_is_1_over_683_002_watt() {
    // ȳ(555 nm) = 1 in the CIE 1931 table, so 1 lm of 555 nm light is 1/K_m W.
    let lambda: Length = parse("555 nm").unwrap();
    let w = radiant_power_monochromatic(LuminousFlux::new::<luminous_flux::lumen>(1.0), lambda);
    assert!(
        (w.get::<power::watt>() - 1.0 / 683.002).abs() < 1e-12,
        "{:?}",
        w
    );
    let back = luminous_flux_monochromatic(w, lambda);
    assert!((back.get::<luminous_flux::lumen>() - 1.0).abs() < 1e-12);
    // no luminous flux beyond the CIE range
    let ir: Length = parse("900 nm").unwrap();
    assert_eq!(
        luminous_flux_monochromatic(Power::new::<power::watt>(1.0), ir)
            .get::<luminous_flux::lumen>(),
        0.0
    );
}

#[test]
fn equal_energy_white_efficacy() {
    // A flat spectrum over 360–830 nm: K = K_m ∫ȳ / 470 nm = 683.002 × 106.8569 / 470 lm/W.
    let flat = spectrace::spectrum::Spectrum::Constant(1.0);
    let k = luminous_efficacy(&flat, 360.0, 830.0);
    assert!((k - 683.002 * 106.856895 / 470.0).abs() < 0.01, "{k}");
    let p = radiant_power_of(
        LuminousFlux::new::<luminous_flux::lumen>(k),
        &flat,
        360.0,
        830.0,
    );
    assert!((p.get::<power::watt>() - 1.0).abs() < 1e-9);
}

#[test]
fn typed_products_have_the_right_dimension() {
    // radiance × area × solid angle is a power (W); the kinds do not block multiplication.
    let l = Radiance::new::<radiance::watt_per_square_meter_steradian>(2.0);
    let a = Area::new::<area::square_meter>(3.0);
    let w = SolidAngle::new::<solid_angle::steradian>(0.5);
    let p: Power = l * a * w;
    assert_eq!(p.get::<power::watt>(), 3.0);
}
