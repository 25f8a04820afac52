//! Diffuse area emitter on any shape.

use glam::{Vec2, Vec3};

use super::bounds::{DirectionCone, LightBounds};
use super::{EmissionPdf, EmissionSample, LightSample};
use crate::geometry::Frame;
use crate::geometry::shape::Shape;
use crate::sampling::cosine_hemisphere;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use crate::texture::Texture;

/// A Lambertian emitter on shape `shape`, of a spectral radiance that may vary over the surface
/// (a texture looked up at the point's uv). One-sided emitters emit on the side of the shape's
/// geometric normal; power Φ = π·L·A (two-sided: 2π·L·A) per nm for a uniform L.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// Index of the shape in `Scene::shapes`.
    pub shape: u32,
    /// Spectral radiance, W·m⁻²·sr⁻¹·nm⁻¹, at each point's uv (a uniform spectrum for most
    /// emitters, looked up without the texture's dispatch).
    pub radiance: Texture,
    pub two_sided: bool,
    /// Never met by rays (its shape's alpha test is 0: pbrt-v4's invisible area light), so
    /// only light sampling reaches it: its samples are flagged `delta`, which gives next-event
    /// estimation the whole weight (pbrt-v4 makes such a light `DeltaPosition` for the same
    /// reason), and [`crate::light::Light::is_delta`] says so to the bidirectional weights.
    pub invisible: bool,
}

impl AreaLight {
    /// Bounds for the light tree: the box of `shape` (this light's), the cone of its front-face
    /// normals (every direction for spheres and cylinders; a mesh with vertex normals, whose
    /// front face follows them, counts as two-sided), Lambertian emission (θe = π/2); `phi` is
    /// the light's power, W, of which the tree takes 4π times the peak intensity
    /// ([`LightBounds::phi`]). Per unit radiance that peak is the largest projected area, taken
    /// as the larger of |Σ Aᵢ nᵢ| (the vector area: A for a flat emitter) and A/4 (a convex
    /// closed surface's mean projected area, Cauchy: a sphere's πr²), so the tree's φ is
    /// Φ · 4·max(|Σ Aᵢ nᵢ|, A/4) / (sides · A).
    pub fn bounds(&self, shape: &Shape, phi: f32) -> LightBounds {
        let area = shape.area();
        let vector_area = match shape {
            Shape::Disk(_) => area,
            Shape::Mesh(m) => {
                let p = m.positions();
                let v = m.indices().iter().fold(Vec3::ZERO, |v, t| {
                    let [a, b, c] = t.map(|i| p[i as usize]);
                    v + 0.5 * (b - a).cross(c - a)
                });
                v.length()
            }
            _ => 0.0,
        };
        // Φ / I_peak = sides·π·L·A / (L·max(|Σ Aᵢ nᵢ|, A/4)), sr
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        let omega = sides * std::f32::consts::PI * area / vector_area.max(0.25 * area);
        let phi = LightBounds::phi_of(phi, omega);
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for i in 0..shape.primitive_count() {
            let (a, b) = shape.primitive_aabb(i);
            (lo, hi) = (lo.min(a), hi.max(b));
        }
        let (normals, flips) = match shape {
            Shape::Sphere(_)
            | Shape::Cylinder(_)
            | Shape::Curve(_)
            | Shape::BSpline(_)
            | Shape::SdfGrid(_) => (DirectionCone::ALL, false),
            Shape::Disk(d) => (DirectionCone::of(d.normal()), false),
            Shape::Mesh(m) => {
                let p = m.positions();
                let mut cone: Option<DirectionCone> = None;
                for t in m.indices() {
                    let [a, b, c] = t.map(|v| p[v as usize]);
                    let n = (b - a).cross(c - a).normalize_or_zero();
                    if n == Vec3::ZERO {
                        continue;
                    }
                    let one = DirectionCone::of(n);
                    cone = Some(cone.map_or(one, |k| DirectionCone::union(k, one)));
                    if cone.is_some_and(|k| k.cos_theta <= -1.0) {
                        break;
                    }
                }
                (cone.unwrap_or(DirectionCone::ALL), m.has_normals())
            }
        };
        LightBounds {
            lo,
            hi,
            phi,
            normals,
            cos_e: 0.0,
            two_sided: self.two_sided || flips,
        }
    }

