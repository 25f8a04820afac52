//! Geometry: rays, frames, transforms, shapes, the BVH and cameras.
//!
//! Units: metres and radians, `f32`. Shapes live in world space (transforms are applied when
//! they are built). Intersections carry a conservative error bound on the hit point, and
//! [`ray::spawn_ray`] uses it to start secondary rays without self-intersection (pbrt-v4 §6.8).
//! Invalid user input gives a [`GeometryError`], never a panic.

// `!(a > b)` is used on purpose throughout: unlike `a <= b` it is also true when a value is NaN,
// so NaN input falls on the "no hit" / "invalid" side.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod accel;
pub mod camera;
pub mod error;
pub mod float;
pub mod frame;
pub mod instance;
pub mod ray;
pub mod shape;
pub mod transform;
mod wide;

pub use accel::Accel;
pub use camera::{Camera, FovAxis, Realistic, RealisticError};
pub use error::GeometryError;
pub use frame::Frame;
pub use instance::{Group, Instance};
pub use ray::{Ray, flip_toward, offset_ray_origin, spawn_ray, spawn_ray_to};
pub use shape::{
    Cylinder, Disk, Intersection, Mesh, PrimHit, Shape, SolidAngleSample, Sphere, SurfaceSample,
};
pub use transform::Transform;
