//! CIE 1931 2° colour-matching functions and the film's photometric calibration
//! (`../shared/PHYSICS.md`, "From spectrum to film").

use std::sync::OnceLock;

use crate::data::{embedded, embedded_table};

/// Maximum luminous efficacy K_m, lm/W (683 lm/W exactly at 540 THz = 555.016 nm).
pub const K_M: f64 = 683.002;
/// ∫ȳ(λ) dλ over 360–830 nm at 1 nm, nm (the value the film's XYZ normalisation refers to).
pub const CIE_Y_INTEGRAL: f64 = 106.856_895;
/// First and last wavelength of the CIE table, nm.
pub const CIE_MIN_NM: f32 = 360.0;
pub const CIE_MAX_NM: f32 = 830.0;

/// The colour-matching functions x̄, ȳ, z̄ at 1 nm from 360 to 830 nm (dimensionless,
/// ȳ(555 nm) = 1). Zero outside that range.
pub struct Cmf {
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
}

impl Cmf {
    fn load() -> Self {
        let t = embedded_table(embedded::CIE_1931_2DEG);
        let l = t.column(0);
        // The loader relies on the table's 1 nm spacing from 360 nm; checked by a test.
        debug_assert!(l.iter().enumerate().all(|(i, &v)| v == 360.0 + i as f64));
        let col = |i: usize| t.column(i).iter().map(|&v| v as f32).collect();
        Self {
            x: col(1),
            y: col(2),
            z: col(3),
        }
    }

    /// Number of tabulated wavelengths (471).
    pub fn len(&self) -> usize {
        self.y.len()
    }

    /// Whether the table is empty (never, for the built-in table).
    pub fn is_empty(&self) -> bool {
        self.y.is_empty()
    }

    /// Tabulated (x̄, ȳ, z̄) at 360 + i nm.
    #[inline]
    pub fn at_index(&self, i: usize) -> [f32; 3] {
        [self.x[i], self.y[i], self.z[i]]
    }

    /// (x̄, ȳ, z̄) at `lambda_nm`, linearly interpolated; zero outside 360–830 nm.
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> [f32; 3] {
        if !(CIE_MIN_NM..=CIE_MAX_NM).contains(&lambda_nm) {
            return [0.0; 3];
        }
        let f = lambda_nm - CIE_MIN_NM;
        let i = (f as usize).min(self.y.len() - 2);
        let t = f - i as f32;
        let lerp = |a: &[f32]| a[i] + t * (a[i + 1] - a[i]);
        [lerp(&self.x), lerp(&self.y), lerp(&self.z)]
    }

    /// ȳ at `lambda_nm`.
    #[inline]
    pub fn y_bar(&self, lambda_nm: f32) -> f32 {
        self.eval(lambda_nm)[1]
    }
}

/// The shared colour-matching-function table.
pub fn cmf() -> &'static Cmf {
    static C: OnceLock<Cmf> = OnceLock::new();
    C.get_or_init(Cmf::load)
}

/// ∫ S(λ) (x̄, ȳ, z̄)(λ) dλ over 360–830 nm, by the trapezoid rule on the 1 nm table.
/// The result is in S's unit times nm; multiply by [`K_M`] for photometric XYZ when S is a
/// spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹ (then Y is in cd/m²).
pub fn integrate_xyz(s: impl Fn(f32) -> f64) -> [f64; 3] {
    let c = cmf();
    let n = c.len();
    let mut acc = [0.0f64; 3];
    for i in 0..n {
        let w = if i == 0 || i == n - 1 { 0.5 } else { 1.0 };
        let v = s(CIE_MIN_NM + i as f32) * w;
        let [x, y, z] = c.at_index(i);
        acc[0] += v * x as f64;
        acc[1] += v * y as f64;
        acc[2] += v * z as f64;
    }
    acc
}

/// Absolute XYZ of a spectral radiance S in W·m⁻²·sr⁻¹·nm⁻¹: K_m ∫ S (x̄, ȳ, z̄) dλ.
/// Y is luminance in cd/m²; X and Z share its scale.
pub fn radiance_to_xyz(s: impl Fn(f32) -> f64) -> [f64; 3] {
    integrate_xyz(s).map(|v| v * K_M)
}

/// Luminance in cd/m² of a spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹.
pub fn luminance_cd_m2(s: impl Fn(f32) -> f64) -> f64 {
    radiance_to_xyz(s)[1]
}

/// XYZ of a reflectance ρ(λ) under an illuminant S(λ), normalised so that the perfect
/// reflector (ρ = 1) has Y = 1 (CIE 015 colorimetry).
pub fn reflectance_xyz(
    reflectance: impl Fn(f32) -> f64,
    illuminant: impl Fn(f32) -> f64,
) -> [f64; 3] {
    let white = integrate_xyz(&illuminant)[1];
    integrate_xyz(|l| reflectance(l) * illuminant(l)).map(|v| v / white)
}

/// Chromaticity (x, y) of XYZ.
pub fn xyz_to_xy(xyz: [f64; 3]) -> [f64; 2] {
    let s = xyz[0] + xyz[1] + xyz[2];
    [xyz[0] / s, xyz[1] / s]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_1nm_from_360() {
        let t = embedded_table(embedded::CIE_1931_2DEG);
        let l = t.column(0);
        assert_eq!(l.len(), 471);
        assert!(l.iter().enumerate().all(|(i, &v)| v == 360.0 + i as f64));
    }

    #[test]
    fn eval_matches_table_and_is_zero_outside() {
        let c = cmf();
        assert_eq!(c.eval(555.0), c.at_index(195));
        assert!((c.y_bar(555.0) - 1.0).abs() < 1e-6);
        assert_eq!(c.eval(359.9), [0.0; 3]);
        assert_eq!(c.eval(830.1), [0.0; 3]);
        assert!(c.eval(830.0)[1] > 0.0);
    }
}
