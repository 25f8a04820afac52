//! Watertight ray–triangle intersection.
//!
//! Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013: the triangle
//! is translated to the ray origin, the axes are permuted so that the ray's largest direction
//! component is z, and the vertices are sheared so that the ray becomes the +z axis. The 2D edge
//! functions at the origin then decide the hit; they are evaluated identically for the two
//! triangles sharing an edge, so a ray through a shared edge or vertex cannot slip between them.
//! If an edge function is exactly zero it is recomputed in f64, which is exact for products of
//! f32 values. A hit is accepted only if it is provably ahead of the origin: its distance
//! exceeds a conservative bound on its rounding error (pbrt-v4 §6.8.4, tightened for sheared
//! coordinates), or else the origin is provably off the triangle's plane and moving toward it.
//! This keeps spawned rays from re-hitting their triangle.

use crate::geometry::float::gamma;
use crate::geometry::ray::Ray;
use glam::Vec3;

/// The per-ray part of the watertight test (Woop et al. 2013 §3): the axis permutation that
/// makes the ray's largest direction component z, and the shear that maps the ray onto +z.
/// Computed once per ray and shared by every triangle the ray is tested against.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightRay {
    /// The axis of the largest |d| component, which becomes z; x and y are the next two axes
    /// in cyclic order (kz + 1, kz + 2 mod 3).
    pub(super) kz: usize,
    pub(super) shear_x: f32,
    pub(super) shear_y: f32,
    pub(super) scale_z: f32,
}

impl WatertightRay {
    #[inline]
    pub(crate) fn new(ray: &Ray) -> Self {
        let kz = ray.d.abs().max_position();
        let kx = if kz == 2 { 0 } else { kz + 1 };
        let ky = if kx == 2 { 0 } else { kx + 1 };
        let (dx, dy, dz) = (ray.d[kx], ray.d[ky], ray.d[kz]);
        Self {
            kz,
            shear_x: -dx / dz,
            shear_y: -dy / dz,
            scale_z: 1.0 / dz,
        }
    }
}

/// Intersects `ray` with the triangle `p` (either winding). Returns the distance `t` in
/// (0, `ray.t_max`) and the barycentric coordinates of the hit for vertices 0, 1, 2.
#[inline]
pub(crate) fn intersect_triangle(p: [Vec3; 3], ray: &Ray) -> Option<(f32, [f32; 3])> {
    intersect_triangle_with(p, ray, &WatertightRay::new(ray), ray.t_max)
}

/// [`intersect_triangle`] with the per-ray part precomputed (`w` must come from `ray`) and the
/// distance limit `t_max` in place of `ray.t_max` (a traversal's closest hit so far).
///
/// The test is compiled once per permutation (the ray's z axis), so that the permutation is a
/// choice of registers rather than indexing through memory; the branch between them takes the
/// same way for every triangle a ray meets.
#[inline]
pub(crate) fn intersect_triangle_with(
    p: [Vec3; 3],
    ray: &Ray,
    w: &WatertightRay,
    t_max: f32,
) -> Option<(f32, [f32; 3])> {
    match w.kz {
        0 => intersect_permuted::<1, 2, 0>(p, ray, w, t_max),
        1 => intersect_permuted::<2, 0, 1>(p, ray, w, t_max),
        _ => intersect_permuted::<0, 1, 2>(p, ray, w, t_max),
    }
}

/// Component `K` (0 = x, 1 = y, 2 = z) of `v`.
#[inline(always)]
pub(super) fn component<const K: usize>(v: Vec3) -> f32 {
    match K {
        0 => v.x,
        1 => v.y,
        _ => v.z,
    }
}

/// [`intersect_triangle_with`] for the permutation (KX, KY, KZ) of `w`.
#[inline(always)]
fn intersect_permuted<const KX: usize, const KY: usize, const KZ: usize>(
    p: [Vec3; 3],
    ray: &Ray,
    w: &WatertightRay,
    t_max: f32,
) -> Option<(f32, [f32; 3])> {
    let (shear_x, shear_y, scale_z) = (w.shear_x, w.shear_y, w.scale_z);

    // Vertices relative to the origin, permuted, then sheared in x and y. (Written out: the
    // closures of `[T; 3]::map` were not inlined and cost a fifth of the test.)
    let permute = |v: Vec3| {
        let a = v - ray.o;
        Vec3::new(component::<KX>(a), component::<KY>(a), component::<KZ>(a))
    };
    let rel = [permute(p[0]), permute(p[1]), permute(p[2])];
    let shear = |v: Vec3| Vec3::new(v.x + shear_x * v.z, v.y + shear_y * v.z, v.z);
    let q = [shear(rel[0]), shear(rel[1]), shear(rel[2])];

    let mut e = [
        q[1].x * q[2].y - q[1].y * q[2].x,
        q[2].x * q[0].y - q[2].y * q[0].x,
        q[0].x * q[1].y - q[0].y * q[1].x,
    ];
    if e[0] == 0.0 || e[1] == 0.0 || e[2] == 0.0 {
        e = edges_f64(&q);
    }
    let any_neg = e[0] < 0.0 || e[1] < 0.0 || e[2] < 0.0;
    let any_pos = e[0] > 0.0 || e[1] > 0.0 || e[2] > 0.0;
    if any_neg && any_pos {
        return None;
    }
    let det = e[0] + e[1] + e[2];

    let z = [q[0].z * scale_z, q[1].z * scale_z, q[2].z * scale_z];
    let t_scaled = e[0] * z[0] + e[1] * z[1] + e[2] * z[2];
    // t = t_scaled / det must lie in (0, t_max); compare without dividing.
    if det < 0.0 {
        if t_scaled >= 0.0 || t_scaled < t_max * det {
            return None;
        }
    } else if det > 0.0 {
        if t_scaled <= 0.0 || t_scaled > t_max * det {
            return None;
        }
    } else {
        return None; // zero (edge-on or degenerate) or NaN
    }

    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    if !(t < t_max) {
        return None;
    }

    // Conservative bound on the rounding error of t (after pbrt-v4 §6.8.4). The sheared x and
    // y carry the translation error of z scaled by the shear factor, so their bounds use
    // |shear|·max|z| (pbrt bounds |shear| by 1, which rejects valid hits of grazing rays on
    // large triangles at distances of metres).
    let max_x = q[0].x.abs().max(q[1].x.abs()).max(q[2].x.abs());
    let max_y = q[0].y.abs().max(q[1].y.abs()).max(q[2].y.abs());
    let max_rel_z = rel[0].z.abs().max(rel[1].z.abs()).max(rel[2].z.abs());
    let max_z = z[0].abs().max(z[1].abs()).max(z[2].abs());
    let delta_z = gamma(3) * max_z;
    let delta_x = gamma(5) * (max_x + 2.0 * shear_x.abs() * max_rel_z);
    let delta_y = gamma(5) * (max_y + 2.0 * shear_y.abs() * max_rel_z);
    let delta_e = 2.0 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
    let max_e = e[0].abs().max(e[1].abs()).max(e[2].abs());
    let delta_t =
        3.0 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * inv_det.abs();
    if !(t > delta_t || origin_clearly_in_front(p, ray)) {
        return None;
    }
    Some((t, [e[0] * inv_det, e[1] * inv_det, e[2] * inv_det]))
}

