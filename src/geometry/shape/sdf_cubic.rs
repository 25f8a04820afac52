//! The cubic along a ray through an SDF grid's voxel and its first root (see
//! [`super::SdfGrid`]).

use glam::Vec3;

/// Coefficients [c0, c1, c2, c3] of the trilinear interpolant of corners `c` (index bits x, y,
/// z) along p + t·d in voxel space.
pub(super) fn voxel_cubic(c: &[f32; 8], p: Vec3, d: Vec3) -> [f32; 4] {
    // f = Σ c_ijk · X_i(x) Y_j(y) Z_k(z) with X_0 = 1 − x, X_1 = x: each factor linear in t
    let lin = |o: f32, dd: f32, bit: bool| if bit { (o, dd) } else { (1.0 - o, -dd) };
    let mut out = [0.0f32; 4];
    for (i, &ci) in c.iter().enumerate() {
        let (a0, a1) = lin(p.x, d.x, i & 1 == 1);
        let (b0, b1) = lin(p.y, d.y, i & 2 == 2);
        let (e0, e1) = lin(p.z, d.z, i & 4 == 4);
        // (a0 + a1 t)(b0 + b1 t)(e0 + e1 t)
        let q = [a0 * b0, a0 * b1 + a1 * b0, a1 * b1];
        out[0] += ci * q[0] * e0;
        out[1] += ci * (q[1] * e0 + q[0] * e1);
        out[2] += ci * (q[2] * e0 + q[1] * e1);
        out[3] += ci * q[2] * e1;
    }
    out
}

/// The first t in [0, t_len] where the cubic changes sign (or is zero), splitting at its
/// derivative's roots and bisecting the first piece whose ends differ in sign.
pub(super) fn first_root(c: [f32; 4], t_len: f32) -> Option<f32> {
    let f = |t: f32| ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
    // f' = 3c3 t² + 2c2 t + c1; its roots (NaN where absent) cut [0, t_len] into monotone
    // pieces (no allocation: this runs per ray and voxel)
    let (a, b, cc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut roots = [f32::NAN; 2];
    if a.abs() > 1e-12 {
        let disc = b * b - 4.0 * a * cc;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            roots = [q / a, if q != 0.0 { cc / q } else { f32::NAN }];
        }
    } else if b.abs() > 1e-12 {
        roots[0] = -cc / b;
    }
    let inside = |r: f32| if r > 0.0 && r < t_len { r } else { t_len };
    let (r0, r1) = (inside(roots[0]), inside(roots[1]));
    let cuts = [0.0, r0.min(r1), r0.max(r1), t_len];
    for w in cuts.windows(2) {
        if w[1] <= w[0] {
            continue;
        }
        let (mut lo, mut hi) = (w[0], w[1]);
        let (mut flo, fhi) = (f(lo), f(hi));
        if flo == 0.0 {
            return Some(lo);
        }
        if flo * fhi > 0.0 {
            continue;
        }
        for _ in 0..50 {
            let mid = 0.5 * (lo + hi);
            let fm = f(mid);
            if fm * flo > 0.0 {
                lo = mid;
                flo = fm;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-6 {
                break;
            }
        }
        return Some(0.5 * (lo + hi));
    }
    None
}
