//! Display transforms: linear sRGB, already divided by the exposure's white (1 = the saturating
//! luminance, see `crate::output`), to the linear display values in [0, 1] that the PNG
//! encodes. They shape only the 8-bit preview; the EXR's channels stay absolute (cd/m² and
//! W·m⁻²·sr⁻¹) and never pass through them.
//!
//! # Why `standard` desaturates toward the grey of the same luminance
//!
//! A spectral colour lies outside every RGB gamut: a 5 nm line at 470 nm has a negative red
//! and green channel in sRGB. Clamping each channel to [0, 1] (`clip`, the transform before
//! issue 30) moves such a colour toward the nearest corner of the RGB cube, so a rainbow
//! collapses onto the six primaries and secondaries: hue plateaus at 0°, 60°, 120°, 180°, 240°
//! and 300° with jumps between them, and violet turns magenta. Over-exposure does the same,
//! one channel after another reaching 1.
//!
//! `standard` instead moves the colour along the straight line toward the grey of its own
//! luminance Y = 0.2126 R + 0.7152 G + 0.0722 B. In linear light that line is the additive
//! mixture of the colour with white, so its chromaticity moves on the segment from the colour's
//! chromaticity toward D65: the dominant wavelength is kept exactly, and a spectral sweep keeps
//! its order of hues (a test sweeps 5 nm lines across 400–700 nm). The colour's relative
//! saturation s = the largest step along that line, in units of the step that reaches the
//! nearest face of the cube (s ≤ 1 inside the gamut), is compressed smoothly above
//! [`KNEE`]:
//!
//! s′ = s for s ≤ k; s′ = k + (1 − k) · tanh((s − k)/(1 − k)) above,
//!
//! which has slope 1 at the knee and tends to 1 (the gamut's face) as s → ∞. With k = 0.96 an
//! in-gamut colour moves by less than 1 % of white. Because the faces close in on the grey as
//! Y approaches 1, a brightening colour pales continuously and reaches white at Y = 1, the
//! way film and the eye see an over-exposed light; luminance above white is white. Hue and
//! luminance are kept; only colourfulness is given up, and only where the display cannot
//! show it. This is the idea of ACES 2's gamut compression and of hue-preserving tone mappers,
//! reduced to its simplest form that is exact in the gamut.

/// Relative saturation from which `standard` compresses (see the module doc).
pub const KNEE: f32 = 0.96;

/// The PNG's display transform.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// Out-of-gamut and over-exposed colours pale toward the grey of their own luminance,
    /// keeping their hue (dominant wavelength); in-gamut colours below white pass unchanged.
    #[default]
    Standard,
    /// Each channel clamped to [0, 1] on its own (hues collapse onto the primaries).
    Clip,
}

impl View {
    /// The names accepted by `--view`.
    pub const NAMES: [&'static str; 2] = ["standard", "clip"];

    /// The view called `name` (one of [`View::NAMES`]).
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "standard" => Some(View::Standard),
            "clip" => Some(View::Clip),
            _ => None,
        }
    }

    /// Display-linear RGB in [0, 1] of `rgb` (linear sRGB, 1 = white). Non-finite input
    /// is passed on for the writer to report; +∞ luminance gives white.
    pub fn apply(self, rgb: [f32; 3]) -> [f32; 3] {
        match self {
            View::Clip => rgb.map(|v| if v.is_nan() { v } else { v.clamp(0.0, 1.0) }),
            View::Standard => standard(rgb),
        }
    }
}

/// Rec. 709 luminance weights (the Y row of sRGB to XYZ).
const LUMA: [f32; 3] = [0.2126, 0.7152, 0.0722];

fn standard(rgb: [f32; 3]) -> [f32; 3] {
    if rgb.iter().any(|v| v.is_nan()) {
        return rgb;
    }
    let y = LUMA[0] * rgb[0] + LUMA[1] * rgb[1] + LUMA[2] * rgb[2];
    if y.is_nan() {
        // +∞ and −∞ channels together: nothing meaningful to show
        return [f32::NAN; 3];
    }
    if y <= 0.0 {
        return [0.0; 3];
    }
    if y >= 1.0 {
        return [1.0; 3];
    }
    // relative saturation: the step along (rgb − y) in units of the step reaching a face
    let mut s = 0.0f32;
    for v in rgb {
        let d = v - y;
        let rel = if d > 0.0 { d / (1.0 - y) } else { -d / y };
        s = s.max(rel);
    }
    if s <= KNEE {
        return rgb;
    }
    let s_new = if s.is_finite() {
        KNEE + (1.0 - KNEE) * ((s - KNEE) / (1.0 - KNEE)).tanh()
    } else {
        1.0
    };
    let k = s_new / s;
    rgb.map(|v| {
        let d = if v.is_finite() { v - y } else { 0.0 };
        (y + k * d).clamp(0.0, 1.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_and_in_gamut_pass_and_extremes_are_bounded() {
        assert_eq!(View::Standard.apply([0.3; 3]), [0.3; 3]);
        let c = [0.2, 0.5, 0.1];
        assert_eq!(View::Standard.apply(c), c);
        assert_eq!(View::Standard.apply([2.0, 3.0, 2.5]), [1.0; 3]);
        assert_eq!(View::Standard.apply([-1.0, 0.0, 0.5]), [0.0; 3]);
        let inf = View::Standard.apply([f32::INFINITY, 0.0, 0.0]);
        assert_eq!(inf, [1.0; 3]);
        for v in View::Standard.apply([0.0, 0.0, 5.0]) {
            assert!((0.0..=1.0).contains(&v));
        }
        assert!(View::Standard.apply([f32::NAN, 0.0, 0.0])[0].is_nan());
        assert_eq!(View::Clip.apply([-1.0, 0.5, 2.0]), [0.0, 0.5, 1.0]);
    }

    #[test]
    fn luminance_is_kept_below_white() {
        // a saturated out-of-gamut blue-green: luminance unchanged, channels in [0, 1]
        let c = [-0.2, 0.6, 0.9];
        let y = LUMA[0] * c[0] + LUMA[1] * c[1] + LUMA[2] * c[2];
        let d = View::Standard.apply(c);
        let yd = LUMA[0] * d[0] + LUMA[1] * d[1] + LUMA[2] * d[2];
        assert!((y - yd).abs() < 1e-6, "{y} {yd}");
        assert!(d.iter().all(|v| (0.0..=1.0).contains(v)), "{d:?}");
    }
}
