//! The Lambertian (ideal diffuse) reflector.

use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

use super::BsdfSample;
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::spectrum::SampledSpectrum;
use crate::texture::Texture;

/// Ideal diffuse reflection, f = ρ(λ)/π, sampled with the cosine-weighted hemisphere.
///
/// One-sided: f = 0 unless `wo.z > 0` and `wi.z > 0`; the scene flips the shading frame for
/// two-sided surfaces. Under a uniform environment of radiance L it reflects ρ·L (the
/// directional albedo is ρ for every `wo`), so ρ ≤ 1 conserves energy.
#[derive(Clone, Debug, PartialEq)]
pub struct Lambert {
    /// Reflectance ρ(λ), dimensionless, in [0, 1], possibly varying over the surface.
    pub reflectance: Texture,
}

impl Lambert {
    pub fn new(reflectance: impl Into<Texture>) -> Self {
        Self {
            reflectance: reflectance.into(),
        }
    }

    #[inline]
    pub fn eval<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        rho: SampledSpectrum<N>,
    ) -> SampledSpectrum<N> {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return SampledSpectrum::zero();
        }
        rho * FRAC_1_PI
    }

    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        cosine_hemisphere_pdf(wi.z)
    }

    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        rho: SampledSpectrum<N>,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = cosine_hemisphere(u);
        let pdf = cosine_hemisphere_pdf(wi.z);
        if pdf <= 0.0 {
            return None;
        }
        Some(BsdfSample::reflection(rho * FRAC_1_PI, wi, pdf))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{SampledWavelengths, Spectrum};

    #[test]
    fn lambert_weight_is_reflectance_and_one_sided() {
        let m = Lambert::new(Spectrum::Constant(0.7));
        let w = SampledWavelengths::<4> {
            lambda: [400.0, 500.0, 600.0, 700.0],
            pdf: [1.0; 4],
        };
        let wo = Vec3::new(0.0, 0.6, 0.8);
        let rho = m.reflectance.sample(Vec2::ZERO, &w);
        let s = m.sample(wo, rho, Vec2::new(0.3, 0.7)).unwrap();
        let weight = s.f * s.wi.z / s.pdf;
        assert!(weight.0.iter().all(|&x| (x - 0.7).abs() < 1e-5));
        assert_eq!(s.pdf, m.pdf(wo, s.wi));
        assert!(m.sample(-wo, rho, Vec2::new(0.3, 0.7)).is_none());
        assert!(m.eval(wo, -s.wi, rho).is_zero());
        assert_eq!(m.pdf(-wo, s.wi), 0.0);
    }
}
