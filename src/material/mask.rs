//! Mitsuba's `mask`: a partly transparent surface.

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample, Material, TransportMode};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A partly transparent surface (Mitsuba's `mask`): f = α·f_inner for the opacity α at the hit,
/// plus a straight-through delta lobe of weight 1 − α. The nested material is never a mask.
#[derive(Clone, Debug, PartialEq)]
pub struct Mask {
    /// Opacity α in [0, 1]: a number or a grey image, the same at every wavelength.
    pub opacity: crate::texture::Texture,
    pub inner: Material,
}

impl<const N: usize> Bsdf<'_, N> {
    /// The nested material of a mask, with this hit's albedo; [`Bsdf::weight`] is the opacity.
    #[inline]
    pub(super) fn masked<'b>(&self, m: &'b Mask) -> Bsdf<'b, N> {
        Bsdf {
            weight: 1.0,
            ..self.with_material(&m.inner)
        }
    }

    /// Straight through with probability 1 − α, else the nested material with α·f and α·pdf
    /// (the same sample weight), as Mitsuba's `mask` samples.
    #[inline]
    pub(super) fn mask_sample(
        &self,
        m: &Mask,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        let a = self.weight;
        if uc >= a {
            return (wo.z != 0.0).then(|| BsdfSample {
                f: SampledSpectrum::splat((1.0 - a) / wo.z.abs()),
                wi: -wo,
                pdf: 1.0 - a,
                specular: true,
                transmission: true,
                dispersive: false,
                eta: 1.0,
            });
        }
        let mut bs = self.masked(m).sample(wo, w, uc / a, u, mode)?;
        bs.f *= a;
        bs.pdf *= a;
        Some(bs)
    }
}
