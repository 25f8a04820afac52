use super::*;

/// A straight B-spline (collinear, evenly spaced points) is a cylinder of its radius
/// between c(0) and c(1) of each segment, open at the curve's ends.
#[test]
fn straight_curve_is_a_capsule() {
    let r = 0.25;
    let pts: Vec<(Vec3, f32)> = (0..6).map(|k| (Vec3::new(k as f32, 0.0, 0.0), r)).collect();
    let c = BSplineCurve::new(&[pts]).unwrap();
    assert_eq!(c.segment_count(), 3);
    let first = |o: Vec3, d: Vec3| {
        let ray = Ray::new(o, d.normalize());
        (0..c.segment_count())
            .filter_map(|i| c.intersect(i, &ray).map(|h| (i, h)))
            .min_by(|a, b| a.1.0.total_cmp(&b.1.0))
    };
    // the centre line runs from c(0) of segment 0 = x 1 to c(1) of segment 2 = x 4
    let (i, (t, s)) = first(Vec3::new(2.3, 0.0, 5.0), -Vec3::Z).unwrap();
    assert!((t - (5.0 - r)).abs() < 1e-4, "{t}");
    let x = c.eval(i, s).c.x;
    assert!((x - 2.3).abs() < 1e-4, "{x}");
    // along the axis into the open end: only the inside, culled; just past the end: nothing
    assert!(first(Vec3::new(-5.0, 0.0, 0.0), Vec3::X).is_none());
    assert!(first(Vec3::new(0.95, 0.0, 5.0), -Vec3::Z).is_none());
    assert!(first(Vec3::new(1.05, 0.0, 5.0), -Vec3::Z).is_some());
    // a grazing miss just outside the radius, and a ray from inside: nothing
    assert!(first(Vec3::new(2.0, r * 1.001, 5.0), -Vec3::Z).is_none());
    assert!(first(Vec3::new(2.0, 0.0, 0.0), Vec3::Z).is_none());
    // uv: v over the three segments, the normal outward
    let probe = Ray::new(Vec3::new(2.5, 0.0, 5.0), Vec3::NEG_Z);
    let it = c.interaction(1, Vec3::new(2.5, 0.0, r), 0.5, &probe);
    assert!((it.uv.y - 0.5).abs() < 1e-6 && (it.n_geom - Vec3::Z).length() < 1e-5);
}

/// On a bent curve, every hit lies at distance r(s) from c(s) with q ⟂ c' (the sweep's
/// envelope), for rays from many directions.
#[test]
fn hits_lie_on_the_envelope() {
    let pts = vec![
        (Vec3::new(-1.0, 0.0, -1.0), 0.1),
        (Vec3::new(-0.5, 0.0, 1.0), 0.1),
        (Vec3::new(-0.25, 0.0, -1.0), 0.1),
        (Vec3::new(0.0, 0.0, 1.0), 0.1),
        (Vec3::new(0.25, 0.0, -1.0), 0.1),
    ];
    let c = BSplineCurve::new(&[pts]).unwrap();
    let mut hits = 0;
    for k in 0..400 {
        let x = -0.6 + 1.2 * (k as f32 + 0.5) / 400.0;
        let ray = Ray::new(Vec3::new(x, -3.0, 0.13 * (k % 7) as f32 - 0.4), Vec3::Y);
        for i in 0..c.segment_count() {
            if let Some((t, s)) = c.intersect(i, &ray) {
                let e = c.eval(i, s);
                let q = ray.at(t) - e.c;
                assert!((q.length() - e.r).abs() < 1e-4, "{} vs {}", q.length(), e.r);
                assert!(q.normalize().dot(e.dc.normalize()).abs() < 1e-3);
                hits += 1;
            }
        }
    }
    assert!(hits > 50, "{hits}");
}

/// With a varying radius, a hit's s is the centre line's closest point ((p − c)·c' = 0) and
/// its normal is the gradient of |p − c(s*(p))|² − r(s*(p))² (Mitsuba's), checked by finite
/// differences of that function.
#[test]
fn varying_radius_normal_is_mitsubas() {
    let radii = [0.06, 0.10, 0.14, 0.10, 0.08];
    let xs = [-1.0f32, -0.6, -0.3, 0.0, 0.3];
    let zs = [-0.6f32, 0.6, -0.6, 0.6, -0.6];
    let pts: Vec<(Vec3, f32)> = (0..5)
        .map(|k| (Vec3::new(xs[k], 0.0, zs[k]), radii[k]))
        .collect();
    let c = BSplineCurve::new(&[pts]).unwrap();
    let field = |i: usize, p: Vec3, s0: f32| -> Option<f32> {
        let s = c.closest(i, p, s0)?;
        let e = c.eval(i, s);
        Some((p - e.c).length_squared() - e.r * e.r)
    };
    let mut checked = 0;
    for k in 0..60 {
        let x = -0.55 + 0.7 * (k as f32 + 0.5) / 60.0;
        let ray = Ray::new(Vec3::new(x, -3.0, 0.05), Vec3::Y);
        for i in 0..c.segment_count() {
            let Some((t, s)) = c.intersect(i, &ray) else {
                continue;
            };
            let p = ray.at(t);
            let e = c.eval(i, s);
            assert!(
                (p - e.c).dot(e.dc).abs() < 1e-4 * e.dc.length(),
                "not the closest point"
            );
            let h = 1e-3;
            let g = Vec3::new(
                field(i, p + Vec3::X * h, s).unwrap() - field(i, p - Vec3::X * h, s).unwrap(),
                field(i, p + Vec3::Y * h, s).unwrap() - field(i, p - Vec3::Y * h, s).unwrap(),
                field(i, p + Vec3::Z * h, s).unwrap() - field(i, p - Vec3::Z * h, s).unwrap(),
            )
            .normalize();
            let n = c.interaction(i, p, s, &ray).n_geom;
            assert!(n.dot(g) > 0.9999, "normal {n} vs gradient {g}");
            checked += 1;
        }
    }
    assert!(checked > 10, "{checked}");
}

