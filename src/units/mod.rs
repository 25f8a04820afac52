//! Typed physical quantities (uom) at the public API, and the one place where they become plain
//! `f32` numbers in the render loop's fixed units.
//!
//! - [`quantities`]: spectrace's uom system, including radiance, spectral radiance, radiant
//!   intensity, irradiance and luminous flux, which uom's SI lacks.
//! - [`parse`]: quantity strings (`"100 W"`, `"0.55 um"`, `"800 cd/m^2"`).
//! - [`plain`]: typed → `f32` in the render loop's units (nm, m, rad, W·m⁻²·sr⁻¹·nm⁻¹, …).

pub mod parse;
pub mod plain;
pub mod quantities;

pub use quantities::f64::*;
pub use quantities::{
    angle, area, attenuation, illuminance, irradiance, length, luminance, luminous_flux,
    luminous_intensity, power, radiance, radiant_intensity, solid_angle, spectral_radiance,
    thermodynamic_temperature, time,
};
