//! Spectrum curves: functions of wavelength (nm) evaluated per sample in the render loop.

use std::sync::Arc;

use super::blackbody::Blackbody;
use super::rgb2spec::SigmoidPolynomial;
use super::sampled::{SampledSpectrum, SampledWavelengths};

/// A piecewise-linear function of wavelength, from samples (λ_i in nm, v_i), strictly increasing
/// in λ. Zero outside [λ_0, λ_last]. Uniformly spaced tables are evaluated in O(1).
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseLinear {
    lambda: Vec<f32>,
    value: Vec<f32>,
    /// (λ_0, λ_last), nm: the domain, kept apart for the render loop's range test.
    domain: (f32, f32),
    /// 1/step in nm⁻¹ for uniform tables; for others, cells of the guide table per nm.
    inv_step: f32,
    /// Uniform tables, evaluated on a grid of step (λ_last − λ_0)/(len − 1) nm from λ_0 (the
    /// λ_i are uniformly spaced, or all lie on such a grid, see [`PiecewiseLinear::new`]): the
    /// values at the grid points (the samples themselves when uniformly spaced). Empty for
    /// the others.
    grid: Vec<f32>,
    /// Non-uniform tables: `guide[c]` is the last sample i with λ_i ≤ the start of guide cell
    /// c (cells of 1/`inv_step` nm from λ_0), so a lookup starts there and walks forward a few
    /// samples instead of a binary search. Empty for uniform tables.
    guide: Vec<u32>,
}

/// Whether the O(1) lookup may serve the domain [`lo`, `hi`] with grid `step`: the span, the
/// step and 1/step finite and positive, so that its position (λ − λ_0)/step is finite and at
/// most about the grid's length for every λ of the domain (the lookup's unchecked conversion
/// relies on it). Samples closer than about 3·10⁻³⁹ nm, or a span beyond f32, are looked up
/// through the guide table instead.
fn lookup_step_ok(lo: f32, hi: f32, step: f32) -> bool {
    (hi - lo).is_finite() && step.is_finite() && step > 0.0 && (1.0 / step).is_finite()
}

/// Most grid points a table whose samples lie on a uniform grid is expanded to (see
/// [`PiecewiseLinear::new`]): 64 KiB of values.
const MAX_GRID: usize = 16_384;

/// Why a table of samples is not a valid piecewise-linear spectrum.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TableError {
    #[error("a spectrum needs at least 2 samples, got {0}")]
    TooFew(usize),
    #[error("wavelengths and values differ in length ({0} vs {1})")]
    LengthMismatch(usize, usize),
    #[error("sample {index}: wavelength {lambda} nm is not greater than the previous one")]
    NotIncreasing { index: usize, lambda: f32 },
    #[error("sample {index}: value {value} at {lambda} nm is not finite")]
    NonFinite {
        index: usize,
        lambda: f32,
        value: f32,
    },
}

impl PiecewiseLinear {
    /// Builds the table; wavelengths in nm, strictly increasing, values finite.
    pub fn new(lambda: Vec<f32>, value: Vec<f32>) -> Result<Self, TableError> {
        if lambda.len() != value.len() {
            return Err(TableError::LengthMismatch(lambda.len(), value.len()));
        }
        if lambda.len() < 2 {
            return Err(TableError::TooFew(lambda.len()));
        }
        for i in 0..lambda.len() {
            if !lambda[i].is_finite() || !value[i].is_finite() {
                return Err(TableError::NonFinite {
                    index: i,
                    lambda: lambda[i],
                    value: value[i],
                });
            }
            if i > 0 && lambda[i] <= lambda[i - 1] {
                return Err(TableError::NotIncreasing {
                    index: i,
                    lambda: lambda[i],
                });
            }
        }
        let step = (lambda[lambda.len() - 1] - lambda[0]) / (lambda.len() - 1) as f32;
        let uniform = lambda
            .iter()
            .enumerate()
            .all(|(i, &l)| (l - (lambda[0] + i as f32 * step)).abs() <= 1e-4 * step.max(1.0));
        if uniform && lookup_step_ok(lambda[0], lambda[lambda.len() - 1], step) {
            return Ok(Self {
                grid: value.clone(),
                domain: (lambda[0], lambda[lambda.len() - 1]),
                lambda,
                value,
                inv_step: 1.0 / step,
                guide: Vec::new(),
            });
        }
        let guided = {
            // four cells per sample on average: about one step of walking per lookup for
            // roughly even spacing, a few more where samples crowd
            let cells = 4 * lambda.len();
            let inv = cells as f32 / (lambda[lambda.len() - 1] - lambda[0]);
            let guide = (0..cells)
                .map(|c| {
                    let start = lambda[0] + c as f32 / inv;
                    let i = lambda.partition_point(|&l| l <= start).saturating_sub(1);
                    i.min(lambda.len() - 2) as u32
                })
                .collect();
            Self {
                domain: (lambda[0], lambda[lambda.len() - 1]),
                lambda,
                value,
                inv_step: inv,
                grid: Vec::new(),
                guide,
            }
        };
        Ok(guided.on_grid().unwrap_or(guided))
    }

