//! Conductors (metals): the smooth mirror and the GGX rough conductor, both with the exact
//! complex Fresnel reflectance per wavelength.

use glam::{Vec2, Vec3};

use super::BsdfSample;
use super::fresnel::{fresnel_conductor, reflect};
use super::microfacet::{Distribution, Microfacet, Smith};
use crate::optics::thin_film::Coating;
use crate::spectrum::ior::ComplexIor;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Fresnel reflectance of a conductor of index `ior(λ)` = n + ik in a medium of index `ext` at
/// every sampled wavelength.
#[inline]
fn conductor_reflectance<const N: usize>(
    ior: &ComplexIor,
    ext: f32,
    coating: Option<&Coating>,
    cos_theta_i: f32,
    w: &SampledWavelengths<N>,
) -> SampledSpectrum<N> {
    if let Some(c) = coating {
        return SampledSpectrum(w.lambda.map(|l| {
            super::coated::on_conductor(c, ext, ior, cos_theta_i, l).r_unpolarised() as f32
        }));
    }
    SampledSpectrum(w.lambda.map(|l| {
        let (n, k) = ior.eval(l);
        fresnel_conductor(cos_theta_i, n / ext, k / ext)
    }))
}

/// A smooth metal: delta reflection wi = (−wo.x, −wo.y, wo.z) with f = F(λ)/cos θᵢ and pdf 1,
/// F the exact unpolarised conductor Fresnel term for n(λ) + ik(λ) relative to `ext_ior`.
///
/// One-sided: `None` unless `wo.z > 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Conductor {
    pub ior: ComplexIor,
    /// Index of the outside medium.
    pub ext_ior: f32,
    /// Thin-film layers on the metal (`coated.rs`): R(λ) of the stack replaces F.
    pub coating: Option<Box<Coating>>,
}

impl Conductor {
    pub fn new(ior: ComplexIor, ext_ior: f32) -> Self {
        Self {
            ior,
            ext_ior,
            coating: None,
        }
    }

    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = Vec3::new(-wo.x, -wo.y, wo.z);
        let f =
            conductor_reflectance(&self.ior, self.ext_ior, self.coating.as_deref(), wo.z, w) / wi.z;
        Some(BsdfSample {
            f,
            wi,
            pdf: 1.0,
            specular: true,
            transmission: false,
            dispersive: false,
            eta: 1.0,
        })
    }
}

/// A rough metal: GGX or Beckmann microfacets (roughness `alpha`, clamped to at least
/// [`MIN_ALPHA`](super::microfacet::MIN_ALPHA)) with height-correlated Smith G and the exact
/// conductor Fresnel term:
///
/// f = D(wm)·G(wo, wi)·F(wo·wm) / (4 cos θₒ cos θᵢ), wm = normalize(wo + wi),
///
/// sampled through [`Microfacet::sample_normal`] (the visible normals from `wo`):
/// pdf = p(wm)/(4 wo·wm) with p = [`Microfacet::normal_pdf`]. Reflections below
/// the horizon are rejected (`None`). Reciprocal. One-sided: zero unless `wo.z > 0` and
/// `wi.z > 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct RoughConductor {
    pub ior: ComplexIor,
    pub ext_ior: f32,
    /// Roughness α along the shading frame's first tangent (Mitsuba's ∂p/∂u) and the second;
    /// equal for an isotropic surface.
    pub alpha_u: f32,
    pub alpha_v: f32,
    pub distribution: Distribution,
    /// The masking–shadowing function (Mitsuba's scenes: separable).
    pub smith: Smith,
    /// Thin-film layers on the metal: R(λ) of the stack at the microfacet's cosine replaces F.
    pub coating: Option<Box<Coating>>,
}

impl RoughConductor {
    /// A GGX rough conductor.
    pub fn new(ior: ComplexIor, ext_ior: f32, alpha: f32) -> Self {
        Self {
            ior,
            ext_ior,
            alpha_u: alpha,
            alpha_v: alpha,
            distribution: Distribution::Ggx,
            smith: Smith::HeightCorrelated,
            coating: None,
        }
    }

