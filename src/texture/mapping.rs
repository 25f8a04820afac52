//! Textures looked up by position instead of the surface's (u, v): pbrt-v4's 2D texture
//! mappings `spherical`, `cylindrical` and `planar` (`src/pbrt/textures.h`,
//! `SphericalMapping`, `CylindricalMapping`, `PlanarMapping`; pbrt-v4 §10.2). Each maps the
//! hit's world position, taken into the texture's own space (the inverse of the transformation
//! in force where the texture was declared), to texture coordinates (s, t) at which an inner
//! texture is looked up as by uv.
//!
//! The lookup is at a point, not filtered over a ray's footprint (pbrt-v4 uses the mapping's
//! derivatives to choose a MIP level): the same means.

use std::f32::consts::PI;

use glam::{Mat4, Vec2, Vec3};

use super::Texture;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A map from world positions (m) to texture coordinates (s, t), dimensionless.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mapping {
    /// s = θ/π, t = φ/(2π) of the direction from the texture space's origin, θ from its +z,
    /// φ from its +x toward +y in [0, 2π).
    Spherical { to_texture: Mat4 },
    /// s = (π + atan2(y, x))/(2π), t = z in texture space.
    Cylindrical { to_texture: Mat4 },
    /// s = ds + v_s·p, t = dt + v_t·p of the texture-space point p (the vectors are per unit
    /// of texture-space length).
    Planar {
        to_texture: Mat4,
        vs: Vec3,
        vt: Vec3,
        ds: f32,
        dt: f32,
    },
}

impl Mapping {
    /// The texture coordinates of the world point `p` (m).
    #[inline]
    pub fn st(&self, p: Vec3) -> Vec2 {
        match self {
            Mapping::Spherical { to_texture } => {
                let d = to_texture.transform_point3(p).normalize_or_zero();
                let theta = d.z.clamp(-1.0, 1.0).acos();
                let phi = d.y.atan2(d.x);
                let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
                Vec2::new(theta / PI, phi / (2.0 * PI))
            }
            Mapping::Cylindrical { to_texture } => {
                let q = to_texture.transform_point3(p);
                Vec2::new((PI + q.y.atan2(q.x)) / (2.0 * PI), q.z)
            }
            Mapping::Planar {
                to_texture,
                vs,
                vt,
                ds,
                dt,
            } => {
                let q = to_texture.transform_point3(p);
                Vec2::new(ds + q.dot(*vs), dt + q.dot(*vt))
            }
        }
    }
}

/// `inner` looked up at the coordinates `mapping` gives a hit's position; `inner` takes them
/// where it would take (u, v).
#[derive(Clone, Debug, PartialEq)]
pub struct Mapped {
    pub mapping: Mapping,
    pub inner: Texture,
}

impl Mapped {
    #[inline]
    pub fn sample<const N: usize>(&self, p: Vec3, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        self.inner.sample(self.mapping.st(p), w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).length() < 1e-6
    }

    /// Each mapping at points whose coordinates follow from pbrt-v4's definitions by hand.
    #[test]
    fn mappings_give_pbrt_v4_s_coordinates() {
        let id = Mat4::IDENTITY;
        let sph = Mapping::Spherical { to_texture: id };
        // +z: θ = 0; −y on the equator: θ = π/2, φ = 3π/2
        assert!(close(sph.st(Vec3::new(0.0, 0.0, 2.0)), Vec2::new(0.0, 0.0)));
        assert!(close(
            sph.st(Vec3::new(0.0, -3.0, 0.0)),
            Vec2::new(0.5, 0.75)
        ));
        // moved by the texture's transform: the centre is at (1, 0, 0) in the world
        let moved = Mapping::Spherical {
            to_texture: Mat4::from_translation(Vec3::new(-1.0, 0.0, 0.0)),
        };
        assert!(close(
            moved.st(Vec3::new(1.0, 1.0, 0.0)),
            Vec2::new(0.5, 0.25)
        ));
        let cyl = Mapping::Cylindrical { to_texture: id };
        // atan2(0, 1) = 0: s = ½; atan2(1, 0) = π/2: s = ¾; t = z
        assert!(close(cyl.st(Vec3::new(2.0, 0.0, 0.3)), Vec2::new(0.5, 0.3)));
        assert!(close(
            cyl.st(Vec3::new(0.0, 2.0, -1.0)),
            Vec2::new(0.75, -1.0)
        ));
        let planar = Mapping::Planar {
            to_texture: Mat4::from_scale(Vec3::splat(0.5)),
            vs: Vec3::new(1.0, 0.0, 0.0),
            vt: Vec3::new(0.0, 0.0, 2.0),
            ds: 0.25,
            dt: -1.0,
        };
        // p = (4, 7, 1) → (2, 3.5, 0.5): s = 0.25 + 2, t = −1 + 1
        assert!(close(
            planar.st(Vec3::new(4.0, 7.0, 1.0)),
            Vec2::new(2.25, 0.0)
        ));
    }
}
