//! Directional light: collimated, or a disk of finite angular diameter such as the sun.

use glam::{Vec2, Vec3};

use super::{EmissionSample, LightSample};
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
    /// 1 − cos α of the disk's angular radius α (0 for a collimated, delta light), computed in
    /// f64 so that the sun's 0.27° stays accurate.
    pub one_minus_cos: f32,
    /// Frame around the direction toward the light (−`direction`).
    pub frame: Frame,
}

impl DirectionalLight {
    /// A light along `direction` (normalised here) with angular radius `alpha_rad`.
    pub fn new(direction: Vec3, irradiance: Spectrum, alpha_rad: f64) -> Self {
        let d = direction.normalize();
        let omc = 2.0 * (alpha_rad / 2.0).sin().powi(2);
        Self {
            direction: d,
            irradiance,
            one_minus_cos: omc as f32,
            frame: Frame::from_normal(-d),
        }
    }

    pub fn is_delta(&self) -> bool {
        self.one_minus_cos <= 0.0
    }

    /// Radiance of the disk per unit irradiance, sr⁻¹: 1/(π sin²α), sin²α = (1−c)(1+c).
    fn disk_radiance_factor(&self) -> f32 {
        let omc = self.one_minus_cos as f64;
        (1.0 / (std::f64::consts::PI * omc * (2.0 - omc))) as f32
    }

    fn in_disk(&self, dir: Vec3) -> bool {
        !self.is_delta() && 1.0 - dir.dot(self.frame.n) <= self.one_minus_cos
    }

    pub fn sample_li<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<LightSample<N>> {
        let (wi, li, pdf, delta) = if self.is_delta() {
            (-self.direction, self.irradiance.sample(w), 1.0, true)
        } else {
            let wi = self.frame.to_world(uniform_cone(u, self.one_minus_cos));
            (
                wi,
                self.irradiance.sample(w) * self.disk_radiance_factor(),
                uniform_cone_pdf(self.one_minus_cos),
                false,
            )
        };
        Some(LightSample {
            wi,
            li,
            pdf,
            delta,
            p: Vec3::ZERO,
            p_error: Vec3::ZERO,
            n: Vec3::ZERO,
            distance: f32::INFINITY,
        })
    }

    pub fn pdf_li(&self, wi: Vec3) -> f32 {
        if self.in_disk(wi) {
            uniform_cone_pdf(self.one_minus_cos)
        } else {
            0.0
        }
    }

    /// Radiance seen along an escaping ray in direction `dir` (only for a finite disk).
    pub fn escaped<const N: usize>(
        &self,
        dir: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        if self.in_disk(dir) {
            self.irradiance.sample(w) * self.disk_radiance_factor()
        } else {
            SampledSpectrum::zero()
        }
    }

    /// A particle from this light (light tracing). The direction of travel is `direction`
    /// (collimated: `le` = E⊥, pdf_dir = 1) or uniform in the disk's cone (le = E⊥/(π sin²α),
    /// pdf_dir = 1/(2π(1 − cos α)) sr⁻¹, `u_dir`); the origin is uniform on the disk of the
    /// scene's bounding sphere (`center`, `radius`) perpendicular to it (pdf 1/(π r²) m⁻²,
    /// `u_pos`).
    pub fn sample_le<const N: usize>(
        &self,
        center: Vec3,
        radius: f32,
        w: &SampledWavelengths<N>,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> EmissionSample<N> {
        let (d, le, pdf_dir) = if self.is_delta() {
            (self.direction, self.irradiance.sample(w), 1.0)
        } else {
            // frame.n points toward the light; the particle travels the other way
            (
                -self.frame.to_world(uniform_cone(u_dir, self.one_minus_cos)),
                self.irradiance.sample(w) * self.disk_radiance_factor(),
                uniform_cone_pdf(self.one_minus_cos),
            )
        };
        EmissionSample::from_infinity(center, radius, d, le, pdf_dir, u_pos)
    }
}
