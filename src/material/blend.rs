//! Mitsuba's `blendbsdf`: a linear blend of two materials by a weight that may be textured.

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample, Material, TransportMode};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// f = (1 − w)·f_a + w·f_b for the weight w ∈ [0, 1] at the hit (Mitsuba's `blendbsdf`: 0 is the
/// first material, 1 the second). Neither component is a blend or a mask.
///
/// Sampling picks component b with probability w, else a, and samples it. A delta lobe keeps
/// its own weight (f and the lobe probability both scale by the choice probability). A sample
/// from a non-delta lobe is returned with the *blended* f and pdf at its direction,
/// (1 − w)·f_a + w·f_b and (1 − w)·p_a + w·p_b: the density with which the blend as a whole
/// produces that direction (one-sample MIS with the balance heuristic, Veach 1997 §9.2.4), so
/// that the pdf a path tracer weighs against light sampling is the same one `pdf` returns.
#[derive(Clone, Debug, PartialEq)]
pub struct Blend {
    /// w in [0, 1]: a number or a grey image, the same at every wavelength.
    pub weight: crate::texture::Texture,
    pub a: Material,
    pub b: Material,
}

impl<const N: usize> Bsdf<'_, N> {
    /// The two components with this hit's albedos.
    #[inline]
    fn components<'b>(&self, m: &'b Blend) -> (Bsdf<'b, N>, Bsdf<'b, N>) {
        let a = Bsdf {
            material: &m.a,
            albedo: self.albedo,
            albedo_b: SampledSpectrum::zero(),
            weight: 1.0,
            perturb: self.perturb,
            alpha: self.alpha,
            spec_r: self.spec_r,
            spec_t: self.spec_t,
            disney: self.disney,
            fibre_h: self.fibre_h,
        };
        let b = Bsdf {
            material: &m.b,
            albedo: self.albedo_b,
            ..a
        };
        (a, b)
    }

    /// (1 − w)·(f_a, p_a) + w·(f_b, p_b); delta lobes contribute 0 to both.
    #[inline]
    pub(super) fn blend_eval_pdf(
        &self,
        m: &Blend,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> (SampledSpectrum<N>, f32) {
        let (a, b) = self.components(m);
        let wb = self.weight;
        let (fa, pa) = if wb < 1.0 {
            a.eval_pdf(wo, wi, w, mode)
        } else {
            (SampledSpectrum::zero(), 0.0)
        };
        let (fb, pb) = if wb > 0.0 {
            b.eval_pdf(wo, wi, w, mode)
        } else {
            (SampledSpectrum::zero(), 0.0)
        };
        (fa * (1.0 - wb) + fb * wb, (1.0 - wb) * pa + wb * pb)
    }

    /// Component b with probability w (using the rest of `uc`), else a; see [`Blend`].
    #[inline]
    pub(super) fn blend_sample(
        &self,
        m: &Blend,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        let (a, b) = self.components(m);
        let wb = self.weight;
        let (chosen, p, uc) = if uc < wb {
            (b, wb, uc / wb)
        } else {
            (
                a,
                1.0 - wb,
                ((uc - wb) / (1.0 - wb)).min(1.0 - f32::EPSILON / 2.0),
            )
        };
        let mut bs = chosen.sample(wo, w, uc, u, mode)?;
        if bs.specular {
            bs.f *= p;
            bs.pdf *= p;
        } else {
            let (f, pdf) = self.blend_eval_pdf(m, wo, bs.wi, w, mode);
            if !(pdf > 0.0) {
                return None;
            }
            // the dispersive flag stays: a transmission through a dispersive component is valid
            // at the hero wavelength only, in the blend as in the component
            bs.f = f;
            bs.pdf = pdf;
        }
        Some(bs)
    }
}
