//! Camera sensors (vision science, imaging pipelines; pbrt-v4's `PixelSensor` does the same
//! job): spectral sensitivities, the exposure of the sensor plane, raw values and white
//! balance.
//!
//! - **Exposure** of the sensor plane at a pixel whose chief ray makes the angle θ with the
//!   optical axis: H = (π/4)·L·t·cos⁴θ / N² (ISO 12232's q = π/4·cos⁴θ: lens transmittance 1,
//!   no vignetting but the cosine-fourth law), L the scene luminance (cd/m²) gives H_v in lx·s;
//!   spectral radiance gives spectral exposure in J·m⁻²·nm⁻¹.
//! - **Raw values**: each channel k integrates the spectral exposure against its sensitivity
//!   s_k, r_k = K_m·c·∫ H(λ) s_k(λ) dλ, the constant c making the green (or ȳ) channel equal
//!   H_v for light of D65's spectrum (for the CIE 1931 sensor, s = x̄, ȳ, z̄ and c = 1, so
//!   r = the exposure's XYZ in lx·s); then the ISO speed sets the scale as ISO 12232's standard
//!   output sensitivity does: raw = 0.18·r·ISO/10, so an exposure of 10/ISO lx·s reads 0.18,
//!   linear middle grey.
//! - **White balance** to an illuminant: von Kries in the sensor's space (each channel divided
//!   by its response to the illuminant, times the green one's), or Bradford: raw → XYZ (the
//!   CIE sensor's raw is XYZ; a camera's through the 3 × 3 least-squares fit of the 24
//!   ColorChecker patches under the illuminant), Bradford from the illuminant's white to D65,
//!   then linear sRGB. A grey surface under the illuminant comes out neutral (R = G = B).

use glam::{DMat3, DVec3};

pub mod pbrt;

use crate::colour::cie::{K_M, cmf};
use crate::spectrum::Spectrum;

/// How white balance adapts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Adaptation {
    VonKries,
    Bradford,
    /// pbrt-v4's RGB film matrix ([`pbrt::output_matrix`]): linear sRGB as pbrt-v4 writes it.
    PbrtV4,
}

/// What a raw value means.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Calibration {
    /// The module doc's: exposure of the sensor plane (f-number, cos⁴θ) and ISO 12232's scale.
    Iso12232,
    /// pbrt-v4's `PixelSensor`: raw_k = (t·ISO/100)·∫ s_k L dλ with the raw curves (x̄, ȳ, z̄
    /// for the CIE sensor), L in W·m⁻²·sr⁻¹·nm⁻¹; no f-number, no cos⁴θ (pbrt-v4's pixel is
    /// its camera's radiance estimate). 1 reads as 1/K_m cd/m² for the CIE sensor's Y.
    PbrtV4,
}

/// A sensor with its exposure settings and, optionally, white balance.
#[derive(Clone, Debug)]
pub struct CameraSensor {
    /// "cie-1931", a camera's name, or a file's.
    pub name: String,
    /// r, g, b sensitivities (dimensionless), or None for the CIE 1931 observer.
    pub curves: Option<[Spectrum; 3]>,
    /// c of the module doc.
    pub norm: f64,
    pub iso: f64,
    /// Exposure time, s.
    pub shutter_s: f64,
    pub f_number: f64,
    /// (illuminant name, adaptation, raw → balanced matrix).
    pub white_balance: Option<(String, Adaptation, DMat3)>,
    pub calibration: Calibration,
}

/// ∫ f dλ over 360–830 nm at 1 nm (the CIE table's grid), trapezoids.
fn integrate(f: impl Fn(f32) -> f64) -> f64 {
    (360..830)
        .map(|l| 0.5 * (f(l as f32) + f((l + 1) as f32)))
        .sum()
}

