//! Isotropic point light.

use glam::Vec3;

use super::bounds::LightBounds;
use super::{EmissionSample, LightSample};
use crate::spectrum::{SampledWavelengths, Spectrum};

/// An isotropic point light of spectral intensity `intensity` (W·sr⁻¹·nm⁻¹); its power is
/// Φ = 4π ∫ I dλ (`../shared/PHYSICS.md`, "Lights").
#[derive(Clone, Debug)]
pub struct PointLight {
    /// Position, m.
    pub position: Vec3,
    /// Spectral intensity, W·sr⁻¹·nm⁻¹.
    pub intensity: Spectrum,
}

impl PointLight {
    /// Bounds for the light tree: an isotropic emitter of power `phi` (W) at its position.
    pub fn bounds(&self, phi: f32) -> LightBounds {
        LightBounds::point(self.position, phi)
    }

    /// Irradiance-producing sample at `p`: li = I / r² (W·m⁻²·nm⁻¹), pdf 1, delta.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        super::point_like_sample(self.position, p, |_| Some(self.intensity.sample(w)))
    }

    /// A particle (light tracing, `bdpt`): a direction uniform on the sphere from `u`,
    /// pdf_dir = 1/(4π) sr⁻¹; `le` is the intensity.
    pub fn sample_le<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: glam::Vec2,
    ) -> EmissionSample<N> {
        EmissionSample::from_point(
            self.position,
            crate::sampling::uniform_sphere(u),
            self.intensity.sample(w),
            crate::sampling::UNIFORM_SPHERE_PDF,
        )
    }
}
