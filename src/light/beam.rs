//! A collimated beam of finite section: a laser, or a white beam (round, or through a slit)
//! for dispersion studies.

use glam::{Vec2, Vec3};

use super::{EmissionPdf, EmissionSample, LightSample};
use crate::geometry::Frame;
use crate::sampling::concentric_disk;
use crate::spectrum::{SampledWavelengths, Spectrum};

/// A beam's cross-section in its plane, in the coordinates of `frame.s` and `frame.t`, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Section {
    /// A disk of this radius.
    Disk { radius: f32 },
    /// A rectangle (a slit) of these half-extents along `frame.s` and `frame.t`.
    Rect { half_s: f32, half_t: f32 },
}

impl Section {
    /// Area, m².
    pub fn area(&self) -> f32 {
        match *self {
            Section::Disk { radius } => std::f32::consts::PI * radius * radius,
            Section::Rect { half_s, half_t } => 4.0 * half_s * half_t,
        }
    }

    /// A point uniform on the section from `u` (density 1/area).
    fn sample(&self, u: Vec2) -> Vec2 {
        match *self {
            Section::Disk { radius } => concentric_disk(u) * radius,
            Section::Rect { half_s, half_t } => {
                Vec2::new((2.0 * u.x - 1.0) * half_s, (2.0 * u.y - 1.0) * half_t)
            }
        }
    }

    /// Whether the in-plane offset (s, t) lies in the section.
    fn contains(&self, s: f32, t: f32) -> bool {
        match *self {
            Section::Disk { radius } => s * s + t * t <= radius * radius,
            Section::Rect { half_s, half_t } => s.abs() <= half_s && t.abs() <= half_t,
        }
    }
}

/// Parallel light leaving a disk or a slit (`section`) centred at `center`, travelling along
/// `frame.n`, with total spectral power `power` (W·nm⁻¹) spread uniformly over the section.
/// Its irradiance on a plane across the beam is power / area.
#[derive(Clone, Debug)]
pub struct BeamLight {
    pub center: Vec3,
    /// `n` is the direction of travel; a slit's sides run along `s` and `t`.
    pub frame: Frame,
    pub section: Section,
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
        let e = self.power.sample(w) * (1.0 / self.section.area());
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

    /// A particle (light tracing, `bdpt`): a point uniform on the section from `u`
    /// (pdf_pos = 1/area, m⁻²), travelling along the beam (a delta direction, pdf_dir = 1),
    /// `le` the irradiance across the beam, power/area.
    pub fn sample_le<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> EmissionSample<N> {
        let d = self.section.sample(u);
        let inv_area = 1.0 / self.section.area();
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

    /// Densities of [`BeamLight::sample_le`] for a particle reaching `p`: 1/area if `p` lies
    /// in the beam's prism ahead of the section, else 0; the direction is a delta (0).
    pub fn pdf_le(&self, p: Vec3) -> EmissionPdf {
        EmissionPdf {
            pos: if self.reaches(p).is_some() {
                1.0 / self.section.area()
            } else {
                0.0
            },
            dir: 0.0,
        }
    }

    /// The distance (m) from the section to `p` along the beam if `p` lies in the beam ahead
    /// of the section; None otherwise.
    fn reaches(&self, p: Vec3) -> Option<f32> {
        let local = p - self.center;
        let along = local.dot(self.frame.n);
        if along <= 0.0 {
            return None;
        }
        let (s, t) = (local.dot(self.frame.s), local.dot(self.frame.t));
        self.section.contains(s, t).then_some(along)
    }
}
