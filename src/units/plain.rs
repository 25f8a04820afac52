//! The one documented place where typed quantities become plain `f32` numbers.
//!
//! The render loop works in fixed units (see `../shared/PHYSICS.md`, "Units inside the render
//! loop"): wavelengths in nm, lengths in metres, angles in radians, spectral radiance in
//! W·m⁻²·sr⁻¹·nm⁻¹. The build step calls these functions and nothing else to leave the typed
//! world; the reverse direction (`*_from_*`) is for reporting values back at the public API.

use super::quantities::{
    angle::radian, length::meter, length::nanometer, power::watt,
    radiance::watt_per_square_meter_steradian,
    spectral_radiance::watt_per_square_meter_steradian_nanometer,
    thermodynamic_temperature::kelvin,
};
use super::{Angle, Length, Power, Radiance, SpectralRadiance, ThermodynamicTemperature};

/// Wavelength in nanometres.
pub fn nm(l: Length) -> f32 {
    l.get::<nanometer>() as f32
}
/// Length in metres.
pub fn metres(l: Length) -> f32 {
    l.get::<meter>() as f32
}
/// Angle in radians.
pub fn radians(a: Angle) -> f32 {
    a.get::<radian>() as f32
}
/// Temperature in kelvin.
pub fn kelvin_f32(t: ThermodynamicTemperature) -> f32 {
    t.get::<kelvin>() as f32
}
/// Power in watts.
pub fn watts(p: Power) -> f32 {
    p.get::<watt>() as f32
}
/// Radiance in W·m⁻²·sr⁻¹.
pub fn w_m2_sr(l: Radiance) -> f32 {
    l.get::<watt_per_square_meter_steradian>() as f32
}
/// Spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹, the render loop's radiance unit.
pub fn w_m2_sr_nm(l: SpectralRadiance) -> f32 {
    l.get::<watt_per_square_meter_steradian_nanometer>() as f32
}

/// Typed wavelength from nanometres.
pub fn length_from_nm(v: f64) -> Length {
    Length::new::<nanometer>(v)
}
/// Typed spectral radiance from W·m⁻²·sr⁻¹·nm⁻¹.
pub fn spectral_radiance_from_w_m2_sr_nm(v: f64) -> SpectralRadiance {
    SpectralRadiance::new::<watt_per_square_meter_steradian_nanometer>(v)
}
/// Typed radiance from W·m⁻²·sr⁻¹.
pub fn radiance_from_w_m2_sr(v: f64) -> Radiance {
    Radiance::new::<watt_per_square_meter_steradian>(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::parse::parse;

    #[test]
    fn fixed_units() {
        assert!((nm(parse("0.55 um").unwrap()) - 550.0).abs() < 1e-4);
        assert!((metres(parse("2.5 mm").unwrap()) - 0.0025).abs() < 1e-9);
        assert!((radians(parse("180 deg").unwrap()) - std::f32::consts::PI).abs() < 1e-6);
        let l: SpectralRadiance = parse("0.25 W/m^2/sr/nm").unwrap();
        assert!((w_m2_sr_nm(l) - 0.25).abs() < 1e-7);
    }
}
