//! Reconstruction filters, applied by importance sampling (pbrt-v4 §8.8.3): each camera sample
//! is offset from the pixel centre with the filter's own distribution and counts with weight 1
//! in its pixel only, so tiles never overlap and the image does not depend on the thread count.

use glam::Vec2;

use crate::params::Kind;
use crate::sampling::CdfGuide;

/// The registry of pixel filter kinds: one line per kind, naming its enum variant and its file.
/// Each file holds the kind's description (`Desc`, in pixels), its one-axis kernel (`Kernel`,
/// `Copy`, with `fn eval(self, x: f32) -> f32`: unnormalised, x in pixels, |x| ≤ radius) and its
/// reader (`KIND`: its names in TOML and Mitsuba XML and a `fn(&mut dyn Params)`). The macro
/// makes [`FilterDesc`] and the kernel a closed enum of these with `match` dispatch, and
/// [`KINDS`] the list both loaders look names up in and take their "expected …" lists from.
macro_rules! filter_kinds {
    ($($variant:ident => $module:ident),* $(,)?) => {
        $(pub mod $module;)*

        /// A pixel filter as the description states it, in pixels (the build step makes the
        /// [`Filter`] the film samples from it): one variant per kind of [`KINDS`].
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum FilterDesc {
            $($variant($module::Desc),)*
        }

        /// Every filter kind, for the loaders (see [`crate::params`]).
        pub const KINDS: &[Kind<FilterDesc>] = &[$($module::KIND,)*];

        /// One axis of the filter, unnormalised, for |x| ≤ radius.
        #[derive(Clone, Copy, Debug)]
        enum Kernel {
            $($variant($module::Kernel),)*
        }

        impl Kernel {
            fn eval(self, x: f32) -> f32 {
                match self {
                    $(Kernel::$variant(k) => k.eval(x),)*
                }
            }
        }

        impl FilterDesc {
            /// The half-width of the support (pixels) and the one-axis kernel.
            fn kernel(&self) -> (f32, Kernel) {
                match self {
                    $(FilterDesc::$variant(d) => (d.radius(), Kernel::$variant(d.kernel())),)*
                }
            }
        }
    };
}

filter_kinds! {
    Box => box_filter,
    Gaussian => gaussian,
    Tent => tent,
}

impl FilterDesc {
    /// A box of width 1 pixel: each sample counts in the pixel it falls in.
    pub const BOX: Self = FilterDesc::Box(box_filter::Desc { radius: 0.5 });
}

/// `x` rounded towards 0 to a multiple of `step` when `step` > 0 (Mitsuba 3's scalar variants
/// evaluate a filter from a table of its values at the ends of `MI_FILTER_RESOLUTION` = 31
/// steps over [0, radius], each step holding the value at its inner end:
/// `ReconstructionFilter::eval_discretized` in src/core/rfilter.cpp); `x` itself when `step`
/// is 0.
pub fn stepped(x: f32, step: f32) -> f32 {
    if step > 0.0 {
        (x.abs() / step).floor() * step
    } else {
        x
    }
}

/// Steps of Mitsuba 3's filter table over [0, radius] (`MI_FILTER_RESOLUTION`).
pub const MITSUBA_FILTER_RESOLUTION: f32 = 31.0;

/// A separable pixel filter, sampled per axis by inverting a finely tabulated CDF.
#[derive(Clone, Debug)]
pub struct Filter {
    /// Half-width of the support, pixels.
    pub radius: f32,
    kernel: Kernel,
    /// CDF of one axis over `CELLS` equal cells of [−radius, radius], `CELLS + 1` entries from
    /// 0 to 1.
    cdf: Vec<f32>,
    /// 1 / ∫ f dx over [−radius, radius] for one axis (px⁻¹ → normalised), by the same
    /// midpoint rule as `cdf`, for [`Filter::weight`].
    inv_integral: f32,
    /// Guide table for inverting `cdf` in O(1).
    guide: CdfGuide,
}

/// Entries of the CDF's guide table.
const GUIDE: usize = 1024;

const CELLS: usize = 8192;

impl Filter {
    /// The filter a description states, tabulated for sampling.
    pub fn from_desc(d: &FilterDesc) -> Self {
        let (radius, kernel) = d.kernel();
        Self::tabulate(radius, kernel)
    }

    /// The filter's weight at `offset` from the pixel centre (pixels): the product of the two
    /// axes' kernels, unnormalised (1 at the centre of a truncated Gaussian or a box), 0 outside
    /// the square of half-width `radius`.
    pub fn eval(&self, offset: Vec2) -> f32 {
        if offset.x.abs() > self.radius || offset.y.abs() > self.radius {
            return 0.0;
        }
        self.kernel.eval(offset.x) * self.kernel.eval(offset.y)
    }

