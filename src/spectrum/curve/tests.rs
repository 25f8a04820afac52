//! Tests of `curve`.

use super::*;

#[test]
fn piecewise_interpolates_and_is_zero_outside() {
    let t = PiecewiseLinear::new(vec![400.0, 500.0, 600.0], vec![0.0, 1.0, 3.0]).unwrap();
    assert_eq!(t.eval(450.0), 0.5);
    assert_eq!(t.eval(550.0), 2.0);
    assert_eq!(t.eval(600.0), 3.0);
    assert_eq!(t.eval(399.9), 0.0);
    assert_eq!(t.eval(f32::NAN), 0.0);
    let nu = PiecewiseLinear::new(vec![400.0, 410.0, 600.0], vec![0.0, 1.0, 20.0]).unwrap();
    assert!((nu.eval(505.0) - 10.5).abs() < 1e-5);
}

#[test]
fn non_uniform_lookup_matches_a_binary_search() {
    // irregular spacing, crowded in places (gaps from 0.01 to 40 nm), knots hit exactly
    let mut lambda = vec![360.0f32];
    let mut k = 1u32;
    while *lambda.last().unwrap() < 830.0 {
        k = k.wrapping_mul(1_103_515_245).wrapping_add(12345);
        let gap = [0.01, 0.5, 5.0, 40.0][(k >> 16) as usize % 4];
        lambda.push(lambda.last().unwrap() + gap);
    }
    let value: Vec<f32> = (0..lambda.len()).map(|i| (i as f32 * 0.37).sin()).collect();
    let t = PiecewiseLinear::new(lambda.clone(), value.clone()).unwrap();
    assert!(t.uniform_step().is_none());
    let binary = |x: f32| {
        let n = lambda.len();
        if !(x >= lambda[0] && x <= lambda[n - 1]) {
            return 0.0;
        }
        let i = lambda
            .partition_point(|&l| l <= x)
            .saturating_sub(1)
            .min(n - 2);
        let f = ((x - lambda[i]) / (lambda[i + 1] - lambda[i])).clamp(0.0, 1.0);
        value[i] + f * (value[i + 1] - value[i])
    };
    let probes = lambda
        .iter()
        .copied()
        .chain((0..20_000).map(|j| 350.0 + j as f32 * 0.0249));
    for x in probes {
        assert_eq!(t.eval(x), binary(x), "λ = {x}");
    }
}

