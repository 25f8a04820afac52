//! A homogeneous medium: absorption and scattering coefficients that vary with wavelength but
//! not with position, its transmittance (Beer–Lambert) and free-flight sampling with spectral
//! MIS over the path's wavelengths.
//!
//! Free flights are sampled by the hero wavelength's extinction σt(λ₀). The hero is a uniformly
//! random member of the path's wavelength set (`render::draw_wavelengths`: wavelength j sits in
//! stratum (h + j) mod N with the hero's stratum h uniform), so sampling by the hero's σt is
//! one-sample MIS over the N techniques "sample by σt(λⱼ)", and dividing by the average of
//! their densities, (1/N) Σⱼ pⱼ(t), is the balance heuristic (Veach 1997 §9.2.4; the hero
//! scheme of Wilkie et al. 2014 and the spectral MIS of Miller, Georgiev and Jarosz 2019, §5).
//! Terminated secondary wavelengths (pdf 0) take no part in the average.

use super::PhaseFunction;
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

/// A homogeneous medium. Coefficients are per metre.
#[derive(Clone, Debug)]
pub struct Homogeneous {
    /// Absorption coefficient σa(λ), m⁻¹ (λ in nm).
    pub sigma_a: Spectrum,
    /// Scattering coefficient σs(λ), m⁻¹.
    pub sigma_s: Spectrum,
    /// The phase function of its scattering.
    pub phase: PhaseFunction,
}

/// The outcome of a sampled free flight along a segment of length `t_max`.
#[derive(Clone, Copy, Debug)]
pub enum Flight<const N: usize> {
    /// A scattering event at distance `t` (m): the path continues from there with its
    /// throughput times `weight` = Tr(t)·σs(λ) / p̄(t), dimensionless (the phase function is
    /// sampled or evaluated next).
    Scatter { t: f32, weight: SampledSpectrum<N> },
    /// No event before `t_max`: the path reaches the segment's end with its throughput times
    /// `weight` = Tr(t_max) / P̄(t ≥ t_max).
    Pass { weight: SampledSpectrum<N> },
}

impl Homogeneous {
    /// σt(λ) = σa(λ) + σs(λ) at the path's wavelengths, m⁻¹.
    pub fn sigma_t<const N: usize>(&self, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        self.sigma_a.sample(w) + self.sigma_s.sample(w)
    }

    /// Beer–Lambert transmittance exp(−σt(λ) t) over `t` metres.
    pub fn transmittance<const N: usize>(
        &self,
        t: f32,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        self.sigma_t(w).map(|s| (-s * t).exp())
    }

