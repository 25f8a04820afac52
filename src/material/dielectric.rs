//! The smooth (specular) dielectric interface, with dispersion.

use glam::Vec3;

use super::fresnel::{fresnel_dielectric, refract};
use super::{BsdfSample, TransportMode};
use crate::spectrum::ior::Ior;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A smooth interface between an outside medium of constant index `ext_ior` (the +z side) and
/// an inside of index `int_ior(λ)` (the −z side). Delta reflection and refraction only.
///
/// With η(λ) = int_ior(λ)/ext_ior, F(λ) the exact unpolarised Fresnel reflectance
/// ([`fresnel_dielectric`]) at cos θₒ = `wo.z`:
/// - reflection: wi = (−wo.x, −wo.y, wo.z), f = F/|cos θᵢ|, chosen with probability F(λ₀);
/// - transmission: wi from Snell's law at the hero wavelength λ₀, f = (1 − F)/|cos θᵢ|, times
///   1/η'² in [`TransportMode::Radiance`], where η' = n(wi side)/n(wo side) (η' = η for `wo`
///   outside, 1/η for `wo` inside); chosen with probability 1 − F(λ₀). Total internal
///   reflection has F = 1.
///
/// So the sample weight f·|cos θᵢ|/pdf is F(λ)/F(λ₀) for reflection and
/// (1 − F(λ))/(1 − F(λ₀))/η'² for transmission; in Importance mode the lobes' energies sum to
/// R + T = 1. If `int_ior` is dispersive a transmission sample is flagged `dispersive`; the
/// secondary wavelengths still get their own F and η' (but the hero's direction), for the
/// caller to drop. Reflection is not dispersive in direction.
#[derive(Clone, Debug, PartialEq)]
pub struct Dielectric {
    /// Index of the inside (−z side), as a function of λ in nm.
    pub int_ior: Ior,
    /// Index of the outside (+z side), e.g. 1.0 for vacuum, 1.000277 for air.
    pub ext_ior: f32,
    /// Thin-film layers on the outside face (`coated.rs`): they replace F and 1 − F by the
    /// stack's R(λ) and T(λ); the directions stay the bare interface's.
    pub coating: Option<Box<crate::optics::thin_film::Coating>>,
}

impl Dielectric {
    pub fn new(int_ior: Ior, ext_ior: f32) -> Self {
        Self {
            int_ior,
            ext_ior,
            coating: None,
        }
    }

    /// Relative index η(λ) = n_int(λ)/n_ext.
    #[inline]
    pub fn eta(&self, lambda_nm: f32) -> f32 {
        self.int_ior.eval(lambda_nm) / self.ext_ior
    }

    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 {
            return None;
        }
        if let Some(c) = &self.coating {
            return super::coated::dielectric_sample(
                c,
                self.ext_ior,
                &self.int_ior,
                wo,
                w,
                uc,
                mode,
            );
        }
        let etas = w.lambda.map(|l| self.eta(l));
        let fr = etas.map(|e| fresnel_dielectric(wo.z, e));
        let pr = fr[0];
        if uc < pr {
            let wi = Vec3::new(-wo.x, -wo.y, wo.z);
            let inv_cos = 1.0 / wi.z.abs();
            return Some(BsdfSample {
                f: SampledSpectrum(fr) * inv_cos,
                wi,
                pdf: pr,
                specular: true,
                transmission: false,
                dispersive: false,
                eta: 1.0,
            });
        }
        let (wi, etap) = refract(wo, Vec3::Z, etas[0])?;
        if wi.z == 0.0 || wi.z * wo.z >= 0.0 {
            return None;
        }
        Some(BsdfSample {
            f: transmitted(fr.map(|r| 1.0 - r), &etas, wo, wi, mode),
            wi,
            pdf: 1.0 - pr,
            specular: true,
            transmission: true,
            dispersive: self.int_ior.is_dispersive(),
            eta: etap,
        })
    }
}

/// A specular transmission's f per wavelength from its transmittances `t` (power fractions):
/// t/|cos θᵢ|, divided in [`TransportMode::Radiance`] by η'² = (n(wi side)/n(wo side))² at each
/// wavelength's relative index `etas` (inside over outside).
#[inline]
pub(super) fn transmitted<const N: usize>(
    t: [f32; N],
    etas: &[f32; N],
    wo: Vec3,
    wi: Vec3,
    mode: TransportMode,
) -> SampledSpectrum<N> {
    let inv_cos = 1.0 / wi.z.abs();
    let mut f = [0.0; N];
    for j in 0..N {
        f[j] = t[j] * inv_cos;
        if mode == TransportMode::Radiance {
            let ep = if wo.z > 0.0 { etas[j] } else { 1.0 / etas[j] };
            f[j] /= ep * ep;
        }
    }
    SampledSpectrum(f)
}
