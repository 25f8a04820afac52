//! RGB → spectrum → RGB round trips for the three Jakob–Hanika variants.

mod support;

use spectrace::colour::cie::{integrate_xyz, reflectance_xyz};
use spectrace::colour::spaces::xyz_to_srgb;
use spectrace::spectrum::Spectrum;
use spectrace::spectrum::rgb2spec::{albedo, illuminant, srgb_table, unbounded};
use support::curve;

/// Max |RGB_out − RGB_in| over a 21³ grid of the sRGB cube, evaluated under D65 with the CIE
/// 1931 observer, for the spectrum `make` builds.
fn worst_round_trip(make: impl Fn([f32; 3]) -> Spectrum) -> (f64, [f32; 3]) {
    let d65 = curve("cie-d65");
    let mut worst = (0.0f64, [0.0f32; 3]);
    let n = 20;
    for r in 0..=n {
        for g in 0..=n {
            for b in 0..=n {
                let rgb = [r, g, b].map(|v| v as f32 / n as f32);
                let s = make(rgb);
                // every reflectance stays in [0, 1]
                for l in (360..=830).step_by(10) {
                    let v = s.eval(l as f32);
                    assert!((0.0..=1.0).contains(&v), "{rgb:?} at {l} nm: {v}");
                }
                let out = xyz_to_srgb(reflectance_xyz(
                    |l| s.eval(l) as f64,
                    |l| d65.eval(l) as f64,
                ));
                for k in 0..3 {
                    let e = (out[k] - rgb[k] as f64).abs();
                    if e > worst.0 {
                        worst = (e, rgb);
                    }
                }
            }
        }
    }
    worst
}

/// The albedo variant, as scenes use it (table + Gauss–Newton polish).
#[test]
fn albedo_round_trip_below_1e_3() {
    let worst = worst_round_trip(|rgb| albedo(rgb).unwrap());
    println!(
        "worst albedo round-trip error {:.2e} at {:?}",
        worst.0, worst.1
    );
    assert!(
        worst.0 < 1e-3,
        "worst error {:.3e} at {:?}",
        worst.0,
        worst.1
    );
}

/// The raw table (trilinear interpolation of the 64³ coefficients, no polish), as a texture
/// lookup would use it.
#[test]
fn table_interpolation_round_trip_below_1e_3() {
    let table = srgb_table();
    let worst = worst_round_trip(|rgb| Spectrum::Rgb {
        poly: table.lookup(rgb),
        scale: 1.0,
    });
    println!(
        "worst table-only round-trip error {:.2e} at {:?}",
        worst.0, worst.1
    );
    assert!(
        worst.0 < 1e-3,
        "worst error {:.3e} at {:?}",
        worst.0,
        worst.1
    );
}

#[test]
fn unbounded_and_illuminant_round_trip() {
    let d65 = curve("cie-d65");
    for rgb in [
        [2.0f32, 0.5, 0.25],
        [0.1, 3.0, 1.0],
        [5.0, 5.0, 5.0],
        [0.3, 0.2, 0.9],
    ] {
        let s = unbounded(rgb).unwrap();
        let out = xyz_to_srgb(reflectance_xyz(
            |l| s.eval(l) as f64,
            |l| d65.eval(l) as f64,
        ));
        for k in 0..3 {
            assert!(
                (out[k] - rgb[k] as f64).abs() < 1e-3 * rgb[k].max(1.0) as f64,
                "unbounded {rgb:?} → {out:?}"
            );
        }
        // illuminant: ∫ S (x̄,ȳ,z̄) dλ is the RGB's XYZ directly (unit-luminance D65 white)
        let e = illuminant(rgb).unwrap();
        let out = xyz_to_srgb(integrate_xyz(|l| e.eval(l) as f64));
        for k in 0..3 {
            assert!(
                (out[k] - rgb[k] as f64).abs() < 1e-3 * rgb[k].max(1.0) as f64,
                "illuminant {rgb:?} → {out:?}"
            );
        }
    }
    assert_eq!(unbounded([0.0; 3]).unwrap().eval(500.0), 0.0);
}