impl CameraSensor {
    /// A sensor; `white_balance` is the illuminant's name and spectrum, and the adaptation
    /// ([`Adaptation::PbrtV4`] goes with [`Calibration::PbrtV4`] and no other).
    pub fn new(
        name: String,
        curves: Option<[Spectrum; 3]>,
        exposure: (f64, f64, f64, Calibration),
        white_balance: Option<(String, Spectrum, Adaptation)>,
    ) -> Result<Self, String> {
        let (iso, shutter_s, f_number, calibration) = exposure;
        let d65 = d65()?;
        let norm = match &curves {
            _ if calibration == Calibration::PbrtV4 => 1.0 / K_M,
            None => 1.0,
            Some(c) => {
                let g = integrate(|l| d65.eval(l) as f64 * c[1].eval(l) as f64);
                let y = integrate(|l| d65.eval(l) as f64 * cmf().y_bar(l) as f64);
                if !(g > 0.0) {
                    return Err("the green sensitivity is zero under D65".into());
                }
                y / g
            }
        };
        let mut s = Self {
            name,
            curves,
            norm,
            iso,
            shutter_s,
            f_number,
            white_balance: None,
            calibration,
        };
        let pbrt = matches!(&white_balance, Some((_, _, Adaptation::PbrtV4)));
        if pbrt != (calibration == Calibration::PbrtV4) {
            return Err("pbrt-v4's film matrix goes with pbrt-v4's calibration only".into());
        }
        if let Some((wb_name, illum, adaptation)) = white_balance {
            let m = s.balance(&illum, adaptation)?;
            s.white_balance = Some((wb_name, adaptation, m));
        }
        Ok(s)
    }

    /// K_m·c·∫ S s_k dλ of a spectral radiance S (W·m⁻²·sr⁻¹·nm⁻¹): the sensor's response to
    /// it on the luminance scale (XYZ in cd/m² for the CIE sensor).
    pub fn response(&self, s: &Spectrum) -> [f64; 3] {
        self.response_fn(&|l| s.eval(l) as f64)
    }

    fn response_fn(&self, s: &dyn Fn(f32) -> f64) -> [f64; 3] {
        [0, 1, 2].map(|k| {
            K_M * self.norm
                * integrate(|l| {
                    let sens = match &self.curves {
                        None => cmf().eval(l)[k],
                        Some(c) => c[k].eval(l),
                    };
                    s(l) * sens as f64
                })
        })
    }

    /// The raw → balanced matrix for `illum` (see the module doc).
    fn balance(&self, illum: &Spectrum, a: Adaptation) -> Result<DMat3, String> {
        let w = self.response(illum);
        if !w.iter().all(|&v| v > 0.0) {
            return Err("a channel does not respond to the white-balance illuminant".into());
        }
        Ok(match a {
            Adaptation::VonKries => DMat3::from_diagonal(DVec3::new(w[1] / w[0], 1.0, w[1] / w[2])),
            Adaptation::PbrtV4 => pbrt::output_matrix(self.curves.as_ref(), Some(illum))?,
            Adaptation::Bradford => {
                let to_xyz = self.to_xyz(illum)?;
                let white = to_xyz * DVec3::from(w);
                let white = (white / white.y).to_array();
                let d65w = crate::colour::spaces::D65_WHITE;
                crate::colour::spaces::SRGB.xyz_to_rgb()
                    * crate::colour::spaces::bradford(white, d65w)
                    * to_xyz
            }
        })
    }

    /// Raw (on the luminance scale) → XYZ: identity for the CIE sensor; for a camera, the
    /// least-squares 3 × 3 fit M = (Σ xyz rawᵀ)(Σ raw rawᵀ)⁻¹ over the ColorChecker's 24
    /// patches under `illum`.
    pub fn to_xyz(&self, illum: &Spectrum) -> Result<DMat3, String> {
        if self.curves.is_none() {
            return Ok(DMat3::IDENTITY);
        }
        let cie = |f: &dyn Fn(f32) -> f64| -> [f64; 3] {
            [0, 1, 2].map(|k| K_M * integrate(|l| f(l) * cmf().eval(l)[k] as f64))
        };
        let mut pairs = Vec::new();
        for (name, _) in crate::spectrum::named::names() {
            if !name.starts_with("colorchecker:") {
                continue;
            }
            let Ok(crate::spectrum::named::Named::Curve { spectrum: refl, .. }) =
                crate::spectrum::named::lookup(&name)
            else {
                continue;
            };
            let lit = |l: f32| illum.eval(l) as f64 * refl.eval(l) as f64;
            pairs.push((DVec3::from(self.response_fn(&lit)), DVec3::from(cie(&lit))));
        }
        least_squares(pairs)
    }

