//! pbrt-v4's pixel sensor (`PixelSensor` of pbrt-v4's `src/pbrt/film.h` and `film.cpp`), for
//! its scenes' `"string sensor"`, `"float iso"` and `"float whitebalance"`: its named camera
//! curves, its daylight illuminant for white balance, and the matrix its RGB film applies.
//!
//! pbrt-v4's film value of a spectral radiance L is `M · ratio · (∫ s_k L dλ)_k`: s_k the
//! sensor's curves (x̄, ȳ, z̄ for `cie1931`, a camera's raw r, g, b sensitivities otherwise),
//! `ratio` = exposure time · ISO / 100, and M = (linear sRGB from XYZ) · (XYZ from sensor RGB).
//! XYZ from sensor RGB is, for `cie1931`, the identity or, with `whitebalance` T, pbrt-v4's
//! Bradford von Kries transform from the chromaticity of its daylight at T to sRGB's white; for
//! a camera, the least-squares 3 × 3 fit that carries the 24 ColorChecker swatches' camera RGB
//! under the daylight at T (default 6500 K) to their XYZ under sRGB's D65, both sides divided
//! by the illuminant's green (ȳ for XYZ) response and the XYZ side then scaled by the
//! illuminant's ȳ over its green. Its sums run over 360–830 nm at 1 nm, as pbrt-v4's do.

use std::sync::Arc;

use glam::{DMat3, DVec3};

use crate::colour::cie::cmf;
use crate::spectrum::{PiecewiseLinear, Spectrum};

/// A pbrt-v4 table (nm, value) extended with its end values to 359 and 831 nm, as pbrt-v4's
/// `PiecewiseLinearSpectrum::FromInterleaved` extends it; None if it is not a valid table.
pub fn extended_table(mut l: Vec<f32>, mut v: Vec<f32>) -> Option<PiecewiseLinear> {
    if l.is_empty() || l.len() != v.len() {
        return None;
    }
    if l[0] > 360.0 {
        l.insert(0, 359.0);
        v.insert(0, v[0]);
    }
    if l[l.len() - 1] < 830.0 {
        l.push(831.0);
        v.push(v[v.len() - 1]);
    }
    PiecewiseLinear::new(l, v).ok()
}

/// [`extended_table`] of f64 columns as a spectrum.
fn extended(l: &[f64], v: &[f64]) -> Option<Spectrum> {
    let f = |c: &[f64]| c.iter().map(|&x| x as f32).collect();
    extended_table(f(l), f(v)).map(|c| Spectrum::Piecewise(Arc::new(c)))
}

/// The r, g, b sensitivities of one of pbrt-v4's named camera sensors (`canon_eos_5d_mkiv`, …;
/// `spectra/pbrt/cameras/`), or None for a name pbrt-v4 does not know.
pub fn camera_curves(name: &str) -> Option<[Spectrum; 3]> {
    let (_, file) = crate::data::embedded::PBRT_CAMERAS
        .iter()
        .find(|(n, _)| *n == name)?;
    let t = crate::data::embedded_table(*file);
    let l = t.column(0);
    let c = |k: usize| extended(&l, &t.column(k));
    Some([c(1)?, c(2)?, c(3)?])
}

/// The names of pbrt-v4's camera sensors, for error messages.
pub fn camera_names() -> Vec<&'static str> {
    crate::data::embedded::PBRT_CAMERAS
        .iter()
        .map(|(n, _)| *n)
        .collect()
}

/// pbrt-v4's `Spectra::D(T)` (relative): the temperature is first scaled by 1.4388/1.4380 to a
/// correlated colour temperature; below 4000 K it is a blackbody, otherwise CIE daylight
/// S0 + M1·S1 + M2·S2 with x_D(T) of CIE 015 and M1, M2 not rounded.
pub fn daylight(t_k: f64) -> Option<Spectrum> {
    let cct = t_k * 1.4388 / 1.4380;
    if !(cct > 0.0 && cct.is_finite()) {
        return None;
    }
    if cct < 4000.0 {
        let l: Vec<f64> = (360..=830).map(f64::from).collect();
        let v: Vec<f64> = l
            .iter()
            .map(|&x| crate::spectrum::blackbody::planck(x, cct))
            .collect();
        let peak = v.iter().cloned().fold(0.0, f64::max);
        return extended(&l, &v.iter().map(|x| x / peak).collect::<Vec<_>>());
    }
    let [m1, m2] = crate::spectrum::named::daylight_m1_m2(cct);
    let b = crate::data::embedded_table(crate::spectrum::data::embedded::CIE_DAYLIGHT_BASIS);
    let (l, s0, s1, s2) = (b.column(0), b.column(1), b.column(2), b.column(3));
    let v: Vec<f64> = (0..l.len())
        .map(|i| (s0[i] + m1 * s1[i] + m2 * s2[i]) * 0.01)
        .collect();
    extended(&l, &v)
}

