//! A homogeneous medium: extinction and albedo that vary with wavelength but not with
//! position, its transmittance (Beer–Lambert) and free-flight sampling by the hero wavelength.
//!
//! Free flights are sampled by the hero wavelength's extinction σt(λ₀). The hero is a uniformly
//! random member of the path's wavelength set (`render::draw_wavelengths`: wavelength j sits in
//! stratum (h + j) mod N with the hero's stratum h uniform), so sampling by the hero's σt is
//! one-sample MIS over the N techniques "sample by σt(λⱼ)". [`Flight`] returns every
//! technique's density of the sampled event; dividing by their average over the path's
//! segments is the balance heuristic (Veach 1997 §9.2.4; Wilkie et al. 2014; Miller, Georgiev
//! and Jarosz 2019 §5). [`Flight::weight`] does it for one segment alone.

use glam::Vec3;

use super::{PhaseFunction, Volume};
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

/// A homogeneous medium. Coefficients are per metre.
#[derive(Clone, Debug)]
pub struct Homogeneous {
    /// Extinction coefficient σt(λ) = σa + σs, m⁻¹ (λ in nm).
    pub sigma_t: Spectrum,
    /// Single-scattering albedo σs/σt, dimensionless in [0, 1]: a spectrum, or a volume
    /// (Mitsuba's `homogeneous` takes a textured albedo with a constant extinction).
    pub albedo: Volume,
    /// The phase function of its scattering.
    pub phase: PhaseFunction,
    /// Emitted radiance Le(λ), W·m⁻²·sr⁻¹·nm⁻¹ (source term σa·Le); None: none.
    pub emission: Option<Spectrum>,
    /// Whether the albedo is 0 at every wavelength of the scene's range (decided once by the
    /// build step): then nothing scatters, free flights are not sampled and the transmittance
    /// is the weight.
    pub absorbing: bool,
}

/// The outcome of a free flight sampled along a segment of length `t_max`, per wavelength of
/// the path: the value of the event and its density had that wavelength been the hero.
#[derive(Clone, Copy, Debug)]
pub enum Flight<const N: usize> {
    /// A scattering event at distance `t` (m): `f` = Tr(t)·σs(λ), m⁻¹ (the phase function is
    /// sampled or evaluated next), and `pdf` = σt(λ)·Tr(t), the density of t, m⁻¹.
    Scatter {
        t: f32,
        f: SampledSpectrum<N>,
        pdf: SampledSpectrum<N>,
    },
    /// No event before `t_max`: `tr` = Tr(t_max) and `pdf` = P(t ≥ t_max) = Tr(t_max), both
    /// dimensionless.
    Pass {
        tr: SampledSpectrum<N>,
        pdf: SampledSpectrum<N>,
    },
}

impl<const N: usize> Flight<N> {
    /// The event's value over the average of its densities over the live wavelengths: the
    /// one-segment balance-heuristic weight (Tr·σs/p̄ for a scattering event, Tr/P̄ for a
    /// pass), unbiased at every wavelength for a lone segment. 0 where every density is 0.
    pub fn weight(&self, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        let (f, pdf) = match *self {
            Flight::Scatter { f, pdf, .. } => (f, pdf),
            Flight::Pass { tr, pdf } => (tr, pdf),
        };
        let p = super::live_average(pdf, w);
        if p > 0.0 {
            f / p
        } else {
            SampledSpectrum::zero()
        }
    }
}

impl Homogeneous {
    /// σt(λ) at the path's wavelengths, m⁻¹.
    #[inline]
    pub fn sigma_t<const N: usize>(&self, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        self.sigma_t.sample(w)
    }

    /// Whether the medium only absorbs (see [`Homogeneous::absorbing`]): then free flights are
    /// not sampled and the transmittance is applied as a weight.
    #[inline]
    pub fn absorbs_only(&self) -> bool {
        self.absorbing
    }

    /// The medium's emission collected along the free flight `flight` sampled over
    /// `o + t d`, t < `t_max`, as a value and its density per wavelength (see
    /// [`super::Walk::emitted`]): the exact integral ∫ Tr σa Le over the segment when nothing
    /// scatters (no distance was sampled), else the collision estimator at a scattering event
    /// (Tr(t)·σa(t)·Le over the density σt·Tr(t)), and nothing at a pass.
    pub fn emitted<const N: usize>(
        &self,
        flight: &Flight<N>,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        w: &SampledWavelengths<N>,
    ) -> Option<(SampledSpectrum<N>, SampledSpectrum<N>)> {
        let le = self.emission.as_ref()?.sample(w);
        let sigma_t = self.sigma_t(w);
        match *flight {
            Flight::Scatter { t, pdf, .. } => {
                let albedo = self.albedo.eval(o + d * t, w);
                let sigma_a = sigma_t - sigma_t * albedo;
                let tr = sigma_t.map(|s| beer_lambert(s, t));
                Some((tr * sigma_a * le, pdf))
            }
            Flight::Pass { pdf, .. } if self.absorbs_only() => {
                // ∫₀^t_max e^{−σa s} σa Le ds = Le (1 − e^{−σa t_max})
                let tr = sigma_t.map(|s| beer_lambert(s, t_max));
                Some((le * (SampledSpectrum::splat(1.0) - tr), pdf))
            }
            Flight::Pass { .. } => None,
        }
    }

