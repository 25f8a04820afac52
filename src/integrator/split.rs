//! Splitting a camera sample into its wavelengths where it meets dispersion.
//!
//! A path that refracts through a dispersive interface can carry only its hero wavelength: the
//! other wavelengths would leave in other directions (Wilkie et al. 2014 §4,
//! `SampledWavelengths::terminate_secondary`). A pixel seen through glass then gets one
//! wavelength per sample, and its colour is noise ("confetti"). Here such a sample is traced
//! `N` times, once with each of its wavelengths as the hero (the arrays rotated,
//! [`SampledWavelengths::rotated`]), from the same sampler streams, and the `N` estimates are
//! averaged. Only samples whose first dispersive hit the camera sees through delta lobes
//! (the glass itself, or in a mirror) split: there the colour noise shows; where the path
//! reaches glass after a diffuse or glossy bounce, its colour is averaged with many others'
//! and a split would cost more than it saves.
//!
//! # Why the average is unbiased
//!
//! The hero's stratum is chosen by a uniform random number independent of everything else
//! the path samples (`WavelengthSampler::sample`). Rotating the set by `j` gives the estimator
//! that would have followed had that number picked stratum `k + j mod N`, so each rotation has
//! the same distribution as the original estimator, and so has their average. The decision to
//! split is taken after the first rotation, by whether its camera path met a dispersive
//! interface through delta lobes only; it does not depend on which wavelength is the hero,
//! because everything a path samples before its first dispersive hit is the same for every
//! hero (directions, lobe choices by sums over the wavelengths, Russian roulette by the
//! largest throughput). So conditioned on the split, every rotation still has the original's
//! distribution, and the expected estimate is unchanged. Scenes with media, whose free flights
//! are sampled by the hero's extinction, and polarised renders do not split
//! ([`super::Integrator::split_dispersion`]).
//!
//! # Where the values go
//!
//! A rotation's estimate is at its own wavelengths with its own pdfs (the hero's divided by
//! `N` when the secondaries were terminated). [`to_original`] expresses it at the sample's
//! original wavelengths with their original pdfs, so that the film's weight
//! (1/N) Σᵢ L(λᵢ)·x̄(λᵢ)/p(λᵢ) gives the same value: a terminated rotation's hero value `v`
//! becomes `N·v` at its original index, and the average over the `N` rotations divides by
//! `N` again. Each wavelength thus keeps the estimate of the path that was traced with it as
//! the hero.

use super::Integrator;
use crate::geometry::Ray;
use crate::sampler::Sampler;
use crate::scene::IntegratorKind;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// `l`, an estimate at `wj` (the sample's wavelengths `w0` rotated by `j`, possibly with its
/// secondaries terminated), as the equivalent values at `w0`'s indices and pdfs: index `i`
/// of the result is `l[m]·p₀(λᵢ)/p_j[m]` with `m = (i − j) mod N`, 0 where `p_j[m]` is 0.
#[inline]
pub fn to_original<const N: usize>(
    w0: &SampledWavelengths<N>,
    j: usize,
    wj: &SampledWavelengths<N>,
    l: &SampledSpectrum<N>,
) -> SampledSpectrum<N> {
    SampledSpectrum(std::array::from_fn(|i| {
        let m = (i + N - j % N) % N;
        if wj.pdf[m] > 0.0 {
            l.0[m] * (w0.pdf[i] / wj.pdf[m])
        } else {
            0.0
        }
    }))
}

impl Integrator<'_> {
    /// [`Integrator::radiance`], and whether the sample should split: its wavelengths were
    /// all alive at its first dispersive hit, and that hit was seen through delta lobes only
    /// (`path`), or came at all (the integrators with short paths, `whitted` and `direct`).
    fn radiance_seen<const N: usize>(
        &self,
        ray: Ray,
        w: &mut SampledWavelengths<N>,
        s: &mut Sampler,
    ) -> (SampledSpectrum<N>, bool) {
        match self.kind {
            IntegratorKind::Path | IntegratorKind::Light | IntegratorKind::Bdpt
                if self.scene.media.is_empty() =>
            {
                super::path::radiance_seen(self, ray, w, s)
            }
            _ => {
                let alive = !w.secondary_terminated();
                let l = self.radiance(ray, w, s);
                (l, alive && w.secondary_terminated())
            }
        }
    }

    /// [`Integrator::radiance`], split at dispersion when the scene asks for it (see the module
    /// doc): returns the estimate at `w`'s wavelengths, which are left unterminated when the
    /// sample was split.
    pub fn radiance_split<const N: usize>(
        &self,
        ray: Ray,
        w: &mut SampledWavelengths<N>,
        s: &mut Sampler,
    ) -> SampledSpectrum<N> {
        let (w0, s0) = (*w, self.split_dispersion.then(|| s.clone()));
        let Some(s0) = s0 else {
            return self.radiance(ray, w, s);
        };
        let (l, seen) = self.radiance_seen(ray, w, s);
        if !seen {
            return l;
        }
        let mut sum = to_original(&w0, 0, w, &l);
        for j in 1..N {
            let mut wj = w0.rotated(j);
            let lj = self.radiance(ray, &mut wj, &mut s0.clone());
            sum += to_original(&w0, j, &wj, &lj);
        }
        *w = w0;
        sum * (1.0 / N as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_terminated_rotation_lands_at_its_original_index_with_weight_n() {
        let w0 = SampledWavelengths::<4> {
            lambda: [500.0, 600.0, 700.0, 400.0],
            pdf: [0.01, 0.02, 0.03, 0.04],
        };
        let mut w2 = w0.rotated(2);
        assert_eq!(w2.lambda, [700.0, 400.0, 500.0, 600.0]);
        w2.terminate_secondary();
        let l = SampledSpectrum([3.0, 9.0, 9.0, 9.0]);
        let o = to_original(&w0, 2, &w2, &l);
        // λ = 700 nm is index 2 of w0: 3 × 0.03 / (0.03 / 4) = 12
        assert_eq!(o.0[0], 0.0);
        assert_eq!(o.0[1], 0.0);
        assert!((o.0[2] - 12.0).abs() < 1e-5, "{o:?}");
        assert_eq!(o.0[3], 0.0);
        // an unterminated rotation is the same estimate, reindexed
        let w1 = w0.rotated(1);
        let o = to_original(&w0, 1, &w1, &SampledSpectrum([1.0, 2.0, 3.0, 4.0]));
        assert_eq!(o.0, [4.0, 1.0, 2.0, 3.0]);
    }
}