/// A table sampled at 5 nm with a first sample 20 nm before the rest (as measured
/// reflectances are given) is evaluated on the 5 nm grid: the same function as the f64
/// interpolation of its samples, within rounding, and its samples exactly.
#[test]
fn tables_on_a_grid_are_evaluated_on_the_grid() {
    let mut lambda = vec![360.0f32];
    lambda.extend((0..71).map(|k| 380.0 + 5.0 * k as f32));
    let value: Vec<f32> = (0..lambda.len())
        .map(|i| 0.05 + 0.9 * (0.5 + 0.5 * (i as f32 * 0.41).sin()))
        .collect();
    let t = PiecewiseLinear::new(lambda.clone(), value.clone()).unwrap();
    assert_eq!(t.uniform_step(), Some(5.0));
    assert_eq!(t.grid.len(), 75);
    assert_eq!((t.wavelengths(), t.values()), (&lambda[..], &value[..]));
    let exact = |x: f64| {
        let i = lambda
            .partition_point(|&l| l as f64 <= x)
            .clamp(1, lambda.len() - 1)
            - 1;
        let (l0, l1) = (lambda[i] as f64, lambda[i + 1] as f64);
        let (v0, v1) = (value[i] as f64, value[i + 1] as f64);
        v0 + (x - l0) / (l1 - l0) * (v1 - v0)
    };
    for (l, v) in lambda.iter().zip(&value) {
        assert_eq!(t.eval(*l), *v, "λ = {l}");
    }
    // The uniform lookup finds its place x = (λ − λ₀)/step (up to 74 grid cells) to a few
    // ulp of x, so it may be off by 4·74·ε cells, times the largest change of value per
    // cell, plus the rounding of the interpolation itself.
    let max_change = t
        .grid
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f32::max);
    let bound = (4.0 * 74.0 * max_change + 4.0) as f64 * f32::EPSILON as f64;
    for j in 0..=37_000 {
        let x = 360.0 + j as f32 * 0.01;
        let err = (t.eval(x) as f64 - exact(x as f64)).abs();
        assert!(err <= bound, "λ = {x}: {err:e} > {bound:e}");
    }
    assert_eq!(t.eval(359.99), 0.0);
    assert_eq!(t.eval(735.01), 0.0);
    // scaled tables scale the grid too
    assert_eq!(t.scaled(2.0).eval(382.5), 2.0 * t.eval(382.5));
    // samples so close that 1/step overflows keep the guided lookup, uniform or not
    let sub = f32::from_bits; // subnormal wavelengths, 1.4·10⁻⁴⁵ nm apart
    for lambda in [vec![0.0, sub(1), sub(2)], vec![0.0, sub(1), sub(3)]] {
        let tiny = PiecewiseLinear::new(lambda, vec![1.0, 2.0, 3.0]).unwrap();
        assert!(tiny.uniform_step().is_none());
        assert_eq!(tiny.eval(sub(1)), 2.0);
    }
    // spans beyond f32 keep the guided lookup (their step or position would not be finite)
    let wide = PiecewiseLinear::new(vec![-3e38, 0.0, 3e38], vec![1.0, 2.0, 3.0]).unwrap();
    assert!(wide.uniform_step().is_none());
    assert_eq!(wide.eval(3e38), 3.0);
    let wider = PiecewiseLinear::new(vec![-3e38, 3e38], vec![1.0, 3.0]).unwrap();
    assert!(wider.uniform_step().is_none());
    // samples near a grid but not on it keep the guided lookup, and their kinks
    let near = PiecewiseLinear::new(vec![400.0, 405.002, 410.0], vec![0.0, 1.0, 0.0]).unwrap();
    assert!(near.uniform_step().is_none());
    assert_eq!(near.eval(405.002), 1.0);
    // samples off any grid of their smallest spacing keep the guided lookup
    let off = PiecewiseLinear::new(vec![400.0, 403.3, 410.0], vec![1.0, 2.0, 0.0]).unwrap();
    assert!(off.uniform_step().is_none());
    assert!((off.eval(403.3) - 2.0).abs() < 1e-6);
}

#[test]
fn piecewise_rejects_bad_tables() {
    assert!(PiecewiseLinear::new(vec![400.0], vec![1.0]).is_err());
    assert!(PiecewiseLinear::new(vec![400.0, 400.0], vec![1.0, 1.0]).is_err());
    assert!(PiecewiseLinear::new(vec![400.0, 500.0], vec![1.0, f32::NAN]).is_err());
    assert!(PiecewiseLinear::new(vec![400.0, 500.0], vec![1.0]).is_err());
}

#[test]
fn integrate_is_exact_for_tables_with_jumps() {
    let s = Spectrum::Constant(2.0);
    assert!((s.integrate(360.0, 830.0, 1.0) - 940.0).abs() < 1e-6);
    // zero outside 500–600 nm, linear from 1 to 3 inside: exactly 200 nm
    let t = Spectrum::Piecewise(Arc::new(
        PiecewiseLinear::new(vec![500.0, 600.0], vec![1.0, 3.0]).unwrap(),
    ));
    assert!((t.integrate(360.0, 830.0, 0.25) - 200.0).abs() < 1e-4);
    assert!((t.integrate(550.0, 830.0, 7.0) - 125.0).abs() < 1e-4);
    // times a linear weight: ∫_500^600 (1 + (λ−500)/50) λ dλ
    let exact = {
        let f = |l: f64| l * l / 2.0 + (l * l * l / 3.0 - 500.0 * l * l / 2.0) / 50.0;
        f(600.0) - f(500.0)
    };
    assert!((t.integrate_weighted(360.0, 830.0, 1.0, |l| l as f64) / exact - 1.0).abs() < 1e-6);
}
