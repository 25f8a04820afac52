//! Plastic: a diffuse base under a smooth or rough dielectric coating, as Mitsuba 3.9.1's
//! `plastic` and `roughplastic` define it (src/bsdfs/plastic.cpp, roughplastic.cpp; the
//! formulas were checked numerically against Mitsuba's own BSDF values).
//!
//! With η = n_int/n_ext, F(cos) the unpolarised dielectric Fresnel reflectance at η, ρ the
//! diffuse reflectance at the hit and R_int the coating's internal reflectance seen from inside,
//! the diffuse base scattered any number of times under the coating gives
//!
//!   ρ' = ρ / (1 − R_int)          (ρ / (1 − ρ·R_int) with `nonlinear`),
//!   f_diffuse(wo, wi) = ρ'/π · (1/η²) · T(wo) · T(wi),
//!
//! where T is the coating's transmittance: 1 − F(cos θ) for the smooth coating, with R_int the
//! diffuse Fresnel reflectance Fdr(1/η) (Egan & Hilgeman's fit, as Mitsuba); for the rough
//! coating T(cos θ) and R_int are the rough dielectric's transmittance and its cosine-weighted
//! internal reflectance, tabulated at 64 cosines when the scene is built (Mitsuba integrates
//! them by quadrature; here a 128 × 128 stratified quadrature over sampled microfacet normals,
//! within 3·10⁻⁴ of Mitsuba's values).
//! The rough coating adds the microfacet reflection F(wo·h)·D(h)·G(wo, wi)/(4 cos θₒ cos θᵢ)
//! with Mitsuba's separable Smith G = G₁(wo)·G₁(wi). The smooth coating adds a delta reflection
//! of weight F(cos θₒ).
//!
//! Sampling (as Mitsuba): the specular part with probability ∝ F(cos θₒ)·w_s (smooth) or
//! (1 − T(cos θₒ))·w_s (rough) against ∝ T(cos θₒ)·(1 − w_s) for the diffuse part, where w_s is
//! the `specular_sampling_weight` = mean specular / (mean diffuse + mean specular). One-sided:
//! zero unless `wo.z > 0` and `wi.z > 0`.

use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

use super::BsdfSample;
use super::fresnel::{fresnel_dielectric, reflect};
use super::microfacet::{Distribution, Microfacet};
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use crate::texture::Texture;

/// Cosines at which the rough coating's transmittance is tabulated.
const T_RES: usize = 64;

/// Mitsuba's `fresnel_diffuse_reflectance(eta)`: the hemispherical average of F at relative
/// index `eta`; Egan & Hilgeman's fit for η < 1, d'Eon & Irving's polynomial in 1/η otherwise.
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    if eta < 1.0 {
        -1.4399 * eta * eta + 0.7099 * eta + 0.6681 + 0.0636 / eta
    } else {
        let inv = 1.0 / eta;
        let c = [0.919317, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881];
        c.iter().rev().fold(0.0, |acc, &k| acc * inv + k)
    }
}

/// The rough coating: its microfacets and tabulated transmittance.
#[derive(Clone, Debug, PartialEq)]
pub struct RoughCoating {
    pub distribution: Microfacet,
    /// T(μ) at μ_k = max(10⁻⁶, k/63), k = 0…63.
    t: [f32; T_RES],
}

/// Mitsuba's G₁(v, m): 0 unless v is on the side of m that faces the macro-surface, else
/// 1/(1 + Λ(v)).
pub(super) fn g1(d: &Microfacet, v: Vec3, m: Vec3) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    1.0 / (1.0 + d.lambda(v))
}

