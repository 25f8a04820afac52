//! What sampling a light returns: a sample toward a receiver ([`LightSample`]), a particle
//! leaving the light ([`EmissionSample`]) and the densities of an emitted ray
//! ([`EmissionPdf`]).

use glam::{Vec2, Vec3};

use crate::spectrum::SampledSpectrum;

/// A light sample seen from a reference point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample<const N: usize> {
    /// Unit direction from the reference point toward the light (world space).
    pub wi: Vec3,
    /// Radiance arriving along `-wi`, W·m⁻²·sr⁻¹·nm⁻¹ (delta lights: I/r² or E, W·m⁻²·nm⁻¹).
    pub li: SampledSpectrum<N>,
    /// Density of `wi` per unit solid angle, sr⁻¹ (1 for delta lights).
    pub pdf: f32,
    pub delta: bool,
    /// Point on the light (for shadow rays), its absolute error bound and its normal. For
    /// lights at infinity `distance` is infinite and `p` is unused.
    pub p: Vec3,
    pub p_error: Vec3,
    pub n: Vec3,
    /// Distance to `p`, m (infinite for lights at infinity).
    pub distance: f32,
}

impl<const N: usize> LightSample<N> {
    /// A sample of a light at infinity toward unit `wi` (world), with radiance `li` and a
    /// solid-angle density `pdf`; not a delta.
    pub(crate) fn at_infinity(wi: Vec3, li: SampledSpectrum<N>, pdf: f32) -> Self {
        LightSample {
            wi,
            li,
            pdf,
            delta: false,
            p: Vec3::ZERO,
            p_error: Vec3::ZERO,
            n: Vec3::ZERO,
            distance: f32::INFINITY,
        }
    }
}

/// A particle leaving a light: the emission sample of light tracing and of bidirectional path
/// tracing's light subpaths (Veach 1997 §8.3.2 and §10.2; pbrt-v4 §12.5, `SampleLe`). Every
/// light owns its sampling ([`super::Light::sample_le`]) and the densities of it ([`super::Light::pdf_le`]).
#[derive(Clone, Copy, Debug)]
pub struct EmissionSample<const N: usize> {
    /// Ray origin, m: a point on an area light, the position of a point-like light, a point on
    /// a beam's disk, or, for a light at infinity, a point on a disk perpendicular to `d`
    /// outside the scene's bounding sphere.
    pub o: Vec3,
    /// Absolute error bound of `o` per axis, m (zero where `o` is exact or not on a surface).
    pub o_error: Vec3,
    /// Unit geometric normal at `o` on the side the particle leaves (area lights); zero for
    /// lights without a surface.
    pub n: Vec3,
    /// Unit direction of travel.
    pub d: Vec3,
    /// What the light emits along `d`: radiance for area lights and lights at infinity,
    /// W·m⁻²·sr⁻¹·nm⁻¹; spectral intensity for point-like lights (point, spot, projector),
    /// W·sr⁻¹·nm⁻¹; irradiance across the beam for collimated lights (directional without a
    /// disk, beam), W·m⁻²·nm⁻¹.
    pub le: SampledSpectrum<N>,
    /// Surface coordinates of `o` on an area light (textured radiance); zero otherwise.
    pub uv: Vec2,
    /// Density of `o`: per m² of the light's surface (area lights) or of the disk perpendicular
    /// to `d` (lights at infinity, beams); 1 for a delta position (point-like lights).
    pub pdf_pos: f32,
    /// Density of `d` per unit solid angle, sr⁻¹; 1 for a delta direction (collimated lights).
    pub pdf_dir: f32,
}

impl<const N: usize> EmissionSample<N> {
    /// The particle's spectral power per unit probability, W·nm⁻¹:
    /// Le·|cos θ|/(pdf_pos·pdf_dir), cos θ between `n` and `d` (1 without a surface).
    pub fn weight(&self) -> SampledSpectrum<N> {
        let cos = if self.n == Vec3::ZERO {
            1.0
        } else {
            self.n.dot(self.d).abs()
        };
        self.le * (cos / (self.pdf_pos * self.pdf_dir))
    }

    /// A particle from a light at infinity travelling along `d` (unit) with radiance `le`
    /// chosen with density `pdf_dir` (sr⁻¹): its origin is uniform on the disk of the bounding
    /// sphere (`center`, `radius`) perpendicular to `d` (from `u_pos`), placed a diameter
    /// upstream of the centre so it lies outside the sphere.
    pub fn from_infinity(
        center: Vec3,
        radius: f32,
        d: Vec3,
        le: SampledSpectrum<N>,
        pdf_dir: f32,
        u_pos: Vec2,
    ) -> Self {
        let f = crate::geometry::Frame::from_normal(d);
        let p = crate::sampling::concentric_disk(u_pos) * radius;
        Self {
            o: center - d * (2.0 * radius) + f.s * p.x + f.t * p.y,
            o_error: Vec3::ZERO,
            n: Vec3::ZERO,
            d,
            le,
            uv: Vec2::ZERO,
            pdf_pos: 1.0 / (std::f32::consts::PI * radius * radius),
            pdf_dir,
        }
    }

    /// A particle from a point-like light at `o` along `d` with intensity `le` (W·sr⁻¹·nm⁻¹),
    /// `d` chosen with density `pdf_dir` (sr⁻¹).
    pub fn from_point(o: Vec3, d: Vec3, le: SampledSpectrum<N>, pdf_dir: f32) -> Self {
        Self {
            o,
            o_error: Vec3::ZERO,
            n: Vec3::ZERO,
            d,
            le,
            uv: Vec2::ZERO,
            pdf_pos: 1.0,
            pdf_dir,
        }
    }
}

/// The densities with which a light's emission sampling produces a given particle (see
/// [`super::Light::pdf_le`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmissionPdf {
    /// Density of the origin, m⁻² (of the light's surface, or of the disk perpendicular to the
    /// direction for lights that emit parallel light); 0 for a delta position.
    pub pos: f32,
    /// Density of the direction, sr⁻¹; 0 for a delta direction.
    pub dir: f32,
}

/// The sample of a point-like light at `position` seen from `p`: `intensity(wi)` gives the
/// spectral intensity (W·sr⁻¹·nm⁻¹) toward the receiver for the direction `wi` from `p` to the
/// light (None: no light that way); li = I / r², pdf 1, delta.
pub(super) fn point_like_sample<const N: usize>(
    position: Vec3,
    p: Vec3,
    intensity: impl FnOnce(Vec3) -> Option<SampledSpectrum<N>>,
) -> Option<LightSample<N>> {
    let d = position - p;
    let r2 = d.length_squared();
    if r2 == 0.0 {
        return None;
    }
    let r = r2.sqrt();
    let wi = d / r;
    Some(LightSample {
        wi,
        li: intensity(wi)? * (1.0 / r2),
        pdf: 1.0,
        delta: true,
        p: position,
        p_error: Vec3::ZERO,
        n: Vec3::ZERO,
        distance: r,
    })
}
