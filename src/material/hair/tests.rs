//! Unit tests of the fibre model.

use super::*;

/// The pigment curves in normalised wavelength equal Mitsuba's in nm.
#[test]
fn pigment_polynomials_change_variable_exactly() {
    let s = Hair::pigments(1.0, 1.0);
    for l in [360.0f64, 450.0, 600.0, 830.0] {
        let x = (EUMELANIN_NM[0] * l + EUMELANIN_NM[1]) * l + EUMELANIN_NM[2];
        let want = 0.5 + x / (2.0 * (1.0 + x * x).sqrt());
        assert!((s[0].eval(l as f32) as f64 - want).abs() < 1e-4, "{l}");
    }
}

/// Without absorption the lobes' attenuations sum to 1 (Chiang's A_p series is a partition
/// of the light that enters: f + (1 − f)²(1 + f) + (1 − f)f² = 1).
#[test]
fn attenuations_partition_the_light() {
    let hair = Hair::new(
        [Spectrum::Constant(0.0), Spectrum::Constant(0.0)],
        1.55,
        0.3,
        0.3,
        0.0,
    );
    for view in [Vec3::new(0.3, 0.2, 0.9), Vec3::new(-0.8, -0.5, 0.3)] {
        let inc = hair.incident(view.normalize(), 0.0);
        let a = hair.attenuation::<4>(&inc, SampledSpectrum::zero());
        let sum: f32 = a.iter().map(|a| a[0]).sum();
        assert!((sum - 1.0).abs() < 1e-5, "{sum}");
    }
}
