//! Warps from the unit square to directions and points, with their densities.
//!
//! Directions are in a local frame with the normal along +z. Densities are per unit solid angle
//! (sr⁻¹) for directions and per unit area (m⁻²) for points. References: pbrt-v4 §A.5
//! (Pharr, Jakob & Humphreys 2023), Shirley & Chiu 1997 (concentric disk).

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, PI};

/// Shirley–Chiu concentric map from [0,1)² to the unit disk (area-preserving).
#[inline]
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, FRAC_PI_4 * (o.y / o.x))
    } else {
        (o.y, FRAC_PI_2 - FRAC_PI_4 * (o.x / o.y))
    };
    r * Vec2::new(theta.cos(), theta.sin())
}

/// Cosine-weighted hemisphere direction (z ≥ 0); pdf = cos θ / π sr⁻¹.
#[inline]
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// Density of [`cosine_hemisphere`] at a direction with cos θ = `cos_theta`, sr⁻¹.
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// Uniform direction on the unit sphere; pdf = 1/(4π) sr⁻¹.
#[inline]
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Density of [`uniform_sphere`], sr⁻¹.
pub const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// Uniform direction in the cone around +z with cos θ ≥ 1 − `one_minus_cos_max`;
/// pdf = 1/(2π·one_minus_cos_max). Taking 1 − cos θ_max keeps narrow cones (the sun's 0.27°)
/// accurate in f32.
#[inline]
pub fn uniform_cone(u: Vec2, one_minus_cos_max: f32) -> Vec3 {
    let omc = u.x * one_minus_cos_max;
    let cos_t = 1.0 - omc;
    let sin_t = (omc * (2.0 - omc)).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t)
}

/// Density of [`uniform_cone`], sr⁻¹.
#[inline]
pub fn uniform_cone_pdf(one_minus_cos_max: f32) -> f32 {
    1.0 / (2.0 * PI * one_minus_cos_max)
}

/// A guide table for inverting a tabulated CDF in O(1) (Chen & Asau 1974's cutpoint method):
/// for a CDF of n cells (n + 1 non-decreasing values from 0 to 1 at the cell edges), entry k is
/// the cell that holds u = k / entries, so a search for u starts at entry ⌊u·entries⌋, which
/// never lies past the answer, and walks forward a cell or two.
#[derive(Clone, Debug, Default)]
pub struct CdfGuide {
    guide: Vec<u32>,
}

impl CdfGuide {
    /// The table for `cdf` with `entries` (≥ 1) cutpoints.
    pub fn new<T: Copy + Into<f64>>(cdf: &[T], entries: usize) -> Self {
        let n = cdf.len() - 1;
        let guide = (0..entries.max(1))
            .map(|k| {
                let u = k as f64 / entries as f64;
                cdf[1..].partition_point(|&c| c.into() <= u).min(n - 1) as u32
            })
            .collect();
        Self { guide }
    }

    /// The cell i < n with `cdf[i] ≤ u < cdf[i + 1]` (the last cell for u ≥ 1): the cell a binary
    /// search finds, for u in [0, 1].
    #[inline]
    pub fn cell<T: Copy + Into<f64>>(&self, cdf: &[T], u: f64) -> usize {
        let n = cdf.len() - 1;
        let k = ((u * self.guide.len() as f64) as usize).min(self.guide.len() - 1);
        let mut i = self.guide[k] as usize;
        while i + 1 < n && cdf[i + 1].into() <= u {
            i += 1;
        }
        i
    }
}

/// Sample reuse: a uniform `u` that fell in [lo, hi) (a discrete choice made with it), rescaled
/// to a fresh uniform number in [0, 1) (Mitsuba 3's `DiscreteDistribution::sample_reuse`;
/// pbrt-v4 `SampleDiscrete`'s `uRemapped`). The choice and the point chosen with the rest of
/// `u` then come from one stratified dimension instead of two independent ones, so a
/// stratified set of `u` stays stratified within each choice. Returns 0.5 for an empty
/// interval. Precision: log₂(1/(hi − lo)) of the 24 bits of `u` go to the choice.
#[inline]
pub fn reuse(u: f32, lo: f32, hi: f32) -> f32 {
    if hi > lo {
        ((u - lo) / (hi - lo)).clamp(0.0, 1.0 - f32::EPSILON / 2.0)
    } else {
        0.5
    }
}

/// Uniform point on a triangle as barycentrics (b0, b1), b2 = 1 − b0 − b1 (Heitz 2019,
/// "A Low-Distortion Map Between Triangle and Square").
#[inline]
pub fn uniform_triangle(u: Vec2) -> (f32, f32) {
    let (b0, b1);
    if u.x < u.y {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    (b0, b1)
}

/// The power heuristic with β = 2 (Veach 1997, §9.2.4) for `nf` samples of pdf `f_pdf` against
/// `ng` samples of pdf `g_pdf`.
#[inline]
pub fn power_heuristic(nf: f32, f_pdf: f32, ng: f32, g_pdf: f32) -> f32 {
    let (f, g) = (nf * f_pdf, ng * g_pdf);
    if f.is_infinite() {
        return 1.0;
    }
    if f == 0.0 && g == 0.0 {
        0.0
    } else {
        f * f / (f * f + g * g)
    }
}

/// The unit direction a point of the unit square maps to by Clarberg's equal-area octahedral
/// mapping (pbrt-v4's `EqualAreaSquareToSphere`; its inverse is
/// `crate::light::sphere_to_square`): equal areas of the square to equal solid angles.
pub fn equal_area_square_to_sphere(p: Vec2) -> Vec3 {
    let (u, v) = (2.0 * p.x - 1.0, 2.0 * p.y - 1.0);
    let (up, vp) = (u.abs(), v.abs());
    let signed = 1.0 - (up + vp);
    let r = 1.0 - signed.abs();
    let phi = if r == 0.0 { 1.0 } else { (vp - up) / r + 1.0 } * FRAC_PI_4;
    let z = (1.0 - r * r).copysign(signed);
    let (cos_phi, sin_phi) = (phi.cos().copysign(u), phi.sin().copysign(v));
    let s = r * (2.0 - r * r).max(0.0).sqrt();
    Vec3::new(cos_phi * s, sin_phi * s, z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warps_land_where_they_should() {
        for i in 0..16 {
            for j in 0..16 {
                let u = Vec2::new((i as f32 + 0.5) / 16.0, (j as f32 + 0.5) / 16.0);
                assert!(concentric_disk(u).length() <= 1.0 + 1e-6);
                let h = cosine_hemisphere(u);
                assert!(h.z >= 0.0 && (h.length() - 1.0).abs() < 1e-5);
                assert!((uniform_sphere(u).length() - 1.0).abs() < 1e-5);
                assert!(uniform_cone(u, 0.1).z >= 0.9 - 1e-6);
                let (b0, b1) = uniform_triangle(u);
                assert!(b0 >= 0.0 && b1 >= 0.0 && b0 + b1 <= 1.0 + 1e-6);
            }
        }
    }

    #[test]
    fn power_heuristic_weights_sum_to_one() {
        let a = power_heuristic(1.0, 0.3, 1.0, 0.7);
        let b = power_heuristic(1.0, 0.7, 1.0, 0.3);
        assert!((a + b - 1.0).abs() < 1e-6);
    }
}
