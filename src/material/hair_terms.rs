//! The one-dimensional functions of the hair model (`super::hair`): the modified Bessel
//! function I₀ of d'Eon et al.'s longitudinal lobes, exactly and as Mitsuba 3.9.1 evaluates it,
//! the logistic distribution of Chiang et al.'s azimuthal lobes, trimmed to [−π, π], the lobes'
//! selection weights, and sigmoid coefficients in nm turned into spectrace's normalised form.

use std::f32::consts::{PI, TAU};

use crate::colour::cie::cmf;
use crate::spectrum::rgb2spec::SigmoidPolynomial;
use glam::Vec3;

use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// ln I₀(x) to f32 precision: the power series Σ (x²/4)ᵏ/(k!)² up to 15 (at most 30 terms),
/// above it Hankel's asymptotic series to x⁻³ (relative error below 3·10⁻⁶ at 15).
pub(super) fn log_i0_exact(x: f32) -> f32 {
    let x = f64::from(x.abs());
    if x <= 15.0 {
        let q = 0.25 * x * x;
        let (mut sum, mut term) = (1.0f64, 1.0f64);
        for k in 1..=60 {
            term *= q / f64::from(k * k);
            sum += term;
            if term < 1e-9 * sum {
                break;
            }
        }
        sum.ln() as f32
    } else {
        let r = 1.0 / x;
        let series = 1.0 + r * (1.0 / 8.0 + r * (9.0 / 128.0 + r * (225.0 / 3072.0)));
        (x - 0.5 * (std::f64::consts::TAU * x).ln() + series.ln()) as f32
    }
}

/// Mitsuba's I₀: the series Σ (x²/4)ᵏ/(k!)² cut after k = 10 (`warp::detail::i0`).
#[cfg(test)]
pub(super) fn i0_mitsuba(x: f32) -> f32 {
    i0_series(x, 11)
}

/// I₀ by the first `terms` terms of its series Σ (x²/4)ⁱ/(i!)² (Mitsuba 3.9.1 sums 11,
/// pbrt-v4's `I0` 10).
pub(super) fn i0_series(x: f32, terms: usize) -> f32 {
    let (mut result, x2) = (1.0, x * x);
    let (mut xi, mut denom) = (x2, 4.0);
    for i in 1..terms {
        result += xi / denom;
        xi *= x2;
        let factor = (i + 1) as f32;
        denom *= 4.0 * factor * factor;
    }
    result
}

/// Mitsuba's ln I₀: its series up to 12, above an asymptotic form with 1/(16x) where Hankel's
/// expansion has 1/(8x) (`warp::detail::log_i0`).
#[cfg(test)]
pub(super) fn log_i0_mitsuba(x: f32) -> f32 {
    log_i0_series(x, 11)
}

/// ln I₀ as Mitsuba and pbrt-v4 (`LogI0`) write it: the asymptotic form above 12, else the
/// logarithm of the series of `terms` terms.
pub(super) fn log_i0_series(x: f32, terms: usize) -> f32 {
    if x > 12.0 {
        x + 0.5 * ((1.0 / (TAU * x)).ln() + 1.0 / (8.0 * x))
    } else {
        i0_series(x, terms).ln()
    }
}

/// The logistic density of scale `s` at x.
pub(super) fn logistic(x: f32, s: f32) -> f32 {
    let e = (-x.abs() / s).exp();
    e / (s * (1.0 + e) * (1.0 + e))
}

pub(super) fn logistic_cdf(x: f32, s: f32) -> f32 {
    1.0 / (1.0 + (-x / s).exp())
}

/// Inverts the logistic's CDF restricted to [−π, π].
pub(super) fn trimmed_logistic_sample(u: f32, s: f32) -> f32 {
    let k = logistic_cdf(PI, s) - logistic_cdf(-PI, s);
    let x = -s * (1.0 / (u * k + logistic_cdf(-PI, s)) - 1.0).ln();
    x.clamp(-PI, PI)
}

/// The probabilities of the lobes: each A_p's luminance (the mean of ȳ·A_p over the
/// wavelengths, Mitsuba's spectral `luminance`) over their sum; by the plain mean when every
/// wavelength has ȳ = 0.
pub(super) fn lobe_weights<const N: usize>(
    a: &[SampledSpectrum<N>; 4],
    w: &SampledWavelengths<N>,
) -> [f32; 4] {
    let y = w.lambda.map(|l| cmf().y_bar(l));
    let mut lum = a.map(|a| a.0.iter().zip(&y).map(|(a, y)| a * y).sum::<f32>());
    if lum.iter().sum::<f32>() <= 0.0 {
        lum = a.map(|a| a.average());
    }
    let total: f32 = lum.iter().sum();
    lum.map(|l| l / total)
}

