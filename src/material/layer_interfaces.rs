//! The interfaces of a layered BSDF ([`super::layered`]) as pbrt-v4 defines them
//! (`src/pbrt/bxdfs.h`, `bxdfs.cpp`; pbrt-v4 book §9.4–9.5): a dielectric coating (smooth, or
//! Trowbridge–Reitz microfacets), and the base under it, Lambertian or a conductor.
//!
//! Conventions are the module's (`super`): local frame, +z the normal, both directions away
//! from the surface, f in sr⁻¹ without the cosine. Each interface can be sampled or its pdf
//! asked for one kind of event only ([`Events`]), which the layered random walk needs: "the
//! light enters the slab" is a transmission, "it stays in the slab" a reflection. pdfs are per
//! steradian of `wi`, or for a delta lobe the discrete probability of choosing it; a delta
//! lobe's f is F/|cos θᵢ| and its `f()` and `pdf()` are 0. Failure (total internal reflection
//! on a sampled microfacet, a direction on the wrong side) returns None.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::TransportMode;
use super::fresnel::{fresnel_conductor, fresnel_dielectric, reflect, refract};
use super::microfacet::{Distribution, Microfacet};
use crate::sampling::cosine_hemisphere;
use crate::spectrum::SampledSpectrum;

/// Which events a sample or pdf may contain (pbrt-v4's `BxDFReflTransFlags`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Events {
    Reflection,
    Transmission,
    All,
}

impl Events {
    fn reflection(self) -> bool {
        self != Events::Transmission
    }
    fn transmission(self) -> bool {
        self != Events::Reflection
    }
}

/// A sampled direction at one interface.
#[derive(Clone, Copy, Debug)]
pub struct Scatter<const N: usize> {
    pub f: SampledSpectrum<N>,
    pub wi: Vec3,
    pub pdf: f32,
    pub specular: bool,
    pub transmission: bool,
}

/// pbrt-v4's Trowbridge–Reitz distribution: GGX with the height-correlated Smith G and
/// visible-normal sampling; None below α = 10⁻³ (its `EffectivelySmooth`).
pub fn trowbridge_reitz(alpha: [f32; 2]) -> Option<Microfacet> {
    (alpha[0].max(alpha[1]) >= 1e-3)
        .then(|| Microfacet::anisotropic(alpha[0], alpha[1], Distribution::Ggx))
}

/// pbrt-v4's `DielectricBxDF`: index `eta` = n(below)/n(above), smooth when `mf` is None.
#[derive(Clone, Copy, Debug)]
pub struct DielectricIf {
    pub eta: f32,
    pub mf: Option<Microfacet>,
}

/// The radiance scaling of a transmission in `mode`: 1/η'² for radiance (η' = n_t/n_i).
fn transmit_scale(mode: TransportMode, etap: f32) -> f32 {
    match mode {
        TransportMode::Radiance => 1.0 / (etap * etap),
        TransportMode::Importance => 1.0,
    }
}

impl DielectricIf {
    pub fn is_specular(&self) -> bool {
        self.eta == 1.0 || self.mf.is_none()
    }

    /// The generalised half vector of a pair on the +z side, with the relative index of the
    /// crossing, or None where pbrt-v4 gives 0 (grazing, or a back-facing microfacet).
    fn half(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, f32, bool)> {
        let (co, ci) = (wo.z, wi.z);
        let reflect = ci * co > 0.0;
        let etap = match (reflect, co > 0.0) {
            (true, _) => 1.0,
            (false, true) => self.eta,
            (false, false) => 1.0 / self.eta,
        };
        let wm = wi * etap + wo;
        if ci == 0.0 || co == 0.0 || wm.length_squared() == 0.0 {
            return None;
        }
        let wm = wm.normalize();
        let wm = if wm.z < 0.0 { -wm } else { wm };
        if wm.dot(wi) * ci < 0.0 || wm.dot(wo) * co < 0.0 {
            return None;
        }
        Some((wm, etap, reflect))
    }

    pub fn f<const N: usize>(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> SampledSpectrum<N> {
        let Some(mf) = self.mf.filter(|_| self.eta != 1.0) else {
            return SampledSpectrum::zero();
        };
        let Some((wm, etap, reflect)) = self.half(wo, wi) else {
            return SampledSpectrum::zero();
        };
        let fr = fresnel_dielectric(wo.dot(wm), self.eta);
        let v = if reflect {
            mf.d(wm) * mf.g(wo, wi) * fr / (4.0 * wi.z * wo.z).abs()
        } else {
            let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2) * wi.z * wo.z;
            mf.d(wm)
                * (1.0 - fr)
                * mf.g(wo, wi)
                * (wi.dot(wm) * wo.dot(wm) / denom).abs()
                * transmit_scale(mode, etap)
        };
        SampledSpectrum::splat(v)
    }

