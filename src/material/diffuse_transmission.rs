//! A diffuse reflector and transmitter: pbrt-v4's `diffusetransmission` (its
//! `DiffuseTransmissionBxDF`, pbrt-v4 `src/pbrt/bxdfs.h`), a Lambertian lobe on each side.

use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

use super::BsdfSample;
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::spectrum::SampledSpectrum;
use crate::texture::Texture;

/// f = R(λ)/π when `wo` and `wi` are on the same side, T(λ)/π when they are on opposite sides.
///
/// Two-sided and symmetric (f(wo, wi) = f(wi, wo) in both transport modes): the sides are
/// alike, so a two-sided surface may flip it to face the ray or not. Under a uniform
/// environment of radiance L it sends back R·L and passes T·L, for every `wo`: R + T ≤ 1
/// conserves energy (pbrt-v4 clamps R and T to [0, 1] each, not their sum; so does this).
///
/// Sampling chooses reflection with probability p_R = max R/(max R + max T) over the sampled
/// wavelengths (pbrt-v4's choice), then a cosine-weighted direction on that side; the density
/// of `wi` (sr⁻¹) is p_R·|cos θᵢ|/π on `wo`'s side and (1 − p_R)·|cos θᵢ|/π on the other.
#[derive(Clone, Debug, PartialEq)]
pub struct DiffuseTransmission {
    /// Reflectance R(λ), dimensionless, clamped to [0, 1] where looked up.
    pub reflectance: Texture,
    /// Transmittance T(λ), dimensionless, clamped to [0, 1] where looked up.
    pub transmittance: Texture,
}

/// The probability of choosing reflection for looked-up R and T; None when both are black.
#[inline]
fn reflect_probability<const N: usize>(
    r: SampledSpectrum<N>,
    t: SampledSpectrum<N>,
) -> Option<f32> {
    let pr = r.0.iter().fold(0.0f32, |a, &x| a.max(x));
    let pt = t.0.iter().fold(0.0f32, |a, &x| a.max(x));
    (pr + pt > 0.0).then(|| pr / (pr + pt))
}

impl DiffuseTransmission {
    /// f(wo, wi) in sr⁻¹ (no cosine) for the looked-up `r` and `t`.
    #[inline]
    pub fn eval<const N: usize>(
        wo: Vec3,
        wi: Vec3,
        r: SampledSpectrum<N>,
        t: SampledSpectrum<N>,
    ) -> SampledSpectrum<N> {
        if wo.z * wi.z > 0.0 {
            r * FRAC_1_PI
        } else if wo.z * wi.z < 0.0 {
            t * FRAC_1_PI
        } else {
            SampledSpectrum::zero()
        }
    }

    /// The density (sr⁻¹) with which [`DiffuseTransmission::sample`] returns `wi`.
    #[inline]
    pub fn pdf<const N: usize>(
        wo: Vec3,
        wi: Vec3,
        r: SampledSpectrum<N>,
        t: SampledSpectrum<N>,
    ) -> f32 {
        let Some(p) = reflect_probability(r, t) else {
            return 0.0;
        };
        let c = cosine_hemisphere_pdf(wi.z.abs());
        if wo.z * wi.z > 0.0 {
            p * c
        } else if wo.z * wi.z < 0.0 {
            (1.0 - p) * c
        } else {
            0.0
        }
    }

    /// Chooses a side with `uc`, a cosine-weighted direction on it with `u`. None when R and T
    /// are black or `wo` is in the surface.
    #[inline]
    pub fn sample<const N: usize>(
        wo: Vec3,
        r: SampledSpectrum<N>,
        t: SampledSpectrum<N>,
        uc: f32,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        let p = reflect_probability(r, t)?;
        if wo.z == 0.0 {
            return None;
        }
        let mut wi = cosine_hemisphere(u);
        let reflect = uc < p;
        // on wo's side for reflection, the other for transmission
        if (wo.z < 0.0) == reflect {
            wi.z = -wi.z;
        }
        let pdf = cosine_hemisphere_pdf(wi.z.abs()) * if reflect { p } else { 1.0 - p };
        if pdf <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            transmission: !reflect,
            ..BsdfSample::reflection(if reflect { r } else { t } * FRAC_1_PI, wi, pdf)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weight_is_the_chosen_sides_value_over_its_probability() {
        let r = SampledSpectrum::<4>([0.2, 0.3, 0.1, 0.25]);
        let t = SampledSpectrum::<4>([0.6, 0.1, 0.2, 0.3]);
        // p_R = 0.3/(0.3 + 0.6)
        let p = 1.0 / 3.0;
        for wo in [Vec3::new(0.0, 0.6, 0.8), Vec3::new(0.0, 0.6, -0.8)] {
            for (uc, reflect) in [(0.2, true), (0.5, false)] {
                let s = DiffuseTransmission::sample(wo, r, t, uc, Vec2::new(0.3, 0.7)).unwrap();
                assert_eq!(s.transmission, !reflect);
                assert_eq!(wo.z * s.wi.z > 0.0, reflect);
                let w = s.f * s.wi.z.abs() / s.pdf;
                let (v, q) = if reflect { (r, p) } else { (t, 1.0 - p) };
                for i in 0..4 {
                    assert!((w.0[i] - v.0[i] / q).abs() < 1e-5, "{w:?}");
                }
                assert!((s.pdf - DiffuseTransmission::pdf(wo, s.wi, r, t)).abs() < 1e-6);
                assert_eq!(s.f, DiffuseTransmission::eval(wo, s.wi, r, t));
            }
        }
        let zero = SampledSpectrum::<4>::zero();
        assert!(DiffuseTransmission::sample(Vec3::Z, zero, zero, 0.5, Vec2::splat(0.5)).is_none());
        assert_eq!(DiffuseTransmission::pdf(Vec3::Z, -Vec3::Z, zero, zero), 0.0);
    }
}