    /// Tables whose samples all lie exactly on one uniform grid (λ_0 + k·step in f32 for
    /// integers k, the step the smallest spacing, at most [`MAX_GRID`] points), such as
    /// measured reflectances at 5 nm with a first sample 20 nm before the rest: the same
    /// function, its values at the grid points computed once, so that the render loop takes
    /// the O(1) lookup of uniform tables (one multiply instead of a guide table, a walk and a
    /// division). Between samples the values differ from the guided lookup's only by rounding
    /// (a few ulp). `None` otherwise.
    fn on_grid(&self) -> Option<Self> {
        let (l0, n) = (self.lambda[0] as f64, self.lambda.len());
        let d = self
            .lambda
            .windows(2)
            .map(|w| (w[1] - w[0]) as f64)
            .fold(f64::INFINITY, f64::min);
        let last = (self.lambda[n - 1] as f64 - l0) / d;
        if !(d > 0.0 && last.round() < MAX_GRID as f64) {
            return None;
        }
        let count = last.round() as usize + 1;
        if count < 2 {
            return None;
        }
        let step = (self.lambda[n - 1] - self.lambda[0]) / (count - 1) as f32;
        if !lookup_step_ok(self.lambda[0], self.lambda[n - 1], step) {
            return None;
        }
        // every sample exactly on a grid point as the lookup computes them, so that the kinks
        // of the function stay where they are
        let aligned = self.lambda.iter().all(|&l| {
            let k = ((l as f64 - l0) / d).round() as f32;
            self.lambda[0] + k * step == l
        });
        if !aligned {
            return None;
        }
        let grid = (0..count)
            .map(|k| self.eval_guided((self.lambda[0] + k as f32 * step).min(self.lambda[n - 1])))
            .collect();
        Some(Self {
            inv_step: 1.0 / step,
            grid,
            guide: Vec::new(),
            ..self.clone()
        })
    }

    pub fn wavelengths(&self) -> &[f32] {
        &self.lambda
    }
    pub fn values(&self) -> &[f32] {
        &self.value
    }
    /// The step of the grid a uniform table is evaluated on, nm (None for the others).
    #[cfg(test)]
    fn uniform_step(&self) -> Option<f32> {
        let (lo, hi) = self.domain;
        (!self.grid.is_empty()).then(|| (hi - lo) / (self.grid.len() - 1) as f32)
    }

    /// (first, last) tabulated wavelength in nm.
    pub fn domain(&self) -> (f32, f32) {
        self.domain
    }

