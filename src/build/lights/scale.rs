//! A light's scale k from the amount the scene states (see the table in `mod.rs`).

use crate::colour::cie::{K_M, cmf};
use crate::loader::desc::{EmitAmount, PointAmount};
use crate::spectrum::{Spectrum, WavelengthRange};
use crate::units::{
    luminance, luminous_flux, luminous_intensity, power, radiance, radiant_intensity,
};

/// ∫ S dλ over the range, in S's unit × nm. Power outside the range is not counted: a radiometric
/// amount (W, W/sr, W/m², W/m²/sr) is the power *within* the range.
pub(super) fn band_integral(s: &Spectrum, r: WavelengthRange) -> f64 {
    s.integrate(r.min_nm, r.max_nm, 1.0)
}

/// K_m ∫ S ȳ dλ over the range ∩ 360–830 nm, lm per (W per S's unit). Light of the spectrum
/// outside the range is not counted.
pub(super) fn luminous_integral(s: &Spectrum, r: WavelengthRange) -> f64 {
    K_M * s.integrate_weighted(r.min_nm.max(360.0), r.max_nm.min(830.0), 1.0, |l| {
        cmf().y_bar(l) as f64
    })
}

pub(super) enum Per {
    /// Radiometric: divide by the band integral.
    Band(f64),
    /// Photometric: divide by the luminous integral.
    Luminous(f64),
    Scale(f64),
}

pub(super) fn scaled(
    s: &Spectrum,
    per: Per,
    geometry: f64,
    r: WavelengthRange,
) -> Result<Spectrum, String> {
    let k = match per {
        Per::Band(v) => {
            let b = band_integral(s, r) * geometry;
            if !(b > 0.0) {
                return Err(format!(
                    "the spectrum carries no power in {}–{} nm",
                    r.min_nm, r.max_nm
                ));
            }
            v / b
        }
        Per::Luminous(v) => {
            let l = luminous_integral(s, r) * geometry;
            if !(l > 0.0) {
                return Err("the spectrum has no visible light, so a photometric amount cannot set its scale".into());
            }
            v / l
        }
        Per::Scale(v) => v,
    };
    if !k.is_finite() || k as f32 == f32::INFINITY {
        return Err(format!("the light's scale ({k}) is not representable"));
    }
    Ok(s.scaled(k as f32))
}

pub(super) fn emit(amount: &EmitAmount, area_factor: Option<f64>) -> Result<(Per, f64), String> {
    Ok(match amount {
        EmitAmount::Radiance(l) => (
            Per::Band(l.get::<radiance::watt_per_square_meter_steradian>()),
            1.0,
        ),
        EmitAmount::Luminance(l) => (
            Per::Luminous(l.get::<luminance::candela_per_square_meter>()),
            1.0,
        ),
        EmitAmount::Power(p) => (
            Per::Band(p.get::<power::watt>()),
            area_factor.ok_or("power needs an area")?,
        ),
        EmitAmount::LuminousFlux(f) => (
            Per::Luminous(f.get::<luminous_flux::lumen>()),
            area_factor.ok_or("power needs an area")?,
        ),
        EmitAmount::Scale(s) => (Per::Scale(*s), 1.0),
    })
}

pub(super) fn point_amount(a: &PointAmount, solid_angle: f64) -> (Per, f64) {
    match a {
        PointAmount::Power(p) => (Per::Band(p.get::<power::watt>()), solid_angle),
        PointAmount::LuminousFlux(f) => {
            (Per::Luminous(f.get::<luminous_flux::lumen>()), solid_angle)
        }
        PointAmount::Intensity(i) => (
            Per::Band(i.get::<radiant_intensity::watt_per_steradian>()),
            1.0,
        ),
        PointAmount::LuminousIntensity(i) => {
            (Per::Luminous(i.get::<luminous_intensity::candela>()), 1.0)
        }
        PointAmount::Scale(s) => (Per::Scale(*s), 1.0),
    }
}
