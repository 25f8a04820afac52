//! Mitsuba's `bsplinecurve`: uniform cubic B-splines of control points (x, y, z, radius), the
//! surface swept by a sphere of the interpolated radius along the interpolated centre line
//! (the "round B-spline curves" of Embree and OptiX that Mitsuba traces). Only hits entering
//! the tube count (Mitsuba culls curve backfaces).
//!
//! Each segment (four consecutive control points; a curve of n points has n − 3) is
//! c(s) = Σ Bₖ(s)·pₖ and r(s) = Σ Bₖ(s)·rₖ, s ∈ [0, 1], with the uniform cubic B-spline basis
//! B = ((1−s)³, 3s³ − 6s² + 4, −3s³ + 3s² + 3s + 1, s³)/6 (Mitsuba's `cubic_interpolation`).
//!
//! Intersection, exact to f32 rounding rather than tessellated:
//! 1. the segment is cut into [`PIECES`] chords; the capsule around each chord with the
//!    piece's largest radius plus a bound on the curve's distance from the chord (|c''|·Δs²/8,
//!    |c''| linear in s, so largest at an end) contains the piece's tube;
//! 2. where the ray enters a capsule, Newton's method solves for (t, s) on the exact surface:
//!    |q|² = r² and q·c' + r·r' = 0 with q = o + t·d − c(s) (the sphere at s touching the
//!    envelope of the sweep);
//! 3. the nearest converged hit that enters the surface wins, if the centre line's point
//!    closest to it lies on the segment (its parameter s*, in [0, 1]). So the tube is cut open at a
//!    curve's ends by the planes normal to the curve there, as Mitsuba's renders show.
//!
//! The hit's s is s*, as Mitsuba's: its normal (|c'|² − q·c'')·q − r·r'·c', q = p − c(s*), is the
//! gradient of |p − c(s*)|² − r(s*)², and its renders of a varying radius match this reading only.
//!
//! uv as Mitsuba 3.9.1 defines it (`bsplinecurve.cpp`): v = (segment + s)/segments over all
//! curves, u the angle of the hit around the tangent c'(s) (as `linearcurve`'s, over 2π).
//!
//! Curves read from pbrt-v4 are hit and shaded as pbrt-v4's ribbons instead
//! ([`BSplineCurve::with_pbrt_shading`]).

use super::Intersection;
use super::curve::{angle_around, capsule_hit, read_polylines};
use crate::geometry::error::GeometryError;
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use std::path::Path;

mod ribbon;

/// Chords per segment for the bounding capsules of step 1.
const PIECES: usize = 8;

/// Cubic B-spline curves of world-space control points (m) with radii (m, untouched by the
/// transform).
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineCurve {
    points: Vec<Vec3>,
    radii: Vec<f32>,
    /// Index of each segment's first control point (three more follow it).
    segments: Vec<u32>,
    /// Hit and shaded as pbrt-v4's curves of this type ([`BSplineCurve::with_pbrt_shading`]).
    pbrt: Option<PbrtCurve>,
    /// A [`PbrtCurve::Ribbon`]'s unit normals at each segment's start and end (world space).
    ribbon_normals: Vec<[Vec3; 2]>,
}

/// The pbrt-v4 curve types spectrace reads (`CurveType`, src/pbrt/shapes.h).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PbrtCurve {
    /// The ribbon shaded with its own normal, facing the ray.
    Flat,
    /// The ribbon's normal turned across the width to look round.
    Cylinder,
    /// A ribbon oriented by normals given at each segment's ends, which it turns between
    /// ([`BSplineCurve::with_ribbon_normals`]).
    Ribbon,
}

/// One of a segment's [`PIECES`] chords: its parameters s0 and s0 + ds, its end points, and the
/// largest radius along it plus a bound on the curve's distance from the chord (|c''|·Δs²/8,
/// |c''| linear in s, so largest at an end).
struct Piece {
    s0: f32,
    ds: f32,
    a: Vec3,
    b: Vec3,
    bound: f32,
}