    /// Linear interpolation at `lambda_nm`; 0 outside the tabulated domain. (Inlined: the
    /// uniform lookup is a few instructions; the guided one is out of line.)
    #[inline(always)]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        let (lo, hi) = self.domain;
        if !(lambda_nm >= lo && lambda_nm <= hi) {
            return 0.0;
        }
        if !self.grid.is_empty() {
            // O(1): the bin and the fraction from one multiply by the precomputed 1/step
            let g = &self.grid;
            let x = (lambda_nm - lo) * self.inv_step;
            // 0 ≤ x ≤ (λ_last − λ_0)/step·(1 + ε) ≈ g.len() − 1: λ is inside the domain (not
            // NaN), and the span and 1/step are finite and positive (`lookup_step_ok`, checked
            // wherever a table is made uniform)
            debug_assert!((0.0..=g.len() as f32).contains(&x), "{x}");
            // SAFETY: x is finite, not negative and at most about the grid's length, far below
            // 2³² (a grid that long would not fit in memory), so the truncation is defined.
            let i = (unsafe { x.to_int_unchecked::<u32>() } as usize).min(g.len() - 2);
            let t = (x - i as f32).clamp(0.0, 1.0);
            // (one bounds check for both samples; i ≤ len − 2 holds, so never 0)
            return match g.get(i..i + 2) {
                Some(&[a, b]) => a + t * (b - a),
                _ => 0.0,
            };
        }
        self.eval_guided(lambda_nm)
    }

    /// Linear interpolation between the samples around `lambda_nm` (inside the domain), found
    /// through the guide table.
    #[inline(never)]
    fn eval_guided(&self, lambda_nm: f32) -> f32 {
        let (n, lo) = (self.lambda.len(), self.lambda[0]);
        // the last sample i ≤ n − 2 with λ_i ≤ λ, as a binary search would find it
        let c = (((lambda_nm - lo) * self.inv_step) as usize).min(self.guide.len() - 1);
        let mut i = self.guide[c] as usize;
        while i + 2 < n && self.lambda[i + 1] <= lambda_nm {
            i += 1;
        }
        let (l0, l1) = (self.lambda[i], self.lambda[i + 1]);
        let t = ((lambda_nm - l0) / (l1 - l0)).clamp(0.0, 1.0);
        self.value[i] + t * (self.value[i + 1] - self.value[i])
    }

    /// The same table with every value multiplied by `k`.
    pub fn scaled(&self, k: f32) -> Self {
        Self {
            value: self.value.iter().map(|v| v * k).collect(),
            grid: self.grid.iter().map(|v| v * k).collect(),
            ..self.clone()
        }
    }

    /// Largest tabulated value.
    pub fn max_value(&self) -> f32 {
        self.value.iter().copied().fold(f32::NEG_INFINITY, f32::max)
    }
}

/// A spectral curve. Its unit is set by where it is used: a reflectance (1), an emitter's
/// spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹), a relative spectral power distribution, …
///
/// A closed enum, matched in the hot loop; tables are shared behind `Arc`.
#[derive(Clone, Debug, PartialEq)]
pub enum Spectrum {
    /// The same value at every wavelength.
    Constant(f32),
    /// A measured or tabulated curve.
    Piecewise(Arc<PiecewiseLinear>),
    /// Planck's law times a scale (see [`Blackbody`]).
    Blackbody(Blackbody),
    /// `scale · s(c₀λ² + c₁λ + c₂)` from an RGB upsampled by the Jakob–Hanika method; with
    /// `scale = 1` and an RGB in [0, 1] this is the bounded albedo variant.
    Rgb { poly: SigmoidPolynomial, scale: f32 },
    /// The unbounded RGB variant times an illuminant table: an emission spectrum whose colour is
    /// the RGB under the colour space's white (see `rgb2spec`).
    RgbIlluminant {
        poly: SigmoidPolynomial,
        scale: f32,
        illuminant: Arc<PiecewiseLinear>,
    },
}

