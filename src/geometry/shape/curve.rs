//! Mitsuba's `linearcurve`: tubes along polylines of control points, each segment the capsule
//! of its (constant) radius around it, joined and ended by the spheres of the control points
//! (the "round linear curves" of Embree and OptiX that Mitsuba traces). Only hits entering the
//! tube count (Mitsuba culls curve backfaces, so a ray from inside sees nothing).
//!
//! uv as Mitsuba 3.9.1 defines it (`linearcurve.cpp`): v = (segment + s)/segments, s ∈ [0, 1]
//! the hit's position along its segment (its centre-line point c = (1 − s)·p0 + s·p1, clamped
//! at the joints); u the angle of p − c around the axis from `rad` toward `rot`, over 2π, in the
//! frame `rot` = the +z guide made perpendicular to the axis (+y along z), `rad` = rot × axis.

use super::{Intersection, SurfaceSample};
use crate::geometry::error::GeometryError;
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use std::path::Path;

/// Polylines of world-space control points (m) with radii (m, untouched by the transform).
#[derive(Clone, Debug, PartialEq)]
pub struct LinearCurve {
    points: Vec<Vec3>,
    radii: Vec<f32>,
    /// Index of each segment's first control point (the second follows it).
    segments: Vec<u32>,
    /// Cumulative lateral area 2π·r·length per segment, m², for area sampling.
    cdf: Vec<f32>,
}

impl LinearCurve {
    /// Curves from polylines of (point, radius); each polyline needs two control points or
    /// more, finite coordinates and a radius > 0 that is the same along each segment.
    pub fn new(polylines: &[Vec<(Vec3, f32)>]) -> Result<Self, GeometryError> {
        let bad = |m: String| GeometryError::Curve(m);
        let (mut points, mut radii, mut segments, mut cdf) = (vec![], vec![], vec![], vec![]);
        let mut total = 0.0f32;
        for (k, line) in polylines.iter().enumerate() {
            if line.len() < 2 {
                return Err(bad(format!(
                    "curve {k} has {} control point(s), not 2 or more",
                    line.len()
                )));
            }
            for (i, &(p, r)) in line.iter().enumerate() {
                if !(p.is_finite() && r > 0.0 && r.is_finite()) {
                    return Err(bad(format!("curve {k}, control point {i}: {p} radius {r}")));
                }
                if i > 0 {
                    let (q, rq) = line[i - 1];
                    if rq != r {
                        return Err(bad(format!(
                            "curve {k}, segment {}: radius {rq} to {r}; a radius varying along a segment is not supported",
                            i - 1
                        )));
                    }
                    segments.push(points.len() as u32 - 1);
                    total += 2.0 * PI * r * (p - q).length();
                    cdf.push(total);
                }
                points.push(p);
                radii.push(r);
            }
        }
        if segments.is_empty() {
            return Err(bad("no curves".into()));
        }
        Ok(Self {
            points,
            radii,
            segments,
            cdf,
        })
    }

