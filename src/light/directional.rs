//! Directional light: collimated, or a disk of finite angular diameter such as the sun.

use glam::{Vec2, Vec3};

use super::LightSample;
use crate::geometry::Frame;
use crate::sampling::{uniform_cone, uniform_cone_pdf};
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

/// Light travelling along `direction` with spectral irradiance `irradiance` (W·m⁻²·nm⁻¹) on a
/// plane perpendicular to it. With an angular radius α > 0 it is a disk of uniform radiance
/// L = E / (π sin²α), since E⊥ = ∫_cone L cos θ dω = π L sin²α.
#[derive(Clone, Debug)]
pub struct DirectionalLight {
    /// Unit direction the light travels.
    pub direction: Vec3,
    /// Spectral irradiance on a perpendicular plane, W·m⁻²·nm⁻¹.
    pub irradiance: Spectrum,
    /// cos α of the disk's angular radius; 1 for a collimated (delta) light.
    pub cos_half_angle: f32,
    /// Frame around the direction toward the light (−`direction`).
    pub frame: Frame,
}

impl DirectionalLight {
    /// Radiance of the disk, W·m⁻²·sr⁻¹·nm⁻¹ per unit irradiance: 1/(π sin²α).
    fn disk_radiance_factor(&self) -> f32 {
        let sin2 = 1.0 - self.cos_half_angle * self.cos_half_angle;
        1.0 / (std::f32::consts::PI * sin2)
    }

    pub fn sample_li<const N: usize>(&self, w: &SampledWavelengths<N>, u: Vec2) -> Option<LightSample<N>> {
        let (wi, li, pdf, delta) = if self.cos_half_angle >= 1.0 {
            (-self.direction, self.irradiance.sample(w), 1.0, true)
        } else {
            let local = uniform_cone(u, self.cos_half_angle);
            let wi = self.frame.to_world(local);
            (wi, self.irradiance.sample(w) * self.disk_radiance_factor(), uniform_cone_pdf(self.cos_half_angle), false)
        };
        Some(LightSample { wi, li, pdf, delta, p: Vec3::ZERO, p_error: Vec3::ZERO, n: Vec3::ZERO, distance: f32::INFINITY })
    }

    pub fn pdf_li(&self, wi: Vec3) -> f32 {
        if self.cos_half_angle < 1.0 && wi.dot(self.frame.n) >= self.cos_half_angle {
            uniform_cone_pdf(self.cos_half_angle)
        } else {
            0.0
        }
    }

    /// Radiance seen along an escaping ray in direction `dir` (only for a finite disk).
    pub fn escaped<const N: usize>(&self, dir: Vec3, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        if self.cos_half_angle < 1.0 && dir.dot(self.frame.n) >= self.cos_half_angle {
            self.irradiance.sample(w) * self.disk_radiance_factor()
        } else {
            SampledSpectrum::zero()
        }
    }
}
