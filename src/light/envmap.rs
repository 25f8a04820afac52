//! An environment map: radiance at infinity from a latitude–longitude image, as Mitsuba 3.9.1's
//! `envmap` defines it (src/emitters/envmap.cpp, checked numerically against Mitsuba itself).
//!
//! - **Directions** (the map's local frame, +y up; world = `to_world` · local): a direction d is
//!   at u = atan2(d.x, −d.z)/2π (wrapped into [0, 1)) and v = acos(d.y)/π, so u = 0 looks
//!   along −z, u = ¼ along +x, and v = 0 (the image's first row) is the zenith +y.
//! - **Lookup**: pixel columns are centred at u = (i + ½)/W and wrap around; pixel rows sit at
//!   v = j/(H − 1), row 0 exactly at the zenith and row H − 1 at the nadir. Values are blended
//!   bilinearly between the four pixels around (u, v).
//! - **Colour**: each pixel's linear sRGB becomes a spectrum once, the way Mitsuba makes
//!   emission spectra: s = 2·max(rgb) and the bounded sigmoid of rgb/s. A lookup blends the four
//!   sigmoids and, separately, the four s, and multiplies them by the illuminant:
//!   L(λ) = (Σ wₖ sigmoidₖ(λ)) · (Σ wₖ sₖ) · illuminant(λ), W·m⁻²·sr⁻¹·nm⁻¹. The illuminant
//!   carries the absolute scale (the build step's table in `build/lights.rs`).
//! - **Sampling**: a cell between four pixel centres ∝ their mean luminance × sin θ at the
//!   cell's centre, then a point in it by the bilinear interpolation of their luminance (the
//!   density follows the map's own bilinear radiance, so it is positive wherever the radiance
//!   is); the solid-angle pdf is p(u, v) / (2π² sin θ).

use std::f32::consts::PI;

use glam::{Mat3, Vec2, Vec3};

use super::distribution2d::Distribution2D;
use super::{EmissionSample, LightSample};

mod integrals;
use crate::spectrum::rgb2spec::{SigmoidPolynomial, srgb_table};
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

#[derive(Clone, Debug)]
pub struct EnvMapLight {
    width: usize,
    height: usize,
    coeffs: Vec<SigmoidPolynomial>,
    /// 2·max(rgb) per pixel.
    scales: Vec<f32>,
    /// Spectral shape and absolute scale, W·m⁻²·sr⁻¹·nm⁻¹ per unit of pixel value.
    pub illuminant: Spectrum,
    to_world: Mat3,
    to_local: Mat3,
    /// Luminance of each pixel (Rec. 709 weights of its linear RGB): the sampling density is
    /// bilinear in it within each cell.
    lum: Vec<f32>,
    /// Chooses a cell ∝ its mean corner luminance × sin θ at its centre: over (u − ½/W, v),
    /// W columns × (H − 1) rows.
    dist: Distribution2D,
}

/// A sample of the linear density ∝ (1 − t)·a + t·b on [0, 1] (pbrt-v4 `SampleLinear`).
#[inline]
fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + (a * a + u * (b * b - a * a)).max(0.0).sqrt());
    x.clamp(0.0, 1.0 - f32::EPSILON / 2.0)
}

/// sRGB / Rec. 709 luminance weights of linear RGB.
fn luminance(rgb: [f32; 3]) -> f32 {
    0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]
}

impl EnvMapLight {
    /// From linear sRGB pixels (row-major, top row = zenith, `width × height`, at least 2 × 3
    /// as Mitsuba requires; negative components count as 0), the illuminant that gives them
    /// their absolute scale, and the rotation from the map's frame to the world.
    pub fn new(
        width: usize,
        height: usize,
        rgb: &[[f32; 3]],
        illuminant: Spectrum,
        to_world: Mat3,
    ) -> Result<Self, String> {
        if width < 2 || height < 3 {
            return Err(format!(
                "an environment map must be at least 2 × 3 pixels, not {width} × {height}"
            ));
        }
        if rgb.len() != width * height {
            return Err(format!("{} pixels for {width} × {height}", rgb.len()));
        }
        let table = srgb_table();
        let rgb: Vec<[f32; 3]> = rgb.iter().map(|p| p.map(|v| v.max(0.0))).collect();
        let scales: Vec<f32> = rgb.iter().map(|p| 2.0 * p[0].max(p[1]).max(p[2])).collect();
        let coeffs = rgb
            .iter()
            .zip(&scales)
            .map(|(p, &s)| table.lookup(p.map(|v| v / s.max(1e-8))))
            .collect();
        let lum: Vec<f32> = rgb.iter().map(|&p| luminance(p)).collect();
        let rows = height - 1;
        let mut weights = Vec::with_capacity(width * rows);
        for r in 0..rows {
            let sin = (PI * (r as f32 + 0.5) / rows as f32).sin();
            for c in 0..width {
                let c1 = (c + 1) % width;
                // the integral of the bilinear luminance over the cell
                let m = 0.25
                    * (lum[r * width + c]
                        + lum[r * width + c1]
                        + lum[(r + 1) * width + c]
                        + lum[(r + 1) * width + c1]);
                weights.push(m * sin);
            }
        }
        let dist = Distribution2D::new(&weights, width, rows)
            .ok_or("the environment map is black: every pixel is 0")?;
        let to_local = to_world.inverse();
        if !to_local.is_finite() {
            return Err("to_world is singular".into());
        }
        Ok(Self {
            width,
            height,
            coeffs,
            scales,
            illuminant,
            to_world,
            to_local,
            lum,
            dist,
        })
    }