/// Σ over λ = 360…830 nm at 1 nm of f(λ), as pbrt-v4's `InnerProduct` and `ProjectReflectance`.
fn sum(f: impl Fn(f32) -> f64) -> f64 {
    (360..=830).map(|l| f(l as f32)).sum()
}

/// The chromaticity xy of a spectrum (pbrt-v4's `SpectrumToXYZ(s).xy()`).
fn xy(s: &Spectrum) -> [f64; 2] {
    let v = [0, 1, 2].map(|k| sum(|l| cmf().eval(l)[k] as f64 * s.eval(l) as f64));
    let t = v[0] + v[1] + v[2];
    [v[0] / t, v[1] / t]
}

fn xyz_of_xy(c: [f64; 2]) -> [f64; 3] {
    [c[0] / c[1], 1.0, (1.0 - c[0] - c[1]) / c[1]]
}

/// pbrt-v4's RGB film matrix, linear sRGB from sensor RGB (see the module doc): `curves` None
/// for `cie1931`; `illum` the white-balance daylight (None: `cie1931` without white balance).
/// Fails if the camera fit is singular.
pub fn output_matrix(
    curves: Option<&[Spectrum; 3]>,
    illum: Option<&Spectrum>,
) -> Result<DMat3, String> {
    let rgb_from_xyz = crate::colour::spaces::SRGB.xyz_to_rgb();
    let d65 = super::d65()?;
    let white = xy(&d65);
    let (curves, illum) = match (curves, illum) {
        (None, None) => return Ok(rgb_from_xyz),
        (None, Some(i)) => {
            let wb = crate::colour::spaces::bradford(xyz_of_xy(xy(i)), xyz_of_xy(white));
            return Ok(rgb_from_xyz * wb);
        }
        (Some(c), Some(i)) => (c, i),
        (Some(_), None) => return Err("a camera sensor needs its white-balance daylight".into()),
    };
    let sw = crate::data::embedded_table(crate::data::embedded::PBRT_SWATCHES);
    let l = sw.column(0);
    let ill = |x: f32| illum.eval(x) as f64;
    let g_white = sum(|x| curves[1].eval(x) as f64 * ill(x));
    let y_white = sum(|x| cmf().y_bar(x) as f64 * ill(x));
    let y_d65 = sum(|x| cmf().y_bar(x) as f64 * d65.eval(x) as f64);
    if !(g_white > 0.0) {
        return Err(
            "the camera's green channel does not respond to the white-balance daylight".into(),
        );
    }
    let mut pairs = Vec::new();
    for k in 1..sw.columns.len() {
        let refl = extended(&l, &sw.column(k)).ok_or("a swatch table is not increasing")?;
        let lit = |x: f32| refl.eval(x) as f64 * ill(x);
        let cam = DVec3::from([0, 1, 2].map(|c| sum(|x| curves[c].eval(x) as f64 * lit(x))));
        let xyz = [0, 1, 2]
            .map(|c| sum(|x| cmf().eval(x)[c] as f64 * refl.eval(x) as f64 * d65.eval(x) as f64));
        let xyz = DVec3::from(xyz) / y_d65 * (y_white / g_white);
        pairs.push((cam / g_white, xyz));
    }
    Ok(rgb_from_xyz * super::least_squares(pairs)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pbrt_camera_reads() {
        for n in camera_names() {
            let c = camera_curves(n).unwrap();
            assert!(c.iter().all(|s| s.eval(550.0) >= 0.0), "{n}");
            output_matrix(Some(&c), daylight(6500.0).as_ref()).unwrap();
        }
        assert!(camera_curves("canon_eos_6d").is_none());
    }

    /// Without white balance the CIE sensor's matrix is sRGB's; balanced to the daylight
    /// whose chromaticity is D65's it stays so (pbrt-v4's white is D65's xy).
    #[test]
    fn cie_sensor_matrix() {
        let m = output_matrix(None, None).unwrap();
        let s = crate::colour::spaces::SRGB.xyz_to_rgb();
        assert!((m - s).abs().to_cols_array().iter().all(|&d| d < 1e-12));
        let m = output_matrix(None, Some(&crate::sensor::d65().unwrap())).unwrap();
        assert!((m - s).abs().to_cols_array().iter().all(|&d| d < 1e-9));
    }

    /// pbrt-v4's daylight at 6500 K has (after its 1.4388/1.4380 scaling) the chromaticity of
    /// CIE daylight at 6503.6 K: x_D = 0.31271 (CIE 015's D65 is 0.31272 at 6504 K).
    #[test]
    fn daylight_chromaticity() {
        let c = xy(&daylight(6500.0).unwrap());
        assert!(
            (c[0] - 0.3127).abs() < 3e-4 && (c[1] - 0.3290).abs() < 3e-4,
            "{c:?}"
        );
        // a blackbody below 4000 K: Planck's locus at 2856 K is illuminant A's xy
        let a = xy(&daylight(2856.0 * 1.4380 / 1.4388).unwrap());
        assert!(
            (a[0] - 0.44757).abs() < 5e-4 && (a[1] - 0.40745).abs() < 5e-4,
            "{a:?}"
        );
    }
}
