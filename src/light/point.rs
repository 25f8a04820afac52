//! Isotropic point light.

use glam::Vec3;

use super::LightSample;
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
    /// Irradiance-producing sample at `p`: li = I / r² (W·m⁻²·nm⁻¹), pdf 1, delta.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        let d = self.position - p;
        let r2 = d.length_squared();
        if r2 == 0.0 {
            return None;
        }
        let r = r2.sqrt();
        Some(LightSample {
            wi: d / r,
            li: self.intensity.sample(w) * (1.0 / r2),
            pdf: 1.0,
            delta: true,
            p: self.position,
            p_error: Vec3::ZERO,
            n: Vec3::ZERO,
            distance: r,
        })
    }
}