    /// Radiance leaving the surface (normal `n`, surface coordinates `uv`) toward `w_out`.
    pub fn emitted<const N: usize>(
        &self,
        n: Vec3,
        w_out: Vec3,
        uv: Vec2,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        if self.two_sided || n.dot(w_out) > 0.0 {
            self.radiance_at(uv, w)
        } else {
            SampledSpectrum::zero()
        }
    }

    /// The radiance at surface coordinates `uv`.
    #[inline(always)]
    pub fn radiance_at<const N: usize>(
        &self,
        uv: Vec2,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match &self.radiance {
            Texture::Uniform(s) => s.sample(w),
            t => t.sample(uv, w),
        }
    }

    /// Samples a point of the shape seen from `p` ([`Shape::sample_solid_angle`]: the cone a
    /// sphere subtends, a one-sided cylinder's wall facing `p`, else uniform by area converted
    /// to solid angle). `pdf` is per sr.
    pub fn sample_li<const N: usize>(
        &self,
        shapes: &[Shape],
        p: Vec3,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<LightSample<N>> {
        let x = shapes[self.shape as usize].sample_solid_angle(p, u, !self.two_sided)?;
        if !self.two_sided && x.cos_light < 0.0 {
            return None;
        }
        Some(LightSample {
            wi: x.wi,
            li: self.radiance_at(x.s.uv, w),
            pdf: x.pdf,
            delta: self.invisible,
            p: x.s.p,
            p_error: x.s.p_error,
            n: x.s.n,
            distance: x.distance,
        })
    }

    /// Solid-angle density, sr⁻¹, of [`AreaLight::sample_li`] from `p` reaching `p_light`
    /// (normal `n_light`) on `shape` (this light's) along `wi` ([`Shape::pdf_solid_angle`]).
    pub fn pdf_li(&self, shape: &Shape, p: Vec3, wi: Vec3, p_light: Vec3, n_light: Vec3) -> f32 {
        shape.pdf_solid_angle(p, wi, p_light, n_light, !self.two_sided)
    }

    /// A particle (light tracing, `bdpt`): a point uniform by area on `shape` (this light's)
    /// from `u_pos`, a side (two-sided emitters: each with probability ½, from `u_dir.x`) and a
    /// cosine-distributed direction on it: pdf_pos = 1/A m⁻², pdf_dir = (½)·cos θ/π sr⁻¹.
    /// None for a degenerate point or a direction along the surface.
    pub fn sample_le<const N: usize>(
        &self,
        shape: &Shape,
        w: &SampledWavelengths<N>,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<EmissionSample<N>> {
        let ps = shape.sample_area(u_pos);
        if !(ps.pdf_area > 0.0) {
            return None;
        }
        let (n, u_dir, side) = if !self.two_sided {
            (ps.n, u_dir, 1.0)
        } else if u_dir.x < 0.5 {
            (-ps.n, Vec2::new(u_dir.x * 2.0, u_dir.y), 0.5)
        } else {
            (ps.n, Vec2::new(u_dir.x * 2.0 - 1.0, u_dir.y), 0.5)
        };
        let local = cosine_hemisphere(u_dir);
        let pdf_dir = side * local.z * std::f32::consts::FRAC_1_PI;
        if !(pdf_dir > 0.0) {
            return None;
        }
        Some(EmissionSample {
            o: ps.p,
            o_error: ps.p_error,
            n,
            d: Frame::from_normal(n).to_world(local),
            le: self.radiance_at(ps.uv, w),
            uv: ps.uv,
            pdf_pos: ps.pdf_area,
            pdf_dir,
        })
    }

    /// Densities of [`AreaLight::sample_le`] for a particle leaving along `d` from a point of
    /// `shape` with geometric normal `n` (either side): 1/A and (½)·|cos θ|/π, the direction's
    /// 0 behind a one-sided emitter.
    pub fn pdf_le(&self, shape: &Shape, n: Vec3, d: Vec3) -> EmissionPdf {
        let cos = n.dot(d);
        let dir = if self.two_sided {
            0.5 * cos.abs() * std::f32::consts::FRAC_1_PI
        } else {
            cos.max(0.0) * std::f32::consts::FRAC_1_PI
        };
        let area = shape.area();
        EmissionPdf {
            pos: if area > 0.0 { 1.0 / area } else { 0.0 },
            dir,
        }
    }
}
