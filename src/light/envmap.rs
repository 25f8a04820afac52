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
use crate::spectrum::rgb2spec::{SigmoidPolynomial, srgb_table};
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum, WavelengthRange};

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
        Some(LightSample {
            wi,
            li: self.eval_uv(uv, w),
            pdf,
            delta: false,
            p: Vec3::ZERO,
            p_error: Vec3::ZERO,
            n: Vec3::ZERO,
            distance: f32::INFINITY,
        })
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

    /// ∫ L dω over the sphere of the radiance integrated over `range`, W·m⁻²: pixels weighted by
    /// their solid angle, at 10 nm steps (for light selection and the build step's scales).
    pub fn band_radiant_exitance(&self, range: WavelengthRange) -> f64 {
        self.weighted_integral(range, |_| 1.0)
    }

    /// ∫ L(λ) g(λ) dλ dω over the sphere, numerically: each pixel stands for its share of the
    /// sphere under the lookup's bilinear interpolation (see [`EnvMapLight::integral_where`]).
    pub fn weighted_integral(&self, range: WavelengthRange, g: impl Fn(f32) -> f64) -> f64 {
        self.integral_where(range, &g, |_| 1.0)
    }

    /// ∫ L(λ) g(λ) dλ · h(d) dω over the sphere, `d` a world direction.
    pub fn integral_where(
        &self,
        range: WavelengthRange,
        g: &impl Fn(f32) -> f64,
        h: impl Fn(Vec3) -> f64,
    ) -> f64 {
        let steps = ((range.max_nm - range.min_nm) / 10.0).ceil().max(1.0) as usize;
        let dl = (range.max_nm - range.min_nm) as f64 / steps as f64;
        let lambdas: Vec<f32> = (0..steps)
            .map(|k| range.min_nm + (k as f32 + 0.5) * dl as f32)
            .collect();
        let shape: Vec<f64> = lambdas
            .iter()
            .map(|&l| self.illuminant.eval(l) as f64 * g(l) * dl)
            .collect();
        let (wd, ht) = (self.width, self.height);
        // Each pixel's radiance spreads over the sphere as the lookup's bilinear tent around
        // it: ± one column in u, ± one row in v. Its share of the integral is
        // ∫ tent(u) tent(v) h(ω) dω with dω = 2π² sin θ du dv, by the midpoint rule on
        // SUB × SUB cells of the tent's support (exact solid angles when h = 1: the tents sum
        // to 1 everywhere).
        const SUB: usize = 8;
        let du = 1.0 / wd as f32;
        let dv = 1.0 / (ht - 1) as f32;
        let tent = |a: usize| -1.0 + (a as f32 + 0.5) * 2.0 / SUB as f32;
        // (sin φ, cos φ) of every sub-column, wrapping around
        let cols: Vec<(f32, f32)> = (0..wd * SUB)
            .map(|c| {
                let u = ((c / SUB) as f32 + 0.5) * du + tent(c % SUB) * du;
                (2.0 * PI * u).sin_cos()
            })
            .collect();
        let mut total = 0.0;
        for j in 0..ht {
            // (tent weight × sin θ, sin θ, cos θ) of the row's sub-rows inside the sphere
            let rows: Vec<(f32, f32, f32)> = (0..SUB)
                .filter_map(|b| {
                    let v = j as f32 * dv + tent(b) * dv;
                    (0.0..=1.0).contains(&v).then(|| {
                        let (st, ct) = (PI * v).sin_cos();
                        ((1.0 - tent(b).abs()) * st, st, ct)
                    })
                })
                .collect();
            for i in 0..wd {
                let k = j * wd + i;
                if self.scales[k] <= 0.0 {
                    continue;
                }
                let mut weight = 0.0f64;
                for a in 0..SUB {
                    let (sp, cp) = cols[i * SUB + a];
                    let wu = 1.0 - tent(a).abs();
                    for &(w_sin, st, ct) in &rows {
                        let local = Vec3::new(sp * st, ct, -cp * st);
                        weight += (wu * w_sin) as f64 * h(self.to_world * local);
                    }
                }
                if weight == 0.0 {
                    continue;
                }
                let cell = (2.0 * du * 2.0 * dv) as f64 / (SUB * SUB) as f64;
                let d_omega = weight * cell * 2.0 * (PI as f64) * (PI as f64);
                let s: f64 = lambdas
                    .iter()
                    .zip(&shape)
                    .map(|(&l, &sh)| self.coeffs[k].eval(l) as f64 * sh)
                    .sum();
                total += s * self.scales[k] as f64 * d_omega;
            }
        }
        total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(rgb: &[[f32; 3]], w: usize, h: usize) -> EnvMapLight {
        EnvMapLight::new(w, h, rgb, Spectrum::Constant(1.0), Mat3::IDENTITY).unwrap()
    }

    fn wl() -> SampledWavelengths<4> {
        SampledWavelengths {
            lambda: [450.0, 520.0, 600.0, 680.0],
            pdf: [1.0; 4],
        }
    }

    /// Mitsuba's frame: u = 0 along −z, ¼ along +x; v = 0 at +y; columns centred at (i + ½)/W.
    #[test]
    fn directions_and_pixels_as_mitsuba() {
        let (w, h) = (4, 3);
        // column i has grey value i + 1 in every row
        let rgb: Vec<[f32; 3]> = (0..w * h)
            .map(|k| [(k % w) as f32 * 0.1 + 0.1; 3])
            .collect();
        let m = map(&rgb, w, h);
        let at = |d: Vec3| m.escaped(d.normalize(), &wl()).0[0];
        // the equator toward -z is u = 0: half column 3, half column 0
        assert!((at(Vec3::new(0.0, 0.0, -1.0)) - 0.5 * (0.4 + 0.1)).abs() < 1e-4);
        // u = 1/8 (column 0's centre): atan2(x, -z) = π/4
        assert!((at(Vec3::new(1.0, 0.0, -1.0)) - 0.1).abs() < 1e-4);
        // +x is u = 1/4: halfway between columns 0 and 1
        assert!((at(Vec3::X) - 0.15).abs() < 1e-4);
    }

    /// The sampled density integrates to 1 over the sphere and matches `pdf_li`; a constant map
    /// integrates to 4π times its radiance.
    #[test]
    fn pdf_is_normalised_and_consistent() {
        let (w, h) = (8, 5);
        let rgb: Vec<[f32; 3]> = (0..w * h)
            .map(|k| {
                if k % 7 == 3 {
                    [3.0, 1.0, 0.2]
                } else {
                    [0.2, 0.3, 0.4]
                }
            })
            .collect();
        let m = map(&rgb, w, h);
        let n = 200;
        let mut integral = 0.0f64;
        for i in 0..n {
            for j in 0..2 * n {
                // midpoint rule over (θ, φ): dω = sin θ dθ dφ
                let theta = PI * (i as f32 + 0.5) / n as f32;
                let phi = 2.0 * PI * (j as f32 + 0.5) / (2 * n) as f32;
                let d = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                integral += m.pdf_li(d) as f64
                    * theta.sin() as f64
                    * (std::f64::consts::PI / n as f64)
                    * (2.0 * std::f64::consts::PI / (2 * n) as f64);
            }
        }
        assert!((integral - 1.0).abs() < 2e-3, "∫ pdf dω = {integral}");
        for k in 0..50 {
            let u = Vec2::new((k as f32 * 0.618_034).fract(), (k as f32 + 0.5) / 50.0);
            if let Some(s) = m.sample_li(&wl(), u) {
                let p = m.pdf_li(s.wi);
                assert!((s.pdf / p - 1.0).abs() < 1e-3, "{} vs {p}", s.pdf);
            }
        }
        let white = map(&vec![[1.0; 3]; w * h], w, h);
        let r = WavelengthRange {
            min_nm: 400.0,
            max_nm: 700.0,
        };
        let e = white.band_radiant_exitance(r);
        // RGB (1,1,1): sigmoid ½ × scale 2 = 1 at every wavelength
        let want = 4.0 * std::f64::consts::PI * 300.0;
        assert!((e / want - 1.0).abs() < 2e-3, "{e} vs {want}");
    }
}
