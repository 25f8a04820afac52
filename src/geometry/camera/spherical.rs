//! pbrt-v4's `spherical` camera (`SphericalCamera`, cameras.cpp): every direction around the
//! camera's position on one image, by Clarberg's equal-area octahedral mapping (pbrt-v4's
//! default) or the equirectangular one.
//!
//! For raster position (x, y) the image coordinates are (u, v) = (x / width, y / height); the
//! direction is `equal_area_square_to_sphere(u, v)`, or (sin θ cos φ, sin θ sin φ, cos θ)
//! with θ = πv, φ = 2πu, in pbrt-v4's camera space, whose y and z are then swapped (pbrt-v4
//! puts the mapping's pole on its camera's up axis). pbrt-v4's camera x is spectrace's camera
//! −x (`Camera`'s module doc; `build` gives a pbrt-v4 camera the placement that makes the two
//! images the same), so the world direction is `to_world` of (−x, y, z).
//!
//! A pixel is the radiance arriving from its directions (W·m⁻²·sr⁻¹·nm⁻¹, as a pinhole's).
//! The camera's importance is not modelled: light tracing and BDPT refuse it (as pbrt-v4's).

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

use super::Film;
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use crate::sampling::equal_area_square_to_sphere;

/// An omnidirectional camera at its `to_world` origin (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Spherical {
    pub(super) to_world: Transform,
    pub(super) film: Film,
    /// Equal-area octahedral mapping (true) or equirectangular.
    pub(super) equal_area: bool,
}

impl Spherical {
    /// A spherical camera with an image of `width` × `height` pixels.
    pub fn new(
        to_world: Transform,
        equal_area: bool,
        width: u32,
        height: u32,
    ) -> Result<Spherical, crate::geometry::GeometryError> {
        Ok(Spherical {
            to_world,
            film: Film::new(width, height)?,
            equal_area,
        })
    }

    /// The world ray through `raster` (pixels, (0, 0) the image's top-left corner).
    #[inline]
    pub(super) fn ray(&self, raster: Vec2) -> Ray {
        let uv =
            self.film.full(raster) / Vec2::new(self.film.width as f32, self.film.height as f32);
        let d = if self.equal_area {
            equal_area_square_to_sphere(uv.clamp(Vec2::ZERO, Vec2::ONE))
        } else {
            let (theta, phi) = (PI * uv.y, 2.0 * PI * uv.x);
            Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            )
        };
        // pbrt-v4 swaps y and z; its camera x is spectrace's −x
        Ray::new(
            self.to_world.point(Vec3::ZERO),
            self.to_world.vector(Vec3::new(-d.x, d.z, d.y)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both mappings cover the sphere evenly: every ray is a unit vector and the mean
    /// direction over the image, each pixel weighted by its solid angle, is zero; the
    /// equirectangular image's top row looks up.
    #[test]
    fn both_mappings_cover_the_sphere_evenly() {
        for equal_area in [true, false] {
            let c = Spherical::new(Transform::identity(), equal_area, 64, 32).unwrap();
            let mut sum = Vec3::ZERO;
            let mut weight = 0.0;
            for j in 0..32 {
                for i in 0..64 {
                    let d = c.ray(Vec2::new(i as f32 + 0.5, j as f32 + 0.5)).d;
                    assert!((d.length() - 1.0).abs() < 1e-5);
                    // equirectangular pixels subtend solid angle ∝ sin θ = |d × pole|
                    let w = if equal_area {
                        1.0
                    } else {
                        (1.0 - d.y * d.y).sqrt()
                    };
                    sum += d * w;
                    weight += w;
                }
            }
            assert!((sum / weight).length() < 0.02, "{equal_area}: {sum}");
        }
        // equirectangular: the top row looks up (pbrt-v4's camera +z after the swap is +y)
        let c = Spherical::new(Transform::identity(), false, 64, 32).unwrap();
        assert!(c.ray(Vec2::new(10.0, 0.0)).d.y > 0.999);
    }
}
