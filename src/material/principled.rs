//! Mitsuba 3's `principled` BSDF: the Disney/Burley "principled" model (Burley 2012, 2015) as
//! Mitsuba 3.9.1 implements it (`src/bsdfs/principled.cpp`, `principledhelpers.h`), spectral
//! through the uplifted base colour. Its thin-sheet variant `principledthin` is in
//! `principled_thin.rs`.
//!
//! Lobes, each f(wo, wi) in sr⁻¹ without the cosine (the module conventions, `super`):
//! - **main specular**: anisotropic GGX of (α_u, α_v) from `roughness`² and `anisotropic`
//!   (Mitsuba's `calc_dist_params`), separable Smith G, a Fresnel term mixing the dielectric one
//!   of index `eta` with Schlick's for `metallic` (F0 = base colour) and `spec_tint`;
//! - **specular transmission** (weight (1 − metallic)·`spec_trans`): the rough dielectric with
//!   the colour √base, and in radiance mode the 1/η² of non-symmetric scattering;
//! - **clearcoat**: GTR1 of α = lerp(0.1, 0.001, `clearcoat_gloss`), Schlick F0 = 0.04 and a
//!   GGX G of α = 0.25, scaled by 0.25·`clearcoat`; as Mitsuba defines it, without the
//!   microfacet 1/(4 cos θₒ cos θᵢ);
//! - **diffuse** (weight (1 − metallic)(1 − spec_trans)): Burley's retro-reflective diffuse,
//!   flattened towards the Hanrahan–Krueger-like term by `flatness`;
//! - **sheen**: Schlick's weight of the half angle times `sheen`, tinted by `sheen_tint`.
//!
//! Front side only (wo.z > 0) except the dielectric lobes, which seen from inside are the plain
//! rough dielectric's reflection and transmission.
//!
//! Sampling (Mitsuba's): a visible GGX normal m is drawn first; a lobe is then chosen with
//! probabilities diffuse ∝ rate_d·brdf, clearcoat ∝ 0.25·rate_c·clearcoat, transmission ∝
//! rate_s·bsdf·(1 − F(m)), reflection ∝ rate_s·(1 − bsdf·(1 − F(m))). With the default rates
//! (all 1) the two specular ones sum to 1 whatever F is, so the choice among the lobes does not
//! depend on m, and [`Principled::pdf`] is the exact density of [`Principled::sample`]
//! (`tests/materials_chi2.rs` checks it).

use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

use super::disney::{
    DisneyAt, burley_diffuse, compatible, dist_params, ggx, gtr1_d, gtr1_pdf, gtr1_sample,
    half_vector, normalised, r0_eta, schlick, schlick_weight, smith_ggx1, tint,
};
use super::fresnel::{fresnel_dielectric, reflect, refract};
use super::{BsdfSample, TransportMode};
use crate::sampling::cosine_hemisphere;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use crate::texture::Texture;

/// A principled material: its parameters as (scalar or spectral) textures. A parameter that is
/// `None` was not given, and its lobe is absent (Mitsuba's `m_has_*` flags); given as 0 it is
/// `None` too (Mitsuba's `get_flag`).
#[derive(Clone, Debug, PartialEq)]
pub struct Principled {
    /// Base colour, a reflectance (dimensionless).
    pub base_color: Texture,
    /// Roughness in [0, 1]; α = roughness².
    pub roughness: Texture,
    pub anisotropic: Option<Texture>,
    pub spec_trans: Option<Texture>,
    pub metallic: Option<Texture>,
    pub clearcoat: Option<Texture>,
    pub clearcoat_gloss: Texture,
    pub sheen: Option<Texture>,
    pub sheen_tint: Option<Texture>,
    pub flatness: Option<Texture>,
    pub spec_tint: Option<Texture>,
    /// `principledthin`'s diffuse transmission in [0, 2] (Mitsuba halves it).
    pub diff_trans: Option<Texture>,
    /// Index of the inside relative to the outside (the thin sheet's own index).
    pub eta: f32,
    /// Mitsuba's sampling rates. Solid: [diffuse, main specular, clearcoat, unused]; thin:
    /// [specular reflection, specular transmission, diffuse reflection, diffuse transmission].
    pub rates: [f32; 4],
    /// `principledthin` rather than `principled`.
    pub thin: bool,
}

