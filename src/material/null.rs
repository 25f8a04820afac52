//! What crosses a surface undeviated: Mitsuba's `null` (everything) and `thindielectric` (what
//! the sheet does not reflect), for shadow rays and the volumetric path tracer's crossings.

use super::{Material, fresnel};

impl Material {
    /// The fraction of light that crosses the surface undeviated at incidence cosine `cos`
    /// (Mitsuba's `eval_null_transmission`): 1 for `null`, an element's unpolarised transmittance, 1 − R for `thindielectric` (R its
    /// reflectance with inner reflections), 0 for every other material (a shadow ray stops
    /// there). Wavelength-independent.
    #[inline]
    pub fn null_transmission(&self, cos: f32) -> f32 {
        match self {
            Material::Null => 1.0,
            Material::Element(e) => e.transmittance(),
            Material::ThinDielectric { eta } => 1.0 - thin_reflectance(cos.abs(), *eta),
            _ => 0.0,
        }
    }
}

/// A thin dielectric sheet's reflectance with its inner reflections, R = 2F/(1 + F), for the
/// Fresnel reflectance F at incidence cosine `cos` (in [0, 1]) and relative index `eta`.
#[inline]
pub fn thin_reflectance(cos: f32, eta: f32) -> f32 {
    let f = fresnel::fresnel_dielectric(cos, eta);
    2.0 * f / (1.0 + f)
}