    /// Samples a free flight of at most `t_max` metres (may be infinite) from a uniform `u`:
    /// t = −ln(1 − u)/σt(λ₀), a scattering event if t < `t_max`. The weights divide by the
    /// balance heuristic's average density over the live wavelengths, so that the estimate is
    /// unbiased at every wavelength (see the module's doc). A medium with σt(λ₀) = 0 is passed
    /// through.
    pub fn sample_flight<const N: usize>(
        &self,
        u: f32,
        t_max: f32,
        w: &SampledWavelengths<N>,
    ) -> Flight<N> {
        let sigma_t = self.sigma_t(w);
        let live = |j: usize| w.pdf[j] > 0.0;
        let n_live = (0..N).filter(|&j| live(j)).count().max(1) as f32;
        let hero = sigma_t[0];
        let t = if hero > 0.0 {
            -(1.0 - u).max(f32::MIN_POSITIVE).ln() / hero
        } else {
            f32::INFINITY
        };
        if t < t_max {
            let tr = sigma_t.map(|s| (-s * t).exp());
            // p̄(t) = (1/N) Σⱼ σt(λⱼ) exp(−σt(λⱼ) t), the average free-flight density
            let p: f32 = (0..N)
                .filter(|&j| live(j))
                .map(|j| sigma_t[j] * tr[j])
                .sum::<f32>()
                / n_live;
            let weight = if p > 0.0 {
                tr * self.sigma_s.sample(w) / p
            } else {
                SampledSpectrum::zero()
            };
            return Flight::Scatter { t, weight };
        }
        let tr = sigma_t.map(|s| (-s * t_max).exp());
        // P̄(t ≥ t_max) = (1/N) Σⱼ exp(−σt(λⱼ) t_max)
        let p: f32 = (0..N).filter(|&j| live(j)).map(|j| tr[j]).sum::<f32>() / n_live;
        let weight = if p > 0.0 {
            tr / p
        } else {
            SampledSpectrum::zero()
        };
        Flight::Pass { weight }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn medium(sa: [f32; 2], ss: [f32; 2]) -> Homogeneous {
        let line = |v: [f32; 2]| {
            Spectrum::Piecewise(std::sync::Arc::new(
                crate::spectrum::PiecewiseLinear::new(vec![400.0, 700.0], v.to_vec())
                    .expect("a valid table"),
            ))
        };
        Homogeneous {
            sigma_a: line(sa),
            sigma_s: line(ss),
            phase: PhaseFunction::Isotropic,
        }
    }

    /// Four wavelengths with the hero at index 0, rotated so that the hero is member `h` of
    /// the set (as `draw_wavelengths` makes it).
    fn wavelengths(h: usize) -> SampledWavelengths<4> {
        let set = [430.0, 520.0, 610.0, 690.0];
        SampledWavelengths {
            lambda: [0, 1, 2, 3].map(|j| set[(h + j) % 4]),
            pdf: [1.0 / 300.0; 4],
        }
    }

    #[test]
    fn transmittance_is_beer_lambert() {
        let m = medium([1.0, 4.0], [0.5, 0.5]);
        let w = wavelengths(0);
        let tr = m.transmittance(0.7, &w);
        for j in 0..4 {
            let sa = 1.0 + 3.0 * (w.lambda[j] - 400.0) / 300.0;
            let want = (-(sa + 0.5) * 0.7f32).exp();
            assert!(
                (tr[j] - want).abs() < 1e-6,
                "{}: {} vs {want}",
                w.lambda[j],
                tr[j]
            );
        }
    }

    /// Unbiased at every wavelength of the set, with the hero a uniform member of it:
    /// E[Pass weight] = Tr(t_max) = exp(−σt t_max) and E[Scatter weight] = ∫₀^{t_max} σs
    /// exp(−σt t) dt = σs/σt (1 − exp(−σt t_max)), each within 5 standard errors, although the
    /// flights follow the hero's σt alone (σt differs fourfold across the set).
    #[test]
    fn spectral_mis_is_unbiased_at_every_wavelength() {
        let m = medium([1.0, 7.0], [2.0, 1.0]);
        let t_max = 0.4f32;
        let n = 200_000;
        // sums per member of the set (indexed by set position), and their squares
        let (mut pass, mut scat) = ([0.0f64; 4], [0.0f64; 4]);
        let (mut pass2, mut scat2) = ([0.0f64; 4], [0.0f64; 4]);
        for i in 0..n {
            let h = i % 4;
            let w = wavelengths(h);
            let u = ((i / 4) as f32 + 0.5) / (n / 4) as f32;
            let flight = m.sample_flight(u, t_max, &w);
            for j in 0..4 {
                let member = (h + j) % 4;
                match flight {
                    Flight::Pass { weight } => {
                        pass[member] += weight[j] as f64;
                        pass2[member] += (weight[j] as f64).powi(2);
                    }
                    Flight::Scatter { weight, .. } => {
                        scat[member] += weight[j] as f64;
                        scat2[member] += (weight[j] as f64).powi(2);
                    }
                }
            }
        }
        let w = wavelengths(0);
        for member in 0..4 {
            let x = (w.lambda[member] - 400.0) / 300.0;
            let (sa, ss) = ((1.0 + 6.0 * x) as f64, (2.0 - x) as f64);
            let st = sa + ss;
            let want_pass = (-st * t_max as f64).exp();
            let want_scat = ss / st * (1.0 - want_pass);
            for (sum, sum2, want, what) in [
                (pass[member], pass2[member], want_pass, "pass"),
                (scat[member], scat2[member], want_scat, "scatter"),
            ] {
                let mean = sum / n as f64;
                let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
                assert!(
                    (mean - want).abs() < 5.0 * se + 1e-4,
                    "{} nm {what}: {mean} vs {want} (se {se})",
                    w.lambda[member]
                );
            }
        }
    }

    /// With the secondaries terminated, the hero alone is exact: a pass weighs 1 and a
    /// scattering event σs/σt.
    #[test]
    fn a_lone_hero_weighs_its_albedo() {
        let m = medium([1.0, 7.0], [2.0, 1.0]);
        let mut w = wavelengths(1);
        w.terminate_secondary();
        let x = (w.lambda[0] - 400.0) / 300.0;
        let albedo = (2.0 - x) / (1.0 + 6.0 * x + 2.0 - x);
        for u in [0.1, 0.5, 0.9] {
            match m.sample_flight(u, 0.3, &w) {
                Flight::Scatter { weight, .. } => {
                    assert!(
                        (weight[0] - albedo).abs() < 1e-5,
                        "{} vs {albedo}",
                        weight[0]
                    )
                }
                Flight::Pass { weight } => assert!((weight[0] - 1.0).abs() < 1e-5),
            }
        }
    }
}
