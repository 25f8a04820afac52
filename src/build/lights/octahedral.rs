//! pbrt-v4's image `infinite` light, an equal-area octahedral map, made render-ready.

use crate::colour::cie::{K_M, cmf};
use crate::light::OctahedralMapLight;
use crate::loader::desc::{EnvMapAmount, TransformStep};
use crate::spectrum::{Spectrum, WavelengthRange};
use crate::units::{illuminance, irradiance, luminance, radiance};

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
    let rgb: Vec<[f32; 3]> = if img.encoding == crate::image_io::Encoding::Srgb {
        img.rgb
            .iter()
            .map(|p| p.map(super::super::textures::srgb_to_linear))
            .collect()
    } else {
        img.rgb
    };
    let rot = glam::Mat3::from_mat4(super::super::shapes::steps(transform, 1.0, false)?.matrix());
    let at = |s: Spectrum| OctahedralMapLight::new(img.width, &rgb, s, rot).map_err(err);
    let unit = at(illuminant.clone())?;
    let four_pi = 4.0 * std::f64::consts::PI;
    let visible = WavelengthRange {
        min_nm: r.min_nm.max(360.0),
        max_nm: r.max_nm.min(830.0),
    };
    let y_bar = |l: f32| cmf().y_bar(l) as f64;
    let zenith = unit.zenith();
    let cosine = |d: glam::Vec3| d.dot(zenith).max(0.0) as f64;
    let k = match amount {
        EnvMapAmount::Scale(k) => *k,
        EnvMapAmount::Radiance(l) => {
            let b = unit.band_radiant_exitance(r) / four_pi;
            l.get::<radiance::watt_per_square_meter_steradian>() / b
        }
        EnvMapAmount::Luminance(lv) => {
            let y = K_M * unit.integral_where(visible, &y_bar, |_| 1.0) / four_pi;
            lv.get::<luminance::candela_per_square_meter>() / y
        }
        EnvMapAmount::Irradiance(e) => {
            e.get::<irradiance::watt_per_square_meter>() / unit.integral_where(r, &|_| 1.0, cosine)
        }
        EnvMapAmount::Illuminance(ev) => {
            let y = K_M * unit.integral_where(visible, &y_bar, cosine);
            ev.get::<illuminance::lux>() / y
        }
    };
    if !(k.is_finite() && k >= 0.0) {
        return Err(err(format!(
            "the map's scale ({k}) is not a finite number ≥ 0 (is its upper half black?)"
        )));
    }
    at(illuminant.scaled(k as f32))
}
