//! Rays and robust spawning of secondary rays from surfaces.
//!
//! Intersection routines report each hit point with a conservative per-axis absolute error bound
//! (`p_error`, metres; pbrt-v4 §6.8). A ray that leaves a surface starts from that point pushed
//! along the geometric normal just beyond the error box, so that it cannot re-hit the surface it
//! leaves ("surface acne"), without the scene-dependent epsilon of older renderers.

use super::float::next_float_toward3;
use glam::Vec3;

/// A ray `o + t·d` for `t` in (0, `t_max`). Lengths in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Origin, world space, m.
    pub o: Vec3,
    /// Direction, unit length. Because it is unit, `t` is a distance in metres.
    pub d: Vec3,
    /// Largest distance of interest, m (`f32::INFINITY` for unbounded rays).
    pub t_max: f32,
}

impl Ray {
    /// An unbounded ray. `d` is normalised; a zero or non-finite `d` gives a ray with a
    /// zero direction that hits nothing.
    #[inline]
    pub fn new(o: Vec3, d: Vec3) -> Ray {
        Ray {
            o,
            d: d.normalize_or_zero(),
            t_max: f32::INFINITY,
        }
    }

    /// The point at distance `t` along the ray.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}

/// Relative amount by which [`spawn_ray_to`] stops short of its target, on top of offsetting
/// the target point off its own surface. It absorbs the rounding of the normalised direction
/// (a few ε of the length) with a wide margin. Occluders closer to the target than
/// `SHADOW_EPSILON × distance` are not seen.
pub const SHADOW_EPSILON: f32 = 1.0e-5;

/// Offsets `p` (with absolute error bound `p_error`, per axis, m) along the geometric normal `n`
/// (unit) to the side of `dir`, so that a ray leaving the surface in direction `dir` cannot
/// re-hit it.
///
/// The offset is the projection of the error box onto the normal, `(|n|·p_error) n`, and each
/// component of the result is then rounded one more float away from the surface (pbrt-v4
/// §6.8.6). A zero `p_error` (an exactly known point) gives `p` unchanged.
#[inline]
pub fn offset_ray_origin(p: Vec3, p_error: Vec3, n: Vec3, dir: Vec3) -> Vec3 {
    let dist = n.abs().dot(p_error);
    let mut offset = n * dist;
    if dir.dot(n) < 0.0 {
        offset = -offset;
    }
    next_float_toward3(p + offset, offset)
}

/// `n` flipped to the side of `d`, for offsetting a ray that leaves a surface along `d`.
#[inline]
pub fn flip_toward(n: Vec3, d: Vec3) -> Vec3 {
    if n.dot(d) < 0.0 { -n } else { n }
}

/// A ray leaving the surface point `p` (error bound `p_error`, geometric normal `n`) in
/// direction `dir` (need not be unit; it is normalised). `t_max` is infinite. A zero `dir`
/// is replaced by `n`, so the result never contains NaN.
#[inline]
pub fn spawn_ray(p: Vec3, p_error: Vec3, n: Vec3, dir: Vec3) -> Ray {
    let d = dir.try_normalize().unwrap_or(n);
    Ray {
        o: offset_ray_origin(p, p_error, n, d),
        d,
        t_max: f32::INFINITY,
    }
}

/// A shadow ray from the surface point `p` to the surface point `target`, which stops just short
/// of the target surface.
///
/// Both ends are offset off their surfaces (toward each other) by their error bounds; `t_max` is
/// the distance between the offset ends times `1 − SHADOW_EPSILON`. For a target that is not on
/// a surface (a point light), pass `target_error = target_n = Vec3::ZERO`. If the two offset
/// points coincide, the ray has `t_max = 0` and hits nothing.
#[inline]
pub fn spawn_ray_to(
    p: Vec3,
    p_error: Vec3,
    n: Vec3,
    target: Vec3,
    target_error: Vec3,
    target_n: Vec3,
) -> Ray {
    let po = offset_ray_origin(p, p_error, n, target - p);
    let pt = offset_ray_origin(target, target_error, target_n, po - target);
    let v = pt - po;
    let len = v.length();
    if len > 0.0 && len.is_finite() {
        Ray {
            o: po,
            d: v / len,
            t_max: len * (1.0 - SHADOW_EPSILON),
        }
    } else {
        Ray {
            o: po,
            d: n,
            t_max: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_goes_to_the_side_of_dir() {
        let p = Vec3::new(1.0, 2.0, 0.0);
        let err = Vec3::splat(1e-6);
        let up = offset_ray_origin(p, err, Vec3::Z, Vec3::new(0.3, 0.0, 1.0));
        let down = offset_ray_origin(p, err, Vec3::Z, Vec3::new(0.3, 0.0, -1.0));
        assert!(up.z >= 1e-6 && down.z <= -1e-6);
        assert_eq!((up.x, up.y), (p.x, p.y));
    }

    #[test]
    fn spawn_to_stops_short() {
        let r = spawn_ray_to(
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::Z,
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::ZERO,
            Vec3::ZERO,
        );
        assert!((r.d - Vec3::Z).length() < 1e-7);
        assert!(r.t_max < 2.0 && r.t_max > 1.999);
    }
}
