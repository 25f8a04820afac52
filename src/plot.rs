//! Line plots as SVG text (spectra of `spectrace spectrum --plot` and `spectrace probe
//! --plot`): axes with ticks at 1, 2 or 5 × 10ⁿ steps (Heckbert, "Nice numbers for graph
//! labels", Graphics Gems 1990), each axis labelled with its quantity and unit, one polyline per
//! series. Tick labels carry the classes `xtick`/`ytick` and sit at their data positions, so a
//! reader can map the drawing back to numbers.

use std::fmt::Write;

/// One curve: a legend name and (x, y) points in data units.
pub struct Series<'a> {
    pub name: &'a str,
    pub points: Vec<(f64, f64)>,
}

const W: f64 = 720.0;
const H: f64 = 440.0;
const LEFT: f64 = 90.0;
const RIGHT: f64 = 700.0;
const TOP: f64 = 40.0;
const BOTTOM: f64 = 380.0;
const COLOURS: [&str; 4] = ["#1f4e9e", "#c0392b", "#2e8b57", "#8e44ad"];

/// Heckbert's nice number near `x` (> 0): 1, 2, 5 or 10 × 10ⁿ, rounded or not below.
fn nice(x: f64, round: bool) -> f64 {
    let e = x.log10().floor();
    let f = x / 10f64.powf(e);
    let n = if round {
        if f < 1.5 {
            1.0
        } else if f < 3.0 {
            2.0
        } else if f < 7.0 {
            5.0
        } else {
            10.0
        }
    } else if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 5.0 {
        5.0
    } else {
        10.0
    };
    n * 10f64.powf(e)
}

/// Axis range and tick step covering [lo, hi] with about five ticks.
fn axis(lo: f64, hi: f64) -> (f64, f64, f64) {
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.05 };
        (lo - pad, hi + pad)
    };
    let step = nice(nice(hi - lo, false) / 5.0, true);
    ((lo / step).floor() * step, (hi / step).ceil() * step, step)
}

/// Formats a tick value with as many decimals as its step needs.
fn tick(v: f64, step: f64) -> String {
    let d = (-step.log10().floor()).max(0.0) as usize;
    let s = format!("{v:.d$}");
    if s == "-0" { "0".into() } else { s }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// An SVG line plot of `series` with axis labels `x_label` and `y_label` (quantity and unit)
/// and a `title`. The y axis includes 0 when every value is ≥ 0 and the smallest is below
/// half the largest.
pub fn svg(series: &[Series<'_>], title: &str, x_label: &str, y_label: &str) -> String {
    let all = || {
        series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| p.0.is_finite() && p.1.is_finite())
    };
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in all() {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if y0 >= 0.0 && y0 < 0.5 * y1 {
        y0 = 0.0;
    }
    let (xa, xb, xs) = axis(x0, x1);
    let (ya, yb, ys) = axis(y0, y1);
    let px = |x: f64| LEFT + (x - xa) / (xb - xa) * (RIGHT - LEFT);
    let py = |y: f64| BOTTOM - (y - ya) / (yb - ya) * (BOTTOM - TOP);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="13">"#
    );
    let _ = writeln!(s, r#"<rect width="{W}" height="{H}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="22" text-anchor="middle" font-size="15">{}</text>"#,
        (LEFT + RIGHT) / 2.0,
        esc(title)
    );
    // grid and ticks
    let n = ((xb - xa) / xs).round() as usize;
    for k in 0..=n {
        let v = xa + k as f64 * xs;
        let x = px(v);
        let _ = writeln!(
            s,
            r##"<line x1="{x:.2}" y1="{TOP}" x2="{x:.2}" y2="{BOTTOM}" stroke="#e4e4e4"/>"##
        );
        let _ = writeln!(
            s,
            r#"<text class="xtick" x="{x:.3}" y="{}" text-anchor="middle">{}</text>"#,
            BOTTOM + 18.0,
            tick(v, xs)
        );
    }
    let n = ((yb - ya) / ys).round() as usize;
    for k in 0..=n {
        let v = ya + k as f64 * ys;
        let y = py(v);
        let _ = writeln!(
            s,
            r##"<line x1="{LEFT}" y1="{y:.2}" x2="{RIGHT}" y2="{y:.2}" stroke="#e4e4e4"/>"##
        );
        let _ = writeln!(
            s,
            r#"<text class="ytick" x="{}" y="{y:.3}" text-anchor="end" dominant-baseline="middle">{}</text>"#,
            LEFT - 6.0,
            tick(v, ys)
        );
    }
    let _ = writeln!(
        s,
        r#"<rect x="{LEFT}" y="{TOP}" width="{}" height="{}" fill="none" stroke="black"/>"#,
        RIGHT - LEFT,
        BOTTOM - TOP
    );
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        (LEFT + RIGHT) / 2.0,
        BOTTOM + 44.0,
        esc(x_label)
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate(22 {}) rotate(-90)" text-anchor="middle">{}</text>"#,
        (TOP + BOTTOM) / 2.0,
        esc(y_label)
    );
    for (i, ser) in series.iter().enumerate() {
        let c = COLOURS[i % COLOURS.len()];
        let pts: Vec<String> = ser
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| format!("{:.3},{:.3}", px(x), py(y)))
            .collect();
        let _ = writeln!(
            s,
            r#"<polyline class="series" fill="none" stroke="{c}" stroke-width="1.8" points="{}"><title>{}</title></polyline>"#,
            pts.join(" "),
            esc(ser.name)
        );
        if series.len() > 1 {
            let y = TOP + 16.0 + 18.0 * i as f64;
            let _ = writeln!(
                s,
                r#"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="{c}" stroke-width="2"/><text x="{}" y="{y}" dominant-baseline="middle">{}</text>"#,
                RIGHT - 120.0,
                RIGHT - 96.0,
                RIGHT - 90.0,
                esc(ser.name)
            );
        }
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_axes() {
        assert_eq!(axis(360.0, 830.0), (300.0, 900.0, 100.0));
        assert_eq!(axis(0.0, 0.93), (0.0, 1.0, 0.2));
        let (a, b, s) = axis(1.5066, 1.5302);
        // 1, 2 or 5 × 10ⁿ, four to ten steps
        assert!(a <= 1.5066 && b >= 1.5302 && s == 0.01, "{a} {b} {s}");
        assert!((4.0..=10.0).contains(&((b - a) / s).round()));
        assert_eq!(tick(0.4, 0.2), "0.4");
        assert_eq!(tick(500.0, 100.0), "500");
        assert_eq!(tick(1.505, 0.005), "1.505");
    }
}
