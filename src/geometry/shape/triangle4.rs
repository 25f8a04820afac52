//! Four triangles side by side, and a prefilter that runs the first steps of the watertight
//! test (`triangle.rs`) on all four at once.
//!
//! Why. A BVH leaf of up to four triangles tested one after the other costs four full tests;
//! most rays miss most of them at the first sign test of the edge functions. The prefilter
//! computes the edge functions, their signs, the determinant and the distance interval for the
//! four lanes together (the compiler turns the lane loops into 4-wide SSE instructions) and
//! keeps only the lanes that may hit; those are then tested exactly, one by one, by
//! [`intersect_triangle_with`](super::triangle::intersect_triangle_with).
//!
//! Exactness. Every operation of the prefilter is the scalar test's own operation on the same
//! operands in the same order (subtract, multiply, add; Rust never fuses them), so a lane it
//! rejects is one the scalar test rejects at the same step, with the same `t_max` or a smaller
//! one. Where an edge function is exactly zero (the scalar test recomputes it in f64) the lane
//! is kept. A lane without a triangle holds NaN, which fails the determinant test. So the
//! hits found, and which of several equal hits wins, are those of testing every triangle.

use glam::Vec3;

use super::triangle::{WatertightRay, component};
use crate::geometry::ray::Ray;

/// Up to four triangles in structure-of-arrays form: corner `c`, axis `a`, lane `l` at
/// `p[c][a][l]`, m. A lane without a triangle holds NaN.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub(crate) struct Tri4 {
    p: [[[f32; 4]; 3]; 3],
}

impl Tri4 {
    /// The block of `lanes` (None: no triangle in that lane).
    pub(crate) fn new(lanes: [Option<[Vec3; 3]>; 4]) -> Tri4 {
        let mut p = [[[f32::NAN; 4]; 3]; 3];
        for (l, tri) in lanes.iter().enumerate() {
            if let Some(tri) = tri {
                for (c, v) in tri.iter().enumerate() {
                    for a in 0..3 {
                        p[c][a][l] = v[a];
                    }
                }
            }
        }
        Tri4 { p }
    }

    /// The corners of lane `l` (NaN if it holds no triangle, see [`Tri4::triangle_lanes`]).
    #[inline(always)]
    pub(crate) fn corners(&self, l: usize) -> [Vec3; 3] {
        let p = &self.p;
        let corner = |c: usize| Vec3::new(p[c][0][l], p[c][1][l], p[c][2][l]);
        [corner(0), corner(1), corner(2)]
    }

    /// Bit l is set for each lane that holds a triangle.
    #[inline(always)]
    pub(crate) fn triangle_lanes(&self) -> u32 {
        let x = &self.p[0][0];
        (0..4).fold(0, |m, l| m | ((!x[l].is_nan()) as u32) << l)
    }

    /// Bit l is set for each lane whose triangle the watertight test might find hit by `ray`
    /// (with its per-ray part `w`) at a distance below `t_max`; a clear bit means the test
    /// would return `None` (or that the lane holds no triangle).
    #[inline]
    pub(crate) fn candidates(&self, ray: &Ray, w: &WatertightRay, t_max: f32) -> u32 {
        match w.kz {
            0 => self.candidates_permuted::<1, 2, 0>(ray, w, t_max),
            1 => self.candidates_permuted::<2, 0, 1>(ray, w, t_max),
            _ => self.candidates_permuted::<0, 1, 2>(ray, w, t_max),
        }
    }

