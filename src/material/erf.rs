//! The error function and its inverse in f64, for Beckmann microfacets (Smith's Λ and the
//! visible-slope sampler in `microfacet.rs`).

/// The erfc of `x` ≥ 0 by Abramowitz & Stegun 7.1.26 (absolute error ≤ 1.5e-7), returned as
/// (t·poly(t), e^{−x²}) so that erfc(x) = product of the two without forming 1 − erf.
#[inline]
pub(super) fn erfc_parts(x: f64) -> (f64, f64) {
    let t = 1.0 / (1.0 + 0.327_591_1 * x);
    let poly = t
        * (0.254_829_592
            + t * (-0.284_496_736
                + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
    (poly, (-x * x).exp())
}

/// erf(x) from [`erfc_parts`] (absolute error ≤ 1.5·10⁻⁷), odd.
#[inline]
pub(super) fn erf(x: f64) -> f64 {
    let (p, e) = erfc_parts(x.abs());
    (1.0 - p * e).copysign(x)
}

/// erf⁻¹(x) for x in (−1, 1) (Giles 2010, "Approximating the erfinv function", GPU Computing
/// Gems: its single-precision polynomials, relative error ≈ 10⁻⁷ in the centre, a few 10⁻⁷ in
/// the tails), refined by one Newton step on [`erf`]. ±∞ at ±1.
#[inline]
pub(super) fn erfinv(x: f64) -> f64 {
    let w = -((1.0 - x) * (1.0 + x)).ln();
    let y = if w < 5.0 {
        let w = w - 2.5;
        let mut p = 2.810_226_36e-08;
        for c in [
            3.432_739_39e-07,
            -3.523_387_7e-06,
            -4.391_506_54e-06,
            0.000_218_580_87,
            -0.001_253_725_03,
            -0.004_177_681_64,
            0.246_640_727,
            1.501_409_41,
        ] {
            p = c + p * w;
        }
        p * x
    } else {
        let w = w.sqrt() - 3.0;
        let mut p = -0.000_200_214_257;
        for c in [
            0.000_100_950_558,
            0.001_349_343_22,
            -0.003_673_428_44,
            0.005_739_507_73,
            -0.007_622_461_3,
            0.009_438_870_47,
            1.001_674_06,
            2.832_976_82,
        ] {
            p = c + p * w;
        }
        p * x
    };
    if !y.is_finite() {
        return y;
    }
    // erf′(y) = 2/√π · e^{−y²}
    let d = 2.0 / std::f64::consts::PI.sqrt() * (-y * y).exp();
    if d > 1e-300 { y - (erf(y) - x) / d } else { y }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// erf matches its Maclaurin series within its stated bound, and erf⁻¹ inverts it across
    /// (−1, 1), tails included.
    #[test]
    fn erfinv_inverts_erf() {
        // erf by its Maclaurin series in f64, |x| ≤ 3 (terms fall below 10⁻¹⁷ by n = 60)
        let series = |x: f64| {
            let (mut term, mut sum) = (x, x);
            for n in 1..120 {
                term *= -x * x / n as f64;
                sum += term / (2 * n + 1) as f64;
            }
            2.0 / std::f64::consts::PI.sqrt() * sum
        };
        for k in -300..=300 {
            let y = k as f64 / 100.0;
            let e = series(y);
            assert!((erf(y) - e).abs() < 2e-7, "erf({y})");
            if e.abs() < 1.0 - 1e-12 {
                // erf's error bound, 1.5·10⁻⁷, moves the inverse by that times d erf⁻¹/dx
                let slope = std::f64::consts::PI.sqrt() / 2.0 * (y * y).exp();
                let back = erfinv(e);
                assert!(
                    (back - y).abs() < 2e-7 * slope + 1e-6,
                    "erfinv(erf({y})) = {back}"
                );
                // and it inverts this module's erf itself closely
                let x = erfinv(erf(y));
                assert!(
                    (erf(x) - erf(y)).abs() < 1e-8,
                    "erf(erfinv({})) = {}",
                    erf(y),
                    erf(x)
                );
            }
        }
    }
}