impl Principled {
    /// The parameters at a hit, `at` looking a texture up there.
    pub fn at_hit<const N: usize>(
        &self,
        at: impl Fn(&Texture) -> SampledSpectrum<N>,
        base: SampledSpectrum<N>,
        w: &SampledWavelengths<N>,
    ) -> DisneyAt {
        let one = |t: &Option<Texture>| t.as_ref().map_or(0.0, |t| at(t)[0]);
        let roughness = at(&self.roughness)[0];
        let aniso = one(&self.anisotropic);
        let has_aniso = self.anisotropic.is_some();
        let alpha = dist_params(aniso, roughness, has_aniso);
        let clearcoat = one(&self.clearcoat);
        let alpha_t = if self.thin {
            dist_params(aniso, (0.65 * self.eta - 0.35) * roughness, has_aniso)
        } else if self.clearcoat.is_some() {
            let gloss = at(&self.clearcoat_gloss)[0];
            [0.1 + (0.001 - 0.1) * gloss, 0.0]
        } else {
            [0.0; 2]
        };
        let lum = if self.spec_tint.is_some() || self.sheen_tint.is_some() {
            let cmf = crate::colour::cie::cmf();
            (0..N)
                .map(|i| cmf.y_bar(w.lambda[i]) * base[i])
                .sum::<f32>()
                / N as f32
        } else {
            1.0
        };
        DisneyAt {
            roughness,
            alpha,
            alpha_t,
            spec_trans: one(&self.spec_trans),
            metallic: one(&self.metallic),
            clearcoat,
            sheen: one(&self.sheen),
            sheen_tint: one(&self.sheen_tint),
            flatness: one(&self.flatness),
            spec_tint: one(&self.spec_tint),
            diff_trans: one(&self.diff_trans) / 2.0,
            lum,
        }
    }

