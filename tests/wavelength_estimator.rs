//! The hero-wavelength estimator of ∫ S(λ) ȳ(λ) dλ is unbiased: the mean of many independent
//! estimates lies within 4 standard errors of the exact integral.

mod support;

use spectrace::colour::cie::cmf;
use spectrace::spectrum::{Spectrum, WavelengthRange, WavelengthSampler};
use support::{Rng, curve};

/// Exact ∫ S ȳ dλ over 360–830 nm for the piecewise-linear S and ȳ the estimator evaluates:
/// their product is quadratic between consecutive breakpoints, and every breakpoint of both
/// (S at 5 nm or coarser, ȳ at 1 nm) lies on the 1 nm grid, so Simpson's rule on each 1 nm
/// interval is exact up to rounding.
fn exact(s: &Spectrum) -> f64 {
    let f = |l: f64| s.eval(l as f32) as f64 * cmf().y_bar(l as f32) as f64;
    (360..830)
        .map(|a| {
            let a = a as f64;
            (f(a) + 4.0 * f(a + 0.5) + f(a + 1.0)) / 6.0
        })
        .sum()
}

/// One estimate from `N` hero wavelengths: (1/N) Σ_j S(λ_j) ȳ(λ_j) / p(λ_j).
fn estimate<const N: usize>(
    s: &Spectrum,
    sampler: &WavelengthSampler,
    u: f32,
    u_hero: f32,
    terminate: bool,
) -> f64 {
    let mut w = sampler.sample::<N>(u, u_hero);
    if terminate {
        w.terminate_secondary();
    }
    let mut acc = 0.0;
    for j in 0..N {
        if w.pdf[j] > 0.0 {
            acc += (s.eval(w.lambda[j]) * cmf().y_bar(w.lambda[j]) / w.pdf[j]) as f64;
        }
    }
    acc / N as f64
}

fn check_unbiased(
    name: &str,
    s: &Spectrum,
    sampler: &WavelengthSampler,
    terminate: bool,
    seed: u64,
) {
    let truth = exact(s);
    let mut rng = Rng::new(seed);
    let runs = 200_000;
    let (mut sum, mut sum2) = (0.0, 0.0);
    for _ in 0..runs {
        let e = estimate::<4>(s, sampler, rng.uniform(), rng.uniform(), terminate);
        sum += e;
        sum2 += e * e;
    }
    let mean = sum / runs as f64;
    let var = (sum2 / runs as f64 - mean * mean).max(0.0);
    let se = (var / runs as f64).sqrt();
    let z = (mean - truth) / se;
    println!("{name}: mean {mean:.6} truth {truth:.6} se {se:.2e} z {z:.2}");
    assert!(
        se > 0.0 && se < 0.01 * truth,
        "{name}: standard error {se} is implausible"
    );
    assert!(
        z.abs() < 4.0,
        "{name}: mean {mean} is {z:.2} standard errors from {truth}"
    );
}

#[test]
fn hero_estimator_is_unbiased_for_smooth_and_spiky_spectra() {
    let visible = WavelengthSampler::visible(WavelengthRange::default());
    let uniform = WavelengthSampler::uniform(WavelengthRange::default());
    let smooth = curve("cie-d65");
    let spiky = curve("cie-f11");
    check_unbiased("D65, visible pdf", &smooth, &visible, false, 1);
    check_unbiased("F11, visible pdf", &spiky, &visible, false, 2);
    check_unbiased("F11, uniform pdf", &spiky, &uniform, false, 3);
    check_unbiased("F11, terminated secondaries", &spiky, &visible, true, 4);
    let bb = Spectrum::Blackbody(spectrace::spectrum::blackbody::Blackbody::normalized(
        3000.0,
    ));
    check_unbiased("blackbody 3000 K", &bb, &visible, false, 5);
}

#[test]
fn wide_sensor_range_is_unbiased_too() {
    // 300–1100 nm: ȳ is zero outside 360–830 nm, so the integral is unchanged.
    let sampler = WavelengthSampler::visible(WavelengthRange::new(300.0, 1100.0).unwrap());
    check_unbiased("F11, 300-1100 nm", &curve("cie-f11"), &sampler, false, 6);
}
