//! Uniform environment light. The lecture notes' ambient term k_a·I_a is this light with
//! radiance I_a seen by a diffuse surface of albedo k_a.

use glam::{Vec2, Vec3};

use super::LightSample;
use crate::sampling::{UNIFORM_SPHERE_PDF, uniform_sphere};
use crate::spectrum::{SampledWavelengths, Spectrum};

/// Uniform spectral radiance from every direction at infinity, W·m⁻²·sr⁻¹·nm⁻¹.
#[derive(Clone, Debug)]
pub struct EnvironmentLight {
    pub radiance: Spectrum,
}

impl EnvironmentLight {
    /// Uniform direction on the sphere, pdf 1/(4π) sr⁻¹.
    pub fn sample_li<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<super::LightSample<N>> {
        Some(LightSample {
            wi: uniform_sphere(u),
            li: self.radiance.sample(w),
            pdf: UNIFORM_SPHERE_PDF,
            delta: false,
            p: Vec3::ZERO,
            p_error: Vec3::ZERO,
            n: Vec3::ZERO,
            distance: f32::INFINITY,
        })
    }
}
