//! Mitsuba 3's polarised plastic, `pplastic` (src/bsdfs/pplastic.cpp): a rough specular
//! reflection off a dielectric interface plus a diffuse term that crosses the interface twice,
//! each with its Fresnel factors, as Mitsuba 3.9.1 defines it. Not energy conserving (Mitsuba's
//! note): the diffuse term is not attenuated by the specular one's rough reflection, and has no
//! inner reflections. What makes it useful is its polarisation: the specular lobe polarises
//! perpendicular to the plane of reflection, the diffuse term weakly and across it (the
//! Mueller matrices are in `polarised.rs`).
//!
//! With η = n_int/n_ext, F(cos) the unpolarised Fresnel reflectance at η, ρ the diffuse
//! reflectance at the hit, k_s the specular factor, D the microfacet distribution (Beckmann by
//! default, as Mitsuba's) and G₁ Smith's shadowing, h the half vector:
//!
//!   f(wo, wi) = k_s·F(wi·h)·D(h)·G₁(wo)·G₁(wi)/(4 cos θₒ cos θᵢ)
//!             + ρ/π·(1 − F(cos θₒ))·(1 − F(cos θᵢ)).
//!
//! Sampling (as Mitsuba): the visible normals with probability w_s = k_s/(mean ρ + k_s), else
//! the cosine-weighted hemisphere; the pdf is the mixture. One-sided: zero unless `wo.z > 0`
//! and `wi.z > 0`.

use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

use super::BsdfSample;
use super::fresnel::{fresnel_dielectric, reflect};
use super::microfacet::Microfacet;
use super::plastic::g1;
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::spectrum::SampledSpectrum;
use crate::texture::Texture;

/// Mitsuba's `pplastic` (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct PPlastic {
    /// ρ, the diffuse reflectance (dimensionless).
    pub diffuse: Texture,
    /// k_s, a factor on the specular lobe (Mitsuba's `specular_reflectance`), dimensionless.
    pub specular: f32,
    /// η = n_int/n_ext.
    pub eta: f32,
    pub distribution: Microfacet,
    /// w_s, the probability of sampling the specular lobe.
    pub specular_weight: f32,
}

impl PPlastic {
    /// `diffuse_mean` is the mean of ρ over the spectrum (Mitsuba's texture `mean`).
    pub fn new(
        diffuse: Texture,
        diffuse_mean: f32,
        specular: f32,
        eta: f32,
        distribution: Microfacet,
    ) -> Self {
        let total = diffuse_mean + specular;
        Self {
            diffuse,
            specular,
            eta,
            distribution,
            specular_weight: if total > 0.0 { specular / total } else { 0.5 },
        }
    }

    /// f(wo, wi) in sr⁻¹ (no cosine), with Mitsuba's separable Smith G₁ (`plastic::g1`) and the sampling density of `wi` (sr⁻¹), for the diffuse
    /// reflectance `rho` at the hit.
    pub fn eval_pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        rho: SampledSpectrum<N>,
    ) -> (SampledSpectrum<N>, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (SampledSpectrum::zero(), 0.0);
        }
        let diffuse = rho
            * (FRAC_1_PI
                * (1.0 - fresnel_dielectric(wo.z, self.eta))
                * (1.0 - fresnel_dielectric(wi.z, self.eta)));
        let Some(h) = (wo + wi).try_normalize() else {
            let pdf = (1.0 - self.specular_weight) * cosine_hemisphere_pdf(wi.z);
            return (diffuse, pdf);
        };
        let d = self.distribution.d(h);
        let (g_o, g_i) = (g1(&self.distribution, wo, h), g1(&self.distribution, wi, h));
        let spec = self.specular * fresnel_dielectric(wi.dot(h), self.eta) * d * g_o * g_i
            / (4.0 * wo.z * wi.z);
        // the visible normals seen from wo, times the reflection Jacobian: D·G₁(wo)/(4 cos θₒ)
        let p_spec = if wo.dot(h) > 0.0 && wi.dot(h) > 0.0 {
            d * g_o / (4.0 * wo.z)
        } else {
            0.0
        };
        let pdf = self.specular_weight * p_spec
            + (1.0 - self.specular_weight) * cosine_hemisphere_pdf(wi.z);
        (diffuse + SampledSpectrum::splat(spec), pdf)
    }

    /// Samples `wi`: `uc` chooses the lobe, `u` the direction.
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        rho: SampledSpectrum<N>,
        uc: f32,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = if uc < self.specular_weight {
            let m = self.distribution.sample_normal(wo, u);
            reflect(wo, m)
        } else {
            cosine_hemisphere(u)
        };
        let (f, pdf) = self.eval_pdf(wo, wi, rho);
        (pdf > 0.0 && wi.z > 0.0).then(|| BsdfSample::reflection(f, wi, pdf))
    }
}
