//! Radiant ↔ luminous conversion through a spectrum: Φ_v = K_m ∫ Φ_e(λ) ȳ(λ) dλ
//! (`../shared/PHYSICS.md`, "Photometric units").

use super::Spectrum;
use crate::colour::cie::{K_M, cmf, integrate_xyz};
use crate::units::{Length, Luminance, LuminousFlux, Power, Radiance};
use crate::units::{luminance, luminous_flux, power, radiance};

/// Luminous efficacy of radiation with spectral shape `shape` over `[lo_nm, hi_nm]`, in lm/W:
/// K_m ∫ S ȳ dλ / ∫ S dλ. Returns 0 when the shape has no power in the range.
pub fn luminous_efficacy(shape: &Spectrum, lo_nm: f32, hi_nm: f32) -> f64 {
    let total = shape.integrate(lo_nm, hi_nm, 0.25);
    if total <= 0.0 {
        return 0.0;
    }
    K_M * integrate_xyz(|l| {
        if (lo_nm..=hi_nm).contains(&l) {
            shape.eval(l) as f64
        } else {
            0.0
        }
    })[1]
        / total
}

/// Luminous flux of radiant power `p` distributed with spectral shape `shape` over
/// `[lo_nm, hi_nm]`.
pub fn luminous_flux_of(p: Power, shape: &Spectrum, lo_nm: f32, hi_nm: f32) -> LuminousFlux {
    LuminousFlux::new::<luminous_flux::lumen>(
        p.get::<power::watt>() * luminous_efficacy(shape, lo_nm, hi_nm),
    )
}

/// Radiant power needed for luminous flux `f` with spectral shape `shape` over
/// `[lo_nm, hi_nm]`; zero when the shape has no luminous efficacy.
pub fn radiant_power_of(f: LuminousFlux, shape: &Spectrum, lo_nm: f32, hi_nm: f32) -> Power {
    let k = luminous_efficacy(shape, lo_nm, hi_nm);
    Power::new::<power::watt>(if k > 0.0 {
        f.get::<luminous_flux::lumen>() / k
    } else {
        0.0
    })
}

/// Luminous flux of monochromatic radiant power `p` at wavelength `lambda`: K_m ȳ(λ) Φ_e.
pub fn luminous_flux_monochromatic(p: Power, lambda: Length) -> LuminousFlux {
    let y = cmf().y_bar(crate::units::plain::nm(lambda)) as f64;
    LuminousFlux::new::<luminous_flux::lumen>(K_M * y * p.get::<power::watt>())
}

/// Radiant power of monochromatic luminous flux `f` at `lambda`; zero where ȳ(λ) = 0.
pub fn radiant_power_monochromatic(f: LuminousFlux, lambda: Length) -> Power {
    let y = cmf().y_bar(crate::units::plain::nm(lambda)) as f64;
    Power::new::<power::watt>(if y > 0.0 {
        f.get::<luminous_flux::lumen>() / (K_M * y)
    } else {
        0.0
    })
}

/// Luminance of a spectral radiance curve in W·m⁻²·sr⁻¹·nm⁻¹: K_m ∫ L(λ) ȳ(λ) dλ.
pub fn luminance_of(spectral_radiance: &Spectrum) -> Luminance {
    Luminance::new::<luminance::candela_per_square_meter>(crate::colour::cie::luminance_cd_m2(
        |l| spectral_radiance.eval(l) as f64,
    ))
}

/// Band radiance ∫ L(λ) dλ over `[lo_nm, hi_nm]` of a spectral radiance curve in
/// W·m⁻²·sr⁻¹·nm⁻¹.
pub fn band_radiance(spectral_radiance: &Spectrum, lo_nm: f32, hi_nm: f32) -> Radiance {
    Radiance::new::<radiance::watt_per_square_meter_steradian>(
        spectral_radiance.integrate(lo_nm, hi_nm, 0.25),
    )
}
