//! A collimated beam of finite radius: a laser, or a white beam for dispersion studies.

use glam::{Vec2, Vec3};

use super::LightSample;
use crate::geometry::Frame;
use crate::sampling::concentric_disk;
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

/// Parallel light leaving a disk of radius `radius` (m) centred at `center`, travelling along
/// `frame.n`, with total spectral power `power` (W·nm⁻¹) spread uniformly over the disk. Its
/// irradiance on a plane across the beam is power / (π r²).
#[derive(Clone, Debug)]
pub struct BeamLight {
    pub center: Vec3,
    /// `n` is the direction of travel.
    pub frame: Frame,
    /// Beam radius, m.
    pub radius: f32,
    /// Total spectral power, W·nm⁻¹.
    pub power: Spectrum,
}

impl BeamLight {
    /// Irradiance-producing sample at `p`: the beam's irradiance if `p` lies in the beam's
    /// cylinder ahead of the disk, else None. Delta in direction.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        let local = p - self.center;
        let along = local.dot(self.frame.n);
        if along <= 0.0 {
            return None;
        }
        let perp = local - self.frame.n * along;
        if perp.length_squared() > self.radius * self.radius {
            return None;
        }
        let e = self.power.sample(w) * (1.0 / (std::f32::consts::PI * self.radius * self.radius));
        Some(LightSample {
            wi: -self.frame.n,
            li: e,
            pdf: 1.0,
            delta: true,
            p: p - self.frame.n * along,
            p_error: Vec3::ZERO,
            n: self.frame.n,
            distance: along,
        })
    }

    /// A particle leaving the beam: (origin, direction, spectral power per unit probability of
    /// this position, W·nm⁻¹).
    pub fn sample_emission<const N: usize>(
        &self,
        u: Vec2,
        w: &SampledWavelengths<N>,
    ) -> (Vec3, Vec3, SampledSpectrum<N>) {
        let d = concentric_disk(u) * self.radius;
        let o = self.center + self.frame.s * d.x + self.frame.t * d.y;
        (o, self.frame.n, self.power.sample(w))
    }
}
