//! Lights made from tables, images and files: environment maps, CIE skies and luminaires.

use glam::Vec3;

use crate::colour::cie::{K_M, cmf};
use crate::light::{EnvMapLight, Fold, GoniometricLight, IntensityTable};
use crate::loader::desc::SkyAmount;
use crate::loader::desc::{EnvMapAmount, LuminaireAmount};
use crate::loader::photometric::{Photometry, Symmetry};
use crate::spectrum::{Spectrum, WavelengthRange};
use crate::units::{illuminance, irradiance, luminance, luminous_flux, power, radiance};

use super::scale::*;

/// An environment map: the image read (8- and 16-bit files decoded from sRGB, as Mitsuba
/// does), its rotation, and its illuminant scaled by `amount`: `Scale(k)` multiplies it;
/// `Radiance(L)` and `Luminance(Lv)` set the mean over the sphere, 1/(4π) ∫ L dω, of the band
/// radiance or of the luminance K_m ∫ L ȳ dλ; `Irradiance(E)` and `Illuminance(Ev)` set
/// ∫ L cos θ dω (band, or K_m ∫ ȳ) on a plane facing the map's zenith.
pub(super) fn envmap(
    path: &std::path::Path,
    transform: &[crate::loader::desc::TransformStep],
    amount: &EnvMapAmount,
    illuminant: &Spectrum,
    r: WavelengthRange,
) -> Result<EnvMapLight, String> {
    let img = crate::image_io::read_rgb(path).map_err(|e| e.to_string())?;
    let rgb = linear_rgb(img.rgb, img.encoding);
    let m = super::super::shapes::steps(transform, 1.0, false)?.matrix();
    let rot = glam::Mat3::from_mat4(m);
    envmap_of(img.width, img.height, &rgb, rot, amount, illuminant, r)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// An image light's pixels as linear RGB: 8- and 16-bit files decoded from sRGB.
pub(super) fn linear_rgb(rgb: Vec<[f32; 3]>, encoding: crate::image_io::Encoding) -> Vec<[f32; 3]> {
    if encoding == crate::image_io::Encoding::Srgb {
        rgb.iter()
            .map(|p| p.map(super::super::textures::srgb_to_linear))
            .collect()
    } else {
        rgb
    }
}

/// An environment map from linear RGB pixels (see [`envmap`]).
fn envmap_of(
    width: usize,
    height: usize,
    rgb: &[[f32; 3]],
    rot: glam::Mat3,
    amount: &EnvMapAmount,
    illuminant: &Spectrum,
    r: WavelengthRange,
) -> Result<EnvMapLight, String> {
    let at = |s: Spectrum| EnvMapLight::new(width, height, rgb, s, rot);
    let unit = at(illuminant.clone())?;
    // cos θ on a plane facing the map's zenith
    let zenith = rot.mul_vec3(glam::Vec3::Y).normalize();
    let k = map_scale(amount, r, zenith, |range, g, h| {
        unit.integral_where(range, &g, h)
    })
    .map_err(|k| {
        format!(
            "the environment map's scale ({k}) is not a finite number ≥ 0 (is the image black?)"
        )
    })?;
    at(illuminant.scaled(k as f32))
}

/// The factor on an image light's illuminant that `amount` asks for, from the light's own
/// integral ∫ g(λ)·L(λ, ω)·h(ω) dλ dω (`integral(range, g, h)`) at factor 1: `Scale(k)` is k;
/// `Radiance` and `Luminance` set the mean over the sphere, 1/(4π) ∫ L dω, of the band radiance
/// or of K_m ∫ L ȳ dλ; `Irradiance` and `Illuminance` set ∫ L cos θ dω (band, or K_m ∫ ȳ) on a
/// plane facing `zenith`. Err(k) when k is not a finite number ≥ 0.
pub(super) fn map_scale(
    amount: &EnvMapAmount,
    r: WavelengthRange,
    zenith: Vec3,
    integral: impl Fn(WavelengthRange, &dyn Fn(f32) -> f64, &dyn Fn(Vec3) -> f64) -> f64,
) -> Result<f64, f64> {
    let four_pi = 4.0 * std::f64::consts::PI;
    let visible = WavelengthRange {
        min_nm: r.min_nm.max(360.0),
        max_nm: r.max_nm.min(830.0),
    };
    let y_bar = |l: f32| cmf().y_bar(l) as f64;
    let one = |_: f32| 1.0;
    let all = |_: Vec3| 1.0;
    let cosine = |d: Vec3| d.dot(zenith).max(0.0) as f64;
    let k = match amount {
        EnvMapAmount::Scale(k) => *k,
        EnvMapAmount::Radiance(l) => {
            l.get::<radiance::watt_per_square_meter_steradian>() * four_pi / integral(r, &one, &all)
        }
        EnvMapAmount::Luminance(lv) => {
            lv.get::<luminance::candela_per_square_meter>() * four_pi
                / (K_M * integral(visible, &y_bar, &all))
        }
        EnvMapAmount::Irradiance(e) => {
            e.get::<irradiance::watt_per_square_meter>() / integral(r, &one, &cosine)
        }
        EnvMapAmount::Illuminance(ev) => {
            ev.get::<illuminance::lux>() / (K_M * integral(visible, &y_bar, &cosine))
        }
    };
    if k.is_finite() && k >= 0.0 {
        Ok(k)
    } else {
        Err(k)
    }
}

/// A CIE sky baked into a 1024 × 513 latitude–longitude map (the horizon on row 256, the
/// zenith on row 0) whose grey pixels are L/L_z, under the illuminant S/(K_m ∫ S ȳ dλ) (one
/// pixel unit = 1 cd/m²), the map's +y turned to `up`; scaled to the zenith luminance, or to
/// the horizontal illuminance or irradiance of the bilinear map itself. Bilinear
/// interpolation errs by O(1/512²) (measured in `tests/daylight.rs`).
pub(super) fn sky(
    model: crate::daylight::sky::SkyModel,
    sun: [f64; 3],
    up: [f64; 3],
    amount: &SkyAmount,
    spectrum: &Spectrum,
    r: WavelengthRange,
) -> Result<EnvMapLight, String> {
    let (w, h) = (1024usize, 513usize);
    let upv = glam::DVec3::from_array(up).normalize();
    let sunv = glam::DVec3::from_array(sun).normalize();
    let x = upv.any_orthonormal_vector();
    let z = x.cross(upv);
    let rot = glam::DMat3::from_cols(x, upv, z);
    let zs = sunv.dot(upv).clamp(-1.0, 1.0).acos();
    let mut rgb = Vec::with_capacity(w * h);
    for j in 0..h {
        let theta = std::f64::consts::PI * j as f64 / (h - 1) as f64;
        for i in 0..w {
            let u = 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / w as f64;
            let d =
                rot * glam::DVec3::new(theta.sin() * u.sin(), theta.cos(), -theta.sin() * u.cos());
            let chi = d.dot(sunv).clamp(-1.0, 1.0).acos();
            let v = if j * 2 > h - 1 {
                0.0
            } else {
                model.relative_luminance(theta.min(std::f64::consts::FRAC_PI_2), chi, zs)
            };
            rgb.push([v as f32; 3]);
        }
    }
    let v = luminous_integral(spectrum, r);
    if !(v > 0.0) {
        return Err(
            "the spectrum has no visible light, so a luminance cannot set its scale".into(),
        );
    }
    let illuminant = spectrum.scaled((1.0 / v) as f32);
    let amount = match amount {
        SkyAmount::ZenithLuminance(l) => {
            EnvMapAmount::Scale(l.get::<luminance::candela_per_square_meter>())
        }
        SkyAmount::HorizontalIlluminance(e) => EnvMapAmount::Illuminance(*e),
        SkyAmount::HorizontalIrradiance(e) => EnvMapAmount::Irradiance(*e),
    };
    envmap_of(w, h, &rgb, rot.as_mat3(), &amount, &illuminant, r)
}

/// A luminaire: the photometric frame from the nadir (`position` → `target`) and the C0
/// direction, the table in plain `f32`, and the spectrum per candela scaled as `amount` says
/// (see the table in the module doc).
pub(super) fn luminaire(
    (position, target, c0): (Vec3, Vec3, Option<[f64; 3]>),
    tilt_deg: f64,
    p: &Photometry,
    amount: &LuminaireAmount,
    spectrum: &Spectrum,
    r: WavelengthRange,
) -> Result<GoniometricLight, String> {
    let Some(up) = (position - target).try_normalize() else {
        return Err("the target is too close to the position to aim the luminaire".into());
    };
    let c0 = match c0 {
        Some(d) => Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32),
        // world +x, or +z when the nadir is within 25° of the x axis
        None if up.x.abs() > 25f32.to_radians().cos() => Vec3::Z,
        None => Vec3::X,
    };
    let Some(x) = (c0 - up * c0.dot(up)).try_normalize() else {
        return Err("the C0 direction is along the nadir".into());
    };
    let frame = glam::Mat3::from_cols(x, up.cross(x), up);
    let table = IntensityTable {
        vertical: p.vertical_deg.iter().map(|&a| a as f32).collect(),
        horizontal: p.horizontal_deg.iter().map(|&a| a as f32).collect(),
        fold: match p.symmetry {
            Symmetry::Axial => Fold::Axial,
            Symmetry::Quadrant => Fold::Quadrant,
            Symmetry::Bilateral0To180 => Fold::Bilateral0To180,
            Symmetry::Bilateral90To270 => Fold::Bilateral90To270,
            Symmetry::Full => Fold::Full,
        },
        cd: p.candela.iter().map(|&c| c as f32).collect(),
    };
    let flux = table.luminous_flux();
    if !(flux > 0.0) {
        return Err(format!(
            "{}: the luminaire emits nothing (every intensity is 0)",
            p.file.display()
        ));
    }
    let v = luminous_integral(spectrum, r);
    if !(v > 0.0) {
        return Err(
            "the spectrum has no visible light, so the file's candela cannot set its scale".into(),
        );
    }
    let tilt = p.tilt_factor(tilt_deg);
    let k = match amount {
        LuminaireAmount::File => tilt / v,
        LuminaireAmount::Scale(s) => s * tilt / v,
        LuminaireAmount::LuminousFlux(f) => f.get::<luminous_flux::lumen>() / (flux * v),
        LuminaireAmount::Power(w) => {
            let b = band_integral(spectrum, r);
            if !(b > 0.0) {
                return Err(format!(
                    "the spectrum carries no power in {}–{} nm",
                    r.min_nm, r.max_nm
                ));
            }
            w.get::<power::watt>() / (flux * b)
        }
    };
    if !(k.is_finite() && (k as f32).is_finite()) {
        return Err(format!("the luminaire's scale ({k}) is not representable"));
    }
    GoniometricLight::new(position, frame, spectrum.scaled(k as f32), table)
        .ok_or_else(|| "the luminaire emits nothing".into())
}