#[test]
fn too_few_points_is_an_error() {
    let pts: Vec<_> = (0..3).map(|k| (Vec3::X * k as f32, 0.1)).collect();
    let e = BSplineCurve::new(&[pts]).unwrap_err().to_string();
    assert!(e.contains("four or more"), "{e}");
}

/// A pbrt-v4 ribbon along x twisting a quarter turn, normal +z at its start to +y at its end:
/// seen along −z its width is r·|n·d̂| = r·cos(πs/2), so at s = 1/3 it is hit within
/// r·cos 30° of the centre line and not beyond; its normal there is the slerp, (0, ½, √3/2).
#[test]
fn pbrt_ribbon_turns_with_its_normals() {
    let r = 0.2;
    let pts: Vec<(Vec3, f32)> = (0..4).map(|k| (Vec3::new(k as f32, 0.0, 0.0), r)).collect();
    let c = BSplineCurve::new(&[pts])
        .unwrap()
        .with_ribbon_normals(vec![[Vec3::Z, Vec3::Y * 3.0]])
        .unwrap();
    // c(s) = 1 + s along x for this segment
    let x = 1.0 + 1.0 / 3.0;
    let w = r * (std::f32::consts::FRAC_PI_6).cos();
    let hit = |y: f32| c.intersect(0, &Ray::new(Vec3::new(x, y, 5.0), Vec3::NEG_Z));
    assert!(hit(0.98 * w).is_some() && hit(1.02 * w).is_none());
    let ray = Ray::new(Vec3::new(x, 0.0, 5.0), Vec3::NEG_Z);
    let (t, s) = hit(0.0).unwrap();
    assert!(
        (t - 5.0).abs() < 1e-4 && (s - 1.0 / 3.0).abs() < 1e-4,
        "{t} {s}"
    );
    let e = c.eval(0, s);
    let it = c.pbrt_interaction(0, &e, s, &ray, PbrtCurve::Ribbon);
    let want = Vec3::new(0.0, 0.5, 0.75f32.sqrt());
    assert!((it.n_geom - want).length() < 1e-4, "{}", it.n_geom);
    // a count other than the segments' is an error
    let pts: Vec<(Vec3, f32)> = (0..5).map(|k| (Vec3::new(k as f32, 0.0, 0.0), r)).collect();
    let two = BSplineCurve::new(&[pts]).unwrap();
    assert!(two.with_ribbon_normals(vec![[Vec3::Z, Vec3::Y]]).is_err());
}

/// A straight segment 5 mm wide (radius 2.5 mm) from (0.4, 3, 0) to (0.5, 6, 0), and whether a
/// ray from 30 m away through its centre line's point at s, offset across it by `off` (m),
/// hits it.
fn thin_far_curve(pbrt: bool) -> (f32, impl Fn(f32, f32) -> bool) {
    let r = 0.0025;
    let pts: Vec<(Vec3, f32)> = (0..4)
        .map(|k| (Vec3::new(0.3 + 0.1 * k as f32, 3.0 * k as f32, 0.0), r))
        .collect();
    let c = BSplineCurve::new(&[pts]).unwrap();
    let c = if pbrt {
        c.with_pbrt_shading(PbrtCurve::Flat)
    } else {
        c
    };
    let across = Vec3::new(0.1, 3.0, 0.0).normalize().cross(Vec3::Z);
    let hit = move |s: f32, off: f32| {
        let at = Vec3::new(0.4 + 0.1 * s, 3.0 + 3.0 * s, 0.0) + across * off;
        let o = Vec3::new(0.0, 4.5, 30.0);
        c.intersect(0, &Ray::new(o, (at - o).normalize())).is_some()
    };
    (r, hit)
}

/// A pbrt-v4 curve 5 mm wide seen from 30 m: rays passing within 0.98 of its half width of
/// the centre line hit it and rays at 1.02 miss, along the segment (a capsule prefilter in
/// squared f32 distances lost such hits to rounding).
#[test]
fn thin_far_pbrt_curve_keeps_its_width() {
    let (r, hit) = thin_far_curve(true);
    for s in (1..40).map(|k| k as f32 / 40.0) {
        assert!(
            hit(s, 0.98 * r) && hit(s, -0.98 * r),
            "s {s}: missed inside"
        );
        assert!(
            !hit(s, 1.02 * r) && !hit(s, -1.02 * r),
            "s {s}: hit outside"
        );
    }
}

/// A round B-spline tube 5 mm across seen from 30 m: rays through it at up to 0.9 of its
/// radius from the axis hit it and rays at 1.05 miss (the capsule prefilter, in squared f32
/// distances, missed 80 of these 195 rays).
#[test]
fn thin_far_tube_keeps_its_width() {
    let (r, hit) = thin_far_curve(false);
    for s in (1..40).map(|k| k as f32 / 40.0) {
        for f in [0.0, 0.5, 0.9, -0.5, -0.9] {
            assert!(hit(s, f * r), "s {s}, offset {f}: missed");
        }
        assert!(
            !hit(s, 1.05 * r) && !hit(s, -1.05 * r),
            "s {s}: hit outside"
        );
    }
}
