//! An environment map in pbrt-v4's equal-area octahedral layout (its `ImageInfiniteLight`,
//! `src/pbrt/lights.cpp`; the mapping of Clarberg 2008, "Fast equal-area mapping of the
//! (hemi)sphere using SIMD", `EqualAreaSphereToSquare` in `util/math.cpp`).
//!
//! - **Directions**: a square image of N × N pixels covers the sphere of the light's local
//!   frame (world = `to_world` · local), +z at the image's centre, −z at its four corners, +x
//!   at (1, ½) and +y at (½, 1) in (u, v), v = 0 being the first row. The mapping is
//!   equal-area: every pixel subtends 4π/N² sr.
//! - **Lookup**: the nearest pixel (pbrt-v4's `LookupNearest`), no interpolation.
//! - **Colour**: a pixel's linear RGB becomes pbrt-v4's `RGBIlluminantSpectrum`: s = 2·max(rgb)
//!   times the bounded sigmoid of rgb/s, times `illuminant` (the colour space's white, which
//!   carries the absolute scale): W·m⁻²·sr⁻¹·nm⁻¹.
//! - **Sampling**: a pixel ∝ its luminance, then a point uniform in it; the solid-angle pdf is
//!   p(pixel)·N²/(4π).

use std::f32::consts::{FRAC_PI_2, PI};

use glam::{Mat3, Vec2, Vec3};

use super::distribution2d::Distribution2D;
use super::{EmissionSample, LightSample};
use crate::spectrum::rgb2spec::{SigmoidPolynomial, srgb_table};
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum, WavelengthRange};

/// The row-major index of the pixel of an n × n image nearest to (u, v) (pbrt-v4's
/// `LookupNearest`: ⌊u·n⌋, ⌊v·n⌋, clamped to the image).
#[inline]
pub(crate) fn nearest_pixel(n: usize, uv: Vec2) -> usize {
    let x = ((uv.x * n as f32) as usize).min(n - 1);
    let y = ((uv.y * n as f32) as usize).min(n - 1);
    y * n + x
}

/// The point of the unit square a unit direction maps to (Clarberg's equal-area octahedral
/// mapping, as pbrt-v4's `EqualAreaSphereToSquare`).
pub fn sphere_to_square(d: Vec3) -> Vec2 {
    let (x, y, z) = (d.x.abs(), d.y.abs(), d.z.abs());
    let r = (1.0 - z).max(0.0).sqrt();
    let (a, b) = (x.max(y), x.min(y));
    let b = if a == 0.0 { 0.0 } else { b / a };
    let mut phi = b.atan() / FRAC_PI_2;
    if x < y {
        phi = 1.0 - phi;
    }
    let mut v = phi * r;
    let mut u = r - v;
    if d.z < 0.0 {
        (u, v) = (1.0 - v, 1.0 - u);
    }
    u = u.copysign(d.x);
    v = v.copysign(d.y);
    Vec2::new(0.5 * (u + 1.0), 0.5 * (v + 1.0))
}

/// The unit direction a point of the unit square maps to (the inverse of [`sphere_to_square`],
/// pbrt-v4's `EqualAreaSquareToSphere`), shared with the spherical camera.
pub use crate::sampling::equal_area_square_to_sphere as square_to_sphere;

#[derive(Clone, Debug)]
pub struct OctahedralMapLight {
    res: usize,
    coeffs: Vec<SigmoidPolynomial>,
    /// 2·max(rgb) per pixel.
    scales: Vec<f32>,
    /// Spectral shape and absolute scale, W·m⁻²·sr⁻¹·nm⁻¹ per unit of pixel value.
    pub illuminant: Spectrum,
    to_world: Mat3,
    to_local: Mat3,
    /// Chooses a pixel ∝ its luminance.
    dist: Distribution2D,
}