/// A segment's centre line and radius at s, with their first and second derivatives in s.
struct Eval {
    c: Vec3,
    dc: Vec3,
    ddc: Vec3,
    r: f32,
    dr: f32,
    ddr: f32,
}

impl BSplineCurve {
    /// Curves from polylines of (point, radius); each needs four control points or more,
    /// finite coordinates and radii, and a radius > 0 at each segment's ends and middle (a
    /// control radius may be ≤ 0, as a linear taper's outer control values are).
    pub fn new(curves: &[Vec<(Vec3, f32)>]) -> Result<Self, GeometryError> {
        let bad = |m: String| GeometryError::Curve(m);
        let mut c = Self {
            points: vec![],
            radii: vec![],
            segments: vec![],
            pbrt: None,
            ribbon_normals: vec![],
        };
        for (k, line) in curves.iter().enumerate() {
            if line.len() < 4 {
                return Err(bad(format!(
                    "B-spline curve {k} has {} control point(s); a B-spline curve needs four or more",
                    line.len()
                )));
            }
            let first = c.points.len() as u32;
            for (i, &(p, r)) in line.iter().enumerate() {
                if !(p.is_finite() && r.is_finite()) {
                    return Err(bad(format!("curve {k}, control point {i}: {p} radius {r}")));
                }
                c.points.push(p);
                c.radii.push(r);
            }
            let n = line.len() as u32 - 3;
            for j in 0..n as usize {
                let r = &c.radii[first as usize + j..first as usize + j + 4];
                let at = |s: f32| {
                    let b = [
                        (1.0 - s).powi(3),
                        3.0 * s * s * s - 6.0 * s * s + 4.0,
                        -3.0 * s * s * s + 3.0 * s * s + 3.0 * s + 1.0,
                        s * s * s,
                    ];
                    (0..4).map(|k| b[k] * r[k]).sum::<f32>() / 6.0
                };
                if !(at(0.0) > 0.0 && at(0.5) > 0.0 && at(1.0) > 0.0) {
                    return Err(bad(format!(
                        "curve {k}, segment {j}: its radius is not positive along it"
                    )));
                }
            }
            c.segments.extend((0..n).map(|j| first + j));
        }
        if c.segments.is_empty() {
            return Err(bad("no curves".into()));
        }
        Ok(c)
    }