impl RoughCoating {
    /// The coating of relative index `eta` = n_int/n_ext; also returns its internal reflectance
    /// R_int = 2 ∫₀¹ R(μ; 1/η) μ dμ.
    pub fn new(alpha: f32, kind: Distribution, eta: f32) -> (Self, f32) {
        let d = Microfacet::new(alpha, kind);
        let n = 128;
        // ∫ over microfacet normals seen from `wi`: the weight of the normal m is
        // D_wi(m) = G₁(wi, m)·⟨wi, m⟩·D(m)/cos θᵢ, estimated by stratified samples of m
        let integrate = |wi: Vec3, f: &dyn Fn(Vec3) -> f32| -> f32 {
            let mut sum = 0.0f64;
            for a in 0..n {
                for b in 0..n {
                    let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
                    let m = d.sample_normal(wi, u);
                    let pdf = d.normal_pdf(wi, m);
                    let dot = wi.dot(m);
                    if !(pdf > 0.0) || dot <= 0.0 {
                        continue;
                    }
                    let weight = g1(&d, wi, m) * dot * d.d(m) / (wi.z * pdf);
                    sum += (weight * f(m)) as f64;
                }
            }
            (sum / (n * n) as f64) as f32
        };
        let dir = |mu: f32| Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
        let mu = |k: usize| (k as f32 / (T_RES - 1) as f32).max(1e-6);
        let mut t = [0.0; T_RES];
        for (k, tk) in t.iter_mut().enumerate() {
            let wi = dir(mu(k));
            *tk = integrate(wi, &|m| {
                let c = wi.dot(m);
                let f = fresnel_dielectric(c, eta);
                // the refracted direction about m, into the coating
                let e = 1.0 / eta;
                let s2 = e * e * (1.0 - c * c);
                if s2 >= 1.0 {
                    return 0.0;
                }
                let wt = (e * c - (1.0 - s2).sqrt()) * m - e * wi;
                if wt.z * wi.z >= 0.0 {
                    return 0.0;
                }
                g1(&d, wt, m) * (1.0 - f)
            });
        }
        // internal reflectance: from inside, relative index 1/η, reflection about m
        let mut r_int = 0.0;
        for k in 0..T_RES {
            let wi = dir(mu(k));
            let r = integrate(wi, &|m| {
                let wr = reflect(wi, m);
                if wr.z <= 0.0 {
                    return 0.0;
                }
                fresnel_dielectric(wi.dot(m), 1.0 / eta) * g1(&d, wr, m)
            });
            r_int += r * mu(k);
        }
        r_int *= 2.0 / T_RES as f32;
        (Self { distribution: d, t }, r_int)
    }

    /// Transmittance into the coating at cos θ = `mu` ∈ [0, 1] (linear in the table).
    #[inline]
    pub fn transmittance(&self, mu: f32) -> f32 {
        let x = mu.clamp(0.0, 1.0) * (T_RES - 1) as f32;
        let i = (x as usize).min(T_RES - 2);
        let f = x - i as f32;
        self.t[i] + f * (self.t[i + 1] - self.t[i])
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Plastic {
    /// Diffuse reflectance ρ of the base, dimensionless, in [0, 1].
    pub diffuse: Texture,
    /// Mitsuba's `specular_reflectance` (a factor on the coating's reflection), 1 by default.
    pub specular: f32,
    /// n_int / n_ext.
    pub eta: f32,
    pub nonlinear: bool,
    /// The coating's internal reflectance R_int (see the module docs).
    pub r_int: f32,
    /// Probability weight w_s of the specular part in sampling.
    pub spec_weight: f32,
    /// None: a smooth coating.
    pub rough: Option<Box<RoughCoating>>,
    /// Thin-film layers on a smooth coating (`coated.rs`): spectral R, T and R_int.
    pub film: Option<Box<super::coated::PlasticFilm>>,
}

impl Plastic {
    /// A plastic of diffuse reflectance `diffuse` whose mean is `diffuse_mean` (for the
    /// sampling weight, as Mitsuba's `mean()`), coating index `int_ior`/`ext_ior`, and
    /// roughness `alpha` (None: smooth). Errors when the two indices are equal.
    pub fn new(
        diffuse: Texture,
        diffuse_mean: f32,
        specular: f32,
        int_ior: f32,
        ext_ior: f32,
        nonlinear: bool,
        rough: Option<(f32, Distribution)>,
    ) -> Result<Self, String> {
        if !(int_ior > 0.0 && ext_ior > 0.0) || int_ior == ext_ior {
            return Err(format!(
                "a plastic needs two different positive indices, not int_ior {int_ior} and ext_ior {ext_ior}"
            ));
        }
        let eta = int_ior / ext_ior;
        let (rough, r_int) = match rough {
            None => (None, fresnel_diffuse_reflectance(1.0 / eta)),
            Some((alpha, kind)) => {
                let (c, r) = RoughCoating::new(alpha, kind, eta);
                (Some(Box::new(c)), r)
            }
        };
        let spec_weight = specular / (diffuse_mean.max(0.0) + specular);
        Ok(Self {
            diffuse,
            specular,
            eta,
            nonlinear,
            r_int,
            spec_weight: if spec_weight.is_finite() {
                spec_weight
            } else {
                0.5
            },
            rough,
            film: None,
        })
    }

    /// T(cos θ): the coating's transmittance.
    #[inline]
    fn transmittance(&self, cos: f32) -> f32 {
        match &self.rough {
            None => 1.0 - fresnel_dielectric(cos, self.eta),
            Some(r) => r.transmittance(cos),
        }
    }

    /// ρ' per wavelength from ρ (`rho`).
    #[inline]
    fn effective<const N: usize>(&self, rho: SampledSpectrum<N>) -> SampledSpectrum<N> {
        rho.map(|d| {
            let den = 1.0
                - if self.nonlinear {
                    d * self.r_int
                } else {
                    self.r_int
                };
            if den > 0.0 { d / den } else { 0.0 }
        })
    }

    /// Probability of sampling the specular part, seen from `wo`.
    #[inline]
    pub(super) fn p_spec(&self, t_o: f32) -> f32 {
        let ps = (1.0 - t_o) * self.spec_weight;
        let pd = t_o * (1.0 - self.spec_weight);
        if ps + pd > 0.0 { ps / (ps + pd) } else { 0.0 }
    }

    /// f(wo, wi) (no cosine) and its pdf, with ρ = `rho` at the hit.
    #[inline]
    pub fn eval_pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        rho: SampledSpectrum<N>,
        w: &SampledWavelengths<N>,
    ) -> (SampledSpectrum<N>, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (SampledSpectrum::zero(), 0.0);
        }
        if let Some(f) = &self.film {
            return self.film_eval_pdf(f, wo, wi, rho, w);
        }
        let (t_o, t_i) = (self.transmittance(wo.z), self.transmittance(wi.z));
        let diffuse = self.effective(rho) * (FRAC_1_PI * t_o * t_i / (self.eta * self.eta));
        let ps = self.p_spec(t_o);
        let pdf_diffuse = (1.0 - ps) * cosine_hemisphere_pdf(wi.z);
        let Some(r) = &self.rough else {
            return (diffuse, pdf_diffuse);
        };
        let h = (wo + wi).normalize();
        let d = &r.distribution;
        let spec = fresnel_dielectric(wo.dot(h), self.eta)
            * d.d(h)
            * g1(d, wo, h)
            * g1(d, wi, h)
            * self.specular
            / (4.0 * wo.z * wi.z);
        let pdf_spec = d.normal_pdf(wo, h) / (4.0 * wo.dot(h).abs());
        (
            diffuse + SampledSpectrum([spec; N]),
            pdf_diffuse + ps * pdf_spec,
        )
    }