impl OctahedralMapLight {
    /// From `res` × `res` linear RGB pixels (row-major, first row at v = 0; negative values
    /// count as 0), the illuminant that gives them their scale, and the rotation from the
    /// light's frame to the world. Errors for a black map or a singular rotation.
    pub fn new(
        res: usize,
        rgb: &[[f32; 3]],
        illuminant: Spectrum,
        to_world: Mat3,
    ) -> Result<Self, String> {
        if res == 0 || rgb.len() != res * res {
            return Err(format!(
                "an equal-area map must be square: {} pixels for {res} × {res}",
                rgb.len()
            ));
        }
        let table = srgb_table();
        let rgb: Vec<[f32; 3]> = rgb.iter().map(|p| p.map(|v| v.max(0.0))).collect();
        let scales: Vec<f32> = rgb.iter().map(|p| 2.0 * p[0].max(p[1]).max(p[2])).collect();
        let coeffs = rgb
            .iter()
            .zip(&scales)
            .map(|(p, &s)| table.lookup(p.map(|v| v / s.max(1e-8))))
            .collect();
        let lum: Vec<f32> = rgb
            .iter()
            .map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2])
            .collect();
        let dist =
            Distribution2D::new(&lum, res, res).ok_or("the map is black: every pixel is 0")?;
        let to_local = to_world.inverse();
        if !to_local.is_finite() {
            return Err("the light's transformation is singular".into());
        }
        Ok(Self {
            res,
            coeffs,
            scales,
            illuminant,
            to_world,
            to_local,
            dist,
        })
    }

    /// The pixel index nearest to (u, v) ([`nearest_pixel`]).
    #[inline]
    fn pixel(&self, uv: Vec2) -> usize {
        nearest_pixel(self.res, uv)
    }

    #[inline]
    fn eval_pixel<const N: usize>(
        &self,
        k: usize,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let s = self.scales[k];
        if s <= 0.0 {
            return SampledSpectrum::zero();
        }
        SampledSpectrum(std::array::from_fn(|n| {
            let l = w.lambda[n];
            self.coeffs[k].eval(l) * s * self.illuminant.eval(l)
        }))
    }

    /// Radiance arriving along a ray travelling in world direction `dir` (unit) that escapes.
    #[inline]
    pub fn escaped<const N: usize>(
        &self,
        dir: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let uv = sphere_to_square((self.to_local * dir).normalize());
        self.eval_pixel(self.pixel(uv), w)
    }

    /// A world direction toward the map, its pixel and its solid-angle pdf.
    fn sample_dir(&self, u: Vec2) -> Option<(Vec3, usize, f32)> {
        let (uv, pdf_uv) = self.dist.sample(u);
        if !(pdf_uv > 0.0) {
            return None;
        }
        let wi = (self.to_world * square_to_sphere(uv)).normalize();
        Some((wi, self.pixel(uv), pdf_uv / (4.0 * PI)))
    }

    /// A direction toward the map, by the luminance of its pixels.
    pub fn sample_li<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<LightSample<N>> {
        let (wi, k, pdf) = self.sample_dir(u)?;
        Some(LightSample::at_infinity(wi, self.eval_pixel(k, w), pdf))
    }

    /// Density per unit solid angle with which [`OctahedralMapLight::sample_li`] returns `wi`.
    pub fn pdf_li(&self, wi: Vec3) -> f32 {
        let uv = sphere_to_square((self.to_local * wi).normalize());
        let k = self.pixel(uv);
        self.dist.pdf_cell(k % self.res, k / self.res) / (4.0 * PI)
    }

    /// A particle from the map (light tracing), as [`super::EnvMapLight::sample_le`].
    pub fn sample_le<const N: usize>(
        &self,
        center: Vec3,
        radius: f32,
        w: &SampledWavelengths<N>,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> EmissionSample<N> {
        match self.sample_dir(u_dir) {
            Some((wi, k, pdf)) => EmissionSample::from_infinity(
                center,
                radius,
                -wi,
                self.eval_pixel(k, w),
                pdf,
                u_pos,
            ),
            None => EmissionSample::from_infinity(
                center,
                radius,
                Vec3::Z,
                SampledSpectrum::zero(),
                1.0,
                u_pos,
            ),
        }
    }

    /// ∫ g(λ)·L(λ, ω)·h(ω) dλ dω over the sphere (ω in the world), by pixels (4π/N² sr each,
    /// their radiance constant: nearest lookup) and 10-nm steps of `range`; h is averaged over
    /// S × S points of each pixel, S = ⌈256/N⌉, so that a cosine cut at the horizon is
    /// integrated to about 10⁻³ even for a small map.
    pub fn integral_where(
        &self,
        range: WavelengthRange,
        g: &impl Fn(f32) -> f64,
        h: impl Fn(Vec3) -> f64,
    ) -> f64 {
        let (lambdas, shape) = super::spectral_steps(range, &self.illuminant, g);
        let n = self.res;
        let sub = 256usize.div_ceil(n).max(1);
        let mut total = 0.0;
        for k in 0..n * n {
            if self.scales[k] <= 0.0 {
                continue;
            }
            let mut weight = 0.0;
            for a in 0..sub * sub {
                let uv = Vec2::new(
                    ((k % n) as f32 + ((a % sub) as f32 + 0.5) / sub as f32) / n as f32,
                    ((k / n) as f32 + ((a / sub) as f32 + 0.5) / sub as f32) / n as f32,
                );
                weight += h((self.to_world * square_to_sphere(uv)).normalize());
            }
            let weight = weight / (sub * sub) as f64;
            if weight == 0.0 {
                continue;
            }
            let spectral: f64 = lambdas
                .iter()
                .zip(&shape)
                .map(|(&l, &s)| s * self.coeffs[k].eval(l) as f64)
                .sum();
            total += weight * self.scales[k] as f64 * spectral;
        }
        total * 4.0 * std::f64::consts::PI / (n * n) as f64
    }

    /// ∫ L dω over the sphere, integrated over `range` (W·m⁻²), for choosing among lights.
    pub fn band_radiant_exitance(&self, range: WavelengthRange) -> f64 {
        self.integral_where(range, &|_| 1.0, |_| 1.0)
    }

    /// The light's +z in the world (pbrt-v4's "upward" for `illuminance`).
    pub fn zenith(&self) -> Vec3 {
        (self.to_world * Vec3::Z).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mapping's landmarks (pbrt-v4's layout), its inverse, and equal areas: directions
    /// from uniform points of the square are uniform on the sphere (mean z and z² of a uniform
    /// sphere, 0 and 1/3).
    #[test]
    fn equal_area_mapping_is_pbrts() {
        let near = |a: Vec2, b: Vec2| (a - b).length() < 1e-5;
        assert!(near(sphere_to_square(Vec3::Z), Vec2::new(0.5, 0.5)));
        assert!(near(sphere_to_square(Vec3::X), Vec2::new(1.0, 0.5)));
        assert!(near(sphere_to_square(Vec3::Y), Vec2::new(0.5, 1.0)));
        assert!(near(sphere_to_square(Vec3::NEG_X), Vec2::new(0.0, 0.5)));
        let c = sphere_to_square(Vec3::NEG_Z);
        assert!(
            near(c, Vec2::new(1.0, 1.0))
                || near(c, Vec2::ZERO)
                || near(c, Vec2::new(0.0, 1.0))
                || near(c, Vec2::new(1.0, 0.0)),
            "{c:?}"
        );
        let (mut z, mut z2, n) = (0.0f64, 0.0f64, 400);
        for i in 0..n {
            for j in 0..n {
                let p = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let d = square_to_sphere(p);
                assert!((d.length() - 1.0).abs() < 1e-5);
                let back = sphere_to_square(d);
                assert!((back - p).length() < 1e-4, "{p:?} → {d:?} → {back:?}");
                z += d.z as f64;
                z2 += (d.z * d.z) as f64;
            }
        }
        let m = (n * n) as f64;
        assert!(
            (z / m).abs() < 1e-4 && (z2 / m - 1.0 / 3.0).abs() < 1e-4,
            "{} {}",
            z / m,
            z2 / m
        );
    }

    /// Sampling's density is what `pdf_li` says: ∫ pdf dω = 1 by pixels, and a sample's pdf is
    /// `pdf_li` of its direction.
    #[test]
    fn sampling_density_is_pdf_li() {
        let n = 8;
        let rgb: Vec<[f32; 3]> = (0..n * n)
            .map(|k| [(k % 5) as f32, 0.5, (k % 3) as f32])
            .collect();
        let l = OctahedralMapLight::new(n, &rgb, Spectrum::Constant(1.0), Mat3::IDENTITY).unwrap();
        let w = SampledWavelengths::<4> {
            lambda: [450.0, 500.0, 550.0, 600.0],
            pdf: [1.0; 4],
        };
        let mut total = 0.0;
        for k in 0..n * n {
            let uv = Vec2::new(
                ((k % n) as f32 + 0.5) / n as f32,
                ((k / n) as f32 + 0.5) / n as f32,
            );
            total +=
                l.pdf_li(square_to_sphere(uv)) as f64 * 4.0 * std::f64::consts::PI / (n * n) as f64;
        }
        assert!((total - 1.0).abs() < 1e-5, "{total}");
        for i in 0..50 {
            let u = Vec2::new((i as f32 + 0.3) / 50.0, ((i * 7) % 50) as f32 / 50.0 + 0.01);
            let s = l.sample_li(&w, u).unwrap();
            assert!(
                (s.pdf - l.pdf_li(s.wi)).abs() <= 1e-4 * s.pdf,
                "{} {}",
                s.pdf,
                l.pdf_li(s.wi)
            );
        }
    }
}
