//! False-colour images for lighting design (Radiance's `falsecolor`): a per-pixel quantity
//! (luminance in cd/m², illuminance in lx) mapped through matplotlib's perceptually uniform
//! `viridis` colour map on a linear or logarithmic scale, with a legend of the scale in its unit
//! to the right of the image.

mod font;
mod viridis;

pub use viridis::VIRIDIS;

/// How values map onto the colour map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// `lo` (first colour) to `hi` (last colour), linearly.
    Linear { lo: f64, hi: f64 },
    /// `lo` to `hi` (both > 0) in log10; values ≤ `lo` take the first colour.
    Log { lo: f64, hi: f64 },
}

/// The smallest of 1, 2, 5 × 10ᵏ that is ≥ `x` (> 0).
pub fn nice_ceil(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

impl Scale {
    /// A scale to the largest finite value rounded up by [`nice_ceil`]: from 0 (linear), or
    /// `decades` decades below it (log). None when no value is positive.
    pub fn auto(values: &[f32], log: bool, decades: u32) -> Option<Scale> {
        let max = values
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, &v| m.max(v as f64));
        if !(max > 0.0) {
            return None;
        }
        let hi = nice_ceil(max);
        Some(if log {
            Scale::Log {
                lo: hi / 10f64.powi(decades.max(1) as i32),
                hi,
            }
        } else {
            Scale::Linear { lo: 0.0, hi }
        })
    }

    /// Position of `v` on the scale, clamped to [0, 1]; NaN reads 0.
    pub fn position(&self, v: f64) -> f64 {
        let t = match *self {
            Scale::Linear { lo, hi } => (v - lo) / (hi - lo),
            Scale::Log { lo, hi } => {
                if v <= lo {
                    0.0
                } else {
                    (v / lo).log10() / (hi / lo).log10()
                }
            }
        };
        if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) }
    }

    /// The value at position `t` in [0, 1].
    pub fn value(&self, t: f64) -> f64 {
        match *self {
            Scale::Linear { lo, hi } => lo + t * (hi - lo),
            Scale::Log { lo, hi } => lo * (hi / lo).powf(t),
        }
    }

    /// The colour of `v`: entry round(255·position).
    pub fn colour(&self, v: f64) -> [u8; 3] {
        VIRIDIS[(self.position(v) * 255.0).round() as usize]
    }

    /// Tick values: six evenly (linear), or each decade (log).
    fn ticks(&self) -> Vec<f64> {
        match *self {
            Scale::Linear { .. } => (0..=5).map(|k| self.value(k as f64 / 5.0)).collect(),
            Scale::Log { lo, hi } => {
                let n = (hi / lo).log10().round().max(1.0) as usize;
                (0..=n).map(|k| self.value(k as f64 / n as f64)).collect()
            }
        }
    }
}

/// A tick label: plain for 0.01 ≤ |v| < 10⁵ with at most three significant decimals, else
/// in exponent form ("2e6").
pub fn label(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (0.01..100_000.0).contains(&a) {
        let digits = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let e = a.log10().floor() as i32;
        let m = (v / 10f64.powi(e) * 100.0).round() / 100.0;
        format!("{m}e{e}")
    }
}

/// Width of the legend panel, pixels.
pub const LEGEND_WIDTH: usize = 140;

