//! The rough dielectric interface: GGX or Beckmann microfacets with reflection and refraction
//! (Walter et al. 2007), GGX sampled through the visible normals (Heitz 2018).

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_dielectric, fresnel_dielectric_pair, reflect, refract};
use super::microfacet::{Distribution, Microfacet, Smith};
use super::{BsdfSample, TransportMode};
use crate::spectrum::ior::Ior;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A rough interface between an outside of index `ext_ior` (+z side) and an inside of index
/// `int_ior(λ)` (−z side), GGX or Beckmann roughness `alpha` (clamped to at least
/// [`MIN_ALPHA`](super::microfacet::MIN_ALPHA)), height-correlated Smith G.
///
/// With η = int_ior(λ₀)/ext_ior at the hero wavelength λ₀, η' = n(wi side)/n(wo side) (η or 1/η
/// for transmission, 1 for reflection) and the generalised half vector
/// wm = ±normalize(wo + η'·wi) turned to the +z side:
/// - reflection (wo, wi on the same side): f = D(wm)·G(wo, wi)·F / (4|cos θₒ||cos θᵢ|), with
///   pdf = D_wo(wm)·F / (4|wo·wm|);
/// - transmission: f = D·G·(1 − F)·|wi·wm||wo·wm| / (|cos θₒ||cos θᵢ|·(wi·wm + wo·wm/η')²),
///   times 1/η'² in [`TransportMode::Radiance`], with
///   pdf = D_wo(wm)·(1 − F)·|wi·wm| / (wi·wm + wo·wm/η')²,
///
/// where F = F(wo·wm) is the exact dielectric Fresnel term (in `eval` evaluated from both
/// microfacet cosines, see [`fresnel_dielectric_pair`]), D_wo the density of sampled normals
/// ([`Microfacet::normal_pdf`]: the normals visible from `wo`), and the lobe is chosen with probability F(wo·wm) at λ₀. Microfacets facing away from
/// either direction contribute nothing.
///
/// The half vector, and hence the transmission direction, uses the hero wavelength's η: a
/// transmission sample of a dispersive `int_ior` is flagged `dispersive`, and in `eval` of a
/// transmission pair only the hero value is meaningful (the secondaries get their own F only).
/// Reflection values are valid at every wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct RoughDielectric {
    pub int_ior: Ior,
    pub ext_ior: f32,
    /// Roughness α along the shading frame's first tangent (Mitsuba's ∂p/∂u) and the second;
    /// equal for an isotropic surface.
    pub alpha_u: f32,
    pub alpha_v: f32,
    pub distribution: Distribution,
    /// The masking–shadowing function (Mitsuba's scenes: separable).
    pub smith: Smith,
}

/// The configuration of a (wo, wi) pair: generalised half vector and η'.
struct Half {
    wm: Vec3,
    etap: f32,
    reflection: bool,
    /// The hero wavelength's relative index η the pair was found with.
    eta: f32,
}

impl RoughDielectric {
    /// A GGX rough interface.
    pub fn new(int_ior: Ior, ext_ior: f32, alpha: f32) -> Self {
        Self {
            int_ior,
            ext_ior,
            alpha_u: alpha,
            alpha_v: alpha,
            distribution: Distribution::Ggx,
            smith: Smith::HeightCorrelated,
        }
    }

    /// The same interface with roughness `alpha_u` along the first tangent, `alpha_v` along the
    /// second.
    pub fn with_anisotropy(self, alpha_u: f32, alpha_v: f32) -> Self {
        Self {
            alpha_u,
            alpha_v,
            ..self
        }
    }

    /// The same interface with another microfacet distribution.
    pub fn with_smith(self, smith: Smith) -> Self {
        Self { smith, ..self }
    }

    pub fn with_distribution(self, distribution: Distribution) -> Self {
        Self {
            distribution,
            ..self
        }
    }

    #[inline]
    pub fn microfacet(&self) -> Microfacet {
        Microfacet::anisotropic(self.alpha_u, self.alpha_v, self.distribution)
            .with_smith(self.smith)
    }

    #[inline]
    fn eta(&self, lambda_nm: f32) -> f32 {
        self.int_ior.eval(lambda_nm) / self.ext_ior
    }

    /// The half vector for (wo, wi) at relative index `eta`, or `None` when the pair cannot
    /// scatter (grazing, degenerate, or a back-facing microfacet).
    #[inline]
    fn half(wo: Vec3, wi: Vec3, eta: f32) -> Option<Half> {
        let (co, ci) = (wo.z, wi.z);
        if co == 0.0 || ci == 0.0 {
            return None;
        }
        let reflection = co * ci > 0.0;
        let etap = if reflection {
            1.0
        } else if co > 0.0 {
            eta
        } else {
            1.0 / eta
        };
        let mut wm = (wi * etap + wo).try_normalize()?;
        if wm.z < 0.0 {
            wm = -wm;
        }
        if wm.z <= 0.0 || wm.dot(wi) * ci <= 0.0 || wm.dot(wo) * co <= 0.0 {
            return None;
        }
        Some(Half {
            wm,
            etap,
            reflection,
            eta,
        })
    }

    #[inline]
    pub fn eval<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> SampledSpectrum<N> {
        let Some(h) = Self::half(wo, wi, self.eta(w.lambda[0])) else {
            return SampledSpectrum::zero();
        };
        self.eval_half(&self.microfacet(), wo, wi, w, mode, &h)
    }

