use super::*;

fn grey(w: usize, h: usize, filter: TexFilter, wrap: Wrap) -> Bitmap {
    let v = (0..w * h).map(|i| i as f32).collect();
    Bitmap::from_grey(w, h, v, filter, wrap, UvTransform::IDENTITY).unwrap()
}

fn at(b: &Bitmap, u: f32, v: f32) -> f32 {
    let w = SampledWavelengths::<4> {
        lambda: [550.0; 4],
        pdf: [1.0; 4],
    };
    b.sample(Vec2::new(u, v), &w).0[0]
}

/// The index rules Mitsuba 3.9.1 follows (values measured in Mitsuba with a 3×1 image).
#[test]
fn nearest_wraps_as_mitsuba() {
    let m = grey(3, 1, TexFilter::Nearest, Wrap::Mirror);
    for (u, want) in [
        (1.1, 2.0),
        (1.5, 1.0),
        (1.9, 0.0),
        (2.1, 0.0),
        (-0.5, 1.0),
        (-1.1, 2.0),
    ] {
        assert_eq!(at(&m, u, 0.5), want, "mirror u = {u}");
    }
    let r = grey(3, 1, TexFilter::Nearest, Wrap::Repeat);
    assert_eq!(at(&r, -0.1, 0.5), 2.0);
    let c = grey(3, 1, TexFilter::Nearest, Wrap::Clamp);
    assert_eq!(at(&c, 7.0, 0.5), 2.0);
}

/// The gradient Mitsuba 3.9.1's `eval_1_grad` returns for a raw 3 × 2 grey image
/// [[0, 1, 4], [2, 3, 7]] (values measured in Mitsuba), with and without `to_uv`.
#[test]
fn gradient_matches_mitsuba() {
    let v = vec![0.0, 1.0, 4.0, 2.0, 3.0, 7.0];
    let b = Bitmap::from_grey(
        3,
        2,
        v.clone(),
        TexFilter::Bilinear,
        Wrap::Repeat,
        UvTransform::IDENTITY,
    )
    .unwrap();
    for (uv, want) in [
        ((0.5, 0.25), (9.0, 4.0)),
        ((0.4, 0.3), (3.0, 4.0)),
        ((0.7, 0.6), (11.1, 5.2)),
        ((0.1, 0.9), (-14.1, -4.4)),
        ((0.5, 0.5), (10.5, 4.0)),
    ] {
        let g = b.gradient(Vec2::new(uv.0, uv.1));
        assert!(
            (g - Vec2::new(want.0, want.1)).length() < 1e-4,
            "{uv:?}: {g}"
        );
    }
    let scaled = UvTransform {
        rows: [[2.0, 0.0, 0.0], [0.0, 3.0, 0.0]],
    };
    let b = Bitmap::from_grey(3, 2, v, TexFilter::Bilinear, Wrap::Repeat, scaled).unwrap();
    let g = b.gradient(Vec2::new(0.2, 0.1));
    assert!((g - Vec2::new(6.0, 12.0)).length() < 1e-4, "to_uv: {g}");
}

#[test]
fn bilinear_centres_and_edges() {
    let r = grey(3, 2, TexFilter::Bilinear, Wrap::Repeat);
    // texel centres return the texel; v = 0.25 is row 0 (top row first)
    assert_eq!(at(&r, 0.5, 0.25), 1.0);
    assert_eq!(at(&r, 0.5, 0.75), 4.0);
    // u = 0 under repeat: half of the last column and half of the first
    assert!((at(&r, 0.0, 0.25) - 1.0).abs() < 1e-6);
    // u = -0.1 (x = -0.8): 0.8 of texel 2 and 0.2 of texel 0
    assert!((at(&r, -0.1, 0.25) - 1.6).abs() < 1e-5);
    let c = grey(3, 2, TexFilter::Bilinear, Wrap::Clamp);
    assert!((at(&c, 0.0, 0.25) - 0.0).abs() < 1e-6);
    // a non-finite uv reads what uv (0, 0) reads, never NaN
    assert_eq!(at(&r, f32::NAN, 0.5), at(&r, 0.0, 0.0));
    assert_eq!(at(&r, f32::INFINITY, f32::NEG_INFINITY), at(&r, 0.0, 0.0));
}
