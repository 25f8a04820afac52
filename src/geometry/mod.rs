//! Geometry: rays, frames, transforms, shapes, the BVH and cameras.

pub mod frame;

pub use frame::Frame;