    /// The probabilities of reflection and transmission allowed by `ev` at Fresnel `fr`.
    fn odds(fr: f32, ev: Events) -> Option<(f32, f32)> {
        let pr = if ev.reflection() { fr } else { 0.0 };
        let pt = if ev.transmission() { 1.0 - fr } else { 0.0 };
        (pr + pt > 0.0).then_some((pr / (pr + pt), pt / (pr + pt)))
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3, ev: Events) -> f32 {
        let Some(mf) = self.mf.filter(|_| self.eta != 1.0) else {
            return 0.0;
        };
        let Some((wm, etap, reflect)) = self.half(wo, wi) else {
            return 0.0;
        };
        let Some((pr, pt)) = Self::odds(fresnel_dielectric(wo.dot(wm), self.eta), ev) else {
            return 0.0;
        };
        if reflect {
            mf.normal_pdf(wo, wm) / (4.0 * wo.dot(wm).abs()) * pr
        } else {
            let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
            mf.normal_pdf(wo, wm) * wi.dot(wm).abs() / denom * pt
        }
    }

    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
        ev: Events,
    ) -> Option<Scatter<N>> {
        let rough = self.mf.filter(|_| self.eta != 1.0);
        let wm = match rough {
            None => Vec3::Z,
            Some(mf) => mf.sample_normal(wo, u),
        };
        let fr = fresnel_dielectric(wo.dot(wm), self.eta);
        let (pr, pt) = Self::odds(fr, ev)?;
        if uc < pr {
            let wi = reflect(wo, wm);
            let (f, pdf) = match rough {
                None => (fr / wi.z.abs(), pr),
                Some(mf) => {
                    if wi.z * wo.z <= 0.0 {
                        return None;
                    }
                    let pdf = mf.normal_pdf(wo, wm) / (4.0 * wo.dot(wm).abs()) * pr;
                    let f = mf.d(wm) * mf.g(wo, wi) * fr / (4.0 * wi.z * wo.z).abs();
                    (f, pdf)
                }
            };
            return Some(Scatter {
                f: SampledSpectrum::splat(f),
                wi,
                pdf,
                specular: rough.is_none(),
                transmission: false,
            });
        }
        // refract about the (micro)normal: `refract` flips it to wo's side
        let (wi, etap) = refract(wo, wm, self.eta)?;
        let (f, pdf) = match rough {
            None => ((1.0 - fr) / wi.z.abs(), pt),
            Some(mf) => {
                if wi.z * wo.z >= 0.0 {
                    return None;
                }
                let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
                let pdf = mf.normal_pdf(wo, wm) * wi.dot(wm).abs() / denom * pt;
                let f = (1.0 - fr)
                    * mf.d(wm)
                    * mf.g(wo, wi)
                    * (wi.dot(wm) * wo.dot(wm) / (wi.z * wo.z * denom)).abs();
                (f, pdf)
            }
        };
        Some(Scatter {
            f: SampledSpectrum::splat(f * transmit_scale(mode, etap)),
            wi,
            pdf,
            specular: rough.is_none(),
            transmission: true,
        })
    }
}

/// The base under the coating: Lambertian of reflectance `r`, or a conductor of relative
/// index `eta` + i`k` per wavelength (pbrt-v4's `DiffuseBxDF`, `ConductorBxDF`).
#[derive(Clone, Copy, Debug)]
pub enum BaseIf<const N: usize> {
    Diffuse(SampledSpectrum<N>),
    Conductor {
        eta: SampledSpectrum<N>,
        k: SampledSpectrum<N>,
        mf: Option<Microfacet>,
    },
}

impl<const N: usize> BaseIf<N> {
    pub fn is_specular(&self) -> bool {
        matches!(self, BaseIf::Conductor { mf: None, .. })
    }

