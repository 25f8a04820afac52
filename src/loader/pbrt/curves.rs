//! pbrt-v4's `curve` shape (`Curve::Create`, src/pbrt/shapes.cpp) read as spectrace's round
//! B-spline curves (`geometry/shape/bspline_curve.rs`).
//!
//! pbrt-v4 intersects a curve as a flat ribbon of width w(u) through its centre line, turned
//! to face each ray, and its `cylinder` type turns the ribbon's normal about the tangent by an
//! angle linear across the width. spectrace's B-spline curves do the same when built with
//! `BSplineCurve::with_pbrt_shading` (the ribbon test, the hit at the centre line's depth,
//! pbrt-v4's normal and error bound), so a `cylinder` curve renders as pbrt-v4's; a true tube's
//! normal would reflect π/4 ÷ 2/π = 1.23 times as much light back toward a light behind the
//! eye, and pbrt-v4 turns the normal away from the hit's side, so its cylinders are lit on the
//! side away from a light. `flat` curves (pbrt-v4's default) keep the ribbon's own normal,
//! facing the ray; `ribbon` curves are oriented by the normals `N` given at the segments'
//! ends (one more than the segments), turned between them as pbrt-v4 turns them
//! (`BSplineCurve::with_ribbon_normals`), and seen as wide as their width times |n·d̂|.
//!
//! The curve's control points: `bezier` segments (degree 3, or degree 2 raised to 3) each
//! become one uniform cubic B-spline of four points with the same centre line
//! (b₀ = 6p₀ − 7p₁ + 2p₂, b₁ = 2p₁ − p₂, b₂ = 2p₂ − p₁, b₃ = 6p₃ − 7p₂ + 2p₁); a degree-3
//! `bspline` is one already. The width runs linearly from `width0` to `width1` over the whole
//! curve, as pbrt-v4 spreads it over the segments; a B-spline reproduces a linear radius with
//! control radii r at its Greville points, one segment before and after each control's own.

use glam::{DMat4, DVec3};

use super::params::{Params, R};
use crate::geometry::shape::PbrtCurve;
use crate::loader::Loc;
use crate::loader::desc::ShapeKind;

/// A `curve`'s B-spline curves, in object space, radii scaled by the CTM's (uniform) scale,
/// of pbrt-v4's `flat` (its default), `cylinder` or `ribbon` type.
pub(super) fn curve(p: &Params, loc: Loc, ctm: &DMat4) -> R<ShapeKind> {
    let width = p.float("width", 1.0)?;
    let (w0, w1) = (p.float("width0", width)?, p.float("width1", width)?);
    let degree = p.int("degree", 3)?;
    let basis = p.string("basis")?.unwrap_or_else(|| "bezier".into());
    let kind = p.string("type")?.unwrap_or_else(|| "flat".into());
    // pbrt-v4's recursion depth for its ribbon test: the tube needs none
    let _ = p.int("splitdepth", 3)?;
    let kind = match kind.as_str() {
        "cylinder" => PbrtCurve::Cylinder,
        "flat" => PbrtCurve::Flat,
        "ribbon" => PbrtCurve::Ribbon,
        other => {
            return Err(p.err(p.loc_of("type"), format!("unknown curve type \"{other}\"")));
        }
    };
    // pbrt-v4 ignores normals on a flat or cylinder curve, with a warning
    let normals: Vec<[f64; 3]> = p
        .nums("N", &["normal", "normal3"])?
        .unwrap_or(&[])
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    if !(w0 > 0.0 && w1 > 0.0 && w0.is_finite() && w1.is_finite()) {
        return Err(p.err(loc, "a curve's widths must be positive"));
    }
    if degree != 2 && degree != 3 {
        return Err(p.err(
            p.loc_of("degree"),
            format!("a curve's degree must be 2 or 3, not {degree}"),
        ));
    }
    let pts: Vec<DVec3> = p
        .nums("P", &["point3", "point"])?
        .ok_or_else(|| p.err(loc, "a curve needs \"point3 P\""))?
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect();
    let d = degree as usize;
    let segments = match basis.as_str() {
        "bezier" if pts.len() > d && (pts.len() - 1).is_multiple_of(d) => (pts.len() - 1) / d,
        "bspline" if pts.len() > d => pts.len() - d,
        "bezier" | "bspline" => {
            return Err(p.err(
                p.loc_of("P"),
                format!(
                    "{} control points do not make a degree-{degree} {basis} curve",
                    pts.len()
                ),
            ));
        }
        other => {
            return Err(p.err(
                p.loc_of("basis"),
                format!("unknown curve basis \"{other}\""),
            ));
        }
    };
    let ribbon_normals = if kind == PbrtCurve::Ribbon {
        if normals.len() != segments + 1 {
            return Err(p.err(
                if normals.is_empty() { p.loc_of("type") } else { p.loc_of("N") },
                format!(
                    "a ribbon curve needs a normal \"N\" at each segment's ends: {} for {segments} segment(s), not {}",
                    segments + 1,
                    normals.len()
                ),
            ));
        }
        normals.windows(2).map(|w| [w[0], w[1]]).collect()
    } else {
        Vec::new()
    };
    // the radius in metres at u ∈ [0, 1] along the curve, scaled as the CTM scales lengths
    let scale = ctm.determinant().abs().cbrt();
    let radius = |u: f64| 0.5 * (w0 + (w1 - w0) * u) * scale;
    let at = |v: DVec3| v.to_array();
    if basis == "bspline" && degree == 3 {
        let n = segments as f64;
        let curve = (0..pts.len())
            .map(|i| (at(pts[i]), radius((i as f64 - 1.0) / n)))
            .collect();
        return Ok(ShapeKind::BSplinePoints {
            curves: vec![curve],
            pbrt: Some(kind),
            ribbon_normals,
        });
    }
    let curves = (0..segments)
        .map(|k| {
            let b = bezier_segment(&pts, k, d, basis == "bspline");
            let bs = [
                6.0 * b[0] - 7.0 * b[1] + 2.0 * b[2],
                2.0 * b[1] - b[2],
                2.0 * b[2] - b[1],
                6.0 * b[3] - 7.0 * b[2] + 2.0 * b[1],
            ];
            let n = segments as f64;
            (0..4)
                .map(|i| (at(bs[i]), radius((k as f64 + i as f64 - 1.0) / n)))
                .collect()
        })
        .collect();
    Ok(ShapeKind::BSplinePoints {
        curves,
        pbrt: Some(kind),
        ribbon_normals,
    })
}

