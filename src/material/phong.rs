//! The lecture notes' Phong model in physically based form: the energy-conserving normalised
//! modified Phong BRDF (Lafortune & Willems 1994, "Using the Modified Phong Reflectance Model for
//! Physically Based Rendering").

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

use super::BsdfSample;
use super::fresnel::reflect;
use crate::geometry::frame::Frame;
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

/// Normalised modified Phong BRDF
///
/// f(wo, wi) = k_d/π + k_s·(n+2)/(2π)·cosⁿα,
///
/// where α is the angle between `wi` and the mirror direction of `wo`, R = 2N(N·wo) − wo
/// (PHYSICS.md errata: the notes' R̂ = L̂ − 2N̂(L̂·N̂) mirrors an *incoming* direction), and cos α
/// is clamped at 0. The notes' diffuse term I_d = k_d(L̂·N̂) is the k_d/π lobe times the cosine
/// the integrator applies; their specular term I_s = k_s(V̂·R̂)ⁿ becomes the normalised lobe,
/// whose albedo at normal incidence is exactly k_s. Both terms are symmetric in (wo, wi), so the
/// BRDF is reciprocal, and k_d + k_s ≤ 1 at every wavelength keeps it energy-conserving (checked
/// by [`Phong::new`]).
///
/// **Ambient term.** The notes' k_a·I_a is not part of a BRDF: it is the light reflected from a
/// uniform environment. A diffuse surface under a uniform environment of radiance L_a reflects
/// ∫ (k_d/π)·L_a·cos θ dω = k_d·L_a. So the ambient term is a uniform environment light of
/// radiance L = I_a, with k_a playing the role of k_d; in a physically based scene, put a
/// uniform environment emitter of radiance I_a in the scene instead of an ambient coefficient.
///
/// One-sided like [`Lambert`](super::Lambert): zero unless `wo.z > 0` and `wi.z > 0`.
///
/// **Sampling.** A lobe is chosen with probability proportional to the mean of k_d and of k_s
/// over the wavelengths the path still carries (the hero and the non-terminated secondaries:
/// using all of them keeps the mixture's support covering every carried wavelength's lobes).
/// The diffuse lobe is cosine-sampled; the specular lobe samples cos α = u^{1/(n+1)} around R,
/// density (n+1)/(2π)·cosⁿα. Directions of the specular lobe below the horizon are rejected
/// (`None`). [`Phong::pdf`] is the mixture density.
#[derive(Clone, Debug, PartialEq)]
pub struct Phong {
    /// Diffuse reflectance k_d(λ).
    pub kd: Spectrum,
    /// Specular reflectance k_s(λ) (the lobe's albedo at normal incidence).
    pub ks: Spectrum,
    /// Phong exponent n ≥ 0 (shininess).
    pub exponent: f32,
}

impl Phong {
    /// Checks k_d ≥ 0, k_s ≥ 0 and k_d + k_s ≤ 1 at every nm over 360–830 nm and at the
    /// tabulated wavelengths of tabulated curves, and that the exponent is finite and ≥ 0.
    pub fn new(kd: Spectrum, ks: Spectrum, exponent: f32) -> Result<Phong, String> {
        if !(exponent.is_finite() && exponent >= 0.0) {
            return Err(format!(
                "Phong exponent must be finite and >= 0, got {exponent}"
            ));
        }
        let mut lambdas: Vec<f32> = (360..=830).map(|l| l as f32).collect();
        for s in [&kd, &ks] {
            match s {
                Spectrum::Piecewise(t) => lambdas.extend_from_slice(t.wavelengths()),
                Spectrum::RgbIlluminant { illuminant, .. } => {
                    lambdas.extend_from_slice(illuminant.wavelengths())
                }
                _ => {}
            }
        }
        for l in lambdas {
            let (d, s) = (kd.eval(l), ks.eval(l));
            if !(d >= 0.0 && d.is_finite()) {
                return Err(format!("Phong kd = {d} at {l} nm: must be in [0, 1]"));
            }
            if !(s >= 0.0 && s.is_finite()) {
                return Err(format!("Phong ks = {s} at {l} nm: must be in [0, 1]"));
            }
            if d + s > 1.0 + 1e-6 {
                return Err(format!(
                    "Phong kd + ks = {d} + {s} = {} > 1 at {l} nm: the BRDF would create energy",
                    d + s
                ));
            }
        }
        Ok(Phong { kd, ks, exponent })
    }

