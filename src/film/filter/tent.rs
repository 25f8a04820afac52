//! The tent (triangle) filter: 1 − |x|/radius per axis.
//!
//! TOML `filter = "tent"` (or `{ type = "tent", radius = … }`; `filter_radius`), Mitsuba
//! `<rfilter type="tent">` (src/rfilters/tent.cpp), both with `radius` in pixels, default 1.
//! spectrace evaluates the tent exactly; a Mitsuba scene gets the tent as Mitsuba's scalar
//! variants evaluate it, from a table of 31 steps over [0, radius] (see [`super::stepped`]).

use super::{FilterDesc, MITSUBA_FILTER_RESOLUTION, stepped};
use crate::params::{Dialect, Kind, ParamError, Params};

/// A tent of half-width `radius`, pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Desc {
    /// Half-width of the support, pixels.
    pub radius: f64,
    /// Evaluated from Mitsuba's 31-step table.
    pub mitsuba: bool,
}

/// max(0, 1 − |x'|/radius) with x' = [`stepped`]`(x, step)`.
#[derive(Clone, Copy, Debug)]
pub struct Kernel {
    inv_radius: f32,
    step: f32,
}

impl Kernel {
    pub(super) fn eval(self, x: f32) -> f32 {
        (1.0 - stepped(x, self.step).abs() * self.inv_radius).max(0.0)
    }
}

impl Desc {
    pub(super) fn radius(&self) -> f32 {
        self.radius as f32
    }

    pub(super) fn kernel(&self) -> Kernel {
        let r = self.radius as f32;
        Kernel {
            inv_radius: 1.0 / r,
            step: if self.mitsuba {
                r / MITSUBA_FILTER_RESOLUTION
            } else {
                0.0
            },
        }
    }
}

/// `tent` in both formats.
pub const KIND: Kind<FilterDesc> = Kind {
    toml: Some("tent"),
    mitsuba: Some("tent"),
    read,
};

fn read(p: &mut dyn Params) -> Result<FilterDesc, ParamError> {
    Ok(FilterDesc::Tent(Desc {
        radius: p.positive("radius", 1.0)?,
        mitsuba: p.dialect() == Dialect::Mitsuba,
    }))
}

#[cfg(test)]
mod tests {
    use super::super::Filter;
    use super::*;
    use glam::Vec2;

    /// Mitsuba 3.9.1's values (`scalar_spectral`, `mi.load_dict({'type': 'tent', 'radius':
    /// r})`: `eval(x)`, then `eval_discretized(x)`).
    #[test]
    fn kernel_is_mitsubas() {
        for (r, x, exact, table) in [
            (1.0, 0.0, 1.0, 1.0),
            (1.0, 0.02, 0.98, 1.0),
            (1.0, 0.1, 0.9, 0.903_225_8),
            (1.0, 0.25, 0.75, 0.774_193_5),
            (1.0, 0.5, 0.5, 0.516_129),
            (1.0, 0.9, 0.1, 0.129_032_3),
            (1.0, 0.99, 0.01, 0.032_258_1),
            (2.0, 0.3, 0.85, 0.870_967_7),
            (2.0, 1.5, 0.25, 0.258_064_5),
            (2.0, 1.99, 0.005, 0.032_258_1),
        ] {
            for (mitsuba, want) in [(false, exact), (true, table)] {
                let got = FilterDesc::Tent(Desc { radius: r, mitsuba }).kernel().1.eval(x);
                assert!((got - want).abs() < 1e-6, "r {r} x {x} {mitsuba}: {got} vs {want}");
            }
        }
    }

    /// Sampled offsets follow the triangle: P(|x| > d) = (1 − d/r)².
    #[test]
    fn samples_have_the_triangles_distribution() {
        let f = Filter::from_desc(&FilterDesc::Tent(Desc {
            radius: 1.5,
            mitsuba: false,
        }));
        let n = 200_000;
        for d in [0.1f64, 0.5, 1.0, 1.4] {
            let beyond = (0..n)
                .filter(|i| (f.sample(Vec2::splat((*i as f32 + 0.5) / n as f32)).x as f64).abs() > d)
                .count() as f64
                / n as f64;
            let want = (1.0 - d / 1.5).powi(2);
            assert!((beyond - want).abs() < 1e-3, "d {d}: {beyond} vs {want}");
        }
    }
}
