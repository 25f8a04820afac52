//! Image textures, as Mitsuba 3.9.1's `bitmap` reads them (src/textures/bitmap.cpp, checked
//! numerically against Mitsuba itself):
//!
//! - uv (after `to_uv`) (0, 0) is the top-left corner of the image as stored (row 0 is the file's
//!   first row), u to the right, v down; texel (i, j) is centred at ((i + ½)/W, (j + ½)/H).
//! - `Nearest` takes texel (⌊u·W⌋, ⌊v·H⌋); `Bilinear` blends the four texels around
//!   (u·W − ½, v·H − ½). Each integer index is wrapped on its own: `Repeat` (modulo), `Clamp`,
//!   `Mirror` (period 2W, the edge texel repeated at the fold).
//! - Colour texels are linear sRGB in [0, 1] (sRGB-encoded files are decoded when loaded, and
//!   values outside [0, 1] are clamped, as Mitsuba clamps them), each turned into Jakob–Hanika
//!   sigmoid coefficients once; a lookup blends the *spectra* of its texels, never their RGB.
//!   Grey images keep one value per texel, the same at every wavelength.

use glam::{Vec2, Vec3};

use super::UvTransform;
use crate::spectrum::rgb2spec::{SigmoidPolynomial, srgb_table};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexFilter {
    Nearest,
    Bilinear,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    Repeat,
    Mirror,
    Clamp,
}

impl Wrap {
    /// The index in 0..`n` (n > 0) that coordinate index `i` reads under this wrap mode
    /// (image textures and volume grids alike).
    #[inline]
    pub fn index(self, i: i64, n: usize) -> usize {
        let n = n as i64;
        (match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let k = i.rem_euclid(2 * n);
                if k < n { k } else { 2 * n - 1 - k }
            }
        }) as usize
    }
}

/// Why pixels cannot become a texture.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BitmapError {
    #[error("the image is empty ({0}×{1})")]
    Empty(usize, usize),
    #[error("{0} pixels given for a {1}×{2} image")]
    Size(usize, usize, usize),
}

#[derive(Clone, Debug, PartialEq)]
enum Texels {
    /// One value per texel, the same at every wavelength.
    Grey(Vec<f32>),
    /// Sigmoid coefficients per texel (bounded reflectance spectra).
    Colour(Vec<SigmoidPolynomial>),
    /// Sigmoid coefficients and a scale per texel (unbounded spectra: an emitter's image).
    Unbounded(Vec<(SigmoidPolynomial, f32)>),
    /// Three raw values per texel (a normal map's encoded directions), never spectra.
    Vector(Vec<[f32; 3]>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Bitmap {
    width: usize,
    height: usize,
    texels: Texels,
    pub filter: TexFilter,
    pub wrap: Wrap,
    pub to_uv: UvTransform,
}

impl Bitmap {
    /// A colour texture from linear sRGB pixels (row-major, top row first), clamped to [0, 1].
    pub fn from_rgb(
        width: usize,
        height: usize,
        rgb: &[[f32; 3]],
        filter: TexFilter,
        wrap: Wrap,
        to_uv: UvTransform,
    ) -> Result<Self, BitmapError> {
        Self::check(width, height, rgb.len())?;
        let table = srgb_table();
        let texels = rgb
            .iter()
            .map(|p| table.lookup(p.map(|v| v.clamp(0.0, 1.0))))
            .collect();
        Ok(Self::of(
            width,
            height,
            Texels::Colour(texels),
            (filter, wrap, to_uv),
        ))
    }

    fn of(
        width: usize,
        height: usize,
        texels: Texels,
        (filter, wrap, to_uv): (TexFilter, Wrap, UvTransform),
    ) -> Self {
        Self {
            width,
            height,
            texels,
            filter,
            wrap,
            to_uv,
        }
    }

    /// A colour texture from linear sRGB pixels (row-major, top row first) of any magnitude
    /// ≥ 0, each the spectrum `2m · s(rgb / 2m)` with m its largest component (pbrt-v4's
    /// `RGBUnboundedSpectrum`, and its `RGBIlluminantSpectrum` before the illuminant);
    /// negative components are clamped to 0.
    pub fn from_rgb_unbounded(
        width: usize,
        height: usize,
        rgb: &[[f32; 3]],
        filter: TexFilter,
        wrap: Wrap,
        to_uv: UvTransform,
    ) -> Result<Self, BitmapError> {
        Self::check(width, height, rgb.len())?;
        let table = srgb_table();
        let texels = rgb
            .iter()
            .map(|p| {
                let p = p.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 });
                let m = p[0].max(p[1]).max(p[2]);
                let scale = 2.0 * m;
                let c = if m > 0.0 {
                    p.map(|v| v / scale)
                } else {
                    [0.0; 3]
                };
                (table.lookup(c), scale)
            })
            .collect();
        Ok(Self::of(
            width,
            height,
            Texels::Unbounded(texels),
            (filter, wrap, to_uv),
        ))
    }

