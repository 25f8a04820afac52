//! Mitsuba's `checkerboard` texture (src/textures/checkerboard.cpp, 3.9.1): with (s, t) the
//! fractional parts of `to_uv(uv)`, the value is `a` (Mitsuba's `color0`) where s > ½ and
//! t > ½ agree, else `b` (`color1`): checks of ½ × ½ in texture space, `a` in the corner
//! [0, ½]², point-sampled (no filtering).

use glam::Vec2;

use super::UvTransform;
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

#[derive(Clone, Debug, PartialEq)]
pub struct Checkerboard {
    /// Value on the checks containing uv = (0.25, 0.25) (Mitsuba's `color0`, default 0.4).
    pub a: Spectrum,
    /// Value on the other checks (`color1`, default 0.2).
    pub b: Spectrum,
    pub to_uv: UvTransform,
}

impl Checkerboard {
    /// Whether `uv` lies on an `a` check.
    #[inline]
    pub fn is_a(&self, uv: Vec2) -> bool {
        let p = self.to_uv.apply(uv);
        let (s, t) = (p.x - p.x.floor(), p.y - p.y.floor());
        (s > 0.5) == (t > 0.5)
    }

    #[inline]
    pub fn sample<const N: usize>(
        &self,
        uv: Vec2,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        if self.is_a(uv) {
            self.a.sample(w)
        } else {
            self.b.sample(w)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_are_half_a_unit_and_a_is_at_the_origin() {
        let c = Checkerboard {
            a: Spectrum::Constant(1.0),
            b: Spectrum::Constant(0.0),
            to_uv: UvTransform::IDENTITY,
        };
        for (uv, a) in [
            ((0.25, 0.25), true),
            ((0.75, 0.25), false),
            ((0.25, 0.75), false),
            ((0.75, 0.75), true),
            ((1.25, 0.25), true),
            ((-0.25, 0.25), false),
            ((0.5, 0.5), true), // ½ itself belongs to the lower check
        ] {
            assert_eq!(c.is_a(Vec2::new(uv.0, uv.1)), a, "{uv:?}");
        }
        let scaled = Checkerboard {
            to_uv: UvTransform {
                rows: [[4.0, 0.0, 0.0], [0.0, 4.0, 0.0]],
            },
            ..c
        };
        assert!(!scaled.is_a(Vec2::new(0.15, 0.05)));
        assert!(scaled.is_a(Vec2::new(0.3, 0.05)));
    }
}
