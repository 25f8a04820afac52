//! Uniform environment light. The lecture notes' ambient term k_a·I_a is this light with
//! radiance I_a seen by a diffuse surface of albedo k_a.

use glam::{Vec2, Vec3};

use super::{EmissionSample, LightSample};
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

    /// A particle from the environment (light tracing): a direction of travel uniform on the
    /// sphere (pdf 1/(4π) sr⁻¹, `u_dir`), then an origin uniform on the disk of the scene's
    /// bounding sphere (`center`, `radius`) perpendicular to it (pdf 1/(π r²) m⁻², `u_pos`).
    /// Particles that miss the scene carry nothing, and none of the scene is missed.
    pub fn sample_le<const N: usize>(
        &self,
        center: Vec3,
        radius: f32,
        w: &SampledWavelengths<N>,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> EmissionSample<N> {
        let d = uniform_sphere(u_dir);
        EmissionSample::from_infinity(
            center,
            radius,
            d,
            self.radiance.sample(w),
            UNIFORM_SPHERE_PDF,
            u_pos,
        )
    }
}