    /// A grey texture: one value per texel (row-major, top row first), used unchanged.
    pub fn from_grey(
        width: usize,
        height: usize,
        v: Vec<f32>,
        filter: TexFilter,
        wrap: Wrap,
        to_uv: UvTransform,
    ) -> Result<Self, BitmapError> {
        Self::check(width, height, v.len())?;
        Ok(Self {
            width,
            height,
            texels: Texels::Grey(v),
            filter,
            wrap,
            to_uv,
        })
    }

    /// A texture of raw triples (row-major, top row first) used unchanged: a normal map, read
    /// through [`Bitmap::vector`] only.
    pub fn from_vectors(
        width: usize,
        height: usize,
        v: Vec<[f32; 3]>,
        filter: TexFilter,
        wrap: Wrap,
        to_uv: UvTransform,
    ) -> Result<Self, BitmapError> {
        Self::check(width, height, v.len())?;
        Ok(Self {
            width,
            height,
            texels: Texels::Vector(v),
            filter,
            wrap,
            to_uv,
        })
    }

    fn check(w: usize, h: usize, n: usize) -> Result<(), BitmapError> {
        if w == 0 || h == 0 {
            return Err(BitmapError::Empty(w, h));
        }
        if w.checked_mul(h) != Some(n) {
            return Err(BitmapError::Size(n, w, h));
        }
        Ok(())
    }

    #[inline]
    fn wrap_index(&self, i: i64, n: usize) -> usize {
        self.wrap.index(i, n)
    }

    #[inline]
    fn texel<const N: usize>(&self, k: usize, w: &SampledWavelengths<N>) -> [f32; N] {
        match &self.texels {
            Texels::Grey(v) => [v[k]; N],
            Texels::Colour(c) => w.lambda.map(|l| c[k].eval(l)),
            Texels::Unbounded(c) => w.lambda.map(|l| c[k].1 * c[k].0.eval(l)),
            // a normal map read as a spectrum (a caller bug): its mean component
            Texels::Vector(v) => [(v[k][0] + v[k][1] + v[k][2]) / 3.0; N],
        }
    }

    /// The texels a lookup at `uv` (before `to_uv`) blends, as row-major indices
    /// [(i0, j0), (i1, j0), (i0, j1), (i1, j1)], and the fractions (fx, fy) between them
    /// (nearest: one texel four times, fractions 0).
    #[inline]
    fn footprint(&self, uv: Vec2) -> ([usize; 4], Vec2) {
        let p = self.to_uv.apply(uv);
        // a non-finite uv (a mesh file's NaN texture coordinate, an overflowing to_uv) reads
        // what uv (0, 0) reads rather than blending NaNs
        let p = if p.is_finite() { p } else { Vec2::ZERO };
        let (wf, hf) = (self.width as f32, self.height as f32);
        match self.filter {
            TexFilter::Nearest => {
                let i = self.wrap_index((p.x * wf).floor() as i64, self.width);
                let j = self.wrap_index((p.y * hf).floor() as i64, self.height);
                ([j * self.width + i; 4], Vec2::ZERO)
            }
            TexFilter::Bilinear => {
                let (x, y) = (p.x * wf - 0.5, p.y * hf - 0.5);
                let (x0, y0) = (x.floor(), y.floor());
                let f = Vec2::new(x - x0, y - y0);
                let (x0, y0) = (x0 as i64, y0 as i64);
                let (i0, i1) = (
                    self.wrap_index(x0, self.width),
                    self.wrap_index(x0 + 1, self.width),
                );
                let (j0, j1) = (
                    self.wrap_index(y0, self.height) * self.width,
                    self.wrap_index(y0 + 1, self.height) * self.width,
                );
                ([j0 + i0, j0 + i1, j1 + i0, j1 + i1], f)
            }
        }
    }

