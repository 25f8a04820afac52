//! Helpers for the geometry tests: test meshes, random directions and brute-force queries.
//! Include with `#[path = "support/geometry.rs"] mod geo;` (next to `mod support;`).
#![allow(dead_code)]

use glam::{Vec2, Vec3};
use spectrace::geometry::{Mesh, Ray, Shape, Transform};
use std::f32::consts::PI;

/// A fan of `n` triangles around the origin approximating the disk of `radius` in the z = 0
/// plane (normal +z), transformed. Vertex 0 is the centre; vertex 1 + k is the rim vertex at
/// angle 2πk/n. Rim vertices on the axes and diagonals have exactly symmetric coordinates.
pub fn fan(n: usize, radius: f32, transform: &Transform) -> Mesh {
    let mut positions = vec![Vec3::ZERO];
    for k in 0..n {
        let phi = 2.0 * PI * k as f32 / n as f32;
        let (s, c) = exact_sin_cos(k, n, phi);
        positions.push(Vec3::new(radius * c, radius * s, 0.0));
    }
    let indices = (0..n)
        .map(|k| [0, 1 + k as u32, 1 + ((k + 1) % n) as u32])
        .collect();
    Mesh::new(positions, None, None, indices, transform).expect("valid fan")
}

/// sin and cos with exact values on multiples of π/4 (n divisible by 8).
fn exact_sin_cos(k: usize, n: usize, phi: f32) -> (f32, f32) {
    if n.is_multiple_of(8) && k.is_multiple_of(n / 8) {
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let table = [
            (0.0, 1.0),
            (h, h),
            (1.0, 0.0),
            (h, -h),
            (0.0, -1.0),
            (-h, -h),
            (-1.0, 0.0),
            (-h, h),
        ];
        table[k / (n / 8)]
    } else {
        phi.sin_cos()
    }
}

/// Two unit tangents (s, t) with s × t = n.
pub fn tangents(n: Vec3) -> (Vec3, Vec3) {
    let f = spectrace::geometry::Frame::from_normal(n);
    (f.s, f.t)
}

/// A unit direction at elevation `elev` (rad) above the plane with normal `n`, azimuth `az`.
pub fn direction_at_elevation(n: Vec3, elev: f32, az: f32) -> Vec3 {
    let (s, t) = tangents(n);
    ((s * az.cos() + t * az.sin()) * elev.cos() + n * elev.sin()).normalize()
}

/// Uniform unit vector from two uniforms.
pub fn sphere_dir(u: Vec2) -> Vec3 {
    spectrace::sampling::uniform_sphere(u)
}

/// The closest hit over every primitive of every shape: (shape, prim, t).
pub fn brute_force(shapes: &[Shape], ray: &Ray) -> Option<(usize, usize, f32)> {
    let mut best: Option<(usize, usize, f32)> = None;
    let mut r = *ray;
    for (s, shape) in shapes.iter().enumerate() {
        for i in 0..shape.primitive_count() {
            if let Some((t, _)) = shape.intersect_primitive(i, &r) {
                r.t_max = t;
                best = Some((s, i, t));
            }
        }
    }
    best
}

/// Every primitive hit along the ray: (shape, prim, t).
pub fn all_hits(shapes: &[Shape], ray: &Ray) -> Vec<(usize, usize, f32)> {
    let mut hits = Vec::new();
    for (s, shape) in shapes.iter().enumerate() {
        for i in 0..shape.primitive_count() {
            if let Some((t, _)) = shape.intersect_primitive(i, ray) {
                hits.push((s, i, t));
            }
        }
    }
    hits
}
