//! Choosing wavelengths: the film's wavelength range and the hero-wavelength sampler.

use super::sampled::SampledWavelengths;
use crate::sampling::CdfGuide;

/// The range of wavelengths a render covers, in nm. Chosen at run time; default 360–830 nm.
/// Outside 360–830 nm the CIE colour-matching functions are zero, which is valid: such light
/// counts in the band radiance `L` but not in XYZ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WavelengthRange {
    /// Shortest wavelength, nm.
    pub min_nm: f32,
    /// Longest wavelength, nm.
    pub max_nm: f32,
}

impl Default for WavelengthRange {
    fn default() -> Self {
        Self {
            min_nm: 360.0,
            max_nm: 830.0,
        }
    }
}

/// Why a wavelength range was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("wavelength range {min_nm} nm to {max_nm} nm is invalid: {why}")]
pub struct RangeError {
    pub min_nm: f32,
    pub max_nm: f32,
    pub why: &'static str,
}

impl WavelengthRange {
    /// A range `min_nm < max_nm`, both finite and positive.
    pub fn new(min_nm: f32, max_nm: f32) -> Result<Self, RangeError> {
        let err = |why| {
            Err(RangeError {
                min_nm,
                max_nm,
                why,
            })
        };
        if !(min_nm.is_finite() && max_nm.is_finite()) {
            return err("bounds must be finite");
        }
        if min_nm <= 0.0 {
            return err("the shortest wavelength must be positive");
        }
        if max_nm <= min_nm {
            return err("the longest wavelength must exceed the shortest");
        }
        Ok(Self { min_nm, max_nm })
    }
    /// Width in nm.
    pub fn width(&self) -> f32 {
        self.max_nm - self.min_nm
    }
}

/// Importance density for visible light: sech²(0.0072 nm⁻¹ · (λ − 538 nm)), a smooth fit to the
/// sum of the CIE colour-matching functions (Radziszewski et al. 2009, as used in pbrt-v4 §4.6.2),
/// plus a floor of 2% of its peak so that ultraviolet and infrared ranges are still sampled.
fn visible_importance(lambda: f64) -> f64 {
    pbrt_visible_importance(lambda) + 0.02
}

/// pbrt-v4's `VisibleWavelengthsPDF` up to its normalisation: sech²(0.0072 nm⁻¹ · (λ − 538 nm)).
fn pbrt_visible_importance(lambda: f64) -> f64 {
    let c = (0.0072 * (lambda - 538.0)).cosh();
    1.0 / (c * c)
}

/// Hero-wavelength sampler over a [`WavelengthRange`].
///
/// The density is piecewise constant on bins of at most 1 nm, tabulated from an importance
/// function at construction; sampling inverts its CDF exactly. `N` wavelengths are drawn at the
/// CDF positions `(j + u)/N`, one in each of the `N` equal-probability strata, and a second
/// number picks which stratum holds the hero (index 0); the others follow in stratum order
/// (stratified and rotated, Wilkie et al. 2014 §4). Each wavelength, the hero included, is
/// marginally distributed with [`WavelengthSampler::pdf`].
///
/// Why the offset within a stratum is `u` itself and not `frac(N·u)`: pbrt-v4's
/// `SampleVisible` draws the set `{u + j/N mod 1}`, which is the same set at offset
/// `frac(N·u)`. Multiplying by `N` discards u's leading log₂N bits, which are exactly the bits a
/// stratified or low-discrepancy sampler stratifies best: with 16 stratified values of `u` and
/// `N` = 4, the 64 wavelengths of a pixel then fall four to each of 16 strata instead of one to
/// each of 64. Using `u` as the offset keeps all 64 apart, which lowers the wavelength noise of
/// a smooth spectrum's pixel about 16-fold at 16 samples (measured in BENCHMARKS.md, issue 25).
#[derive(Clone, Debug)]
pub struct WavelengthSampler {
    range: WavelengthRange,
    bin_width: f64,
    /// Normalised CDF at bin edges, `cdf[0] = 0`, `cdf[bins] = 1`.
    cdf: Vec<f64>,
    /// Density of each bin in nm⁻¹.
    density: Vec<f32>,
    /// Guide table for inverting `cdf` in O(1).
    guide: CdfGuide,
}