    /// Reads Mitsuba's curve file (as `linearcurve`'s: `x y z radius` per line, an empty line
    /// between curves; positions transformed, radii not).
    pub fn load(path: &Path, transform: &Transform) -> Result<Self, GeometryError> {
        let lines = read_polylines(path, transform)?;
        // a file's radii are Mitsuba's: each control point's own, > 0
        if let Some((k, i, r)) = lines.iter().enumerate().find_map(|(k, l)| {
            l.iter()
                .enumerate()
                .find(|(_, (_, r))| !(*r > 0.0))
                .map(|(i, (_, r))| (k, i, *r))
        }) {
            return Err(GeometryError::MeshParse {
                path: path.to_path_buf(),
                message: format!("curve {k}, control point {i}: radius {r} (must be > 0)"),
            });
        }
        Self::new(&lines).map_err(|e| GeometryError::MeshParse {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }

    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    fn control(&self, i: usize) -> ([Vec3; 4], [f32; 4]) {
        let k = self.segments[i] as usize;
        (
            [0, 1, 2, 3].map(|j| self.points[k + j]),
            [0, 1, 2, 3].map(|j| self.radii[k + j]),
        )
    }

    fn eval(&self, i: usize, s: f32) -> Eval {
        let (p, r) = self.control(i);
        let (s2, s3) = (s * s, s * s * s);
        let b = [
            (1.0 - s) * (1.0 - s) * (1.0 - s) / 6.0,
            (3.0 * s3 - 6.0 * s2 + 4.0) / 6.0,
            (-3.0 * s3 + 3.0 * s2 + 3.0 * s + 1.0) / 6.0,
            s3 / 6.0,
        ];
        let db = [
            -(1.0 - s) * (1.0 - s) / 2.0,
            (3.0 * s2 - 4.0 * s) / 2.0,
            (-3.0 * s2 + 2.0 * s + 1.0) / 2.0,
            s2 / 2.0,
        ];
        let ddb = [1.0 - s, 3.0 * s - 2.0, -3.0 * s + 1.0, s];
        let dot3 = |w: [f32; 4]| w[0] * p[0] + w[1] * p[1] + w[2] * p[2] + w[3] * p[3];
        let dot1 = |w: [f32; 4]| w[0] * r[0] + w[1] * r[1] + w[2] * r[2] + w[3] * r[3];
        Eval {
            c: dot3(b),
            dc: dot3(db),
            ddc: dot3(ddb),
            r: dot1(b),
            dr: dot1(db),
            ddr: dot1(ddb),
        }
    }

    /// Bounds of segment `i`: its control points' box (the convex hull holds the segment)
    /// grown by the largest radius.
    pub(crate) fn aabb(&self, i: usize) -> (Vec3, Vec3) {
        let (p, r) = self.control(i);
        let rmax = Vec3::splat(r.into_iter().fold(0.0, f32::max));
        let lo = p.into_iter().fold(Vec3::INFINITY, Vec3::min);
        let hi = p.into_iter().fold(Vec3::NEG_INFINITY, Vec3::max);
        (lo - rmax, hi + rmax)
    }

    /// The entering hit of `ray` with segment `i`, t in (0, t_max), and its s ∈ [0, 1] (module
    /// docs, steps 1–3).
    pub(crate) fn intersect(&self, i: usize, ray: &Ray) -> Option<(f32, f32)> {
        if self.pbrt.is_some() {
            return self.intersect_ribbon(i, ray);
        }
        let (_, radii) = self.control(i);
        let scale = radii.into_iter().fold(0.0, f32::max);
        let t_min = 1e-4 * scale;
        let mut best: Option<(f32, f32)> = None;
        for p in self.pieces(i) {
            let mut shrunk = *ray;
            shrunk.t_max = best.map_or(ray.t_max, |b| b.0);
            let bound = p.bound + 1e-4 * scale;
            let hit = capsule_hit(p.a, p.b, bound, &shrunk, f32::NEG_INFINITY)
                .and_then(|(t0, f)| self.newton(i, ray, t0.max(0.0), p.s0 + f * p.ds, t_min));
            if let Some(h) = hit.filter(|h| best.is_none_or(|b| h.0 < b.0)) {
                best = Some(h);
            }
        }
        best
    }

    /// Segment `i`'s [`PIECES`] chords with their bounds (module docs, step 1), each end
    /// evaluated once.
    fn pieces(&self, i: usize) -> impl Iterator<Item = Piece> + '_ {
        let mut prev = self.eval(i, 0.0);
        (0..PIECES).map(move |k| {
            let (s0, s1) = (k as f32 / PIECES as f32, (k + 1) as f32 / PIECES as f32);
            let next = self.eval(i, s1);
            let ds = s1 - s0;
            let sag = prev.ddc.length().max(next.ddc.length()) * ds * ds / 8.0;
            let piece = Piece {
                s0,
                ds,
                a: prev.c,
                b: next.c,
                bound: prev.r.max(next.r) + sag,
            };
            prev = next;
            piece
        })
    }

    /// Newton's method on (t, s) from (t, s) (module docs, step 2); the hit if it converges
    /// with s ∈ [0, 1], t in (t_min, t_max), entering the surface.
    fn newton(
        &self,
        i: usize,
        ray: &Ray,
        mut t: f32,
        mut s: f32,
        t_min: f32,
    ) -> Option<(f32, f32)> {
        for _ in 0..12 {
            let e = self.eval(i, s.clamp(-0.05, 1.05));
            let q = ray.o + ray.d * t - e.c;
            let f1 = q.dot(q) - e.r * e.r;
            let f2 = q.dot(e.dc) + e.r * e.dr;
            // Jacobian of (f1, f2) in (t, s)
            let (a, b) = (2.0 * q.dot(ray.d), -2.0 * f2);
            let (c, d) = (
                ray.d.dot(e.dc),
                -e.dc.dot(e.dc) + q.dot(e.ddc) + e.dr * e.dr + e.r * e.ddr,
            );
            let det = a * d - b * c;
            if det == 0.0 || !det.is_finite() {
                return None;
            }
            let dt = (f1 * d - b * f2) / det;
            let dsv = (a * f2 - c * f1) / det;
            t -= dt;
            s -= dsv;
            if !(t.is_finite() && s.is_finite() && (-0.5..=1.5).contains(&s)) {
                return None;
            }
            if dt.abs() <= 1e-6 * (1.0 + t.abs()) && dsv.abs() <= 1e-6 {
                break;
            }
        }
        if !(t > t_min && t < ray.t_max) {
            return None;
        }
        let e = self.eval(i, s);
        let p = ray.o + ray.d * t;
        let q = p - e.c;
        // converged onto the surface (not a stationary point off it), and entering it
        if (q.length() - e.r).abs() > 1e-3 * e.r || q.dot(ray.d) >= 0.0 {
            return None;
        }
        // the hit belongs to this segment where the closest point of the centre line does
        self.closest(i, p, s).map(|s| (t, s))
    }

    /// The parameter of the centre line's point closest to `p`, from `s` ((p − c)·c' = 0 by
    /// Newton's method); `None` if it leaves the segment.
    fn closest(&self, i: usize, p: Vec3, mut s: f32) -> Option<f32> {
        for _ in 0..8 {
            let e = self.eval(i, s);
            let q = p - e.c;
            let g = q.dot(e.dc);
            let dg = -e.dc.dot(e.dc) + q.dot(e.ddc);
            if dg == 0.0 {
                break;
            }
            let step = g / dg;
            s -= step;
            if !(-0.01..=1.01).contains(&s) {
                return None;
            }
            if step.abs() <= 1e-7 {
                break;
            }
        }
        (-1e-4..=1.0 + 1e-4)
            .contains(&s)
            .then_some(s.clamp(0.0, 1.0))
    }

    /// The surface point at `p_approx` on segment `i`, its closest centre-line point at `s`
    /// (Mitsuba's normal: (|c'|² − q·c'')·q − r·r'·c', q = p − c), hit by `ray` (which only
    /// pbrt-v4's curves read).
    pub(crate) fn interaction(&self, i: usize, p_approx: Vec3, s: f32, ray: &Ray) -> Intersection {
        let e = self.eval(i, s);
        if let Some(kind) = self.pbrt {
            return self.pbrt_interaction(i, &e, s, ray, kind);
        }
        let axis = e.dc.try_normalize().unwrap_or(Vec3::X);
        let q = (p_approx - e.c)
            .try_normalize()
            .unwrap_or(axis.any_orthonormal_vector());
        let p = p_approx;
        let qr = q * e.r;
        let n = ((e.dc.dot(e.dc) - qr.dot(e.ddc)) * qr - (e.dr * e.r) * e.dc)
            .try_normalize()
            .unwrap_or(q);
        let count = self.segments.len() as f32;
        Intersection {
            t: 0.0,
            p,
            p_error: Vec3::splat(1e-4 * (p.abs().max_element() + e.r)),
            n_geom: n,
            n_shading: n,
            uv: Vec2::new(angle_around(axis, q) / (2.0 * PI), (s + i as f32) / count),
            dpdu: axis.cross(qr) * (2.0 * PI),
            dpdv: e.dc * count,
            shape: 0,
            prim: i as u32,
        }
    }
}

#[cfg(test)]
mod tests;
