//! Optics from the library: a lens file's focal lengths ([`lens`]) and a material's
//! reflectance and transmittance ([`Scene::material_albedo`]), as `spectrace lens` and
//! `spectrace material` print them.

use std::path::Path;

use super::{Error, Scene};
use crate::units::{Angle, Length, angle, length};

/// A lens's first-order optics at one wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LensFocalLengths {
    /// Wavelength in vacuum.
    pub wavelength: Length,
    /// Paraxial effective focal length.
    pub efl: Length,
    /// Paraxial back focal length, from the last vertex.
    pub bfl: Length,
    /// RMS radius of a real axial bundle filling the front aperture on this wavelength's
    /// paraxial focal plane (when asked for).
    pub spot_rms: Option<Length>,
}

/// The focal lengths of the lens file `path` (pbrt-v4's format, glasses allowed) at each of
/// `wavelengths`, with the real-ray spot radius if `spot`.
///
/// ```
/// use spectrace::units::{Length, length::nanometer, length::millimeter};
/// let dir = std::env::temp_dir().join("spectrace-doc-lens");
/// std::fs::create_dir_all(&dir)?;
/// let f = dir.join("singlet.lens");
/// std::fs::write(&f, "0 2 0 10\n51.68 6 N-BK7 25.4\n-51.68 95 1 25.4\n")?;
/// let r = spectrace::api::lens(&f, &[Length::new::<nanometer>(587.56)], false)?;
/// assert!((r[0].efl.get::<millimeter>() - 51.01).abs() < 0.01);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn lens(
    path: &Path,
    wavelengths: &[Length],
    spot: bool,
) -> Result<Vec<LensFocalLengths>, Error> {
    let desc = crate::loader::lens::read(path)?;
    let sys = crate::build::lens_system(&desc)?;
    wavelengths
        .iter()
        .map(|w| {
            let l = nm(w)?;
            let p = sys.paraxial(l);
            let mm = Length::new::<length::millimeter>;
            Ok(LensFocalLengths {
                wavelength: *w,
                efl: mm(p.efl),
                bfl: mm(p.bfl),
                spot_rms: spot
                    .then(|| sys.axial_spot(l, p.bfl, 201).map(|s| mm(s.rms_radius)))
                    .flatten(),
            })
        })
        .collect()
}

/// A material's directional-hemispherical reflectance and transmittance at one wavelength
/// (fractions of the power arriving from the given angle; see `material::albedo`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialAlbedo {
    /// Wavelength in vacuum.
    pub wavelength: Length,
    /// Directional-hemispherical reflectance, dimensionless.
    pub reflectance: f64,
    /// Directional-hemispherical transmittance, dimensionless.
    pub transmittance: f64,
    /// Standard error of the reflectance (0 when exact).
    pub reflectance_se: f64,
    /// Standard error of the transmittance (0 when exact).
    pub transmittance_se: f64,
    /// Exact (a material of delta lobes only) or estimated from samples.
    pub exact: bool,
}

impl Scene {
    /// The reflectance and transmittance of the material `name` for light arriving at `angle`
    /// from the normal, at each of `wavelengths` (exact for smooth materials, else from
    /// `samples` samples with standard errors).
    ///
    /// ```
    /// use spectrace::units::{Angle, Length, angle::degree, length::nanometer};
    /// let s = spectrace::Scene::from_toml("[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[film]\nwidth = 4\nheight = 4\n[materials.glass]\ntype = \"dielectric\"\nior = 1.5\n[[shapes]]\ntype = \"sphere\"\ncenter = [0, 0, 1]\nradius = 0.5\nmaterial = \"glass\"\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"")?;
    /// let r = s.material_albedo("glass", Angle::new::<degree>(0.0), &[Length::new::<nanometer>(550.0)], 1024)?;
    /// assert!((r[0].reflectance - 0.04).abs() < 1e-6);
    /// # Ok::<(), spectrace::Error>(())
    /// ```
    pub fn material_albedo(
        &self,
        name: &str,
        angle: Angle,
        wavelengths: &[Length],
        samples: u32,
    ) -> Result<Vec<MaterialAlbedo>, Error> {
        let Some(i) = self.material_names.iter().position(|n| n == name) else {
            return Err(Error::Options(format!(
                "no material \"{name}\"{}",
                crate::params::did_you_mean(name, self.material_names.iter().map(String::as_str))
            )));
        };
        let theta = angle.get::<angle::radian>();
        if !(0.0..std::f64::consts::FRAC_PI_2).contains(&theta) {
            return Err(Error::Options(format!(
                "angle {} deg: expected 0 to 90 deg (90 excluded)",
                theta.to_degrees()
            )));
        }
        let m = &self.inner.materials[i];
        wavelengths
            .iter()
            .map(|w| {
                let l = nm(w)?;
                let a = crate::material::albedo::albedo(m, theta as f32, l as f32, samples, 0);
                Ok(MaterialAlbedo {
                    wavelength: *w,
                    reflectance: a.reflectance,
                    transmittance: a.transmittance,
                    reflectance_se: a.reflectance_se,
                    transmittance_se: a.transmittance_se,
                    exact: a.exact,
                })
            })
            .collect()
    }
}

/// A wavelength in nm, which must be positive and finite.
fn nm(w: &Length) -> Result<f64, Error> {
    let l = w.get::<length::nanometer>();
    if l.is_finite() && l > 0.0 {
        Ok(l)
    } else {
        Err(Error::Options(format!(
            "wavelength {l} nm must be positive"
        )))
    }
}
