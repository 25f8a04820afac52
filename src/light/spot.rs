//! Spot light: full intensity inside an inner cone, falling to zero at the outer cone, either
//! with a smoothstep in cos θ (pbrt-v4 §12.1.2, spectrace's native spot) or linearly in the
//! angle θ (Mitsuba 3's `spot` emitter).

use super::bounds::{DirectionCone, LightBounds};
use glam::Vec3;

use super::LightSample;
use crate::geometry::Frame;
use crate::spectrum::{SampledWavelengths, Spectrum};

/// How a spot's intensity falls between `falloff_start` (β) and `cone_angle` (γ).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpotFalloff {
    /// smoothstep(cos γ, cos β, cos θ) (pbrt-v4 §12.1.2): spectrace's native spot.
    SmoothstepCos,
    /// (γ − θ)/(γ − β), linear in the angle θ: Mitsuba 3's `spot` emitter.
    LinearAngle,
}

/// A point light emitting `intensity` (W·sr⁻¹·nm⁻¹) along its axis, at full strength inside the
/// half-angle `falloff_start` (cosine `cos_falloff_start`), falling as `falloff_kind` says to
/// zero at the half-angle `total` (cosine `cos_total`).
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
    /// The same two half-angles, rad (0 ≤ falloff_start ≤ total ≤ π/2).
    pub falloff_start: f32,
    pub total: f32,
    pub falloff_kind: SpotFalloff,
    /// Mitsuba's spot `texture`, if any: an image across the cone (see [`SpotTexture`]).
    pub texture: Option<Box<SpotTexture>>,
}

/// An image across a spot's cone (Mitsuba 3's spot `texture`): the direction with local
/// coordinates (x, y, z) in `frame` (columns: the spot's x, y and axis) takes the image at
/// uv = (½ + ½·x/(z·tan γ), ½ + ½·y/(z·tan γ)), γ the cone's half-angle, and the intensity is
/// multiplied by it.
#[derive(Clone, Debug)]
pub struct SpotTexture {
    pub image: crate::texture::Texture,
    pub frame: glam::Mat3,
    pub tan_total: f32,
}

