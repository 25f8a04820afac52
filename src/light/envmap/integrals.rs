//! Integrals of an environment map's radiance over the sphere, for light selection and the
//! build step's scales.

use std::f32::consts::PI;

use glam::Vec3;

use super::EnvMapLight;
use crate::spectrum::WavelengthRange;

impl EnvMapLight {
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
        let (lambdas, shape) = super::super::spectral_steps(range, &self.illuminant, g);
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
