//! pbrt-v4's lights in the equal-area octahedral layout made render-ready: the image
//! `infinite` light and the `goniometric` light.

use crate::light::{GoniometricMapLight, OctahedralMapLight};
use crate::loader::desc::{EnvMapAmount, TransformStep};
use crate::spectrum::{Spectrum, WavelengthRange};

/// The map read (a square image; 8- and 16-bit files decoded from sRGB), its rotation, and its
/// illuminant scaled by `amount` as for a latitude–longitude map (`sources::envmap`), with
/// irradiance and illuminance on a plane facing the map's +z.
pub(super) fn octahedral(
    path: &std::path::Path,
    transform: &[TransformStep],
    amount: &EnvMapAmount,
    illuminant: &Spectrum,
    r: WavelengthRange,
) -> Result<OctahedralMapLight, String> {
    let img = crate::image_io::read_rgb(path).map_err(|e| e.to_string())?;
    let err = |e: String| format!("{}: {e}", path.display());
    if img.width != img.height {
        return Err(err(format!(
            "an equal-area map must be square (pbrt-v4), not {} × {}",
            img.width, img.height
        )));
    }
    let rgb = super::sources::linear_rgb(img.rgb, img.encoding);
    let rot = glam::Mat3::from_mat4(super::super::shapes::steps(transform, 1.0, false)?.matrix());
    let at = |s: Spectrum| OctahedralMapLight::new(img.width, &rgb, s, rot).map_err(err);
    let unit = at(illuminant.clone())?;
    let k = super::sources::map_scale(amount, r, unit.zenith(), |range, g, h| {
        unit.integral_where(range, &g, h)
    })
    .map_err(|k| {
        err(format!(
            "the map's scale ({k}) is not a finite number ≥ 0 (is its upper half black?)"
        ))
    })?;
    at(illuminant.scaled(k as f32))
}

/// A goniometric light's image read (square; 8- and 16-bit files decoded from sRGB), made grey
/// as the mean of its linear R, G, B, and placed by a rigid `transform`.
pub(super) fn goniometric_map(
    path: &std::path::Path,
    transform: &[TransformStep],
    spectrum: &Spectrum,
) -> Result<GoniometricMapLight, String> {
    let img = crate::image_io::read_rgb(path).map_err(|e| e.to_string())?;
    let err = |e: String| format!("{}: {e}", path.display());
    if img.width != img.height {
        return Err(err(format!(
            "a goniometric light's image must be square (equal-area, pbrt-v4), not {} × {}",
            img.width, img.height
        )));
    }
    let grey = super::sources::linear_rgb(img.rgb, img.encoding)
        .iter()
        .map(|p| (p[0] + p[1] + p[2]) / 3.0)
        .collect();
    let (position, m) = super::rigid(transform).ok_or_else(|| {
        "a goniometric light's frame must be a rotation (no scale or shear)".to_string()
    })?;
    GoniometricMapLight::new(position, m, spectrum.clone(), img.width, grey).map_err(err)
}