/// The false-colour image of `values` (`width × height`, row-major) with the legend panel on
/// its right: (pixels, width, height). The panel is at least 220 pixels high; a shorter image
/// is padded below. `unit` heads the legend (e.g. "cd/m²").
pub fn image(
    values: &[f32],
    width: usize,
    height: usize,
    scale: Scale,
    unit: &str,
) -> (Vec<[u8; 3]>, usize, usize) {
    let (w, h) = (width + LEGEND_WIDTH, height.max(220));
    let bg = [32, 32, 32];
    let mut img = vec![bg; w * h];
    for y in 0..height {
        for x in 0..width {
            img[y * w + x] = scale.colour(values[y * width + x] as f64);
        }
    }
    // the bar: from `top` (last colour) to `bottom` (first colour)
    let (x0, bar_w) = (width + 10, 20);
    let (top, bottom) = (10 + font::HEIGHT + 14, h - 14);
    for y in top..=bottom {
        let t = (bottom - y) as f64 / (bottom - top) as f64;
        let c = VIRIDIS[(t * 255.0).round() as usize];
        for x in x0..x0 + bar_w {
            img[y * w + x] = c;
        }
    }
    let white = [235, 235, 235];
    let title = match scale {
        Scale::Linear { .. } => unit.to_string(),
        Scale::Log { .. } => format!("{unit} (log)"),
    };
    font::draw(&mut img, w, width + 8, 10, &title, white);
    for v in scale.ticks() {
        let t = scale.position(v);
        let y = bottom - (t * (bottom - top) as f64).round() as usize;
        // a notch into the bar's right edge, the label beside it
        for x in x0 + bar_w - 6..x0 + bar_w {
            img[y * w + x] = bg;
        }
        let ty = y.saturating_sub(font::HEIGHT / 2);
        font::draw(&mut img, w, x0 + bar_w + 6, ty, &label(v), white);
    }
    (img, w, h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scales_and_labels() {
        assert_eq!(nice_ceil(0.73), 1.0);
        assert_eq!(nice_ceil(1.0), 1.0);
        assert_eq!(nice_ceil(130.0), 200.0);
        assert_eq!(nice_ceil(4100.0), 5000.0);
        let s = Scale::auto(&[0.0, 10.0, 730.0, f32::NAN, f32::INFINITY], true, 3).unwrap();
        assert_eq!(
            s,
            Scale::Log {
                lo: 1.0,
                hi: 1000.0
            }
        );
        assert!((s.position(10.0) - 1.0 / 3.0).abs() < 1e-12);
        assert_eq!(s.colour(1000.0), VIRIDIS[255]);
        assert_eq!(s.colour(0.5), VIRIDIS[0]);
        let l = Scale::Linear { lo: 0.0, hi: 500.0 };
        assert_eq!(l.colour(250.0), VIRIDIS[128]);
        assert_eq!(l.ticks(), vec![0.0, 100.0, 200.0, 300.0, 400.0, 500.0]);
        assert_eq!(label(1000.0), "1000");
        assert_eq!(label(0.125), "0.125");
        assert_eq!(label(2.5), "2.5");
        assert_eq!(label(2e6), "2e6");
        assert_eq!(label(1e-3), "1e-3");
    }

    /// Viridis rises in lightness from its first entry to its last (what makes a level read
    /// as brighter): the relative luminance of the decoded sRGB never falls.
    #[test]
    fn viridis_lightness_rises() {
        let lin = |c: u8| {
            let v = c as f64 / 255.0;
            if v <= 0.04045 {
                v / 12.92
            } else {
                ((v + 0.055) / 1.055).powf(2.4)
            }
        };
        let y = |c: [u8; 3]| 0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2]);
        for i in 1..256 {
            assert!(y(VIRIDIS[i]) >= y(VIRIDIS[i - 1]) - 1e-3, "{i}");
        }
        assert!(y(VIRIDIS[255]) > 10.0 * y(VIRIDIS[0]));
    }

    #[test]
    fn legend_bar_runs_from_first_to_last_colour() {
        let v = vec![1.0f32; 16 * 16];
        let (img, w, h) = image(&v, 16, 16, Scale::Linear { lo: 0.0, hi: 2.0 }, "cd/m²");
        assert_eq!((w, h), (16 + LEGEND_WIDTH, 220));
        assert_eq!(img[0], VIRIDIS[128]);
        let x = 16 + 15;
        assert_eq!(img[(h - 14) * w + x], VIRIDIS[0]);
        assert_eq!(img[(10 + 14 + 14) * w + x], VIRIDIS[255]);
        // the title was drawn
        assert!(img[10 * w..30 * w].contains(&[235, 235, 235]));
    }
}