    /// Beer–Lambert transmittance exp(−σt(λ) t) over `t` metres.
    #[inline]
    pub fn transmittance<const N: usize>(
        &self,
        t: f32,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        self.sigma_t(w).map(|s| beer_lambert(s, t))
    }

    /// Samples a free flight along `o + t d` (d unit) of at most `t_max` metres (may be
    /// infinite) from a uniform `u`:
    /// t = −ln(1 − u)/σt(λ₀), a scattering event if t < `t_max`. A medium with σt(λ₀) = 0 is
    /// passed through; one that only absorbs is passed with its transmittance as the weight
    /// (and densities 1).
    #[inline]
    pub fn sample_flight<const N: usize>(
        &self,
        u: f32,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        w: &SampledWavelengths<N>,
    ) -> Flight<N> {
        let sigma_t = self.sigma_t(w);
        if self.absorbs_only() {
            // nothing scatters: the transmittance is the weight, and no distance is sampled
            // (zero variance; the density of passing is 1 for every hero)
            let tr = sigma_t.map(|s| beer_lambert(s, t_max));
            return Flight::Pass {
                tr,
                pdf: SampledSpectrum::splat(1.0),
            };
        }
        let hero = sigma_t[0];
        let t = if hero > 0.0 {
            -(1.0 - u).max(f32::MIN_POSITIVE).ln() / hero
        } else {
            f32::INFINITY
        };
        if t < t_max {
            let tr = sigma_t.map(|s| (-s * t).exp());
            let sigma_s = sigma_t * self.albedo.eval(o + d * t, w);
            return Flight::Scatter {
                t,
                f: tr * sigma_s,
                pdf: tr * sigma_t,
            };
        }
        let tr = sigma_t.map(|s| beer_lambert(s, t_max));
        Flight::Pass { tr, pdf: tr }
    }
}

/// exp(−σ t), with a clear medium clear over any distance (σ = 0, t = ∞ gives 1, not NaN).
#[inline]
fn beer_lambert(sigma: f32, t: f32) -> f32 {
    if sigma == 0.0 {
        1.0
    } else {
        (-sigma * t).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn medium(sa: [f32; 2], ss: [f32; 2]) -> Homogeneous {
        // σt and albedo tabulated from σa and σs on a 1 nm grid (both linear in λ)
        let lambda: Vec<f32> = (400..=700).map(|l| l as f32).collect();
        let x = |l: f32| (l - 400.0) / 300.0;
        let at = |v: [f32; 2], l: f32| v[0] + (v[1] - v[0]) * x(l);
        let table = |f: &dyn Fn(f32) -> f32| {
            Spectrum::Piecewise(std::sync::Arc::new(
                crate::spectrum::PiecewiseLinear::new(
                    lambda.clone(),
                    lambda.iter().map(|&l| f(l)).collect(),
                )
                .expect("a valid table"),
            ))
        };
        Homogeneous {
            sigma_t: table(&|l| at(sa, l) + at(ss, l)),
            albedo: Volume::Constant(table(&|l| at(ss, l) / (at(sa, l) + at(ss, l)))),
            phase: PhaseFunction::Isotropic,
            emission: None,
            absorbing: false,
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
            let flight = m.sample_flight(u, Vec3::ZERO, Vec3::Z, t_max, &w);
            let weight = flight.weight(&w);
            for j in 0..4 {
                let member = (h + j) % 4;
                match flight {
                    Flight::Pass { .. } => {
                        pass[member] += weight[j] as f64;
                        pass2[member] += (weight[j] as f64).powi(2);
                    }
                    Flight::Scatter { .. } => {
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
            let flight = m.sample_flight(u, Vec3::ZERO, Vec3::Z, 0.3, &w);
            let weight = flight.weight(&w);
            match flight {
                Flight::Scatter { .. } => {
                    assert!(
                        (weight[0] - albedo).abs() < 1e-5,
                        "{} vs {albedo}",
                        weight[0]
                    )
                }
                Flight::Pass { .. } => assert!((weight[0] - 1.0).abs() < 1e-5),
            }
        }
    }
}
