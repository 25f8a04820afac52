//! Spectral samples carried along a path: `N` wavelengths and the values at them.
//!
//! Hero-wavelength sampling (Wilkie et al. 2014, "Hero Wavelength Spectral Sampling"): a path
//! carries `N` wavelengths at once, `N = 4` by default. Values are `[f32; N]`, so the hot loop
//! does no allocation and the compiler can vectorise.

use std::ops::{Add, AddAssign, Div, DivAssign, Index, IndexMut, Mul, MulAssign, Sub, SubAssign};

/// Number of wavelengths per path unless a caller picks another `N`.
pub const N_WAVELENGTHS: usize = 4;

/// The wavelengths a path carries, in nm, and the pdf each was drawn with, in nm⁻¹.
///
/// Index 0 is the hero wavelength. A pdf of 0 marks a terminated secondary wavelength, whose
/// contribution the film must drop (see [`SampledWavelengths::terminate_secondary`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledWavelengths<const N: usize = N_WAVELENGTHS> {
    /// Wavelengths in nm.
    pub lambda: [f32; N],
    /// Sampling density of each wavelength, in nm⁻¹ (0 when terminated).
    pub pdf: [f32; N],
}

impl<const N: usize> SampledWavelengths<N> {
    /// Hero wavelength in nm.
    #[inline]
    pub fn hero(&self) -> f32 {
        self.lambda[0]
    }

    /// Keeps only the hero wavelength, for events whose direction depends on wavelength
    /// (refraction at a dispersive interface).
    ///
    /// The hero's pdf is divided by `N`, so that the film's estimate
    /// `(1/N) Σ_j f(λ_j) / p(λ_j)` still has the expectation of `∫ f dλ` with only the hero term
    /// left (`../shared/PHYSICS.md`, "Monte Carlo estimate"). Calling it twice is a no-op.
    pub fn terminate_secondary(&mut self) {
        if self.secondary_terminated() {
            return;
        }
        self.pdf[0] /= N as f32;
        for p in &mut self.pdf[1..] {
            *p = 0.0;
        }
    }

    /// Whether the secondary wavelengths were terminated (always true for `N = 1`).
    #[inline]
    pub fn secondary_terminated(&self) -> bool {
        self.pdf[1..].iter().all(|&p| p == 0.0)
    }

    /// The same wavelengths with the one at index `j` as the hero: both arrays rotated left by
    /// `j` (index `m` of the result is index `(m + j) mod N` of `self`).
    #[inline]
    pub fn rotated(&self, j: usize) -> Self {
        let mut r = *self;
        r.lambda.rotate_left(j % N);
        r.pdf.rotate_left(j % N);
        r
    }

    /// The pdfs as a spectrum, for dividing a sampled value by them.
    #[inline]
    pub fn pdf_spectrum(&self) -> SampledSpectrum<N> {
        SampledSpectrum(self.pdf)
    }
}

/// Values of a spectral quantity at the `N` wavelengths of a [`SampledWavelengths`]. Its unit is
/// the unit of the quantity it carries (W·m⁻²·sr⁻¹·nm⁻¹ for radiance, 1 for a throughput).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledSpectrum<const N: usize = N_WAVELENGTHS>(pub [f32; N]);

impl<const N: usize> Default for SampledSpectrum<N> {
    fn default() -> Self {
        Self([0.0; N])
    }
}

impl<const N: usize> SampledSpectrum<N> {
    #[inline]
    pub const fn splat(v: f32) -> Self {
        Self([v; N])
    }
    #[inline]
    pub fn zero() -> Self {
        Self([0.0; N])
    }
    #[inline]
    pub fn map(self, f: impl Fn(f32) -> f32) -> Self {
        Self(self.0.map(f))
    }
    #[inline]
    pub fn is_zero(&self) -> bool {
        self.0.iter().all(|&v| v == 0.0)
    }
    #[inline]
    pub fn max_component(&self) -> f32 {
        self.0.iter().copied().fold(f32::NEG_INFINITY, f32::max)
    }
    #[inline]
    pub fn min_component(&self) -> f32 {
        self.0.iter().copied().fold(f32::INFINITY, f32::min)
    }
    #[inline]
    pub fn average(&self) -> f32 {
        self.0.iter().sum::<f32>() / N as f32
    }
    /// Whether every value is finite (no NaN, no ±∞).
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|v| v.is_finite())
    }
    /// Element-wise `self / d`, giving 0 where `d` is 0 (a terminated wavelength's pdf).
    #[inline]
    pub fn safe_div(self, d: Self) -> Self {
        let mut r = self.0;
        for (r, d) in r.iter_mut().zip(d.0) {
            *r = if d != 0.0 { *r / d } else { 0.0 };
        }
        Self(r)
    }
}

impl<const N: usize> Index<usize> for SampledSpectrum<N> {
    type Output = f32;
    #[inline]
    fn index(&self, i: usize) -> &f32 {
        &self.0[i]
    }
}
impl<const N: usize> IndexMut<usize> for SampledSpectrum<N> {
    #[inline]
    fn index_mut(&mut self, i: usize) -> &mut f32 {
        &mut self.0[i]
    }
}

macro_rules! elementwise {
    ($Tr:ident, $f:ident, $TrA:ident, $fa:ident, $op:tt) => {
        impl<const N: usize> $Tr for SampledSpectrum<N> {
            type Output = Self;
            #[inline]
            fn $f(mut self, o: Self) -> Self {
                for i in 0..N {
                    $TrA::$fa(&mut self.0[i], o.0[i]);
                }
                self
            }
        }
        impl<const N: usize> $Tr<f32> for SampledSpectrum<N> {
            type Output = Self;
            #[inline]
            fn $f(mut self, o: f32) -> Self {
                for v in &mut self.0 {
                    $TrA::$fa(v, o);
                }
                self
            }
        }
        impl<const N: usize> $TrA for SampledSpectrum<N> {
            #[inline]
            fn $fa(&mut self, o: Self) {
                *self = *self $op o;
            }
        }
        impl<const N: usize> $TrA<f32> for SampledSpectrum<N> {
            #[inline]
            fn $fa(&mut self, o: f32) {
                *self = *self $op o;
            }
        }
    };
}
elementwise!(Add, add, AddAssign, add_assign, +);
elementwise!(Sub, sub, SubAssign, sub_assign, -);
elementwise!(Mul, mul, MulAssign, mul_assign, *);
elementwise!(Div, div, DivAssign, div_assign, /);

impl<const N: usize> Mul<SampledSpectrum<N>> for f32 {
    type Output = SampledSpectrum<N>;
    #[inline]
    fn mul(self, s: SampledSpectrum<N>) -> SampledSpectrum<N> {
        s * self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn terminate_secondary_keeps_hero_weight() {
        let mut w = SampledWavelengths::<4> {
            lambda: [500.0, 600.0, 700.0, 400.0],
            pdf: [0.01; 4],
        };
        assert!(!w.secondary_terminated());
        w.terminate_secondary();
        assert_eq!(w.pdf, [0.0025, 0.0, 0.0, 0.0]);
        w.terminate_secondary();
        assert_eq!(w.pdf[0], 0.0025);
    }

    #[test]
    fn safe_div_drops_zero_pdf() {
        let s = SampledSpectrum([1.0, 2.0, 3.0, 4.0]);
        let d = SampledSpectrum([2.0, 0.0, 1.0, 0.0]);
        assert_eq!(s.safe_div(d).0, [0.5, 0.0, 3.0, 0.0]);
        assert_eq!((s * 2.0 + s).0, [3.0, 6.0, 9.0, 12.0]);
    }
}
