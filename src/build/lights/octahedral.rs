//! pbrt-v4's image `infinite` light, an equal-area octahedral map, made render-ready.

use crate::light::OctahedralMapLight;
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
