//! Tests of `envmap`.

use super::*;
use crate::spectrum::WavelengthRange;

fn map(rgb: &[[f32; 3]], w: usize, h: usize) -> EnvMapLight {
    EnvMapLight::new(w, h, rgb, Spectrum::Constant(1.0), Mat3::IDENTITY).unwrap()
}

fn wl() -> SampledWavelengths<4> {
    SampledWavelengths {
        lambda: [450.0, 520.0, 600.0, 680.0],
        pdf: [1.0; 4],
    }
}

/// Mitsuba's frame: u = 0 along −z, ¼ along +x; v = 0 at +y; columns centred at (i + ½)/W.
#[test]
fn directions_and_pixels_as_mitsuba() {
    let (w, h) = (4, 3);
    // column i has grey value i + 1 in every row
    let rgb: Vec<[f32; 3]> = (0..w * h)
        .map(|k| [(k % w) as f32 * 0.1 + 0.1; 3])
        .collect();
    let m = map(&rgb, w, h);
    let at = |d: Vec3| m.escaped(d.normalize(), &wl()).0[0];
    // the equator toward -z is u = 0: half column 3, half column 0
    assert!((at(Vec3::new(0.0, 0.0, -1.0)) - 0.5 * (0.4 + 0.1)).abs() < 1e-4);
    // u = 1/8 (column 0's centre): atan2(x, -z) = π/4
    assert!((at(Vec3::new(1.0, 0.0, -1.0)) - 0.1).abs() < 1e-4);
    // +x is u = 1/4: halfway between columns 0 and 1
    assert!((at(Vec3::X) - 0.15).abs() < 1e-4);
}

/// The sampled density integrates to 1 over the sphere and matches `pdf_li`; a constant map
/// integrates to 4π times its radiance.
#[test]
fn pdf_is_normalised_and_consistent() {
    let (w, h) = (8, 5);
    let rgb: Vec<[f32; 3]> = (0..w * h)
        .map(|k| {
            if k % 7 == 3 {
                [3.0, 1.0, 0.2]
            } else {
                [0.2, 0.3, 0.4]
            }
        })
        .collect();
    let m = map(&rgb, w, h);
    let n = 200;
    let mut integral = 0.0f64;
    for i in 0..n {
        for j in 0..2 * n {
            // midpoint rule over (θ, φ): dω = sin θ dθ dφ
            let theta = PI * (i as f32 + 0.5) / n as f32;
            let phi = 2.0 * PI * (j as f32 + 0.5) / (2 * n) as f32;
            let d = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            integral += m.pdf_li(d) as f64
                * theta.sin() as f64
                * (std::f64::consts::PI / n as f64)
                * (2.0 * std::f64::consts::PI / (2 * n) as f64);
        }
    }
    assert!((integral - 1.0).abs() < 2e-3, "∫ pdf dω = {integral}");
    for k in 0..50 {
        let u = Vec2::new((k as f32 * 0.618_034).fract(), (k as f32 + 0.5) / 50.0);
        if let Some(s) = m.sample_li(&wl(), u) {
            let p = m.pdf_li(s.wi);
            assert!((s.pdf / p - 1.0).abs() < 1e-3, "{} vs {p}", s.pdf);
        }
    }
    let white = map(&vec![[1.0; 3]; w * h], w, h);
    let r = WavelengthRange {
        min_nm: 400.0,
        max_nm: 700.0,
    };
    let e = white.band_radiant_exitance(r);
    // RGB (1,1,1): sigmoid ½ × scale 2 = 1 at every wavelength
    let want = 4.0 * std::f64::consts::PI * 300.0;
    assert!((e / want - 1.0).abs() < 2e-3, "{e} vs {want}");
}
