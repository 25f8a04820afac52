//! Textures: spectral quantities that vary over a surface (reflectance, and whatever else a
//! material reads through a [`Texture`]), looked up at a hit's surface coordinates `uv`.
//!
//! # Conventions
//!
//! - `uv` is the shape's parameterisation ([`crate::geometry::Intersection::uv`]), mapped by
//!   the texture's own [`UvTransform`] (Mitsuba's `to_uv`) before the lookup.
//! - Values are per wavelength, dimensionless for reflectances, in the unit of the quantity
//!   the material reads.
//! - RGB texels become spectra once, when the scene is built (Jakob–Hanika coefficients per
//!   texel, from the same table as flat RGB values); a lookup evaluates at most four texel
//!   sigmoids per wavelength and never fits anything.
//!
//! | file | what it holds |
//! | --- | --- |
//! | `mod.rs` | [`Texture`] (closed enum), [`UvTransform`] |
//! | `checkerboard.rs` | [`Checkerboard`], Mitsuba's two-colour checks |
//! | `bitmap.rs` | [`Bitmap`]: images with nearest or bilinear filtering and wrap modes |
//! | `attribute.rs` | [`AttributeTexture`]: a mesh's vertex or face values (Mitsuba's `mesh_attribute`) |
//! | `combine.rs` | [`Scaled`] and [`Mix`]: textures of textures (pbrt-v4's `scale` and `mix`) |
//! | `mapping.rs` | [`Mapped`]: a texture looked up by position (pbrt-v4's `spherical`, `cylindrical`, `planar` mappings) |
//!
//! A lookup takes the hit's surface coordinates `uv` and its world position `p` (m); only
//! [`Mapped`] textures read `p`. [`Texture::sample`] looks up by `uv` alone, for the places
//! that have no position (a shape's alpha, a bump map's gradient, an emitter's image), where
//! the loaders refuse mapped textures.

mod attribute;
mod bitmap;
mod checkerboard;
mod combine;
mod mapping;

use std::sync::Arc;

use glam::{Vec2, Vec3};

pub use attribute::AttributeTexture;
pub use bitmap::{Bitmap, BitmapError, TexFilter, Wrap};
pub use checkerboard::Checkerboard;
pub use combine::{Mix, Scaled};
pub use mapping::{Mapped, Mapping};

use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

/// An affine map of the plane, uv' = M·uv + t, for a texture's `to_uv`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    /// Rows of [M | t].
    pub rows: [[f32; 3]; 2],
}

impl UvTransform {
    pub const IDENTITY: UvTransform = UvTransform {
        rows: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    };

    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let [a, b] = self.rows;
        Vec2::new(
            a[0] * uv.x + a[1] * uv.y + a[2],
            b[0] * uv.x + b[1] * uv.y + b[2],
        )
    }
}

/// A spectrum that may vary over a surface. Closed enum, matched per lookup.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// The same spectrum everywhere.
    Uniform(Spectrum),
    Checkerboard(Arc<Checkerboard>),
    Bitmap(Arc<Bitmap>),
    /// A mesh's attribute, looked up by triangle and barycentric weights
    /// ([`Texture::sample_at`]); a lookup by uv alone gives its mean.
    Attribute(Arc<AttributeTexture>),
    /// A product of two textures.
    Scaled(Arc<Scaled>),
    /// A blend of two textures by a third.
    Mix(Arc<Mix>),
    /// A texture looked up at coordinates given by the hit's position.
    Mapped(Arc<Mapped>),
}

impl From<Spectrum> for Texture {
    fn from(s: Spectrum) -> Self {
        Texture::Uniform(s)
    }
}

impl Texture {
    /// The value at surface coordinates `uv` for the wavelengths `w`, where there is no
    /// position: a [`Mapped`] texture is looked up at the world's origin (the loaders refuse
    /// mapped textures where this is called).
    #[inline]
    pub fn sample<const N: usize>(
        &self,
        uv: Vec2,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        self.sample_p(uv, Vec3::ZERO, w)
    }

    /// The value at surface coordinates `uv` and world position `p` (m) for the wavelengths
    /// `w`.
    #[inline]
    pub fn sample_p<const N: usize>(
        &self,
        uv: Vec2,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self {
            Texture::Uniform(s) => s.sample(w),
            Texture::Checkerboard(c) => c.sample(uv, w),
            Texture::Bitmap(b) => b.sample(uv, w),
            Texture::Attribute(a) => SampledSpectrum::splat(a.mean()),
            Texture::Scaled(s) => s.sample(uv, p, w),
            Texture::Mix(m) => m.sample(uv, p, w),
            Texture::Mapped(m) => m.sample(p, w),
        }
    }

    /// The value at a hit: surface coordinates `uv`, world position `p` (m), triangle `prim`
    /// and its barycentric weights `bary` (which only mesh attributes read), for the
    /// wavelengths `w`.
    #[inline]
    pub fn sample_at<const N: usize>(
        &self,
        uv: Vec2,
        p: Vec3,
        prim: u32,
        bary: [f32; 3],
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self {
            Texture::Attribute(a) => a.sample(prim, bary, w),
            _ => self.sample_p(uv, p, w),
        }
    }

    /// A normal map's raw triple at `uv` (see [`Bitmap::vector`]); (0, 0, 1) for textures
    /// that hold no image.
    #[inline]
    pub fn vector(&self, uv: Vec2) -> glam::Vec3 {
        match self {
            Texture::Bitmap(b) => b.vector(uv),
            _ => glam::Vec3::Z,
        }
    }

    /// A height's gradient (∂/∂u, ∂/∂v) at `uv` (see [`Bitmap::gradient`]); zero for uniform
    /// textures and checkerboards (piecewise constant).
    #[inline]
    pub fn gradient(&self, uv: Vec2) -> Vec2 {
        match self {
            Texture::Bitmap(b) => b.gradient(uv),
            Texture::Scaled(s) => s.gradient(uv),
            Texture::Mix(m) => m.gradient(uv),
            _ => Vec2::ZERO,
        }
    }

    /// The mean value over the surface and over 16 wavelengths from 360 to 830 nm (as Mitsuba's
    /// `mean()` of its textures), for sampling weights.
    pub fn mean(&self) -> f32 {
        let spectral = |f: &dyn Fn(f32) -> f32| -> f32 {
            (0..16)
                .map(|k| f(360.0 + 470.0 * k as f32 / 15.0))
                .sum::<f32>()
                / 16.0
        };
        match self {
            Texture::Uniform(s) => spectral(&|l| s.eval(l)),
            Texture::Checkerboard(c) => {
                0.5 * (spectral(&|l| c.a.eval(l)) + spectral(&|l| c.b.eval(l)))
            }
            Texture::Bitmap(b) => b.mean(spectral),
            Texture::Attribute(a) => a.mean(),
            Texture::Scaled(s) => s.mean(),
            Texture::Mix(m) => m.mean(),
            // the inner texture's mean over its coordinates (exact for a planar mapping
            // whose surface covers whole periods of a repeating image)
            Texture::Mapped(m) => m.inner.mean(),
        }
    }
}
