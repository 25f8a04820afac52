//! Reconstruction filters, applied by importance sampling (pbrt-v4 §8.8.3): each camera sample
//! is offset from the pixel centre with the filter's own distribution and counts with weight 1
//! in its pixel only, so tiles never overlap and the image does not depend on the thread count.

use glam::Vec2;

use crate::loader::desc::FilterDesc;

/// A separable pixel filter, sampled through a tabulated inverse CDF per axis.
#[derive(Clone, Debug)]
pub struct Filter {
    /// Half-width of the support, pixels.
    pub radius: f32,
    /// Inverse CDF of one axis on [0, 1], `INV_CDF_SIZE + 1` entries, in pixels.
    inv_cdf: Vec<f32>,
    /// The one-axis filter f(x) at `values.len()` evenly spaced x from −radius to radius,
    /// divided by ∫ f dx over the support (px⁻¹), for [`Filter::weight`].
    values: Vec<f32>,
}

const INV_CDF_SIZE: usize = 1024;

impl Filter {
    /// Box of width 1 pixel, or a Gaussian of standard deviation σ truncated at 3σ.
    pub fn from_desc(d: &FilterDesc) -> Self {
        match *d {
            FilterDesc::Box => Self::tabulate(0.5, |_| 1.0),
            FilterDesc::Gaussian { sigma } => {
                let s = sigma as f32;
                Self::tabulate(3.0 * s, |x| (-x * x / (2.0 * s * s)).exp())
            }
        }
    }

    fn tabulate(radius: f32, f: impl Fn(f32) -> f32) -> Self {
        // fine CDF of f on [-r, r], then inverted at uniform levels
        let n = 8192;
        let xs: Vec<f32> = (0..=n)
            .map(|i| -radius + 2.0 * radius * i as f32 / n as f32)
            .collect();
        let mut cdf = vec![0.0f64; n + 1];
        for i in 0..n {
            let m = 0.5 * (xs[i] + xs[i + 1]);
            cdf[i + 1] = cdf[i] + f(m) as f64;
        }
        let total = cdf[n];
        // ∫ f dx by the same midpoint rule, pixels
        let integral = total * (2.0 * radius as f64) / n as f64;
        let values = xs
            .iter()
            .map(|&x| (f(x) as f64 / integral) as f32)
            .collect();
        let mut inv_cdf = Vec::with_capacity(INV_CDF_SIZE + 1);
        let mut j = 0;
        for k in 0..=INV_CDF_SIZE {
            let u = k as f64 / INV_CDF_SIZE as f64 * total;
            while j < n - 1 && cdf[j + 1] < u {
                j += 1;
            }
            let t = if cdf[j + 1] > cdf[j] {
                ((u - cdf[j]) / (cdf[j + 1] - cdf[j])).clamp(0.0, 1.0)
            } else {
                0.0
            };
            inv_cdf.push(xs[j] + (xs[j + 1] - xs[j]) * t as f32);
        }
        Self {
            radius,
            inv_cdf,
            values,
        }
    }

    /// The normalised one-axis filter f(x)/∫f at offset `x` (pixels), px⁻¹; 0 outside the
    /// half-open support [−radius, radius), so that a point on the boundary between two pixels
    /// of a box filter counts in one of them.
    fn weight_axis(&self, x: f32) -> f32 {
        if !(x >= -self.radius && x < self.radius) {
            return 0.0;
        }
        let n = self.values.len() - 1;
        let t = ((x + self.radius) / (2.0 * self.radius) * n as f32).clamp(0.0, n as f32);
        let i = (t as usize).min(n - 1);
        let a = t - i as f32;
        self.values[i] + a * (self.values[i + 1] - self.values[i])
    }