    /// (u, v) of a local direction (unit), and sin θ.
    #[inline]
    fn uv(d: Vec3) -> (Vec2, f32) {
        let mut u = d.x.atan2(-d.z) / (2.0 * PI);
        u -= u.floor();
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        (Vec2::new(u, v), (d.x * d.x + d.z * d.z).sqrt())
    }

    /// The half-pixel shift between u and the sampling grid (pixel centres on cell corners).
    #[inline]
    fn shift(&self) -> f32 {
        0.5 / self.width as f32
    }

    /// Radiance at (u, v), W·m⁻²·sr⁻¹·nm⁻¹.
    #[inline]
    fn eval_uv<const N: usize>(&self, uv: Vec2, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        let (wd, ht) = (self.width, self.height);
        let mut us = uv.x - self.shift();
        us -= us.floor();
        let x = us * wd as f32;
        let y = uv.y.clamp(0.0, 1.0) * (ht - 1) as f32;
        let i0 = (x as usize).min(wd - 1);
        let j0 = (y as usize).min(ht - 2);
        let (fx, fy) = (x - i0 as f32, y - j0 as f32);
        let i1 = (i0 + 1) % wd;
        let taps = [
            (j0 * wd + i0, (1.0 - fx) * (1.0 - fy)),
            (j0 * wd + i1, fx * (1.0 - fy)),
            ((j0 + 1) * wd + i0, (1.0 - fx) * fy),
            ((j0 + 1) * wd + i1, fx * fy),
        ];
        let scale: f32 = taps.iter().map(|&(k, t)| t * self.scales[k]).sum();
        if scale <= 0.0 {
            return SampledSpectrum::zero();
        }
        SampledSpectrum(std::array::from_fn(|n| {
            let l = w.lambda[n];
            let s: f32 = taps.iter().map(|&(k, t)| t * self.coeffs[k].eval(l)).sum();
            s * scale * self.illuminant.eval(l)
        }))
    }

    /// Radiance arriving along a ray travelling in world direction `dir` (unit) that escapes.
    #[inline]
    pub fn escaped<const N: usize>(
        &self,
        dir: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let (uv, _) = Self::uv((self.to_local * dir).normalize());
        self.eval_uv(uv, w)
    }