/// Segment `k`'s cubic Bézier control points: a cubic Bézier's own, or a quadratic one's
/// (Bézier, or uniform B-spline when `bspline`) raised to degree 3.
fn bezier_segment(pts: &[DVec3], k: usize, degree: usize, bspline: bool) -> [DVec3; 4] {
    if degree == 3 {
        let i = 3 * k;
        return [pts[i], pts[i + 1], pts[i + 2], pts[i + 3]];
    }
    let q = if bspline {
        let (a, b, c) = (pts[k], pts[k + 1], pts[k + 2]);
        [(a + b) / 2.0, b, (b + c) / 2.0]
    } else {
        let i = 2 * k;
        [pts[i], pts[i + 1], pts[i + 2]]
    };
    [
        q[0],
        (q[0] + 2.0 * q[1]) / 3.0,
        (2.0 * q[1] + q[2]) / 3.0,
        q[2],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The B-spline of the four points made from a Bézier segment has the segment's centre
    /// line: at s = 0, ½, 1 the uniform cubic basis gives the Bézier's points there.
    #[test]
    fn bezier_to_bspline_keeps_the_centre_line() {
        let b = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, -1.0, 1.0),
            DVec3::new(4.0, 0.5, 2.0),
        ];
        let bs = [
            6.0 * b[0] - 7.0 * b[1] + 2.0 * b[2],
            2.0 * b[1] - b[2],
            2.0 * b[2] - b[1],
            6.0 * b[3] - 7.0 * b[2] + 2.0 * b[1],
        ];
        for s in [0.0f64, 0.25, 0.5, 0.9, 1.0] {
            let basis = [
                (1.0 - s).powi(3),
                3.0 * s.powi(3) - 6.0 * s * s + 4.0,
                -3.0 * s.powi(3) + 3.0 * s * s + 3.0 * s + 1.0,
                s.powi(3),
            ];
            let spline: DVec3 = (0..4).map(|i| bs[i] * basis[i] / 6.0).sum();
            let t = 1.0 - s;
            let bezier = b[0] * t.powi(3)
                + b[1] * 3.0 * t * t * s
                + b[2] * 3.0 * t * s * s
                + b[3] * s.powi(3);
            assert!(
                (spline - bezier).length() < 1e-12,
                "s {s}: {spline} vs {bezier}"
            );
        }
    }
}