    /// The conductor's Fresnel reflectance per wavelength at |cos| = `c`.
    fn fresnel(eta: &SampledSpectrum<N>, k: &SampledSpectrum<N>, c: f32) -> SampledSpectrum<N> {
        let mut out = SampledSpectrum::zero();
        for j in 0..N {
            out[j] = fresnel_conductor(c, eta[j], k[j]);
        }
        out
    }

    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if wo.z * wi.z <= 0.0 {
            return SampledSpectrum::zero();
        }
        match self {
            BaseIf::Diffuse(r) => *r * (1.0 / PI),
            BaseIf::Conductor { mf: None, .. } => SampledSpectrum::zero(),
            BaseIf::Conductor {
                eta,
                k,
                mf: Some(mf),
            } => {
                let Some(wm) = (wi + wo).try_normalize() else {
                    return SampledSpectrum::zero();
                };
                let fr = Self::fresnel(eta, k, wo.dot(wm).abs());
                fr * (mf.d(wm) * mf.g(wo, wi) / (4.0 * wi.z * wo.z).abs())
            }
        }
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3, ev: Events) -> f32 {
        if !ev.reflection() || wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        match self {
            BaseIf::Diffuse(_) => wi.z.abs() / PI,
            BaseIf::Conductor { mf: None, .. } => 0.0,
            BaseIf::Conductor { mf: Some(mf), .. } => {
                let Some(wm) = (wi + wo).try_normalize() else {
                    return 0.0;
                };
                let wm = if wm.z < 0.0 { -wm } else { wm };
                mf.normal_pdf(wo, wm) / (4.0 * wo.dot(wm).abs())
            }
        }
    }

    pub fn sample(&self, wo: Vec3, u: Vec2, ev: Events) -> Option<Scatter<N>> {
        if !ev.reflection() || wo.z == 0.0 {
            return None;
        }
        let (f, wi, pdf, specular) = match self {
            BaseIf::Diffuse(r) => {
                let mut wi = cosine_hemisphere(u);
                if wo.z < 0.0 {
                    wi.z = -wi.z;
                }
                (*r * (1.0 / PI), wi, wi.z.abs() / PI, false)
            }
            BaseIf::Conductor { eta, k, mf: None } => {
                let wi = Vec3::new(-wo.x, -wo.y, wo.z);
                let c = wi.z.abs();
                (Self::fresnel(eta, k, c) * (1.0 / c), wi, 1.0, true)
            }
            BaseIf::Conductor {
                eta,
                k,
                mf: Some(mf),
            } => {
                let wm = mf.sample_normal(wo, u);
                let wi = reflect(wo, wm);
                if wo.z * wi.z <= 0.0 {
                    return None;
                }
                let pdf = mf.normal_pdf(wo, wm) / (4.0 * wo.dot(wm).abs());
                let fr = Self::fresnel(eta, k, wo.dot(wm).abs());
                let f = fr * (mf.d(wm) * mf.g(wo, wi) / (4.0 * wi.z * wo.z).abs());
                (f, wi, pdf, false)
            }
        };
        (pdf > 0.0).then_some(Scatter {
            f,
            wi,
            pdf,
            specular,
            transmission: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::uniform_sphere;

    fn rng(i: u64) -> f32 {
        let mut z = i.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A rough dielectric's sampled weights and its evaluated f estimate the same ∫ f|cos| dω,
    /// and its pdf integrates to the probability of a sample, for each kind of event and mode.
    /// The evaluated side uses uniform directions, whose estimate of a lobe compressed by
    /// refraction into the denser side (η² narrower) is skewed at any affordable count, so that
    /// crossing is checked from the denser side only (the same formulas with the roles swapped).
    #[test]
    fn rough_dielectric_samples_what_it_evaluates() {
        let d = DielectricIf {
            eta: 1.5,
            mf: trowbridge_reitz([0.224, 0.224]),
        };
        let n = 1_000_000u64;
        let above = Vec3::new(0.3, 0.1, 0.9).normalize();
        let below = Vec3::new(0.5, 0.0, -0.6).normalize();
        let cases = [
            (above, Events::Reflection),
            (below, Events::Reflection),
            (below, Events::Transmission),
            (below, Events::All),
        ];
        for (wo, ev) in cases {
            for mode in [TransportMode::Radiance, TransportMode::Importance] {
                let (mut ws, mut hits) = (Vec::new(), 0u64);
                let (mut we, mut wp) = (Vec::new(), Vec::new());
                for i in 0..n {
                    let (uc, u) = (rng(3 * i), Vec2::new(rng(3 * i + 1), rng(3 * i + 2)));
                    match d.sample::<1>(wo, uc, u, mode, ev) {
                        Some(s) => {
                            ws.push((s.f[0] * s.wi.z.abs() / s.pdf) as f64);
                            hits += 1;
                            let p = d.pdf(wo, s.wi, ev);
                            assert!((p - s.pdf).abs() <= 1e-2 * s.pdf, "{p} {}", s.pdf);
                        }
                        None => ws.push(0.0),
                    }
                    let wi = uniform_sphere(Vec2::new(rng(7 * i + 5), rng(7 * i + 6)));
                    let keep = match ev {
                        Events::All => true,
                        Events::Reflection => wi.z * wo.z > 0.0,
                        Events::Transmission => wi.z * wo.z < 0.0,
                    };
                    let f = if keep {
                        d.f::<1>(wo, wi, mode)[0] * wi.z.abs()
                    } else {
                        0.0
                    };
                    we.push(f as f64 * 4.0 * PI as f64);
                    wp.push(d.pdf(wo, wi, ev) as f64 * 4.0 * PI as f64);
                }
                let stat = |v: &[f64]| {
                    let m = v.iter().sum::<f64>() / v.len() as f64;
                    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len() as f64;
                    (m, (var / v.len() as f64).sqrt())
                };
                let ((s, ss), (e, se), (p, sp)) = (stat(&ws), stat(&we), stat(&wp));
                let h = hits as f64 / n as f64;
                let z_f = (s - e) / (ss * ss + se * se).sqrt();
                let z_p = (p - h) / sp;
                assert!(
                    z_f.abs() < 5.0 && z_p.abs() < 5.0,
                    "{wo:?} {ev:?} {mode:?}: sampled {s} evaluated {e} (z {z_f}); ∫pdf {p} hits {h} (z {z_p})"
                );
            }
        }
    }
}
