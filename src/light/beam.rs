//! A collimated beam of finite radius: a laser, or a white beam for dispersion studies.

use glam::{Vec2, Vec3};

use super::{EmissionPdf, EmissionSample, LightSample};
use crate::geometry::Frame;
use crate::sampling::concentric_disk;
use crate::spectrum::{SampledWavelengths, Spectrum};

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
        let along = self.reaches(p)?;
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

    /// A particle (light tracing, `bdpt`): a point uniform on the disk from `u`
    /// (pdf_pos = 1/(π r²) m⁻²), travelling along the beam (a delta direction, pdf_dir = 1),
    /// `le` the irradiance across the beam, power/(π r²).
    pub fn sample_le<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> EmissionSample<N> {
        let d = concentric_disk(u) * self.radius;
        let inv_area = 1.0 / (std::f32::consts::PI * self.radius * self.radius);
        EmissionSample {
            o: self.center + self.frame.s * d.x + self.frame.t * d.y,
            o_error: Vec3::ZERO,
            n: Vec3::ZERO,
            d: self.frame.n,
            le: self.power.sample(w) * inv_area,
            uv: Vec2::ZERO,
            pdf_pos: inv_area,
            pdf_dir: 1.0,
        }
    }

    /// Densities of [`BeamLight::sample_le`] for a particle reaching `p`: 1/(π r²) if `p` lies
    /// in the beam's cylinder ahead of the disk, else 0; the direction is a delta (0).
    pub fn pdf_le(&self, p: Vec3) -> EmissionPdf {
        EmissionPdf {
            pos: if self.reaches(p).is_some() {
                1.0 / (std::f32::consts::PI * self.radius * self.radius)
            } else {
                0.0
            },
            dir: 0.0,
        }
    }

    /// The distance (m) from the disk to `p` along the beam if `p` lies in the beam's cylinder
    /// ahead of the disk; None otherwise.
    fn reaches(&self, p: Vec3) -> Option<f32> {
        let local = p - self.center;
        let along = local.dot(self.frame.n);
        if along <= 0.0 {
            return None;
        }
        let perp = local - self.frame.n * along;
        (perp.length_squared() <= self.radius * self.radius).then_some(along)
    }
}
