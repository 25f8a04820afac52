//! pbrt-v4's `goniometric` light: a point whose intensity over the sphere is a grey image in
//! the equal-area octahedral layout (`GoniometricLight`, src/pbrt/lights.cpp):
//!
//! I(λ, ω) = spectrum(λ) · image(nearest pixel of ω)   (W·sr⁻¹·nm⁻¹),
//!
//! ω in the light's frame mapped to the image by Clarberg's equal-area mapping
//! ([`crate::light::octahedral::sphere_to_square`]: +z at the image's centre, −z at its
//! corners), the nearest pixel looked up (pbrt-v4's `LookupNearestChannel`), so every pixel
//! subtends 4π/N² sr.
//!
//! Emission sampling (`sample_le`) picks a pixel ∝ its value and a direction uniform in its
//! solid angle (uniform in the square: the mapping is equal-area), so that the particle weight
//! le/pdf is the same for every direction: 4π·mean(image)·spectrum. The solid-angle pdf is
//! p(pixel)·N²/(4π).

use std::f32::consts::PI;

use glam::{Mat3, Vec2, Vec3};

use super::super::bounds::LightBounds;
use super::super::distribution2d::Distribution2D;
use super::super::octahedral::{sphere_to_square, square_to_sphere};
use super::super::{EmissionPdf, EmissionSample, LightSample};
use crate::spectrum::{SampledWavelengths, Spectrum};

/// A point light with an equal-area intensity image.
#[derive(Clone, Debug)]
pub struct GoniometricMapLight {
    pub position: Vec3,
    /// Columns: the light's local x, y, z in world space, orthonormal.
    pub frame: Mat3,
    /// W·sr⁻¹·nm⁻¹ per unit pixel value.
    pub spectrum: Spectrum,
    res: usize,
    /// res × res values ≥ 0, row-major, the first row at v = 0.
    image: Vec<f32>,
    /// Chooses a pixel ∝ its value.
    dist: Distribution2D,
}