    /// The weight with which a point at `offset` (pixels) from a pixel centre counts in that
    /// pixel: f(offset) / ∫∫ f, px⁻², the density that [`Filter::sample`] draws offsets from.
    /// Splatting a value with this weight into every pixel of the support reconstructs the same
    /// image, ∫ L(x) f(x − centre) dx / ∫ f, as averaging camera samples drawn by `sample`
    /// (pbrt-v4 §5.4.3 and §8.8; the weights over the pixels of the support sum to about 1).
    pub fn weight(&self, offset: Vec2) -> f32 {
        let wx = self.weight_axis(offset.x);
        if wx == 0.0 {
            return 0.0;
        }
        wx * self.weight_axis(offset.y)
    }

    fn sample_axis(&self, u: f32) -> f32 {
        let x = u.clamp(0.0, 1.0) * INV_CDF_SIZE as f32;
        let i = (x as usize).min(INV_CDF_SIZE - 1);
        let t = x - i as f32;
        self.inv_cdf[i] + t * (self.inv_cdf[i + 1] - self.inv_cdf[i])
    }

    /// Offset from the pixel centre, pixels, distributed as the filter.
    pub fn sample(&self, u: Vec2) -> Vec2 {
        Vec2::new(self.sample_axis(u.x), self.sample_axis(u.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_is_uniform_over_the_pixel() {
        let f = Filter::from_desc(&FilterDesc::Box);
        assert!((f.sample(Vec2::ZERO).x + 0.5).abs() < 1e-5);
        assert!((f.sample(Vec2::splat(0.25)).x + 0.25).abs() < 1e-4);
        assert!((f.sample(Vec2::ONE).x - 0.5).abs() < 1e-5);
    }

    #[test]
    fn weight_is_the_sampled_density() {
        for d in [FilterDesc::Box, FilterDesc::Gaussian { sigma: 0.5 }] {
            let f = Filter::from_desc(&d);
            // ∫ weight = 1 over the support (midpoint rule on a 400 × 400 grid)
            let n = 400;
            let h = 2.0 * f.radius / n as f32;
            let mut sum = 0.0f64;
            for i in 0..n {
                for j in 0..n {
                    let o = Vec2::new(
                        -f.radius + (i as f32 + 0.5) * h,
                        -f.radius + (j as f32 + 0.5) * h,
                    );
                    sum += (f.weight(o) * h * h) as f64;
                }
            }
            assert!((sum - 1.0).abs() < 1e-4, "{d:?}: ∫ weight = {sum}");
            // the fraction of sampled offsets with x < a equals ∫_{−r}^{a} weight_axis
            let a = 0.2 * f.radius;
            let m = 20_000;
            let below = (0..m)
                .filter(|&k| f.sample_axis((k as f32 + 0.5) / m as f32) < a)
                .count() as f64
                / m as f64;
            let steps = 20_000;
            let dx = (a + f.radius) / steps as f32;
            let cdf: f64 = (0..steps)
                .map(|k| (f.weight_axis(-f.radius + (k as f32 + 0.5) * dx) * dx) as f64)
                .sum();
            assert!((below - cdf).abs() < 1e-3, "{d:?}: {below} vs {cdf}");
        }
        let b = Filter::from_desc(&FilterDesc::Box);
        assert_eq!(b.weight(Vec2::new(-0.5, 0.0)), 1.0);
        assert_eq!(b.weight(Vec2::new(0.5, 0.0)), 0.0);
    }

    #[test]
    fn gaussian_has_its_sigma() {
        let f = Filter::from_desc(&FilterDesc::Gaussian { sigma: 0.5 });
        let n = 100_000;
        let var: f64 = (0..n)
            .map(|i| (f.sample_axis((i as f32 + 0.5) / n as f32) as f64).powi(2))
            .sum::<f64>()
            / n as f64;
        // a normal truncated at 3σ has variance 0.9733 σ²
        assert!(
            (var.sqrt() - 0.5 * 0.9733f64.sqrt()).abs() < 2e-3,
            "{}",
            var.sqrt()
        );
        assert!((f.sample_axis(0.5)).abs() < 1e-4);
    }
}