    /// The same surface under thin-film layers.
    pub fn with_coating(self, coating: Option<Box<Coating>>) -> Self {
        Self { coating, ..self }
    }

    /// The same surface with roughness `alpha_u` along the first tangent, `alpha_v` along the
    /// second.
    pub fn with_anisotropy(self, alpha_u: f32, alpha_v: f32) -> Self {
        Self {
            alpha_u,
            alpha_v,
            ..self
        }
    }

    /// The same surface with another microfacet distribution.
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

    /// The half vector, or `None` if the pair cannot reflect.
    #[inline]
    fn half(wo: Vec3, wi: Vec3) -> Option<Vec3> {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return None;
        }
        let wm = (wo + wi).try_normalize()?;
        (wm.dot(wo) > 0.0).then_some(wm)
    }

    #[inline]
    pub fn eval<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let Some(wm) = Self::half(wo, wi) else {
            return SampledSpectrum::zero();
        };
        self.eval_half(&self.microfacet(), wo, wi, wm, w)
    }

    /// [`RoughConductor::eval`] for the half vector `wm` of (wo, wi).
    #[inline]
    fn eval_half<const N: usize>(
        &self,
        mf: &Microfacet,
        wo: Vec3,
        wi: Vec3,
        wm: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let k = mf.d(wm) * mf.g(wo, wi) / (4.0 * wo.z * wi.z);
        // wo·wm = wi·wm; their mean keeps the rounding symmetric (exact reciprocity).
        let cos = 0.5 * (wo.dot(wm) + wi.dot(wm));
        conductor_reflectance(&self.ior, self.ext_ior, self.coating.as_deref(), cos, w) * k
    }

    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(wm) = Self::half(wo, wi) else {
            return 0.0;
        };
        self.pdf_half(&self.microfacet(), wo, wm)
    }

    /// [`RoughConductor::pdf`] for the half vector `wm` of (wo, wi): the density of sampling wm
    /// times the reflection Jacobian 1/(4 wo·wm), sr⁻¹.
    #[inline]
    fn pdf_half(&self, mf: &Microfacet, wo: Vec3, wm: Vec3) -> f32 {
        mf.normal_pdf(wo, wm) / (4.0 * wo.dot(wm))
    }

    /// [`RoughConductor::eval`] and [`RoughConductor::pdf`] together, the half vector found
    /// once (the same values as the two calls).
    #[inline]
    pub fn eval_pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> (SampledSpectrum<N>, f32) {
        self.eval_pdf_with(&self.microfacet(), wo, wi, w)
    }

    /// [`RoughConductor::eval_pdf`] with the microfacet distribution `mf` in place of the
    /// material's own roughness (a textured α looked up at the hit).
    #[inline]
    pub fn eval_pdf_with<const N: usize>(
        &self,
        mf: &Microfacet,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> (SampledSpectrum<N>, f32) {
        let Some(wm) = Self::half(wo, wi) else {
            return (SampledSpectrum::zero(), 0.0);
        };
        (self.eval_half(mf, wo, wi, wm, w), self.pdf_half(mf, wo, wm))
    }

    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        self.sample_with(&self.microfacet(), wo, w, u)
    }

    /// [`RoughConductor::sample`] with the distribution `mf` (see
    /// [`RoughConductor::eval_pdf_with`]).
    #[inline]
    pub fn sample_with<const N: usize>(
        &self,
        mf: &Microfacet,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let wm = mf.sample_normal(wo, u);
        if wo.dot(wm) <= 0.0 {
            return None; // a back-facing normal (only at grazing views, from rounding)
        }
        let wi = reflect(wo, wm);
        if wi.z <= 0.0 {
            return None;
        }
        let (f, pdf) = self.eval_pdf_with(mf, wo, wi, w);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        Some(BsdfSample::reflection(f, wi, pdf))
    }
}