impl WavelengthSampler {
    /// Importance sampling for the visible range and beyond (see `visible_importance`).
    pub fn visible(range: WavelengthRange) -> Self {
        Self::tabulate(range, visible_importance)
    }

    /// pbrt-v4's visible density (`SampleVisibleWavelengths`), sech²(0.0072 nm⁻¹·(λ − 538 nm))
    /// without [`WavelengthSampler::visible`]'s floor: for estimates that must be distributed
    /// per sample as pbrt-v4's are (its firefly clamp, [`crate::film::clamp_max_component`]).
    pub fn pbrt_visible(range: WavelengthRange) -> Self {
        Self::tabulate(range, pbrt_visible_importance)
    }

    /// Uniform density 1/(max − min).
    pub fn uniform(range: WavelengthRange) -> Self {
        Self::tabulate(range, |_| 1.0)
    }

    fn tabulate(range: WavelengthRange, f: impl Fn(f64) -> f64) -> Self {
        let (lo, hi) = (range.min_nm as f64, range.max_nm as f64);
        let bins = ((hi - lo).ceil() as usize).max(1);
        let bin_width = (hi - lo) / bins as f64;
        let weights: Vec<f64> = (0..bins)
            .map(|i| f(lo + (i as f64 + 0.5) * bin_width) * bin_width)
            .collect();
        let total: f64 = weights.iter().sum();
        let mut cdf = Vec::with_capacity(bins + 1);
        let mut acc = 0.0;
        cdf.push(0.0);
        for w in &weights {
            acc += w;
            cdf.push(acc / total);
        }
        cdf[bins] = 1.0;
        let density = weights
            .iter()
            .map(|w| (w / total / bin_width) as f32)
            .collect();
        let guide = CdfGuide::new(&cdf, bins);
        Self {
            range,
            bin_width,
            cdf,
            density,
            guide,
        }
    }

    pub fn range(&self) -> WavelengthRange {
        self.range
    }

    /// Density in nm⁻¹ of drawing `lambda_nm` (0 outside the range).
    pub fn pdf(&self, lambda_nm: f32) -> f32 {
        if !(lambda_nm >= self.range.min_nm && lambda_nm <= self.range.max_nm) {
            return 0.0;
        }
        let i = ((lambda_nm - self.range.min_nm) as f64 / self.bin_width) as usize;
        self.density[i.min(self.density.len() - 1)]
    }

    /// One wavelength in nm from a uniform number `u` in [0, 1).
    pub fn sample_one(&self, u: f32) -> f32 {
        let u = (u as f64).clamp(0.0, 1.0);
        let i = self.guide.cell(&self.cdf, u);
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let t = if c1 > c0 { (u - c0) / (c1 - c0) } else { 0.5 };
        let l = self.range.min_nm as f64 + (i as f64 + t) * self.bin_width;
        (l as f32).clamp(self.range.min_nm, self.range.max_nm)
    }