    /// f(wo, wi) in sr⁻¹ per wavelength, without the cosine.
    pub fn eval<const N: usize>(
        &self,
        p: &DisneyAt,
        base: SampledSpectrum<N>,
        wo: Vec3,
        wi: Vec3,
        mode: TransportMode,
    ) -> SampledSpectrum<N> {
        if self.thin {
            return self.thin_eval(p, base, wo, wi);
        }
        let (ci, co) = (wo.z, wi.z);
        if ci == 0.0 || co == 0.0 {
            return SampledSpectrum::zero();
        }
        let (reflect, front) = (ci * co > 0.0, ci > 0.0);
        let brdf = (1.0 - p.metallic) * (1.0 - p.spec_trans);
        let bsdf = (1.0 - p.metallic) * p.spec_trans;
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let wh = half_vector(wo, wi, reflect, eta_path);
        let (cos_oh, cos_ih) = (wo.dot(wh), wi.dot(wh));
        let f_diel = fresnel_dielectric(cos_oh, self.eta);
        let ggx = ggx(p.alpha);
        let dg = ggx.d(wh) * ggx.g1(wo) * ggx.g1(wi);
        let mut f = SampledSpectrum::zero();
        if reflect && compatible(wh, wo, wi, ci, true) {
            // main specular reflection (Mitsuba's `principled_fresnel`)
            let fresnel = if front {
                let eta_it = if cos_oh >= 0.0 {
                    self.eta
                } else {
                    1.0 / self.eta
                };
                let mut fr =
                    SampledSpectrum::splat((1.0 - p.metallic) * (1.0 - p.spec_tint) * f_diel);
                if self.metallic.is_some() {
                    fr += base.map(|b| p.metallic * schlick(b, cos_oh, self.eta));
                }
                if self.spec_tint.is_some() {
                    let r0 = r0_eta(eta_it);
                    let k = (1.0 - p.metallic) * p.spec_tint;
                    fr += tint(base, p.lum).map(|c| k * schlick(c * r0, cos_oh, self.eta));
                }
                fr
            } else {
                SampledSpectrum::splat(bsdf * f_diel)
            };
            if f_diel > 0.0 {
                f += fresnel * (dg / (4.0 * ci.abs() * co.abs()));
            }
            if self.clearcoat.is_some() && p.clearcoat > 0.0 && front {
                let fcc = schlick(0.04, cos_oh, self.eta);
                let gcc = smith_ggx1(wo, wh, 0.25) * smith_ggx1(wi, wh, 0.25);
                f += 0.25 * p.clearcoat * fcc * gtr1_d(p.alpha_t[0], wh) * gcc;
            }
        }
        if !reflect
            && self.spec_trans.is_some()
            && bsdf > 0.0
            && f_diel < 1.0
            && compatible(wh, wo, wi, ci, false)
        {
            // rough dielectric transmission, Walter et al. 2007 eq. 21
            let scale = match mode {
                TransportMode::Radiance => 1.0 / (eta_path * eta_path),
                TransportMode::Importance => 1.0,
            };
            let denom = cos_oh + eta_path * cos_ih;
            let v = scale * (1.0 - f_diel) * dg * eta_path * eta_path * cos_oh * cos_ih
                / (ci * denom * denom);
            f += base.map(f32::sqrt) * (bsdf * v.abs() / co.abs());
        }
        if reflect && front {
            let cos_d = wh.dot(wi);
            if brdf > 0.0 {
                let k = burley_diffuse(p, ci.abs(), co.abs(), cos_d, self.flatness.is_some());
                f += base * (brdf * k * FRAC_1_PI);
            }
            if self.sheen.is_some() && p.sheen > 0.0 && p.metallic < 1.0 {
                f += self.sheen_colour(p, base)
                    * (p.sheen * (1.0 - p.metallic) * schlick_weight(cos_d.abs()));
            }
        }
        f
    }

    /// The sheen's colour: 1, or lerp(1, base/lum, sheen_tint) when `sheen_tint` is given.
    pub(super) fn sheen_colour<const N: usize>(
        &self,
        p: &DisneyAt,
        base: SampledSpectrum<N>,
    ) -> SampledSpectrum<N> {
        if self.sheen_tint.is_some() {
            tint(base, p.lum).map(|c| 1.0 + (c - 1.0) * p.sheen_tint)
        } else {
            SampledSpectrum::splat(1.0)
        }
    }

    /// Probabilities of the lobes [diffuse, clearcoat, transmission, reflection], normalised,
    /// for a microfacet of dielectric Fresnel reflectance `f_diel`.
    fn probabilities(&self, p: &DisneyAt, front: bool, f_diel: f32) -> [f32; 4] {
        let [rd, rs, rc, _] = self.rates;
        let brdf = (1.0 - p.metallic) * (1.0 - p.spec_trans);
        let bsdf = (1.0 - p.metallic) * p.spec_trans;
        let has_t = self.spec_trans.is_some();
        let pr = if front {
            rs * (1.0 - bsdf * (1.0 - f_diel))
        } else {
            f_diel
        };
        let pt = match (has_t, front) {
            (false, _) => 0.0,
            (true, true) => rs * bsdf * (1.0 - f_diel),
            (true, false) => 1.0 - f_diel,
        };
        let pc = if self.clearcoat.is_some() && front {
            0.25 * p.clearcoat * rc
        } else {
            0.0
        };
        let pd = if front { brdf * rd } else { 0.0 };
        normalised([pd, pc, pt, pr])
    }