fn smoothstep(x: f32, a: f32, b: f32) -> f32 {
    if a == b {
        return if x < a { 0.0 } else { 1.0 };
    }
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl SpotLight {
    /// Bounds for the light tree: the axis, full intensity up to the falloff's start (θo) and
    /// light up to the cut-off (θe = total − start, at least 10⁻³ rad so that a hard-edged spot
    /// keeps a non-empty emission cone); `phi` is the spot's power, W, of which the tree takes
    /// 4π times the axial intensity ([`LightBounds::phi`]): power over ∫ falloff dω.
    pub fn bounds(&self, phi: f32) -> LightBounds {
        let theta_e = (self.total - self.falloff_start).max(1e-3);
        let phi = LightBounds::phi_of(phi, self.solid_angle_factor() as f32);
        LightBounds {
            normals: DirectionCone {
                w: self.frame.n,
                cos_theta: self.cos_falloff_start,
            },
            cos_e: theta_e.cos(),
            ..LightBounds::point(self.position, phi)
        }
    }

    /// A spot at `position` aimed along `axis` (unit) with half-angles `falloff_start` ≤
    /// `total` (rad) and zero intensity (build sets it).
    pub fn new(
        position: Vec3,
        axis: Vec3,
        falloff_start: f32,
        total: f32,
        falloff_kind: SpotFalloff,
    ) -> Self {
        let falloff_start = falloff_start.min(total);
        SpotLight {
            position,
            frame: Frame::from_normal(axis),
            intensity: Spectrum::Constant(0.0),
            cos_falloff_start: falloff_start.cos(),
            cos_total: total.cos(),
            falloff_start,
            total,
            falloff_kind,
            texture: None,
        }
    }

    /// The image factor toward `dir` (unit, from the spot): 1 without a texture.
    #[inline]
    pub fn image<const N: usize>(
        &self,
        dir: Vec3,
        w: &SampledWavelengths<N>,
    ) -> crate::spectrum::SampledSpectrum<N> {
        match &self.texture {
            None => crate::spectrum::SampledSpectrum::splat(1.0),
            Some(t) => {
                let d = t.frame.transpose() * dir;
                let k = 0.5 / (d.z * t.tan_total);
                t.image
                    .sample(glam::Vec2::new(0.5 + d.x * k, 0.5 + d.y * k), w)
            }
        }
    }

    /// Relative intensity in direction `dir` (unit, world), in [0, 1]; 0 outside the cone.
    pub fn falloff(&self, dir: Vec3) -> f32 {
        let c = self.frame.n.dot(dir);
        match self.falloff_kind {
            SpotFalloff::SmoothstepCos => smoothstep(c, self.cos_total, self.cos_falloff_start),
            // Mitsuba 3 `spot`: 1 for cos θ ≥ cos(beam_width), (cutoff − θ)/(cutoff − beam_width)
            // between, 0 for cos θ ≤ cos(cutoff_angle)
            SpotFalloff::LinearAngle => {
                if c <= self.cos_total {
                    0.0
                } else if c >= self.cos_falloff_start {
                    1.0
                } else {
                    let theta = c.clamp(-1.0, 1.0).acos();
                    ((self.total - theta) / (self.total - self.falloff_start)).clamp(0.0, 1.0)
                }
            }
        }
    }

    /// ∫ falloff dω over the sphere, sr. Power Φ = this × ∫ I dλ.
    /// - smoothstep in cos θ: 2π[(1 − cos β) + (cos β − cos γ)/2] (the ramp integrates to half
    ///   its width in cos θ);
    /// - linear in θ: 2π[1 − (sin γ − sin β)/(γ − β)] (∫_β^γ (γ − θ) sin θ dθ by parts), which
    ///   tends to 2π(1 − cos γ) as β → γ;
    ///
    /// with β = `falloff_start`, γ = `total`.
    pub fn solid_angle_factor(&self) -> f64 {
        let two_pi = 2.0 * std::f64::consts::PI;
        match self.falloff_kind {
            SpotFalloff::SmoothstepCos => {
                let (cs, ct) = (self.cos_falloff_start as f64, self.cos_total as f64);
                two_pi * ((1.0 - cs) + (cs - ct) / 2.0)
            }
            SpotFalloff::LinearAngle => {
                let (b, g) = (self.falloff_start as f64, self.total as f64);
                if g - b < 1e-6 {
                    two_pi * (1.0 - g.cos())
                } else {
                    two_pi * (1.0 - (g.sin() - b.sin()) / (g - b))
                }
            }
        }
    }

    /// Irradiance-producing sample at `p`: li = I·falloff / r²; None outside the cone.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        super::point_like_sample(self.position, p, |wi| {
            let f = self.falloff(-wi);
            (f > 0.0).then(|| self.intensity.sample(w) * self.image(-wi, w) * f)
        })
    }

    /// A particle (light tracing, `bdpt`): a direction uniform in the cone from `u`,
    /// pdf_dir = 1/(2π(1 − cos θ_total)) sr⁻¹; `le` the intensity with falloff and image.
    pub fn sample_le<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: glam::Vec2,
    ) -> super::EmissionSample<N> {
        let omc = 1.0 - self.cos_total;
        let d = self.frame.to_world(crate::sampling::uniform_cone(u, omc));
        let le = self.intensity.sample(w) * self.image(d, w) * self.falloff(d);
        super::EmissionSample::from_point(
            self.position,
            d,
            le,
            crate::sampling::uniform_cone_pdf(omc),
        )
    }

    /// Densities of [`SpotLight::sample_le`] for the direction `d` (unit): a delta position
    /// (0) and the cone's uniform density inside it, else 0.
    pub fn pdf_le(&self, d: Vec3) -> super::EmissionPdf {
        let omc = 1.0 - self.cos_total;
        let dir = if 1.0 - self.frame.n.dot(d) <= omc {
            crate::sampling::uniform_cone_pdf(omc)
        } else {
            0.0
        };
        super::EmissionPdf { pos: 0.0, dir }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_falloff_is_linear_in_angle() {
        let (b, g) = (10f32.to_radians(), 30f32.to_radians());
        let s = SpotLight::new(Vec3::ZERO, Vec3::Z, b, g, SpotFalloff::LinearAngle);
        let at = |deg: f32| {
            let t = deg.to_radians();
            s.falloff(Vec3::new(t.sin(), 0.0, t.cos()))
        };
        assert_eq!(at(5.0), 1.0);
        assert!((at(20.0) - 0.5).abs() < 1e-4, "{}", at(20.0));
        assert!((at(25.0) - 0.25).abs() < 1e-4, "{}", at(25.0));
        assert_eq!(at(31.0), 0.0);
    }

    #[test]
    fn solid_angle_factors_match_quadrature() {
        for kind in [SpotFalloff::SmoothstepCos, SpotFalloff::LinearAngle] {
            for (b, g) in [(10.0f32, 30.0f32), (20.0, 20.0), (0.0, 45.0)] {
                let s = SpotLight::new(Vec3::ZERO, Vec3::Z, b.to_radians(), g.to_radians(), kind);
                // ∫ f dω = 2π ∫_0^π f(θ) sin θ dθ, midpoint rule in θ
                let n = 200_000;
                let h = std::f64::consts::PI / n as f64;
                let q: f64 = (0..n)
                    .map(|i| {
                        let t = (i as f64 + 0.5) * h;
                        let d = Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
                        s.falloff(d) as f64 * t.sin() * h
                    })
                    .sum::<f64>()
                    * 2.0
                    * std::f64::consts::PI;
                let c = s.solid_angle_factor();
                assert!((q / c - 1.0).abs() < 1e-4, "{kind:?} {b}/{g}: {q} vs {c}");
            }
        }
    }
}
