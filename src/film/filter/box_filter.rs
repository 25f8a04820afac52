//! The box filter: every offset within half-width `radius` weighs the same.
//!
//! TOML `filter = "box"` (or `{ type = "box", radius = … }`; `filter_radius`), Mitsuba
//! `<rfilter type="box">` (`radius`, default 0.5 px, src/rfilters/box.cpp). A box of radius
//! 0.5 px counts each sample in the pixel it falls in.

use super::FilterDesc;
use crate::params::{Kind, ParamError, Params};

/// A box of half-width `radius`, pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Desc {
    /// Half-width of the support, pixels.
    pub radius: f64,
}

/// The box's kernel: 1 everywhere on its support.
#[derive(Clone, Copy, Debug)]
pub struct Kernel;

impl Kernel {
    pub(super) fn eval(self, _x: f32) -> f32 {
        1.0
    }
}

impl Desc {
    pub(super) fn radius(&self) -> f32 {
        self.radius as f32
    }
    pub(super) fn kernel(&self) -> Kernel {
        Kernel
    }
}

/// `box` in both formats.
pub const KIND: Kind<FilterDesc> = Kind {
    toml: Some("box"),
    mitsuba: Some("box"),
    read,
};

fn read(p: &mut dyn Params) -> Result<FilterDesc, ParamError> {
    Ok(FilterDesc::Box(Desc {
        radius: p.positive("radius", 0.5)?,
    }))
}