/// The edge functions in f64, exact for products of f32 values: for rays through an edge or a
/// vertex, where the f32 value rounded to zero.
#[cold]
fn edges_f64(q: &[Vec3; 3]) -> [f32; 3] {
    let edge64 = |a: Vec3, b: Vec3| {
        (f64::from(a.x) * f64::from(b.y) - f64::from(a.y) * f64::from(b.x)) as f32
    };
    [edge64(q[1], q[2]), edge64(q[2], q[0]), edge64(q[0], q[1])]
}

/// Second, independent test that a hit lies ahead of the origin, used when the bound on t is
/// inconclusive (grazing rays on large triangles, where it is very loose): true if the origin's
/// height above the triangle's plane is larger than its rounding error bound and the ray moves
/// toward the plane. Like the t bound it never accepts a hit behind the origin, so a ray spawned
/// off the surface still cannot re-hit it.
#[cold]
fn origin_clearly_in_front(p: [Vec3; 3], ray: &Ray) -> bool {
    // Measure from the nearest vertex: the error grows with the distance.
    let r = (0..3)
        .min_by(|&a, &b| {
            let (da, db) = (
                (ray.o - p[a]).length_squared(),
                (ray.o - p[b]).length_squared(),
            );
            da.total_cmp(&db)
        })
        .unwrap_or(0);
    let (pr, pa, pb) = (p[r], p[(r + 1) % 3], p[(r + 2) % 3]);
    let (e1, e2) = (pa - pr, pb - pr);
    let n = e1.cross(e2);
    // |n_i| ≤ n_abs_i, and the rounding error of n_i is bounded by γ(3)·n_abs_i.
    let n_abs = Vec3::new(
        (e1.y * e2.z).abs() + (e1.z * e2.y).abs(),
        (e1.z * e2.x).abs() + (e1.x * e2.z).abs(),
        (e1.x * e2.y).abs() + (e1.y * e2.x).abs(),
    );
    let w = ray.o - pr;
    let height = w.dot(n);
    let height_err = gamma(8) * w.abs().dot(n_abs);
    height.abs() > height_err && height * ray.d.dot(n) < 0.0
}

/// The point with barycentrics `b` and its absolute error bound per axis (pbrt-v4 §6.8.5).
#[inline]
pub(crate) fn barycentric_point(p: [Vec3; 3], b: [f32; 3]) -> (Vec3, Vec3) {
    let (w0, w1, w2) = (p[0] * b[0], p[1] * b[1], p[2] * b[2]);
    let point = w0 + w1 + w2;
    let error = gamma(7) * (w0.abs() + w1.abs() + w2.abs());
    (point, error)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: [Vec3; 3] = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];

    #[test]
    fn hit_and_barycentrics() {
        let ray = Ray::new(Vec3::new(0.25, 0.5, 2.0), -Vec3::Z);
        let (t, b) = intersect_triangle(TRI, &ray).unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        assert!((b[0] - 0.25).abs() < 1e-6 && (b[1] - 0.25).abs() < 1e-6);
        assert!((b[2] - 0.5).abs() < 1e-6);
        let (p, err) = barycentric_point(TRI, b);
        assert!(
            (p - Vec3::new(0.25, 0.5, 0.0))
                .abs()
                .cmple(err + 1e-7)
                .all()
        );
    }

    #[test]
    fn misses_outside_behind_and_beyond_t_max() {
        assert!(intersect_triangle(TRI, &Ray::new(Vec3::new(0.6, 0.6, 1.0), -Vec3::Z)).is_none());
        assert!(intersect_triangle(TRI, &Ray::new(Vec3::new(0.2, 0.2, 1.0), Vec3::Z)).is_none());
        let mut ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
        ray.t_max = 0.5;
        assert!(intersect_triangle(TRI, &ray).is_none());
    }
}