    /// Samples `wi` given `wo`: `uc` picks the part, `u` the direction.
    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        rho: SampledSpectrum<N>,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let film = self
            .film
            .as_deref()
            .map(|f| super::coated::film_terms(f, wo.z, w));
        let ps = match &film {
            Some((_, t)) => self.p_spec(super::coated::mean(t)),
            None => self.p_spec(self.transmittance(wo.z)),
        };
        if uc < ps {
            if let Some((r, _)) = film {
                let wi = Vec3::new(-wo.x, -wo.y, wo.z);
                let f = SampledSpectrum(r) * (self.specular / wo.z);
                return Some(BsdfSample {
                    specular: true,
                    ..BsdfSample::reflection(f, wi, ps)
                });
            }
            let Some(r) = &self.rough else {
                // the coating's mirror reflection: f = F/cos θᵢ, probability ps
                let wi = Vec3::new(-wo.x, -wo.y, wo.z);
                let f = fresnel_dielectric(wo.z, self.eta) * self.specular / wo.z;
                return Some(BsdfSample {
                    specular: true,
                    ..BsdfSample::reflection(SampledSpectrum([f; N]), wi, ps)
                });
            };
            let m = r.distribution.sample_normal(wo, u);
            let wi = reflect(wo, m);
            if wi.z <= 0.0 {
                return None;
            }
            let (f, pdf) = self.eval_pdf(wo, wi, rho, w);
            return (pdf > 0.0).then(|| BsdfSample::reflection(f, wi, pdf));
        }
        let wi = cosine_hemisphere(u);
        let (f, pdf) = self.eval_pdf(wo, wi, rho, w);
        (pdf > 0.0 && wi.z > 0.0).then(|| BsdfSample::reflection(f, wi, pdf))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mitsuba 3.9.1's numbers for its defaults (η = 1.49/1.000277): Fdr(1/η) = 0.590479, and
    /// for Beckmann α = 0.1 the internal reflectance 0.57466 and the transmittance table
    /// T(1) = 0.96133, T(0.5) = 0.91077, T(0.2) = 0.68125, T(0.05) = 0.44378, obtained by
    /// inverting Mitsuba's `roughplastic` BSDF values (see the module docs).
    #[test]
    fn coating_integrals_match_mitsuba() {
        let eta = 1.49 / 1.000277;
        assert!((fresnel_diffuse_reflectance(1.0 / eta) - 0.590479).abs() < 1e-5);
        let (c, r_int) = RoughCoating::new(0.1, Distribution::Beckmann, eta);
        println!("R_int = {r_int}, Mitsuba 0.57466");
        assert!((r_int - 0.57466).abs() < 5e-4, "R_int {r_int}");
        for (mu, want) in [
            (1.0, 0.96133),
            (0.5, 0.91077),
            (0.2, 0.68125),
            (0.05, 0.44378),
        ] {
            let t = c.transmittance(mu);
            println!("T({mu}) = {t}, Mitsuba {want}");
            assert!((t - want).abs() < 1e-3, "T({mu}) = {t}, Mitsuba {want}");
        }
    }
}
