//! pbrt-v4's curves on [`BSplineCurve`] ([`BSplineCurve::with_pbrt_shading`]): the ray-facing
//! ribbon's test and its hit, and the oriented ribbons of its `ribbon` type.

use super::{BSplineCurve, Eval, PbrtCurve};
use crate::geometry::GeometryError;
use crate::geometry::ray::Ray;
use crate::geometry::shape::Intersection;
use glam::{Vec2, Vec3};

impl BSplineCurve {
    /// These curves hit as pbrt-v4 hits its `cylinder` curves (`Curve::RecursiveIntersect`,
    /// src/pbrt/shapes.cpp): a ribbon through the centre line facing the ray, whose outline is
    /// the tube's but whose ends are where the centre line ends as seen along the ray; the hit
    /// point is where the ray crosses the centre line's depth (pbrt-v4's tHit), with pbrt-v4's
    /// error bound, the width, and its normal is pbrt-v4's: the ribbon's, turned about the
    /// tangent by θ = π·(v − ½), v ∈ [0, 1] the hit's place across the width, linear in the
    /// offset from the centre line (a true tube's angle is its arcsine), and turned the way
    /// pbrt-v4 turns it, away from the hit's side (`Rotate(-theta, dpdu)` applied to ∂p/∂v):
    /// pbrt-v4's cylinders are lit on the side away from a light, as a trough would be.
    /// A [`PbrtCurve::Flat`] curve keeps the ribbon's own normal.
    pub fn with_pbrt_shading(mut self, kind: PbrtCurve) -> Self {
        self.pbrt = Some(kind);
        self
    }

    /// A [`PbrtCurve::Ribbon`]'s normals, one pair (start, end; world space, any length) per
    /// segment in order. Fails on a count other than the segments' or a zero normal.
    pub fn with_ribbon_normals(mut self, normals: Vec<[Vec3; 2]>) -> Result<Self, GeometryError> {
        if normals.len() != self.segments.len() {
            return Err(GeometryError::Curve(format!(
                "{} normal pairs for {} segments",
                normals.len(),
                self.segments.len()
            )));
        }
        self.ribbon_normals = normals
            .iter()
            .map(|[a, b]| Some([a.try_normalize()?, b.try_normalize()?]))
            .collect::<Option<_>>()
            .ok_or_else(|| GeometryError::Curve("a ribbon normal is zero".into()))?;
        self.pbrt = Some(PbrtCurve::Ribbon);
        Ok(self)
    }

    /// A [`PbrtCurve::Ribbon`]'s normal on segment `i` at s (pbrt-v4's `Curve`): its end
    /// normals n₀, n₁ slerped, sin((1 − s)θ)·n₀/sin θ + sin(sθ)·n₁/sin θ with θ the angle
    /// between them (pbrt-v4's `AngleBetween`, the form that stays accurate near 0 and π),
    /// n₀ where θ = 0. None for other curves.
    fn ribbon_normal(&self, i: usize, s: f32) -> Option<Vec3> {
        let [n0, n1] = *self.ribbon_normals.get(i)?;
        let theta = if n0.dot(n1) < 0.0 {
            std::f32::consts::PI - 2.0 * ((n0 + n1).length() / 2.0).min(1.0).asin()
        } else {
            2.0 * ((n1 - n0).length() / 2.0).min(1.0).asin()
        };
        if theta == 0.0 {
            return Some(n0);
        }
        let inv = 1.0 / theta.sin();
        Some(n0 * (((1.0 - s) * theta).sin() * inv) + n1 * ((s * theta).sin() * inv))
    }

