//! Spot light with a smooth falloff (pbrt-v4 §12.1.2 form).

use glam::Vec3;

use super::LightSample;
use crate::geometry::Frame;
use crate::spectrum::{SampledWavelengths, Spectrum};

/// A point light emitting `intensity` (W·sr⁻¹·nm⁻¹) along its axis, at full strength inside the
/// half-angle whose cosine is `cos_falloff_start`, falling with a smoothstep in cos θ to zero at
/// `cos_total`.
#[derive(Clone, Debug)]
pub struct SpotLight {
    /// Position, m.
    pub position: Vec3,
    /// Frame whose `n` is the spot's axis (unit).
    pub frame: Frame,
    /// Spectral intensity on the axis, W·sr⁻¹·nm⁻¹.
    pub intensity: Spectrum,
    pub cos_falloff_start: f32,
    pub cos_total: f32,
}

fn smoothstep(x: f32, a: f32, b: f32) -> f32 {
    if a == b {
        return if x < a { 0.0 } else { 1.0 };
    }
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl SpotLight {
    /// Relative intensity in direction `dir` (unit, world), in [0, 1].
    pub fn falloff(&self, dir: Vec3) -> f32 {
        smoothstep(
            self.frame.n.dot(dir),
            self.cos_total,
            self.cos_falloff_start,
        )
    }

    /// ∫ falloff dω over the sphere, sr: 2π[(1 − cos_start) + (cos_start − cos_total)/2]
    /// (the smoothstep ramp integrates to half its width). Power Φ = this × ∫ I dλ.
    pub fn solid_angle_factor(&self) -> f64 {
        let (cs, ct) = (self.cos_falloff_start as f64, self.cos_total as f64);
        2.0 * std::f64::consts::PI * ((1.0 - cs) + (cs - ct) / 2.0)
    }

    /// Irradiance-producing sample at `p`: li = I·falloff / r²; None outside the cone.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        super::point_like_sample(self.position, p, |wi| {
            let f = self.falloff(-wi);
            (f > 0.0).then(|| self.intensity.sample(w) * f)
        })
    }
}