    /// A world direction toward the map from `u`, with its solid-angle pdf; None where sin θ = 0.
    #[inline]
    fn sample_dir(&self, u: Vec2) -> Option<(Vec3, Vec2, f32)> {
        // a cell, then a point within it by the bilinear luminance of its corners (pbrt-v4
        // `SampleBilinear`, the remainder of `u` reused)
        let (p, _) = self.dist.sample(u);
        let (cols, rows) = (self.width as f32, (self.height - 1) as f32);
        let (cx, cy) = (
            ((p.x * cols) as usize).min(self.width - 1),
            ((p.y * rows) as usize).min(self.height - 2),
        );
        let (fx, fy) = (
            (p.x * cols - cx as f32).clamp(0.0, 1.0),
            (p.y * rows - cy as f32).clamp(0.0, 1.0),
        );
        let [w00, w10, w01, w11] = self.corners(cx, cy);
        let y = sample_linear(fy, w00 + w10, w01 + w11);
        let x = sample_linear(fx, w00 + (w01 - w00) * y, w10 + (w11 - w10) * y);
        // the density from the cell it was drawn in (not re-derived from a rounded position)
        let pdf_uv = self.pdf_in_cell(cx, cy, x, y);
        let q = Vec2::new(
            ((cx as f32 + x) / cols).min(1.0 - f32::EPSILON / 2.0),
            ((cy as f32 + y) / rows).min(1.0),
        );
        let mut uu = q.x + self.shift();
        uu -= uu.floor();
        let (theta, phi) = (PI * q.y, 2.0 * PI * uu);
        let (sin_t, cos_t) = theta.sin_cos();
        if !(sin_t > 0.0) || !(pdf_uv > 0.0) {
            return None;
        }
        let (sin_p, cos_p) = phi.sin_cos();
        let local = Vec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t);
        let wi = (self.to_world * local).normalize();
        Some((wi, Vec2::new(uu, q.y), pdf_uv / (2.0 * PI * PI * sin_t)))
    }

    /// Luminance at the corners (c, r), (c + 1, r), (c, r + 1), (c + 1, r + 1) of cell (c, r).
    #[inline]
    fn corners(&self, c: usize, r: usize) -> [f32; 4] {
        let wd = self.width;
        let (c, r) = (c.min(wd - 1), r.min(self.height - 2));
        let c1 = (c + 1) % wd;
        [
            self.lum[r * wd + c],
            self.lum[r * wd + c1],
            self.lum[(r + 1) * wd + c],
            self.lum[(r + 1) * wd + c1],
        ]
    }

    /// The sampling density on the (u − ½/W, v) square at `q` ∈ [0, 1]²: the cell's density
    /// times the bilinear luminance at `q` over the cell's mean.
    #[inline]
    fn pdf_uv(&self, q: Vec2) -> f32 {
        let (cols, rows) = (self.width as f32, (self.height - 1) as f32);
        let (cx, cy) = (
            ((q.x * cols) as usize).min(self.width - 1),
            ((q.y * rows) as usize).min(self.height - 2),
        );
        let x = (q.x * cols - cx as f32).clamp(0.0, 1.0);
        let y = (q.y * rows - cy as f32).clamp(0.0, 1.0);
        self.pdf_in_cell(cx, cy, x, y)
    }

    /// The density on the (u − ½/W, v) square at (x, y) ∈ [0, 1]² within cell (cx, cy).
    #[inline]
    fn pdf_in_cell(&self, cx: usize, cy: usize, x: f32, y: f32) -> f32 {
        let [w00, w10, w01, w11] = self.corners(cx, cy);
        let sum = w00 + w10 + w01 + w11;
        if !(sum > 0.0) {
            return 0.0;
        }
        let bilerp = (1.0 - y) * ((1.0 - x) * w00 + x * w10) + y * ((1.0 - x) * w01 + x * w11);
        self.dist.pdf_cell(cx, cy) * 4.0 * bilerp / sum
    }

    /// A direction toward the map, by the luminance of its pixels.
    pub fn sample_li<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<LightSample<N>> {
        let (wi, uv, pdf) = self.sample_dir(u)?;
        Some(LightSample::at_infinity(wi, self.eval_uv(uv, w), pdf))
    }

    /// Density per unit solid angle with which [`EnvMapLight::sample_li`] returns `wi` (world,
    /// unit).
    pub fn pdf_li(&self, wi: Vec3) -> f32 {
        let (uv, sin_t) = Self::uv((self.to_local * wi).normalize());
        if !(sin_t > 0.0) {
            return 0.0;
        }
        let mut us = uv.x - self.shift();
        us -= us.floor();
        if us >= 1.0 {
            us = 0.0;
        }
        self.pdf_uv(Vec2::new(us, uv.y)) / (2.0 * PI * PI * sin_t)
    }

    /// A particle from the map (light tracing): a direction by [`EnvMapLight::sample_li`]'s
    /// density, travelling opposite to it, from a point uniform on the disk of the scene's
    /// bounding sphere perpendicular to it. A zero-weight particle where no direction exists.
    pub fn sample_le<const N: usize>(
        &self,
        center: Vec3,
        radius: f32,
        w: &SampledWavelengths<N>,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> EmissionSample<N> {
        match self.sample_dir(u_dir) {
            Some((wi, uv, pdf)) => {
                EmissionSample::from_infinity(center, radius, -wi, self.eval_uv(uv, w), pdf, u_pos)
            }
            None => EmissionSample::from_infinity(
                center,
                radius,
                Vec3::Y,
                SampledSpectrum::zero(),
                1.0,
                u_pos,
            ),
        }
    }
}

#[cfg(test)]
mod tests;