    /// Reads Mitsuba's curve file: `x y z radius` per line, an empty line between curves;
    /// positions transformed, radii not.
    pub fn load(path: &Path, transform: &Transform) -> Result<Self, GeometryError> {
        let lines = read_polylines(path, transform)?;
        Self::new(&lines).map_err(|e| GeometryError::MeshParse {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }

    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// Lateral area Σ 2π·r·length of the segments, m² (joints and caps not counted).
    pub fn area(&self) -> f32 {
        *self.cdf.last().expect("a segment at least")
    }

    fn segment(&self, i: usize) -> (Vec3, Vec3, f32) {
        let k = self.segments[i] as usize;
        (self.points[k], self.points[k + 1], self.radii[k])
    }

    pub(crate) fn aabb(&self, i: usize) -> (Vec3, Vec3) {
        let (a, b, r) = self.segment(i);
        (a.min(b) - Vec3::splat(r), a.max(b) + Vec3::splat(r))
    }

    /// The entering hit of `ray` with segment `i`'s capsule, t in (0, t_max), and the hit's
    /// position s ∈ [0, 1] along the segment (Quílez's capsule test: the body's quadratic
    /// clipped to the segment, else the nearer end's sphere).
    pub(crate) fn intersect(&self, i: usize, ray: &Ray) -> Option<(f32, f32)> {
        let (pa, pb, r) = self.segment(i);
        capsule_hit(pa, pb, r, ray, 1e-5 * r)
    }

    /// The surface point at `p_approx` on segment `i` at position `s` along it.
    pub(crate) fn interaction(&self, i: usize, p_approx: Vec3, s: f32) -> Intersection {
        let (p0, p1, r) = self.segment(i);
        let axis = (p1 - p0).normalize();
        let c = p0 * (1.0 - s) + p1 * s;
        let n = (p_approx - c)
            .try_normalize()
            .unwrap_or(axis.any_orthonormal_vector());
        let p = c + n * r;
        let u = angle_around(axis, n);
        let count = self.segments.len() as f32;
        Intersection {
            t: 0.0,
            p,
            p_error: Vec3::splat(1e-5 * (p.abs().max_element() + r)),
            n_geom: n,
            n_shading: n,
            uv: Vec2::new(u / (2.0 * PI), (s + i as f32) / count),
            dpdu: axis.cross(p - c) * (2.0 * PI),
            dpdv: (p1 - p0) * count,
            shape: 0,
            prim: i as u32,
        }
    }

    /// A point uniform by area on the segments' lateral surfaces (`pdf_area` = 1/[`Self::area`]):
    /// the segment by its area with `u.x`, then height and angle.
    pub fn sample_area(&self, u: Vec2) -> SurfaceSample {
        let total = self.area();
        let x = u.x * total;
        let i = self
            .cdf
            .partition_point(|&c| c <= x)
            .min(self.cdf.len() - 1);
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let s = ((x - lo) / (self.cdf[i] - lo)).clamp(0.0, 1.0);
        let (p0, p1, r) = self.segment(i);
        let axis = (p1 - p0).normalize();
        let e1 = axis.any_orthonormal_vector();
        let e2 = axis.cross(e1);
        let phi = 2.0 * PI * u.y;
        let n = e1 * phi.cos() + e2 * phi.sin();
        let p = p0 + (p1 - p0) * s + n * r;
        SurfaceSample {
            p,
            p_error: Vec3::splat(1e-5 * (p.abs().max_element() + r)),
            n,
            pdf_area: 1.0 / total,
            uv: Vec2::new(u.y, (s + i as f32) / self.segments.len() as f32),
        }
    }
}

/// Reads Mitsuba's curve file (`linearcurve`, `bsplinecurve`): a control point per line,
/// `x y z radius`; an empty line starts a new curve. Positions are transformed, radii are not
/// (Mitsuba's reading). An error names the file and the line.
pub(crate) fn read_polylines(
    path: &Path,
    transform: &Transform,
) -> Result<Vec<Vec<(Vec3, f32)>>, GeometryError> {
    let text = crate::files::read_text(path, crate::files::MAX_MESH_BYTES).map_err(|source| {
        GeometryError::MeshOpen {
            path: path.to_path_buf(),
            source,
        }
    })?;
    let mut lines: Vec<Vec<(Vec3, f32)>> = vec![vec![]];
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            if !lines.last().is_some_and(Vec::is_empty) {
                lines.push(vec![]);
            }
            continue;
        }
        if line.starts_with('#') {
            continue;
        }
        let v: Vec<f32> = line
            .split_whitespace()
            .filter_map(|t| t.parse().ok())
            .collect();
        if v.len() != 4 || line.split_whitespace().count() != 4 {
            return Err(GeometryError::MeshParse {
                path: path.to_path_buf(),
                message: format!(
                    "line {}: expected \"x y z radius\", found \"{line}\"",
                    n + 1
                ),
            });
        }
        let p = transform.point(Vec3::new(v[0], v[1], v[2]));
        lines.last_mut().expect("one line at least").push((p, v[3]));
    }
    lines.retain(|l| !l.is_empty());
    Ok(lines)
}

/// The entering hit of `ray` (unit direction) with the capsule of radius `r` around the
/// segment `pa`–`pb`, t in (`t_min`, t_max), and the hit's position s ∈ [0, 1] along the
/// segment (Quílez's capsule test: the body's quadratic clipped to the segment, else the
/// nearer end's sphere).
///
/// The quadratics' coefficients are written with cross products, a = |u × d|²,
/// b = (u × d)·(u × w), and their discriminants as r²·|u × d|² − (u·(d × w))² (over |u|²) and
/// r² − |d × w|², u = pb − pa, w = o − pa: the same numbers as the dot-product forms, without
/// the cancellation of |u|²|w|² − (u·w)², which lost thin capsules far from the ray's origin
/// to f32 rounding (a 5 mm tube seen from 30 m was missed by 80 of 195 rays through it).
pub(crate) fn capsule_hit(pa: Vec3, pb: Vec3, r: f32, ray: &Ray, t_min: f32) -> Option<(f32, f32)> {
    let (ro, rd) = (ray.o, ray.d);
    let ba = pb - pa;
    let oa = ro - pa;
    let baba = ba.dot(ba);
    let bard = ba.dot(rd);
    let baoa = ba.dot(oa);
    let (p, q) = (ba.cross(rd), ba.cross(oa));
    let a = p.dot(p);
    let b = p.dot(q);
    let triple = ba.dot(rd.cross(oa));
    // b² − a·c = |u|²·(r²·|u × d|² − (u·(d × w))²)
    let h = baba * (r * r * a - triple * triple);
    if h < 0.0 {
        return None;
    }
    let ok = |t: f32| t > t_min && t < ray.t_max;
    if a > 0.0 {
        let t = (-b - h.sqrt()) / a;
        let y = baoa + t * bard;
        if y > 0.0 && y < baba {
            return ok(t).then_some((t, y / baba));
        }
    }
    // the end sphere the body's hit lies beyond
    let y = baoa + ((-b - h.max(0.0).sqrt()) / a.max(f32::MIN_POSITIVE)) * bard;
    let (oc, s) = if y <= 0.0 { (oa, 0.0) } else { (ro - pb, 1.0) };
    let bb = rd.dot(oc);
    // bb² − (|oc|² − r²) = r² − |d × oc|²
    let hh = r * r - rd.cross(oc).length_squared();
    if hh <= 0.0 {
        return None;
    }
    let t = -bb - hh.sqrt();
    ok(t).then_some((t, s))
}

