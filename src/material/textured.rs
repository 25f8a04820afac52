//! Mitsuba's textured lobe parameters on conductors and dielectrics: a roughness α that varies
//! over the surface (`alpha`, `alpha_u`, `alpha_v` as textures) and the `specular_reflectance`
//! and `specular_transmittance` factors (spectra or textures, 1 by default), which scale the
//! reflected and the transmitted lobe without changing how they are sampled (as in Mitsuba).

use glam::{Vec2, Vec3};

use super::microfacet::Microfacet;
use super::{Bsdf, BsdfSample, Material, TransportMode};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use crate::texture::Texture;

/// A conductor or dielectric (smooth or rough) with textured parameters, looked up at the hit.
#[derive(Clone, Debug, PartialEq)]
pub struct TexturedLobes {
    /// α_u and α_v as grey textures, in place of the inner material's constants (rough
    /// materials only); None keeps them.
    pub alpha: Option<[Texture; 2]>,
    /// Whether the textures hold pbrt-v4's roughness r rather than α: α = √r
    /// (`remaproughness`), kept at 10⁻³ or more (below it pbrt-v4 turns the lobe specular).
    pub remap: bool,
    /// Factor on the reflected lobe, dimensionless.
    pub reflectance: Texture,
    /// Factor on the transmitted lobe (dielectrics), dimensionless.
    pub transmittance: Texture,
    /// A `Conductor`, `RoughConductor`, `Dielectric` or `RoughDielectric`.
    pub inner: Material,
}

impl TexturedLobes {
    /// The roughness at `uv`: the textures', else the inner material's (0 for smooth ones).
    #[inline]
    pub(super) fn alpha_at<const N: usize>(
        &self,
        uv: Vec2,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> [f32; 2] {
        match (&self.alpha, &self.inner) {
            // kept off 0, where a microfacet lobe degenerates (pbrt-v4 turns it specular)
            (Some([u, v]), _) if self.remap => {
                roughness_at([u, v], true, uv, p, w).map(|a| a.max(1e-3))
            }
            (Some([u, v]), _) => roughness_at([u, v], false, uv, p, w),
            (None, Material::RoughConductor(m)) => [m.alpha_u, m.alpha_v],
            (None, Material::RoughDielectric(m)) => [m.alpha_u, m.alpha_v],
            _ => [0.0; 2],
        }
    }
}

/// α [α_u, α_v] from grey textures at `uv` and the world position `p` (m): their values, or with `remap` (pbrt-v4's
/// `remaproughness`) their square roots.
#[inline]
pub fn roughness_at<const N: usize>(
    [u, v]: [&Texture; 2],
    remap: bool,
    uv: Vec2,
    p: Vec3,
    w: &SampledWavelengths<N>,
) -> [f32; 2] {
    let a = [u.sample_p(uv, p, w)[0], v.sample_p(uv, p, w)[0]];
    if remap {
        a.map(|r| r.max(0.0).sqrt())
    } else {
        a
    }
}

impl<const N: usize> Bsdf<'_, N> {
    /// The lobe factor for a pair on the same side (reflection) or not (transmission).
    #[inline]
    fn lobe_factor(&self, transmission: bool) -> SampledSpectrum<N> {
        if transmission {
            self.spec_t
        } else {
            self.spec_r
        }
    }

    #[inline]
    pub(super) fn textured_eval_pdf(
        &self,
        m: &TexturedLobes,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> (SampledSpectrum<N>, f32) {
        let (f, pdf) = match &m.inner {
            Material::RoughConductor(c) => {
                let mf = Microfacet::anisotropic(self.alpha[0], self.alpha[1], c.distribution)
                    .with_smith(c.smith);
                c.eval_pdf_with(&mf, wo, wi, w)
            }
            Material::RoughDielectric(d) => {
                let mf = Microfacet::anisotropic(self.alpha[0], self.alpha[1], d.distribution)
                    .with_smith(d.smith);
                d.eval_pdf_with(&mf, wo, wi, w, mode)
            }
            // delta lobes (and any other material, which the build refuses) have no density
            _ => (SampledSpectrum::zero(), 0.0),
        };
        (f * self.lobe_factor(wo.z * wi.z < 0.0), pdf)
    }

    #[inline]
    pub(super) fn textured_sample(
        &self,
        m: &TexturedLobes,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        let mut bs = match &m.inner {
            Material::RoughConductor(c) => {
                let mf = Microfacet::anisotropic(self.alpha[0], self.alpha[1], c.distribution)
                    .with_smith(c.smith);
                c.sample_with(&mf, wo, w, u)
            }
            Material::RoughDielectric(d) => {
                let mf = Microfacet::anisotropic(self.alpha[0], self.alpha[1], d.distribution)
                    .with_smith(d.smith);
                d.sample_with(&mf, wo, w, uc, u, mode)
            }
            Material::Conductor(c) => c.sample(wo, w),
            Material::Dielectric(d) => d.sample(wo, w, uc, mode),
            _ => None,
        }?;
        bs.f *= self.lobe_factor(bs.transmission);
        Some(bs)
    }
}