/// A sigmoid polynomial in normalised wavelength from coefficients for λ in nm.
pub(super) fn poly_from_nm(c: [f64; 3]) -> SigmoidPolynomial {
    let (l0, dl) = (
        f64::from(crate::colour::cie::CIE_MIN_NM),
        f64::from(crate::colour::cie::CIE_MAX_NM - crate::colour::cie::CIE_MIN_NM),
    );
    // c₀λ² + c₁λ + c₂ with λ = l₀ + Δ·x
    SigmoidPolynomial {
        c: [
            (c[0] * dl * dl) as f32,
            ((2.0 * c[0] * l0 + c[1]) * dl) as f32,
            (c[0] * l0 * l0 + c[1] * l0 + c[2]) as f32,
        ],
    }
}

/// M_p (d'Eon et al. 2011, eq. 7; rad⁻¹ over θ_o, normalised with the cos θ_o of the
/// sphere's measure): e^{−sinθᵢ sinθₒ/v}·I₀(cosθᵢ cosθₒ/v)/(2v·sinh(1/v)), in log form for
/// v < 0.1 (Jakob 2013), as Mitsuba and pbrt-v4 arrange it; I₀ by `terms` terms of its series
/// (None: exact).
pub(super) fn longitudinal(
    sin_i: f32,
    cos_i: f32,
    sin_o: f32,
    cos_o: f32,
    v: f32,
    terms: Option<usize>,
) -> f32 {
    let kappa = 1.0 / v;
    let c = cos_i * cos_o * kappa;
    let s = sin_i * sin_o * kappa;
    if let Some(n) = terms {
        if kappa > 10.0 {
            // Mitsuba and pbrt-v4 write ln 2 as 0.6931
            #[allow(clippy::approx_constant)]
            let ln2 = 0.6931;
            (-s + log_i0_series(c, n) - kappa + ln2 + (0.5 * kappa).ln()).exp()
        } else {
            (-s).exp() * i0_series(c, n) * kappa / (2.0 * kappa.sinh())
        }
    } else {
        // κ/(2 sinh κ) = κ e^{−κ}/(1 − e^{−2κ})
        let norm = kappa.ln() - kappa - (-(-2.0 * kappa).exp()).ln_1p();
        (-s + log_i0_exact(c) + norm).exp()
    }
}

/// The azimuth φ = atan2(z, x) of a direction, rad.
pub(super) fn azimuth(w: Vec3) -> f32 {
    w.z.atan2(w.x)
}

pub(super) fn finite_or_zero<const N: usize>(f: SampledSpectrum<N>) -> SampledSpectrum<N> {
    if f.is_finite() {
        f
    } else {
        SampledSpectrum::zero()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// I₀ against tabulated values (Abramowitz & Stegun, table 9.8: e^{−x}I₀(x)), both ways.
    #[test]
    fn bessel_i0_matches_tables() {
        for (x, e_i0) in [
            (1.0f32, 0.4657596f64),
            (2.0, 0.3085083),
            (5.0, 0.1835408),
            (10.0, 0.1278333),
            (20.0, 0.0897803),
            (50.0, 0.05656163),
        ] {
            let want = e_i0.ln() + f64::from(x);
            assert!(
                (f64::from(log_i0_exact(x)) - want).abs() < 2e-6 * want.max(1.0),
                "{x}"
            );
        }
        // Mitsuba's: exact at small x, 0.5 % low just above 12 and 0.7 % low at 12
        assert!((i0_mitsuba(5.0) * (-5.0f32).exp() / 0.1835408 - 1.0).abs() < 1e-5);
        let low = |x: f32| 1.0 - (log_i0_mitsuba(x) - log_i0_exact(x)).exp();
        assert!((0.004..0.008).contains(&low(12.0)), "{}", low(12.0));
        assert!((0.004..0.006).contains(&low(12.01)), "{}", low(12.01));
    }

    /// The trimmed logistic's sampler inverts its CDF: the median is 0, and a sample's CDF
    /// value (within [−π, π]) is the input.
    #[test]
    fn trimmed_logistic_inverts_its_cdf() {
        let s = 0.3;
        assert!(trimmed_logistic_sample(0.5, s).abs() < 1e-6);
        let k = logistic_cdf(PI, s) - logistic_cdf(-PI, s);
        for u in [0.1f32, 0.37, 0.8, 0.99] {
            let x = trimmed_logistic_sample(u, s);
            let back = (logistic_cdf(x, s) - logistic_cdf(-PI, s)) / k;
            assert!((back - u).abs() < 1e-5, "{u}: {back}");
        }
        // the density integrates to the CDF's span
        let n = 20000;
        let h = 2.0 * PI / n as f32;
        let total: f32 = (0..n)
            .map(|i| logistic(-PI + (i as f32 + 0.5) * h, s) * h)
            .sum();
        assert!((total - k).abs() < 1e-4, "{total} vs {k}");
    }
}