    /// [`Tri4::candidates`] for the permutation (KX, KY, KZ) of `w`, in SSE on x86_64 (part
    /// of its baseline), lane by lane elsewhere; the same operations either way.
    #[inline(always)]
    fn candidates_permuted<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        ray: &Ray,
        w: &WatertightRay,
        t_max: f32,
    ) -> u32 {
        let o = [
            component::<KX>(ray.o),
            component::<KY>(ray.o),
            component::<KZ>(ray.o),
        ];
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::*;
            // SAFETY: SSE2 is part of x86_64; the rows are 16-byte aligned arrays of 4 f32
            // (`repr(align(16))`, rows of 16 bytes).
            unsafe {
                let row = |c: usize, a: usize| _mm_load_ps(self.p[c][a].as_ptr());
                let (ox, oy, oz) = (_mm_set1_ps(o[0]), _mm_set1_ps(o[1]), _mm_set1_ps(o[2]));
                let (sx, sy) = (_mm_set1_ps(w.shear_x), _mm_set1_ps(w.shear_y));
                // corners relative to the origin, permuted, sheared (the scalar test's `q`)
                let q = |c: usize| {
                    let rx = _mm_sub_ps(row(c, KX), ox);
                    let ry = _mm_sub_ps(row(c, KY), oy);
                    let rz = _mm_sub_ps(row(c, KZ), oz);
                    (
                        _mm_add_ps(rx, _mm_mul_ps(sx, rz)),
                        _mm_add_ps(ry, _mm_mul_ps(sy, rz)),
                        rz,
                    )
                };
                let ((x0, y0, z0), (x1, y1, z1), (x2, y2, z2)) = (q(0), q(1), q(2));
                let e0 = _mm_sub_ps(_mm_mul_ps(x1, y2), _mm_mul_ps(y1, x2));
                let e1 = _mm_sub_ps(_mm_mul_ps(x2, y0), _mm_mul_ps(y2, x0));
                let e2 = _mm_sub_ps(_mm_mul_ps(x0, y1), _mm_mul_ps(y0, x1));
                let zero = _mm_setzero_ps();
                let any = |f: fn(__m128, __m128) -> __m128| {
                    _mm_or_ps(_mm_or_ps(f(e0, zero), f(e1, zero)), f(e2, zero))
                };
                let on_edge = any(|a, b| _mm_cmpeq_ps(a, b));
                let neg = any(|a, b| _mm_cmplt_ps(a, b));
                let pos = any(|a, b| _mm_cmpgt_ps(a, b));
                let det = _mm_add_ps(_mm_add_ps(e0, e1), e2);
                let sz = _mm_set1_ps(w.scale_z);
                let ts = _mm_add_ps(
                    _mm_add_ps(
                        _mm_mul_ps(e0, _mm_mul_ps(z0, sz)),
                        _mm_mul_ps(e1, _mm_mul_ps(z1, sz)),
                    ),
                    _mm_mul_ps(e2, _mm_mul_ps(z2, sz)),
                );
                let tmd = _mm_mul_ps(_mm_set1_ps(t_max), det);
                // det < 0 && !(ts ≥ 0 || ts < t_max·det), det > 0 && !(ts ≤ 0 || ts > t_max·det)
                let in_neg = _mm_andnot_ps(
                    _mm_or_ps(_mm_cmpge_ps(ts, zero), _mm_cmplt_ps(ts, tmd)),
                    _mm_cmplt_ps(det, zero),
                );
                let in_pos = _mm_andnot_ps(
                    _mm_or_ps(_mm_cmple_ps(ts, zero), _mm_cmpgt_ps(ts, tmd)),
                    _mm_cmpgt_ps(det, zero),
                );
                let keep = _mm_or_ps(
                    on_edge,
                    _mm_andnot_ps(_mm_and_ps(neg, pos), _mm_or_ps(in_neg, in_pos)),
                );
                #[allow(clippy::needless_return)]
                return _mm_movemask_ps(keep) as u32;
            }
        }
        #[allow(unreachable_code)]
        self.candidates_lanes(o, w, t_max, [KX, KY, KZ])
    }

    /// The lane-by-lane form of [`Tri4::candidates_permuted`] (`o`: the permuted origin; `k`:
    /// the axes).
    #[cfg_attr(target_arch = "x86_64", allow(dead_code))]
    fn candidates_lanes(&self, o: [f32; 3], w: &WatertightRay, t_max: f32, k: [usize; 3]) -> u32 {
        let mut mask = 0;
        for l in 0..4 {
            let q = |c: usize| {
                let (rx, ry, rz) = (
                    self.p[c][k[0]][l] - o[0],
                    self.p[c][k[1]][l] - o[1],
                    self.p[c][k[2]][l] - o[2],
                );
                (rx + w.shear_x * rz, ry + w.shear_y * rz, rz)
            };
            let ((x0, y0, z0), (x1, y1, z1), (x2, y2, z2)) = (q(0), q(1), q(2));
            let e0 = x1 * y2 - y1 * x2;
            let e1 = x2 * y0 - y2 * x0;
            let e2 = x0 * y1 - y0 * x1;
            let on_edge = e0 == 0.0 || e1 == 0.0 || e2 == 0.0;
            let neg = e0 < 0.0 || e1 < 0.0 || e2 < 0.0;
            let pos = e0 > 0.0 || e1 > 0.0 || e2 > 0.0;
            let det = e0 + e1 + e2;
            let ts = e0 * (z0 * w.scale_z) + e1 * (z1 * w.scale_z) + e2 * (z2 * w.scale_z);
            let tmd = t_max * det;
            let in_neg = det < 0.0 && !(ts >= 0.0 || ts < tmd);
            let in_pos = det > 0.0 && !(ts <= 0.0 || ts > tmd);
            let keep = on_edge || (!(neg && pos) && (in_neg || in_pos));
            mask |= (keep as u32) << l;
        }
        mask
    }
}