/// Mitsuba's u of a curve's surface (`local_frame`): the angle of the unit `n` around the unit
/// tangent `axis`, from `rad` toward `rot`, over 2π, in the frame `rot` = the +z guide made
/// perpendicular to the axis (+y along z), `rad` = rot × axis. In [0, 2π).
pub(crate) fn angle_around(axis: Vec3, n: Vec3) -> f32 {
    let guide = Vec3::Z;
    let rot = if guide.dot(axis).abs() == 1.0 {
        Vec3::Y
    } else {
        (guide - axis * axis.dot(guide)).normalize()
    };
    let rad = rot.cross(axis);
    let u = n.dot(rot).atan2(n.dot(rad));
    if u < 0.0 { u + 2.0 * PI } else { u }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve() -> LinearCurve {
        let r = 0.5;
        LinearCurve::new(&[vec![
            (Vec3::new(0.0, 0.0, 0.0), r),
            (Vec3::new(4.0, 0.0, 0.0), r),
            (Vec3::new(4.0, 4.0, 0.0), r),
        ]])
        .unwrap()
    }

    fn first_hit(c: &LinearCurve, o: Vec3, d: Vec3) -> Option<(usize, f32, f32)> {
        let ray = Ray::new(o, d.normalize());
        (0..c.segment_count())
            .filter_map(|i| c.intersect(i, &ray).map(|(t, s)| (i, t, s)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// Closed forms: the body at distance r from the axis, the end cap's sphere, the joint's
    /// sphere, a miss beside the tube and no hit from inside.
    #[test]
    fn capsule_hits_are_at_the_radius() {
        let c = curve();
        // down onto the first segment's body: t = 10 − r
        let (i, t, s) = first_hit(&c, Vec3::new(1.0, 0.0, 10.0), -Vec3::Z).unwrap();
        assert_eq!(i, 0);
        assert!((t - 9.5).abs() < 1e-4 && (s - 0.25).abs() < 1e-5, "{t} {s}");
        // along −x into the start cap: the sphere at the origin, t = 10 − r
        let (_, t, s) = first_hit(&c, Vec3::new(-10.0, 0.0, 0.0), Vec3::X).unwrap();
        assert!((t - 9.5).abs() < 1e-4 && s == 0.0, "{t} {s}");
        // diagonally into the joint's outer side at (4, 0): t = |o − joint| − r
        let o = Vec3::new(10.0, -6.0, 0.0);
        let (_, t, _) = first_hit(&c, o, Vec3::new(4.0, 0.0, 0.0) - o).unwrap();
        assert!(
            (t - ((o - Vec3::new(4.0, 0.0, 0.0)).length() - 0.5)).abs() < 1e-4,
            "{t}"
        );
        // beside the tube, 0.6 from the axis
        assert!(first_hit(&c, Vec3::new(1.0, 0.6, 10.0), -Vec3::Z).is_none());
        // from the axis outward: culled
        assert!(first_hit(&c, Vec3::new(1.0, 0.0, 0.0), Vec3::Z).is_none());
        let it = c.interaction(0, Vec3::new(1.0, 0.0, 0.5), 0.25);
        assert!((it.n_geom - Vec3::Z).length() < 1e-6);
        assert!((it.uv.y - 0.125).abs() < 1e-6);
    }

    /// Mitsuba's file: points transformed, radii not; an empty line starts a curve; a radius
    /// varying along a segment and a one-point curve are errors naming the file.
    #[test]
    fn curve_files() {
        let dir = std::env::temp_dir().join(format!("spectrace-curve-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("c.txt");
        std::fs::write(
            &p,
            "0 0 0 0.1\n1 0 0 0.1\n\n0 1 0 0.2\n0 2 0 0.2\n0 3 0 0.2\n",
        )
        .unwrap();
        let t = Transform::scale(Vec3::splat(2.0)).unwrap();
        let c = LinearCurve::load(&p, &t).unwrap();
        assert_eq!(c.segment_count(), 3);
        let expect = 2.0 * PI * (0.1 * 2.0 + 0.2 * 4.0);
        assert!((c.area() - expect).abs() < 1e-4, "{}", c.area());
        for bad in [
            "0 0 0 0.1\n1 0 0 0.2\n",
            "0 0 0 0.1\n",
            "0 0 0\n1 0 0 0.1\n",
        ] {
            std::fs::write(&p, bad).unwrap();
            let e = LinearCurve::load(&p, &t).unwrap_err().to_string();
            assert!(e.contains("c.txt"), "{e}");
        }
    }
}
