//! pbrt-v4's alpha tests in the accelerator ([`Accel::with_alpha`]): a hit on a shape with an
//! alpha function counts only where the function at the hit's uv passes a hash of the ray.
//! Scenes without alpha tests never reach this file's code (one branch on an empty list).

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::{Accel, PrimRef};
use crate::geometry::ray::Ray;
use crate::geometry::shape::{PrimHit, Shape, WatertightRay};

/// A shape's alpha at surface coordinates uv, in [0, 1] (the build step wraps a grey texture;
/// a function here so that the accelerator names no texture type). Called only for hits on
/// shapes that have one.
pub type AlphaFn = Arc<dyn Fn(Vec2) -> f32 + Send + Sync>;

impl Accel {
    /// Gives the shapes alpha tests, by shape index (pbrt-v4's `alpha`): a hit on a shape
    /// with a grey texture `a` at its uv counts only where a ≥ 1, never where a ≤ 0, and in
    /// between where a hash of the ray's origin and direction, uniform in [0, 1), is at most a
    /// (pbrt-v4's `GeometricPrimitive` test): a ray, and a shadow ray along the same line,
    /// pass through the same fraction 1 − a, the same for every thread and run.
    pub fn with_alpha(mut self, alpha: Vec<Option<AlphaFn>>) -> Accel {
        self.alpha = if alpha.iter().any(Option::is_some) {
            alpha
        } else {
            Vec::new()
        };
        self
    }

    /// Whether the hit `h` at `t` on primitive `pr` survives its shape's alpha test (always
    /// without one). Out of line: only scenes with alpha tests call it.
    #[inline(never)]
    pub(super) fn alpha_passes(
        &self,
        shapes: &[Shape],
        pr: PrimRef,
        ray: &Ray,
        t: f32,
        h: &PrimHit,
    ) -> bool {
        let Some(Some(alpha)) = self.alpha.get(pr.shape as usize) else {
            return true;
        };
        let Some(shape) = shapes.get(pr.shape as usize) else {
            return true;
        };
        let a = alpha(shape.interaction(pr.shape, pr.prim as usize, ray, t, h).uv);
        if a >= 1.0 {
            return true;
        }
        if !(a > 0.0) {
            return false;
        }
        let bits = [ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z].map(f32::to_bits);
        let mut hash = 0x9e37_79b9_7f4a_7c15u64;
        for b in bits {
            hash = (hash ^ b as u64).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            hash ^= hash >> 31;
        }
        ((hash >> 40) as f32 / (1u64 << 24) as f32) <= a
    }

    /// [`Accel::intersect_prim`] in a scene with alpha tests: the hit, if it passes its
    /// shape's. Out of line, so that the leaf test of scenes without them stays as small.
    #[inline(never)]
    pub(super) fn intersect_prim_alpha(
        &self,
        shapes: &[Shape],
        id: usize,
        tri: Option<[Vec3; 3]>,
        ray: &Ray,
        wt: &WatertightRay,
        t_max: f32,
    ) -> Option<(f32, PrimHit)> {
        let pr = self.prims[id];
        let (t, h) = self.hit_prim(shapes, id, tri, ray, wt, t_max)?;
        self.alpha_passes(shapes, pr, ray, t, &h).then_some((t, h))
    }
}