    /// The value at `uv` (before `to_uv`) for the wavelengths `w`.
    #[inline]
    pub fn sample<const N: usize>(
        &self,
        uv: Vec2,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let ([ka, kb, kc, kd], f) = self.footprint(uv);
        let (a, b) = (self.texel(ka, w), self.texel(kb, w));
        let (c, d) = (self.texel(kc, w), self.texel(kd, w));
        SampledSpectrum(std::array::from_fn(|k| {
            (1.0 - f.y) * ((1.0 - f.x) * a[k] + f.x * b[k])
                + f.y * ((1.0 - f.x) * c[k] + f.x * d[k])
        }))
    }

    /// The raw triple at `uv` (before `to_uv`), filtered as [`Bitmap::sample`] filters: a
    /// normal map's encoded direction. Grey texels give (g, g, g); colour ones (a caller bug)
    /// give (0, 0, 1).
    #[inline]
    pub fn vector(&self, uv: Vec2) -> Vec3 {
        let ([ka, kb, kc, kd], f) = self.footprint(uv);
        let at = |k: usize| match &self.texels {
            Texels::Vector(v) => Vec3::from(v[k]),
            Texels::Grey(v) => Vec3::splat(v[k]),
            Texels::Colour(_) | Texels::Unbounded(_) => Vec3::Z,
        };
        (1.0 - f.y) * ((1.0 - f.x) * at(ka) + f.x * at(kb))
            + f.y * ((1.0 - f.x) * at(kc) + f.x * at(kd))
    }

    /// The gradient (∂/∂u, ∂/∂v) at `uv` of a grey texture's filtered value, per unit of the
    /// uv before `to_uv` (the chain rule through its linear part), as Mitsuba's `eval_1_grad`:
    /// the derivative of the bilinear blend (zero for nearest filtering, and for other texels).
    #[inline]
    pub fn gradient(&self, uv: Vec2) -> Vec2 {
        let Texels::Grey(v) = &self.texels else {
            return Vec2::ZERO;
        };
        if self.filter == TexFilter::Nearest {
            return Vec2::ZERO;
        }
        let ([ka, kb, kc, kd], f) = self.footprint(uv);
        let (a, b, c, d) = (v[ka], v[kb], v[kc], v[kd]);
        // d/dx, d/dy in texel units, then per unit of the transformed uv
        let g = Vec2::new(
            ((b - a) * (1.0 - f.y) + (d - c) * f.y) * self.width as f32,
            ((c - a) * (1.0 - f.x) + (d - b) * f.x) * self.height as f32,
        );
        let [r0, r1] = self.to_uv.rows;
        Vec2::new(r0[0] * g.x + r1[0] * g.y, r0[1] * g.x + r1[1] * g.y)
    }

    /// (width, height) in texels.
    pub fn resolution(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Whether the image is grey (one value per texel, the same at every wavelength).
    pub fn is_grey(&self) -> bool {
        matches!(self.texels, Texels::Grey(_))
    }

    /// The mean over texels of `spectral`, a mean over wavelengths of a texel's value.
    pub fn mean(&self, spectral: impl Fn(&dyn Fn(f32) -> f32) -> f32) -> f32 {
        let n = (self.width * self.height) as f64;
        let sum: f64 = match &self.texels {
            Texels::Grey(v) => v.iter().map(|&x| x as f64).sum(),
            Texels::Colour(c) => c.iter().map(|p| spectral(&|l| p.eval(l)) as f64).sum(),
            Texels::Unbounded(c) => c
                .iter()
                .map(|(p, s)| spectral(&|l| s * p.eval(l)) as f64)
                .sum(),
            Texels::Vector(v) => v.iter().map(|p| (p[0] + p[1] + p[2]) as f64 / 3.0).sum(),
        };
        (sum / n) as f32
    }
}

#[cfg(test)]
mod tests;