    /// [`RoughDielectric::eval`] for the half vector `h` of (wo, wi) at the hero's η (`h.eta`).
    #[inline]
    fn eval_half<const N: usize>(
        &self,
        mf: &Microfacet,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
        h: &Half,
    ) -> SampledSpectrum<N> {
        let eta_hero = h.eta;
        let dg = mf.d(h.wm) * mf.g(wo, wi);
        let (cos_om, cos_im) = (wo.dot(h.wm), wi.dot(h.wm));
        let cos2 = (wo.z * wi.z).abs();
        // Fresnel: for reflection at the mean of the two (equal) microfacet cosines, for
        // transmission from both cosines of the refracted pair; both forms are symmetric in
        // (wo, wi), which keeps the BSDF exactly reciprocal, and the pair form stays accurate
        // near the critical angle. A secondary wavelength with another index only gets
        // F(wo·wm) at its own η (its direction would differ; see the type's docs).
        let cos_refl = 0.5 * (cos_om + cos_im);
        let fr = w.lambda.map(|l| {
            let eta = self.eta(l);
            if h.reflection {
                fresnel_dielectric(cos_refl, eta)
            } else if eta == eta_hero {
                fresnel_dielectric_pair(cos_om, cos_im, h.etap)
            } else {
                fresnel_dielectric(cos_om, eta)
            }
        });
        if h.reflection {
            return SampledSpectrum(fr) * (dg / (4.0 * cos2));
        }
        let s = cos_im + cos_om / h.etap;
        let mut base = dg * (cos_im * cos_om).abs() / (cos2 * s * s);
        if mode == TransportMode::Radiance {
            base /= h.etap * h.etap;
        }
        SampledSpectrum(fr.map(|f| (1.0 - f) * base))
    }

    #[inline]
    pub fn pdf<const N: usize>(&self, wo: Vec3, wi: Vec3, w: &SampledWavelengths<N>) -> f32 {
        let eta = self.eta(w.lambda[0]);
        let Some(h) = Self::half(wo, wi, eta) else {
            return 0.0;
        };
        self.pdf_half(&self.microfacet(), wo, wi, eta, &h)
    }

    /// [`RoughDielectric::eval`] and [`RoughDielectric::pdf`] together, the index and half
    /// vector found once (the same values as the two calls).
    #[inline]
    pub fn eval_pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> (SampledSpectrum<N>, f32) {
        self.eval_pdf_with(&self.microfacet(), wo, wi, w, mode)
    }

    /// [`RoughDielectric::eval_pdf`] with the microfacet distribution `mf` in place of the
    /// material's own roughness (a textured α looked up at the hit).
    #[inline]
    pub fn eval_pdf_with<const N: usize>(
        &self,
        mf: &Microfacet,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> (SampledSpectrum<N>, f32) {
        let eta = self.eta(w.lambda[0]);
        let Some(h) = Self::half(wo, wi, eta) else {
            return (SampledSpectrum::zero(), 0.0);
        };
        (
            self.eval_half(mf, wo, wi, w, mode, &h),
            self.pdf_half(mf, wo, wi, eta, &h),
        )
    }

    /// [`RoughDielectric::pdf`] for the half vector `h` of (wo, wi) at the hero's `eta`.
    #[inline]
    fn pdf_half(&self, mf: &Microfacet, wo: Vec3, wi: Vec3, eta: f32, h: &Half) -> f32 {
        let (cos_om, cos_im) = (wo.dot(h.wm), wi.dot(h.wm));
        let pdf_wm = mf.normal_pdf(wo, h.wm);
        let r = fresnel_dielectric(cos_om, eta);
        if h.reflection {
            pdf_wm / (4.0 * cos_om.abs()) * r
        } else {
            let s = cos_im + cos_om / h.etap;
            pdf_wm * cos_im.abs() / (s * s) * (1.0 - r)
        }
    }

    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        self.sample_with(&self.microfacet(), wo, w, uc, u, mode)
    }

    /// [`RoughDielectric::sample`] with the distribution `mf` (see
    /// [`RoughDielectric::eval_pdf_with`]).
    #[inline]
    pub fn sample_with<const N: usize>(
        &self,
        mf: &Microfacet,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 {
            return None;
        }
        let eta = self.eta(w.lambda[0]);
        let wm = mf.sample_normal(wo, u);
        if wo.dot(wm) * wo.z <= 0.0 {
            return None; // a back-facing normal (only at grazing views, from rounding)
        }
        let r = fresnel_dielectric(wo.dot(wm), eta);
        let (wi, transmission, etap) = if uc < r {
            (reflect(wo, wm), false, 1.0)
        } else {
            let (wi, etap) = refract(wo, wm, eta)?;
            (wi, true, etap)
        };
        // The lobe must land on its own side of the macro-surface.
        if wi.z == 0.0 || (wi.z * wo.z < 0.0) != transmission {
            return None;
        }
        let (f, pdf) = self.eval_pdf_with(mf, wo, wi, w, mode);
        if !(pdf > 0.0 && pdf.is_finite() && f.is_finite()) {
            return None;
        }
        Some(BsdfSample {
            f,
            wi,
            pdf,
            specular: false,
            transmission,
            dispersive: transmission && self.int_ior.is_dispersive(),
            eta: etap,
        })
    }
}