    /// Density in sr⁻¹ of [`Principled::sample`] returning `wi`.
    pub fn pdf(&self, p: &DisneyAt, wo: Vec3, wi: Vec3) -> f32 {
        if self.thin {
            return self.thin_pdf(p, wo, wi);
        }
        let (ci, co) = (wo.z, wi.z);
        if ci == 0.0 || co == 0.0 {
            return 0.0;
        }
        let (reflect, front) = (ci * co > 0.0, ci > 0.0);
        // seen from inside an opaque one, nothing is sampled (nor reflected: f = 0 there); Mitsuba's
        // pdf is not 0 there, which no estimator notices
        if !front && (1.0 - p.metallic) * p.spec_trans <= 0.0 {
            return 0.0;
        }
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let wh = half_vector(wo, wi, reflect, eta_path);
        let (cos_oh, cos_ih) = (wo.dot(wh), wi.dot(wh));
        let [pd, pc, pt, pr] = self.probabilities(p, front, fresnel_dielectric(cos_oh, self.eta));
        // dωₕ/dωᵢ: 1/(4|wi·h|) for reflection, η²|wi·h|/(wo·h + η wi·h)² for transmission
        let jacobian = if reflect {
            1.0 / (4.0 * cos_ih).abs()
        } else {
            let d = cos_oh + eta_path * cos_ih;
            (eta_path * eta_path * cos_ih / (d * d)).abs()
        };
        let visible = ggx(p.alpha).visible_normal_pdf(wo * ci.signum(), wh);
        let mut pdf = 0.0;
        if reflect {
            pdf += pd * co * FRAC_1_PI;
            if compatible(wh, wo, wi, ci, true) {
                pdf += pr * visible * jacobian;
                if self.clearcoat.is_some() {
                    pdf += pc * gtr1_pdf(p.alpha_t[0], wh) * jacobian;
                }
            }
        } else if self.spec_trans.is_some() && compatible(wh, wo, wi, ci, false) {
            pdf += pt * visible * jacobian;
        }
        pdf
    }

    /// Samples `wi` given `wo` (Mitsuba's procedure, module docs); `uc` picks the lobe, `u` the
    /// direction in it. `None` for a rejected sample (wrong side, total internal reflection).
    pub fn sample<const N: usize>(
        &self,
        p: &DisneyAt,
        base: SampledSpectrum<N>,
        wo: Vec3,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        if self.thin {
            return self.thin_sample(p, base, wo, uc, u);
        }
        let ci = wo.z;
        let front = ci > 0.0;
        let bsdf = (1.0 - p.metallic) * p.spec_trans;
        if ci == 0.0 || !(front || bsdf > 0.0) {
            return None;
        }
        let m = ggx(p.alpha).sample_visible_normal(wo * ci.signum(), u);
        let [pd, pc, pt, _] = self.probabilities(p, front, fresnel_dielectric(wo.dot(m), self.eta));
        let (wi, transmission) = if uc < pd {
            (cosine_hemisphere(u), false)
        } else if uc < pd + pc {
            let mc = gtr1_sample(p.alpha_t[0], u);
            let wi = reflect(wo, mc);
            (compatible(mc, wo, wi, ci, true).then_some(wi)?, false)
        } else if uc < pd + pc + pt {
            let (wi, _) = refract(wo, m, self.eta)?;
            (compatible(m, wo, wi, ci, false).then_some(wi)?, true)
        } else {
            let wi = reflect(wo, m);
            (compatible(m, wo, wi, ci, true).then_some(wi)?, false)
        };
        // a reflection stays on wo's side, a transmission crosses (Mitsuba's masks)
        if (ci * wi.z < 0.0) != transmission || wi.z == 0.0 {
            return None;
        }
        let pdf = self.pdf(p, wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            f: self.eval(p, base, wo, wi, mode),
            wi,
            pdf,
            specular: false,
            transmission,
            dispersive: false,
            eta: match (transmission, front) {
                (false, _) => 1.0,
                (true, true) => self.eta,
                (true, false) => 1.0 / self.eta,
            },
        })
    }
}