impl Spectrum {
    /// Value at `lambda_nm` (nm).
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        match self {
            Spectrum::Constant(c) => *c,
            Spectrum::Piecewise(t) => t.eval(lambda_nm),
            Spectrum::Blackbody(b) => b.eval(lambda_nm),
            Spectrum::Rgb { poly, scale } => scale * poly.eval(lambda_nm),
            Spectrum::RgbIlluminant {
                poly,
                scale,
                illuminant,
            } => scale * poly.eval(lambda_nm) * illuminant.eval(lambda_nm),
        }
    }

    /// Values at the sampled wavelengths.
    #[inline]
    pub fn sample<const N: usize>(&self, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        // the kind chosen once for all N wavelengths (the render loop's most frequent case:
        // reflectances and emitters given as tables)
        // (A loop, not `array::map`, whose closure was compiled out of line.)
        let mut out = [0.0; N];
        match self {
            Spectrum::Constant(c) => out = [*c; N],
            Spectrum::Piecewise(t) => {
                for (o, &l) in out.iter_mut().zip(&w.lambda) {
                    *o = t.eval(l);
                }
            }
            _ => {
                for (o, &l) in out.iter_mut().zip(&w.lambda) {
                    *o = self.eval(l);
                }
            }
        }
        SampledSpectrum(out)
    }

    /// This curve multiplied by `k`.
    pub fn scaled(&self, k: f32) -> Spectrum {
        match self {
            Spectrum::Constant(c) => Spectrum::Constant(c * k),
            Spectrum::Piecewise(t) => Spectrum::Piecewise(Arc::new(t.scaled(k))),
            Spectrum::Blackbody(b) => Spectrum::Blackbody(Blackbody {
                scale: b.scale * k,
                ..*b
            }),
            Spectrum::Rgb { poly, scale } => Spectrum::Rgb {
                poly: *poly,
                scale: scale * k,
            },
            Spectrum::RgbIlluminant {
                poly,
                scale,
                illuminant,
            } => Spectrum::RgbIlluminant {
                poly: *poly,
                scale: scale * k,
                illuminant: illuminant.clone(),
            },
        }
    }

    /// The wavelengths (nm) where this curve may have a kink or a jump: a table's samples.
    fn breakpoints(&self) -> &[f32] {
        match self {
            Spectrum::Piecewise(t) => t.wavelengths(),
            Spectrum::RgbIlluminant { illuminant, .. } => illuminant.wavelengths(),
            _ => &[],
        }
    }

    /// ∫ S(λ) w(λ) dλ over [`lo_nm`, `hi_nm`], in S's unit × w's unit × nm.
    ///
    /// Two-point Gauss–Legendre on every interval between the curve's own breakpoints and the
    /// multiples of `step_nm`. It never evaluates at a breakpoint, so a table's jump to zero at
    /// its ends is integrated exactly, and it is exact whenever S·w is a cubic on each interval
    /// (a piecewise-linear table times a weight that is linear between multiples of `step_nm`,
    /// such as the 1 nm CIE functions).
    pub fn integrate_weighted(
        &self,
        lo_nm: f32,
        hi_nm: f32,
        step_nm: f32,
        w: impl Fn(f32) -> f64,
    ) -> f64 {
        if !(hi_nm > lo_nm) || !(step_nm > 0.0) {
            return 0.0;
        }
        let (lo, hi, step) = (lo_nm as f64, hi_nm as f64, step_nm as f64);
        let mut points: Vec<f64> = ((lo / step).ceil() as i64..=(hi / step).floor() as i64)
            .map(|k| k as f64 * step)
            .chain(self.breakpoints().iter().map(|&l| l as f64))
            .filter(|&l| l > lo && l < hi)
            .chain([lo, hi])
            .collect();
        points.sort_by(f64::total_cmp);
        points.dedup();
        let g = 0.5 / 3f64.sqrt();
        points
            .windows(2)
            .map(|ab| {
                let (a, b) = (ab[0], ab[1]);
                let (m, h) = (0.5 * (a + b), b - a);
                let f = |x: f64| self.eval(x as f32) as f64 * w(x as f32);
                0.5 * h * (f(m - g * h) + f(m + g * h))
            })
            .sum()
    }

    /// ∫ S(λ) dλ over [`lo_nm`, `hi_nm`] (see [`Spectrum::integrate_weighted`]).
    pub fn integrate(&self, lo_nm: f32, hi_nm: f32, step_nm: f32) -> f64 {
        self.integrate_weighted(lo_nm, hi_nm, step_nm, |_| 1.0)
    }
}

#[cfg(test)]
mod tests;