    /// cosⁿα with α between `wi` and the mirror direction of `wo`, clamped at 0.
    #[inline]
    fn lobe(&self, wo: Vec3, wi: Vec3) -> f32 {
        let c = reflect(wo, Vec3::Z).dot(wi).min(1.0);
        if c <= 0.0 { 0.0 } else { c.powf(self.exponent) }
    }

    /// Probability of sampling the specular lobe.
    #[inline]
    fn specular_probability<const N: usize>(&self, w: &SampledWavelengths<N>) -> f32 {
        let (mut d, mut s) = (0.0, 0.0);
        for j in 0..N {
            if j == 0 || w.pdf[j] != 0.0 {
                d += self.kd.eval(w.lambda[j]).max(0.0);
                s += self.ks.eval(w.lambda[j]).max(0.0);
            }
        }
        if d + s > 0.0 { s / (d + s) } else { 0.0 }
    }

    #[inline]
    pub fn eval<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return SampledSpectrum::zero();
        }
        self.eval_with(w, self.lobe(wo, wi))
    }

    /// f for a pair (wo, wi) in the upper hemisphere whose [`Phong::lobe`] is `lobe`.
    #[inline]
    fn eval_with<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        lobe: f32,
    ) -> SampledSpectrum<N> {
        let spec = (self.exponent + 2.0) * (0.5 * FRAC_1_PI) * lobe;
        self.kd.sample(w) * FRAC_1_PI + self.ks.sample(w) * spec
    }

    /// The pdf of `wi` (upper hemisphere) for specular probability `ps` and lobe value `lobe`.
    #[inline]
    fn pdf_with(&self, wi: Vec3, ps: f32, lobe: f32) -> f32 {
        let spec = (self.exponent + 1.0) / (2.0 * PI) * lobe;
        (1.0 - ps) * cosine_hemisphere_pdf(wi.z) + ps * spec
    }

    /// [`Phong::eval`] and [`Phong::pdf`] together, the lobe computed once.
    #[inline]
    pub fn eval_pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> (SampledSpectrum<N>, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (SampledSpectrum::zero(), 0.0);
        }
        let lobe = self.lobe(wo, wi);
        let ps = self.specular_probability(w);
        (self.eval_with(w, lobe), self.pdf_with(wi, ps, lobe))
    }

    #[inline]
    pub fn pdf<const N: usize>(&self, wo: Vec3, wi: Vec3, w: &SampledWavelengths<N>) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        self.pdf_with(wi, self.specular_probability(w), self.lobe(wo, wi))
    }

    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let ps = self.specular_probability(w);
        let wi = if uc < ps {
            let cos_a = u.x.powf(1.0 / (self.exponent + 1.0));
            let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
            let phi = 2.0 * PI * u.y;
            let local = Vec3::new(sin_a * phi.cos(), sin_a * phi.sin(), cos_a);
            Frame::from_normal(reflect(wo, Vec3::Z)).to_world(local)
        } else {
            cosine_hemisphere(u)
        };
        if wi.z <= 0.0 {
            return None;
        }
        // the lobe probability, already known, and the lobe value, once for f and pdf
        let lobe = self.lobe(wo, wi);
        let pdf = self.pdf_with(wi, ps, lobe);
        if pdf <= 0.0 {
            return None;
        }
        Some(BsdfSample::reflection(self.eval_with(w, lobe), wi, pdf))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_rejects_energy_creation_and_names_the_wavelength() {
        assert!(Phong::new(Spectrum::Constant(0.5), Spectrum::Constant(0.5), 10.0).is_ok());
        let e = Phong::new(Spectrum::Constant(0.6), Spectrum::Constant(0.5), 10.0).unwrap_err();
        assert!(e.contains("360 nm"), "{e}");
        assert!(Phong::new(Spectrum::Constant(-0.1), Spectrum::Constant(0.5), 1.0).is_err());
        assert!(Phong::new(Spectrum::Constant(0.1), Spectrum::Constant(0.5), -1.0).is_err());
        assert!(Phong::new(Spectrum::Constant(0.1), Spectrum::Constant(0.5), f32::NAN).is_err());
    }
}