    /// The normalised one-axis filter f(x)/∫f at offset `x` (pixels), px⁻¹; 0 outside the
    /// half-open support [−radius, radius), so that a point on the boundary between two pixels
    /// of a box filter counts in one of them.
    fn weight_axis(&self, x: f32) -> f32 {
        if !(x >= -self.radius && x < self.radius) {
            return 0.0;
        }
        self.kernel.eval(x) * self.inv_integral
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

    fn tabulate(radius: f32, kernel: Kernel) -> Self {
        // CDF of the kernel taken as constant over each of CELLS cells of [−r, r] (its value
        // at the cell's midpoint), normalised to end at 1
        let dx = 2.0 * radius as f64 / CELLS as f64;
        let mut acc = 0.0f64;
        let mut sums = Vec::with_capacity(CELLS + 1);
        sums.push(0.0);
        for i in 0..CELLS {
            let m = -radius as f64 + (i as f64 + 0.5) * dx;
            acc += kernel.eval(m as f32) as f64;
            sums.push(acc);
        }
        let cdf: Vec<f32> = sums.iter().map(|&c| (c / acc) as f32).collect();
        let guide = CdfGuide::new(&cdf, GUIDE);
        Self {
            radius,
            kernel,
            guide,
            cdf,
            inv_integral: (1.0 / (acc * dx)) as f32,
        }
    }

    /// One axis's offset, pixels: the inverse of the piecewise-linear CDF (exact for the
    /// tabulated piecewise-constant kernel, tails included).
    fn sample_axis(&self, u: f32) -> f32 {
        let u = u.clamp(0.0, 1.0);
        if let Kernel::Box(_) = self.kernel {
            // the CDF is the identity: no table needed
            return -self.radius + u * (2.0 * self.radius);
        }
        let i = self.guide.cell(&self.cdf, u as f64);
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let t = if c1 > c0 {
            ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        -self.radius + (i as f32 + t) * (2.0 * self.radius / CELLS as f32)
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
        let f = Filter::from_desc(&FilterDesc::BOX);
        assert!((f.sample(Vec2::ZERO).x + 0.5).abs() < 1e-5);
        assert!((f.sample(Vec2::splat(0.25)).x + 0.25).abs() < 1e-4);
        assert!((f.sample(Vec2::ONE).x - 0.5).abs() < 1e-5);
    }

    #[test]
    fn guide_table_finds_the_cell_a_binary_search_finds() {
        for d in [gaussian::Desc::native(1.5), gaussian::Desc::mitsuba(0.5)] {
            let f = Filter::from_desc(&d);
            for k in 0..=100_000u32 {
                let u = k as f32 / 100_000.0;
                let i = f.cdf.partition_point(|&c| c <= u).clamp(1, CELLS) - 1;
                let (c0, c1) = (f.cdf[i], f.cdf[i + 1]);
                let t = if c1 > c0 {
                    ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let want = -f.radius + (i as f32 + t) * (2.0 * f.radius / CELLS as f32);
                assert_eq!(f.sample_axis(u), want, "{d:?} u = {u}");
            }
        }
    }

    #[test]
    fn weight_is_the_sampled_density() {
        for d in [
            FilterDesc::BOX,
            gaussian::Desc::native(1.5),
            gaussian::Desc::mitsuba(0.5),
        ] {
            let f = Filter::from_desc(&d);
            // ∫∫ weight = (∫ weight_axis)² = 1 over the support: the weight is the product of
            // its axes (checked on a grid), and each axis integrates to 1 (midpoint rule with
            // 200 000 cells, fine enough for the step edges of Mitsuba's tabulated kernel)
            for i in 0..20 {
                for j in 0..20 {
                    let o = Vec2::new(
                        -f.radius + (i as f32 + 0.5) * f.radius / 10.0,
                        -f.radius + (j as f32 + 0.5) * f.radius / 10.0,
                    );
                    let w = f.weight(o);
                    let prod = f.weight_axis(o.x) * f.weight_axis(o.y);
                    assert!((w - prod).abs() <= 1e-6 * prod.max(1.0), "{d:?} at {o}");
                }
            }
            let n = 200_000;
            let h = 2.0 * f.radius as f64 / n as f64;
            let axis: f64 = (0..n)
                .map(|i| f.weight_axis((-f.radius as f64 + (i as f64 + 0.5) * h) as f32) as f64 * h)
                .sum();
            let sum = axis * axis;
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
        let b = Filter::from_desc(&FilterDesc::BOX);
        assert_eq!(b.weight(Vec2::new(-0.5, 0.0)), 1.0);
        assert_eq!(b.weight(Vec2::new(0.5, 0.0)), 0.0);
    }

    #[test]
    fn gaussian_has_its_sigma() {
        let f = Filter::from_desc(&gaussian::Desc::native(1.5));
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

    /// Fraction of one axis's samples beyond `x`, from 200 000 stratified samples.
    fn tail(f: &Filter, x: f32) -> f64 {
        let n = 200_000;
        (0..n)
            .filter(|i| f.sample_axis((*i as f32 + 0.5) / n as f32) > x)
            .count() as f64
            / n as f64
    }

    #[test]
    fn mitsuba_gaussian_is_mitsubas_table() {
        let f = Filter::from_desc(&gaussian::Desc::mitsuba(0.5));
        assert_eq!(f.radius, 2.0);
        // Mitsuba 3.9.1 scalar_spectral, `mi.load_dict({'type': 'gaussian'})
        // .eval_discretized(x)` (its kernel is a polynomial fit of the Gaussian, hence 1e-3)
        for (x, want) in [
            (0.0, 0.999247),
            (0.07, 0.990995),
            (0.5, 0.664957),
            (1.0, 0.153261),
            (1.5, 0.011880),
            (1.99, 0.000221),
            (2.0, 0.0),
        ] {
            let got = f.eval(Vec2::new(x, 0.0));
            assert!((got - want).abs() < 1e-3, "{x}: {got} vs {want}");
        }
        // the fraction of one axis's weight beyond d px: Mitsuba's table integrated by the
        // midpoint rule (8001 points over [−2, 2], the same call); a 3σ-truncated Gaussian
        // gives 0 beyond 1.5 px
        for (d, want) in [
            (0.25, 0.31514),
            (0.5, 0.16605),
            (0.75, 0.07188),
            (1.25, 0.00691),
            (1.5, 0.00143),
            (1.75, 0.00018),
        ] {
            let got = tail(&f, d);
            assert!((got - want).abs() < 2e-4, "{d}: {got} vs {want}");
        }
        let native = Filter::from_desc(&gaussian::Desc::native(1.5));
        assert_eq!(tail(&native, 1.5), 0.0);
    }
}
