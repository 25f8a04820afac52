//! The Gaussian filter, spectrace's and Mitsuba 3's.
//!
//! - TOML `filter = "gaussian"` (the default): exp(−x²/2σ²) per axis, truncated at `radius`
//!   (`filter_radius`, default 1.5 px) with σ = radius/3.
//! - Mitsuba `<rfilter type="gaussian">` as its scalar variants apply it (src/rfilters/
//!   gaussian.cpp, src/core/rfilter.cpp): per axis exp(−x²/2σ²) − exp(−r²/2σ²) of standard
//!   deviation `stddev` (default 0.5 px) with r = 4σ, zero beyond r, tabulated in 31 steps of
//!   |x| over [0, r], each step holding the value at its inner end (`eval_discretized`).
//! - pbrt-v4's `gaussian` (src/pbrt/filters.h, `GaussianFilter`): per axis
//!   max(0, G(x) − G(r)) of `sigma` 0.5 and `xradius`/`yradius` 1.5 px, evaluated exactly.

use super::{FilterDesc, MITSUBA_FILTER_RESOLUTION, stepped};
use crate::params::{Dialect, Kind, ParamError, Params};

/// A Gaussian of standard deviation `sigma` per axis, cut at `radius` (both in pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Desc {
    /// Standard deviation, pixels.
    pub sigma: f64,
    /// Half-width of the support, pixels.
    pub radius: f64,
    /// Mitsuba's form: shifted down by its value at `radius` so it reaches 0 there, and
    /// evaluated from Mitsuba's 31-step table.
    pub mitsuba: bool,
    /// pbrt-v4's form: shifted down by its value at `radius`, evaluated exactly.
    pub shifted: bool,
}

impl Desc {
    /// spectrace's native Gaussian of radius `radius` px, σ = radius/3.
    pub fn native(radius: f64) -> FilterDesc {
        FilterDesc::Gaussian(Desc {
            sigma: radius / 3.0,
            radius,
            mitsuba: false,
            shifted: false,
        })
    }

    /// pbrt-v4's `gaussian` of standard deviation `sigma` px cut at `radius` px.
    pub fn pbrt(sigma: f64, radius: f64) -> FilterDesc {
        FilterDesc::Gaussian(Desc {
            sigma,
            radius,
            mitsuba: false,
            shifted: true,
        })
    }

    /// Mitsuba's `gaussian` of standard deviation `stddev` px.
    pub fn mitsuba(stddev: f64) -> FilterDesc {
        FilterDesc::Gaussian(Desc {
            sigma: stddev,
            radius: 4.0 * stddev,
            mitsuba: true,
            shifted: true,
        })
    }

    pub(super) fn radius(&self) -> f32 {
        self.radius as f32
    }

    pub(super) fn kernel(&self) -> Kernel {
        let alpha = (1.0 / (2.0 * self.sigma * self.sigma)) as f32;
        let r = self.radius as f32;
        if self.shifted {
            Kernel {
                alpha,
                bias: (-alpha * r * r).exp(),
                step: if self.mitsuba {
                    r / MITSUBA_FILTER_RESOLUTION
                } else {
                    0.0
                },
            }
        } else {
            Kernel {
                alpha,
                bias: 0.0,
                step: 0.0,
            }
        }
    }
}

/// max(0, exp(−α x'²) − bias), α = 1/2σ², with x' = [`stepped`]`(x, step)`.
#[derive(Clone, Copy, Debug)]
pub struct Kernel {
    alpha: f32,
    bias: f32,
    step: f32,
}

impl Kernel {
    pub(super) fn eval(self, x: f32) -> f32 {
        let x = stepped(x, self.step);
        ((-self.alpha * x * x).exp() - self.bias).max(0.0)
    }
}

/// `gaussian` in both formats, each read as its format defines it.
pub const KIND: Kind<FilterDesc> = Kind {
    toml: Some("gaussian"),
    mitsuba: Some("gaussian"),
    read,
};

fn read(p: &mut dyn Params) -> Result<FilterDesc, ParamError> {
    Ok(match p.dialect() {
        Dialect::Toml => Desc::native(p.positive("radius", 1.5)?),
        Dialect::Mitsuba => Desc::mitsuba(p.positive("stddev", 0.5)?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// pbrt-v4's Gaussian: G(x) − G(r) with G(x) = exp(−x²/2σ²), exactly (no table).
    #[test]
    fn pbrt_form_is_shifted_and_continuous() {
        let FilterDesc::Gaussian(d) = Desc::pbrt(0.5, 1.5) else {
            unreachable!()
        };
        let k = d.kernel();
        let g = |x: f32| (-x * x / 0.5).exp();
        for x in [0.0f32, 0.3, 0.75, 1.2, 1.49] {
            assert!((k.eval(x) - (g(x) - g(1.5))).abs() < 1e-6, "{x}");
        }
        assert_eq!(k.eval(1.5), 0.0);
    }
}