#[cfg(test)]
mod tests {
    use super::super::triangle::intersect_triangle_with;
    use super::*;

    fn hash(x: u32) -> u32 {
        let mut x = x.wrapping_mul(0x9e37_79b9) ^ 0x5bd1_e995;
        x ^= x >> 15;
        x = x.wrapping_mul(0x2c1b_3c6d);
        x ^= x >> 12;
        x
    }

    /// The prefilter never drops a lane the full test hits, on random triangles and rays and
    /// on rays through the triangles' corners and edges (where edge functions are zero), with
    /// finite and infinite `t_max`; lanes without a triangle are never kept.
    #[test]
    fn keeps_every_lane_the_full_test_hits() {
        let mut k = 1u32;
        let mut rnd = || {
            k = hash(k);
            (k >> 8) as f32 / (1 << 24) as f32
        };
        let (mut hits, mut dropped_misses) = (0, 0);
        for case in 0..20_000 {
            let mut v = || Vec3::new(rnd() * 4.0 - 2.0, rnd() * 4.0 - 2.0, rnd() * 4.0 - 2.0);
            let tris: [[Vec3; 3]; 4] = std::array::from_fn(|_| [v(), v(), v()]);
            let lanes = [Some(tris[0]), Some(tris[1]), Some(tris[2]), None];
            let block = Tri4::new(lanes);
            let o = v() * 3.0;
            // aim at a random point of lane 0: a corner, an edge midpoint or inside
            let target = match case % 3 {
                0 => tris[0][case % 3],
                1 => 0.5 * (tris[0][0] + tris[0][1]),
                _ => (tris[0][0] + tris[0][1] + tris[0][2]) / 3.0,
            };
            let d = (target - o).normalize_or(Vec3::X);
            let t_max = if case % 2 == 0 {
                f32::INFINITY
            } else {
                rnd() * 10.0
            };
            let ray = Ray {
                t_max,
                ..Ray::new(o, d)
            };
            let w = WatertightRay::new(&ray);
            let mask = block.candidates(&ray, &w, t_max);
            let axes = [(w.kz + 1) % 3, (w.kz + 2) % 3, w.kz];
            let o = axes.map(|a| ray.o[a]);
            assert_eq!(block.candidates_lanes(o, &w, t_max, axes), mask);
            assert_eq!(block.triangle_lanes(), 0b0111);
            assert_eq!(mask & 0b1000, 0, "an empty lane was kept");
            for (l, tri) in tris.iter().take(3).enumerate() {
                assert_eq!(block.corners(l), *tri);
                let full = intersect_triangle_with(*tri, &ray, &w, t_max);
                if full.is_some() {
                    hits += 1;
                    assert_ne!(
                        mask & (1 << l),
                        0,
                        "case {case}, lane {l}: a hit was dropped"
                    );
                } else if mask & (1 << l) == 0 {
                    dropped_misses += 1;
                }
            }
        }
        assert_eq!(block_empty().triangle_lanes(), 0);
        // the test means something: many hits, and most misses filtered out
        assert!(hits > 5_000, "{hits} hits");
        assert!(dropped_misses > 20_000, "{dropped_misses} misses filtered");
    }

    fn block_empty() -> Tri4 {
        Tri4::new([None; 4])
    }
}
