//! Instancing (Mitsuba's `shapegroup` and `instance`): a [`Group`] of shapes in its own object
//! space with its own BVH, placed any number of times by [`Instance`]s whose world boxes are
//! primitives of the scene's top-level BVH ([`crate::geometry::Accel`]). A forest of one tree
//! stores the tree once.
//!
//! A ray reaching an instance's box is carried into object space (origin by the inverse
//! transform, direction by its linear part, renormalised, so that object-space distances are
//! k·t for the world distance t and k = |M⁻¹ d|), the group's BVH answers, and the hit comes
//! back to world space: the point and ∂p/∂u, ∂p/∂v by M, normals by M⁻ᵀ. The point's error bound
//! is carried through both transforms conservatively (pbrt-v4 §6.8.5's bound for transformed
//! points, applied to the object-space error plus the rounding of the ray's own trip into
//! object space), so rays spawned from an instanced surface do not re-hit it.

use std::sync::Arc;

use glam::{Mat3, Vec3};

use super::accel::Accel;
use super::float::gamma;
use super::ray::Ray;
use super::shape::{Intersection, Shape};
use super::transform::Transform;

/// Shapes in object space (m) and their BVH; their surfaces are `surface_base + i` in the
/// scene's surface list.
pub struct Group {
    pub shapes: Vec<Shape>,
    pub accel: Accel,
    pub surface_base: u32,
}

impl Group {
    /// A group of `shapes` (object space) whose surfaces start at `surface_base`.
    pub fn new(shapes: Vec<Shape>, surface_base: u32) -> Group {
        let accel = Accel::build(&shapes);
        Group {
            shapes,
            accel,
            surface_base,
        }
    }
}

/// A group placed by an object-to-world transform.
#[derive(Clone)]
pub struct Instance {
    pub group: Arc<Group>,
    to_world: Transform,
    /// |M| and |M⁻¹| (element-wise absolute linear parts) and |translation|s, for error bounds.
    abs_m: Mat3,
    abs_inv: Mat3,
    abs_t: Vec3,
    abs_inv_t: Vec3,
}

impl Instance {
    pub fn new(group: Arc<Group>, to_world: Transform) -> Instance {
        let abs3 = |m: glam::Mat4| {
            let l = Mat3::from_mat4(m);
            Mat3::from_cols(l.x_axis.abs(), l.y_axis.abs(), l.z_axis.abs())
        };
        Instance {
            group,
            abs_m: abs3(to_world.matrix()),
            abs_inv: abs3(to_world.inverse_matrix()),
            abs_t: to_world.matrix().w_axis.truncate().abs(),
            abs_inv_t: to_world.inverse_matrix().w_axis.truncate().abs(),
            to_world,
        }
    }

    /// World bounds (min, max) of the placed group, m: its object box's eight corners
    /// transformed; None for an empty group.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let (lo, hi) = self.group.accel.bounds()?;
        let b = self.to_world.box_bounds(lo, hi);
        // the corners' own rounding
        let pad = (b.0.abs().max(b.1.abs())) * gamma(4);
        Some((b.0 - pad, b.1 + pad))
    }

    /// `ray` in object space with a unit direction, and k = |M⁻¹ d| (object distance per world
    /// distance); None for a degenerate direction.
    #[inline]
    pub(crate) fn to_object(&self, ray: &Ray) -> Option<(Ray, f32)> {
        let inv = self.to_world.inverse();
        let d = inv.vector(ray.d);
        let k = d.length();
        if !(k > 0.0 && k.is_finite()) {
            return None;
        }
        Some((
            Ray {
                o: inv.point(ray.o),
                d: d / k,
                t_max: ray.t_max * k,
            },
            k,
        ))
    }

    /// An object-space hit `it` (found along an object ray of scale `k`) in world space, with
    /// its surface index offset by the group's.
    pub(crate) fn to_world(&self, it: Intersection, k: f32) -> Intersection {
        let m = &self.to_world;
        let p = m.point(it.p);
        // error of the object-space point, plus the rounding of the origin's trip into object
        // space (|M⁻¹|·|p_w| + |t⁻¹| at γ₃) and of this transform back (|M|·|p_o| + |t| at γ₃),
        // all carried to world space by |M|
        let e_obj = it.p_error + (self.abs_inv * p.abs() + self.abs_inv_t) * gamma(6);
        let p_error = (self.abs_m * e_obj) * (1.0 + gamma(3))
            + (self.abs_m * it.p.abs() + self.abs_t) * gamma(6);
        let n = |v: Vec3| m.normal(v).normalize_or_zero();
        Intersection {
            t: it.t / k,
            p,
            p_error,
            n_geom: n(it.n_geom),
            n_shading: n(it.n_shading),
            uv: it.uv,
            dpdu: m.vector(it.dpdu),
            dpdv: m.vector(it.dpdv),
            shape: self.group.surface_base + it.shape,
            prim: it.prim,
        }
    }
}