    /// `N` wavelengths: wavelength `j` at the CDF position `((h + j) mod N + u)/N`, where the
    /// hero's stratum `h = ⌊N·u_hero⌋`; `u` and `u_hero` uniform in [0, 1).
    pub fn sample<const N: usize>(&self, u: f32, u_hero: f32) -> SampledWavelengths<N> {
        let mut lambda = [0.0; N];
        let mut pdf = [0.0; N];
        let hero = ((u_hero * N as f32) as usize).min(N - 1);
        for j in 0..N {
            let stratum = (hero + j) % N;
            let uj = ((stratum as f32 + u) / N as f32).min(1.0);
            lambda[j] = self.sample_one(uj);
            pdf[j] = self.pdf(lambda[j]);
        }
        SampledWavelengths { lambda, pdf }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guide_table_finds_the_binary_search_bin() {
        for s in [
            WavelengthSampler::visible(WavelengthRange::default()),
            WavelengthSampler::visible(WavelengthRange::new(300.0, 1100.0).unwrap()),
            WavelengthSampler::uniform(WavelengthRange::new(400.5, 700.25).unwrap()),
        ] {
            let last = s.density.len() - 1;
            let mut us: Vec<f64> = (0..=100_000).map(|k| k as f64 / 100_000.0).collect();
            us.extend(s.cdf.iter().copied()); // exactly on bin edges
            for u in us {
                let want = s.cdf[1..].partition_point(|&c| c <= u).min(last);
                assert_eq!(s.guide.cell(&s.cdf, u), want, "u = {u}");
            }
        }
    }

    #[test]
    fn pdf_integrates_to_one() {
        for s in [
            WavelengthSampler::visible(WavelengthRange::default()),
            WavelengthSampler::visible(WavelengthRange::new(300.0, 1100.0).unwrap()),
            WavelengthSampler::uniform(WavelengthRange::new(400.5, 700.25).unwrap()),
        ] {
            let r = s.range();
            let n = 200_000;
            let h = r.width() as f64 / n as f64;
            let integral: f64 = (0..n)
                .map(|i| s.pdf(r.min_nm + ((i as f64 + 0.5) * h) as f32) as f64 * h)
                .sum();
            assert!((integral - 1.0).abs() < 1e-4, "{integral}");
        }
    }

    #[test]
    fn samples_stay_in_range_and_match_pdf() {
        let s = WavelengthSampler::visible(WavelengthRange::default());
        for k in 0..1000 {
            let w = s.sample::<4>(k as f32 / 1000.0, (k % 7) as f32 / 7.0);
            for j in 0..4 {
                assert!((360.0..=830.0).contains(&w.lambda[j]));
                assert_eq!(w.pdf[j], s.pdf(w.lambda[j]));
            }
        }
        assert_eq!(s.sample_one(0.0), 360.0);
        assert!(s.sample_one(0.999_999) > 829.0);
    }

    #[test]
    fn the_hero_is_distributed_as_the_pdf() {
        // the hero's wavelength over a uniform grid of (u, u_hero), binned in 10 nm, against
        // the integral of the pdf over each bin: a wrong stratum choice (say, the hero always
        // in the bluest stratum) fails by far more than the grid's discretisation
        let s = WavelengthSampler::visible(WavelengthRange::default());
        let (nu, nh) = (4000, 8);
        let mut hist = [0.0f64; 47];
        for a in 0..nu {
            for b in 0..nh {
                let w = s.sample::<4>((a as f32 + 0.5) / nu as f32, (b as f32 + 0.5) / nh as f32);
                let bin = (((w.lambda[0] - 360.0) / 10.0) as usize).min(46);
                hist[bin] += 1.0 / (nu * nh) as f64;
            }
        }
        for (i, h) in hist.iter().enumerate() {
            let lo = 360.0 + 10.0 * i as f32;
            let want: f64 = (0..100)
                .map(|k| s.pdf(lo + 0.1 * (k as f32 + 0.5)) as f64 * 0.1)
                .sum();
            assert!(
                (h - want).abs() < 2e-3 + 0.01 * want,
                "{lo} nm: {h} against {want}"
            );
        }
    }

    #[test]
    fn stratified_offsets_give_one_wavelength_per_stratum() {
        // 16 offsets, one in each 1/16 of [0, 1), give 64 wavelengths one in each 1/64 of the
        // CDF (the set {u + j/4 mod 1} would put four in each of 16)
        let s = WavelengthSampler::visible(WavelengthRange::default());
        let edges: Vec<f32> = (0..=64).map(|k| s.sample_one(k as f32 / 64.0)).collect();
        let mut count = [0u32; 64];
        for k in 0..16 {
            let u = (k as f32 + 0.3) / 16.0;
            let w = s.sample::<4>(u, 0.6);
            for l in w.lambda {
                let bin = edges[1..].partition_point(|&e| e <= l).min(63);
                count[bin] += 1;
            }
        }
        assert!(count.iter().all(|&c| c == 1), "{count:?}");
    }

    #[test]
    fn rejects_bad_ranges() {
        assert!(WavelengthRange::new(830.0, 360.0).is_err());
        assert!(WavelengthRange::new(0.0, 360.0).is_err());
        assert!(WavelengthRange::new(300.0, f32::NAN).is_err());
    }
}