impl GoniometricMapLight {
    /// From a square image of `res` × `res` values (negative ones count as 0). Errors for an
    /// image that is not square or is black.
    pub fn new(
        position: Vec3,
        frame: Mat3,
        spectrum: Spectrum,
        res: usize,
        image: Vec<f32>,
    ) -> Result<Self, String> {
        if res == 0 || image.len() != res * res {
            return Err(format!(
                "an equal-area image must be square: {} pixels for {res} × {res}",
                image.len()
            ));
        }
        let image: Vec<f32> = image
            .into_iter()
            .map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 })
            .collect();
        let dist = Distribution2D::new(&image, res, res)
            .ok_or("the goniometric image is black: every pixel is 0")?;
        Ok(Self {
            position,
            frame,
            spectrum,
            res,
            image,
            dist,
        })
    }

    /// The pixel nearest to (u, v) (pbrt-v4's `LookupNearest`).
    #[inline]
    fn pixel(&self, uv: Vec2) -> usize {
        super::super::octahedral::nearest_pixel(self.res, uv)
    }

    /// The image's value toward the world direction `dir` (unit).
    #[inline]
    pub fn value(&self, dir: Vec3) -> f32 {
        let l = (self.frame.transpose() * dir).normalize();
        self.image[self.pixel(sphere_to_square(l))]
    }

    /// li = I(ω)/r² toward `p`; None where the image is 0.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        super::super::point_like_sample(self.position, p, |wi| {
            let v = self.value(-wi);
            (v > 0.0).then(|| self.spectrum.sample(w) * v)
        })
    }

    /// A particle (light tracing, `bdpt`): a pixel ∝ its value, a direction uniform within it.
    pub fn sample_le<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> EmissionSample<N> {
        let (uv, density) = self.dist.sample(u);
        let d = (self.frame * square_to_sphere(uv)).normalize();
        let le = self.spectrum.sample(w) * self.image[self.pixel(uv)];
        EmissionSample::from_point(self.position, d, le, density / (4.0 * PI))
    }

    /// Densities of [`GoniometricMapLight::sample_le`] for the world direction `dir` (unit):
    /// a delta position (0) and the pixel's p·N²/(4π).
    pub fn pdf_le(&self, dir: Vec3) -> EmissionPdf {
        let l = (self.frame.transpose() * dir).normalize();
        let k = self.pixel(sphere_to_square(l));
        EmissionPdf {
            pos: 0.0,
            dir: self.dist.pdf_cell(k % self.res, k / self.res) / (4.0 * PI),
        }
    }

    /// The mean pixel value (the mean intensity over the sphere per unit spectrum).
    pub fn mean(&self) -> f64 {
        self.image.iter().map(|&v| v as f64).sum::<f64>() / self.image.len() as f64
    }

    /// The power, W, for `band` the spectrum's integral over the band: 4π·mean·band.
    pub fn power(&self, band: f64) -> f64 {
        4.0 * std::f64::consts::PI * self.mean() * band
    }

    /// Bounds for the light tree: an emitter at its position, of every direction, with `phi`
    /// its power, W, whose peak the tree takes as 4π times the mean intensity over the
    /// solid angle 4π·mean/max ([`LightBounds::phi_of`]).
    pub fn bounds(&self, phi: f32) -> LightBounds {
        let max = self.image.iter().fold(0.0f32, |m, &v| m.max(v)) as f64;
        let omega = (4.0 * std::f64::consts::PI * self.mean() / max.max(1e-30)) as f32;
        LightBounds::point(self.position, LightBounds::phi_of(phi, omega))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn waves() -> SampledWavelengths<4> {
        SampledWavelengths {
            lambda: [550.0; 4],
            pdf: [1.0; 4],
        }
    }

    /// An image of one bright pixel at the centre (+z) over a dim rest: the intensity along +z
    /// is the bright value and along −z the dim one, at 1/r².
    #[test]
    fn intensity_follows_the_image() {
        let n = 8;
        let mut img = vec![0.5f32; n * n];
        img[(n / 2) * n + n / 2] = 10.0;
        let l =
            GoniometricMapLight::new(Vec3::ZERO, Mat3::IDENTITY, Spectrum::Constant(2.0), n, img)
                .unwrap();
        let w = waves();
        // a direction just off +z lands in the centre pixel (½ + ε, ½ + ε)
        let up = Vec3::new(0.01, 0.01, 1.0).normalize() * 2.0;
        let s = l.sample_li(up, &w).unwrap();
        assert!((s.li.0[0] - 2.0 * 10.0 / 4.0).abs() < 1e-4, "{}", s.li.0[0]);
        let s = l.sample_li(Vec3::new(0.0, 0.0, -3.0), &w).unwrap();
        assert!((s.li.0[0] - 2.0 * 0.5 / 9.0).abs() < 1e-5, "{}", s.li.0[0]);
    }

    /// Particles: le/pdf averages to the power over 4π (4π·mean·spectrum per particle), and
    /// pdf_le agrees with the sampled density.
    #[test]
    fn particles_carry_the_power() {
        let n = 16;
        let img: Vec<f32> = (0..n * n).map(|i| ((i * 37) % 11) as f32 * 0.3).collect();
        let l = GoniometricMapLight::new(
            Vec3::ZERO,
            Mat3::from_rotation_x(0.3),
            Spectrum::Constant(1.0),
            n,
            img,
        )
        .unwrap();
        let w = waves();
        let m = 64;
        let mut sum = 0.0f64;
        for i in 0..m {
            for j in 0..m {
                let u = Vec2::new((i as f32 + 0.5) / m as f32, (j as f32 + 0.5) / m as f32);
                let e = l.sample_le(&w, u);
                let pdf = e.pdf_dir;
                let back = l.pdf_le(e.d).dir;
                assert!((pdf - back).abs() <= 1e-3 * pdf, "{pdf} vs {back}");
                sum += (e.le.0[0] / pdf) as f64;
            }
        }
        let got = sum / (m * m) as f64;
        let want = 4.0 * std::f64::consts::PI * l.mean();
        assert!((got / want - 1.0).abs() < 1e-3, "{got} vs {want}");
    }
}