    /// Raw value per unit of [`response`](Self::response) at a pixel whose chief ray makes
    /// cos θ with the axis: ISO 12232's exposure times its scale, or pbrt-v4's t·ISO/100.
    pub fn raw_scale(&self, cos_theta: f64) -> f64 {
        match self.calibration {
            Calibration::Iso12232 => {
                self.exposure_per_radiance(cos_theta) * self.raw_per_exposure()
            }
            Calibration::PbrtV4 => self.shutter_s * self.iso / 100.0,
        }
    }

    /// (π/4)·t·cos⁴θ/N²: exposure (lx·s or J·m⁻²) per unit of luminance or radiance.
    pub fn exposure_per_radiance(&self, cos_theta: f64) -> f64 {
        std::f64::consts::FRAC_PI_4 * self.shutter_s * cos_theta.powi(4)
            / (self.f_number * self.f_number)
    }

    /// Raw value per lx·s of channel response: 0.18·ISO/10.
    pub fn raw_per_exposure(&self) -> f64 {
        0.018 * self.iso
    }

    /// The channels' integrals over spectral bins of `width` nm centred at `centres` (nm):
    /// K_m·c·∫_bin s_k dλ, so that Σ_bins L̄_bin·weight = the response to the binned radiance.
    pub fn bin_weights(&self, centres: &[f32], width: f32) -> Vec<[f64; 3]> {
        centres
            .iter()
            .map(|&c| {
                let n = 20;
                [0, 1, 2].map(|k| {
                    let mut s = 0.0;
                    for i in 0..n {
                        let l = c - width / 2.0 + width * (i as f32 + 0.5) / n as f32;
                        let v = match &self.curves {
                            None => cmf().eval(l)[k],
                            Some(cu) => cu[k].eval(l),
                        };
                        s += v as f64 * (width / n as f32) as f64;
                    }
                    K_M * self.norm * s
                })
            })
            .collect()
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// The 3 × 3 least-squares fit M = (Σ xyz rawᵀ)(Σ raw rawᵀ)⁻¹ carrying each pair's raw to
/// its XYZ (the ColorChecker fit of a camera's matrix); fails when the patches' raw values do
/// not span three dimensions.
pub(crate) fn least_squares(
    pairs: impl IntoIterator<Item = (DVec3, DVec3)>,
) -> Result<DMat3, String> {
    let (mut a, mut b) = (DMat3::ZERO, DMat3::ZERO);
    for (raw, xyz) in pairs {
        a += outer(raw, raw);
        b += outer(xyz, raw);
    }
    if a.determinant().abs() < 1e-12 * a.x_axis.length().powi(3) {
        return Err("the ColorChecker fit of the camera's matrix is singular".into());
    }
    Ok(b * a.inverse())
}

/// CIE D65 (`cie-d65`, the embedded table), relative.
pub(crate) fn d65() -> Result<Spectrum, String> {
    match crate::spectrum::named::lookup("cie-d65") {
        Ok(crate::spectrum::named::Named::Curve { spectrum, .. }) => Ok(spectrum),
        _ => Err("the D65 table is missing".into()),
    }
}

/// A camera's named curves: `nikon-d5100` or `sigma-sd-merrill` (Darrodi et al. 2015, NPL).
pub fn named_curves(name: &str) -> Option<[Spectrum; 3]> {
    use crate::spectrum::data::embedded::{CAMERA_NIKON_D5100, CAMERA_SIGMA_SD_MERRILL};
    let file = match name {
        "nikon-d5100" => CAMERA_NIKON_D5100,
        "sigma-sd-merrill" => CAMERA_SIGMA_SD_MERRILL,
        _ => return None,
    };
    curves_from_text(file.1, file.0).ok()
}

/// Three curves from CSV text with columns wavelength_nm and three sensitivities.
pub fn curves_from_text(text: &str, file: &str) -> Result<[Spectrum; 3], String> {
    let t = crate::spectrum::data::parse_csv(text, file).map_err(|e| e.to_string())?;
    if t.columns.len() != 4 {
        return Err(format!(
            "{file}: expected 4 columns (wavelength_nm and three sensitivities), found {}",
            t.columns.len()
        ));
    }
    let c = |k: usize| -> Result<Spectrum, String> {
        crate::spectrum::data::table_to_curve(&t, 0, k, file)
            .map(|p| Spectrum::Piecewise(std::sync::Arc::new(p)))
            .map_err(|e| e.to_string())
    };
    Ok([c(1)?, c(2)?, c(3)?])
}