    /// pbrt-v4's ribbon test on segment `i` (`Curve::RecursiveIntersect`): seen along the
    /// ray, the centre line's point nearest the ray, c(s) with s ∈ [0, 1] a stationary point of
    /// |P(c(s) − o)|² (P = I − d̂d̂ᵀ: g(s) = P(c − o)·Pc' = 0, by Newton's method from each
    /// piece whose chord passes within its bound of the ray, measured in the plane across the
    /// ray as pbrt-v4 measures in its ray space), must lie within r(s) of it (a `ribbon`'s
    /// r(s)·|n(s)·d̂|, its width as seen along the ray, as pbrt-v4 scales it); the hit is at
    /// c(s)'s depth along the ray, t in (0, t_max). So the curve ends where the projected
    /// centre line does, as pbrt-v4's ribbon ends, rather than at the tube's end planes.
    pub(super) fn intersect_ribbon(&self, i: usize, ray: &Ray) -> Option<(f32, f32)> {
        let dd = ray.d.length_squared();
        let d = ray.d / dd.sqrt();
        let proj = |v: Vec3| v - d * v.dot(d);
        let mut best: Option<(f32, f32)> = None;
        for piece in self.pieces(i) {
            // the chord seen along the ray: projected first, so that a thin curve far from the
            // ray's origin is not lost to rounding in squared distances (a capsule test in
            // f32 missed 28 % of a 0.07-pixel-wide strand 30 m away)
            let (pa, pb) = (proj(piece.a - ray.o), proj(piece.b - ray.o));
            let e = pb - pa;
            let f = if e.length_squared() > 0.0 {
                (-pa.dot(e) / e.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if (pa + e * f).length_squared() > (piece.bound * 1.001).powi(2) {
                continue;
            }
            let mut s = piece.s0 + f * piece.ds;
            for _ in 0..12 {
                let e = self.eval(i, s);
                let (w, dc) = (proj(e.c - ray.o), proj(e.dc));
                let dg = dc.dot(dc) + w.dot(proj(e.ddc));
                if !(dg > 0.0) {
                    break;
                }
                let step = w.dot(dc) / dg;
                s = (s - step).clamp(-0.25, 1.25);
                if step.abs() <= 1e-7 {
                    break;
                }
            }
            if !(0.0..=1.0).contains(&s) {
                continue;
            }
            let e = self.eval(i, s);
            let t = (e.c - ray.o).dot(ray.d) / dd;
            let r = match self.ribbon_normal(i, s) {
                Some(n) => e.r * n.dot(d).abs(),
                None => e.r,
            };
            let near = proj(e.c - ray.o).length_squared() <= r * r;
            if near && t > 0.0 && t < ray.t_max && best.is_none_or(|b| t < b.0) {
                best = Some((t, s));
            }
        }
        best
    }

    /// pbrt-v4's hit on segment `i` at `s` ([`BSplineCurve::with_pbrt_shading`]): the point
    /// of `ray` at the depth of the centre line's point c(s), and the ribbon's normal (facing
    /// the ray, perpendicular to the tangent) turned by θ = (π/2)·x away from the hit's side,
    /// x ∈ [−1, 1] the hit's offset from c(s) across the ribbon in radii; a `ribbon`'s normal
    /// is its n(s) made perpendicular to the tangent (pbrt-v4's ∂p/∂u × (n × ∂p/∂u)). The
    /// normal serves as both the geometric and the shading one, as pbrt-v4's single normal
    /// does.
    pub(super) fn pbrt_interaction(
        &self,
        i: usize,
        e: &Eval,
        s: f32,
        ray: &Ray,
        kind: PbrtCurve,
    ) -> Intersection {
        let axis = e.dc.try_normalize().unwrap_or(Vec3::X);
        let d = ray.d.normalize();
        let p = ray.o + d * (e.c - ray.o).dot(d);
        let facing = (-d - axis * (-d).dot(axis))
            .try_normalize()
            .unwrap_or(axis.any_orthonormal_vector());
        let across = axis.cross(facing);
        let ribbon = self.ribbon_normal(i, s);
        let r = ribbon.map_or(e.r, |n| (e.r * n.dot(d).abs()).max(f32::MIN_POSITIVE));
        let x = ((p - e.c).dot(across) / r).clamp(-1.0, 1.0);
        let theta = match kind {
            PbrtCurve::Cylinder => std::f32::consts::FRAC_PI_2 * x,
            PbrtCurve::Flat | PbrtCurve::Ribbon => 0.0,
        };
        let n = match ribbon {
            Some(n) => (n - axis * n.dot(axis)).try_normalize().unwrap_or(facing),
            None => facing * theta.cos() - across * theta.sin(),
        };
        let count = self.segments.len() as f32;
        Intersection {
            t: 0.0,
            p,
            // pbrt-v4's error bound, the width: rays leave the hit that far off the ribbon
            p_error: Vec3::splat(2.0 * e.r),
            n_geom: n,
            n_shading: n,
            uv: Vec2::new((s + i as f32) / count, 0.5 * (1.0 + x)),
            dpdu: e.dc * count,
            dpdv: across * (2.0 * e.r),
            shape: 0,
            prim: i as u32,
        }
    }
}
