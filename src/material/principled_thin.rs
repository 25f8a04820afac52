//! Mitsuba 3's `principledthin`: the principled model on a sheet of negligible thickness
//! (Burley 2015, §5), as Mitsuba 3.9.1 implements it (`src/bsdfs/principledthin.cpp`). Both
//! sides are alike: directions are first turned so that wo is on +z.
//!
//! Lobes (f in sr⁻¹, no cosine), with spec_trans = s and the halved diffuse transmission d:
//! - **specular reflection**: s · F_thin · D·G/(4 cos θₒ cos θᵢ), GGX of (α_u, α_v), F_thin the
//!   dielectric Fresnel of `eta` lerped to a tinted Schlick by `spec_tint`;
//! - **specular transmission**: s · base · (1 − F) · D·G/(4 cos θₒ |cos θᵢ|), wi mirrored through
//!   the sheet (no bending), GGX of roughness × (0.65η − 0.35);
//! - **diffuse reflection**: (1 − s)(1 − d) · base/π · Burley's diffuse (and its sheen);
//! - **diffuse transmission**: (1 − s) · d · base/π.
//!
//! No η² scaling: light leaves the sheet into the medium it came from.
//!
//! Sampling: a lobe with probability ∝ [s·r₀/2, s·r₁/2, r₂(1 − s)(1 − d), r₃(1 − s)·d] (the
//! rates r, 1 by default), independent of the directions, so [`Principled::pdf`] is exact.

use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

use super::BsdfSample;
use super::Principled;
use super::disney::{
    DisneyAt, burley_diffuse, compatible, ggx, normalised, r0_eta, schlick, schlick_weight, tint,
};
use super::fresnel::{fresnel_dielectric, reflect};
use crate::sampling::cosine_hemisphere;
use crate::spectrum::SampledSpectrum;

impl Principled {
    /// The sheet's f(wo, wi) per wavelength in sr⁻¹, without the cosine.
    pub(super) fn thin_eval<const N: usize>(
        &self,
        p: &DisneyAt,
        base: SampledSpectrum<N>,
        wo: Vec3,
        wi: Vec3,
    ) -> SampledSpectrum<N> {
        let Some((v, l, wh)) = turned(wo, wi) else {
            return SampledSpectrum::zero();
        };
        let (ci, co) = (v.z, l.z);
        let (s, d) = (p.spec_trans, p.diff_trans);
        let mut f = SampledSpectrum::zero();
        if self.spec_trans.is_some() && s > 0.0 {
            let f_diel = fresnel_dielectric(v.dot(wh), self.eta);
            if co > 0.0 && compatible(wh, v, l, ci, true) {
                let g = ggx(p.alpha);
                let dg = g.d(wh) * g.g1(v) * g.g1(l);
                let fr = if self.spec_tint.is_some() {
                    let r0 = r0_eta(self.eta);
                    let cos = v.dot(wh);
                    tint(base, p.lum).map(|c| {
                        let fs = schlick(c * r0, cos, self.eta);
                        f_diel + (fs - f_diel) * p.spec_tint
                    })
                } else {
                    SampledSpectrum::splat(f_diel)
                };
                f += fr * (s * dg / (4.0 * ci * co));
            }
            if co < 0.0 && compatible(wh, v, l, ci, false) {
                let g = ggx(p.alpha_t);
                let dg = g.d(wh) * g.g1(v) * g.g1(l);
                f += base * (s * (1.0 - f_diel) * dg / (4.0 * ci * co.abs()));
            }
        }
        if co > 0.0 && s < 1.0 && d < 1.0 {
            let cos_d = wh.dot(l);
            let k = burley_diffuse(p, ci, co, cos_d, self.flatness.is_some());
            f += base * ((1.0 - s) * (1.0 - d) * k * FRAC_1_PI);
            if self.sheen.is_some() && p.sheen > 0.0 {
                let w = p.sheen * (1.0 - s) * (1.0 - d) * schlick_weight(cos_d.abs());
                f += self.sheen_colour(p, base) * w;
            }
        }
        if self.diff_trans.is_some() && co < 0.0 && s < 1.0 && d > 0.0 {
            f += base * ((1.0 - s) * d * FRAC_1_PI);
        }
        f
    }

    /// Probabilities of [specular reflection, specular transmission, diffuse reflection,
    /// diffuse transmission], normalised.
    fn thin_probabilities(&self, p: &DisneyAt) -> [f32; 4] {
        let [r0, r1, r2, r3] = self.rates;
        let (s, d) = (p.spec_trans, p.diff_trans);
        let has_s = self.spec_trans.is_some();
        normalised([
            if has_s { s * r0 / 2.0 } else { 0.0 },
            if has_s { s * r1 / 2.0 } else { 0.0 },
            r2 * (1.0 - s) * (1.0 - d),
            if self.diff_trans.is_some() {
                r3 * (1.0 - s) * d
            } else {
                0.0
            },
        ])
    }

    /// Density in sr⁻¹ of [`Principled::sample`] returning `wi` from the sheet.
    pub(super) fn thin_pdf(&self, p: &DisneyAt, wo: Vec3, wi: Vec3) -> f32 {
        let Some((v, l, wh)) = turned(wo, wi) else {
            return 0.0;
        };
        let co = l.z;
        let [psr, pst, pdr, pdt] = self.thin_probabilities(p);
        let mut pdf = 0.0;
        if self.spec_trans.is_some() {
            // wh is the half vector of wo and wi mirrored to wo's side: dωₕ/dωᵢ = 1/(4 wi·h)
            let jacobian = 1.0 / (4.0 * Vec3::new(l.x, l.y, co.abs()).dot(wh)).abs();
            if co > 0.0 && compatible(wh, v, l, v.z, true) {
                pdf += psr * ggx(p.alpha).visible_normal_pdf(v, wh) * jacobian;
            }
            if co < 0.0 && compatible(wh, v, l, v.z, false) {
                pdf += pst * ggx(p.alpha_t).visible_normal_pdf(v, wh) * jacobian;
            }
        }
        if co > 0.0 {
            pdf += pdr * co * FRAC_1_PI;
        } else if self.diff_trans.is_some() {
            pdf += pdt * -co * FRAC_1_PI;
        }
        pdf
    }

    /// Samples `wi` from the sheet given `wo`.
    pub(super) fn thin_sample<const N: usize>(
        &self,
        p: &DisneyAt,
        base: SampledSpectrum<N>,
        wo: Vec3,
        uc: f32,
        u: Vec2,
    ) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 {
            return None;
        }
        let sign = wo.z.signum();
        let v = wo * sign;
        let [psr, pst, pdr, _] = self.thin_probabilities(p);
        let l = if uc < psr {
            let m = ggx(p.alpha).sample_visible_normal(v, u);
            let l = reflect(v, m);
            (l.z > 0.0 && compatible(m, v, l, v.z, true)).then_some(l)?
        } else if uc < psr + pst {
            let m = ggx(p.alpha_t).sample_visible_normal(v, u);
            let r = reflect(v, m);
            let l = Vec3::new(r.x, r.y, -r.z);
            (l.z < 0.0 && compatible(m, v, l, v.z, false)).then_some(l)?
        } else if uc < psr + pst + pdr {
            cosine_hemisphere(u)
        } else if self.diff_trans.is_some() {
            -cosine_hemisphere(u)
        } else {
            return None;
        };
        let wi = l * sign;
        let pdf = self.thin_pdf(p, wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            f: self.thin_eval(p, base, wo, wi),
            wi,
            pdf,
            specular: false,
            transmission: l.z < 0.0,
            dispersive: false,
            eta: 1.0,
        })
    }
}

/// wo and wi turned so that wo is on +z, and the half vector of wo and wi mirrored to its
/// side; `None` when either is in the plane of the sheet.
fn turned(wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3, Vec3)> {
    if wo.z == 0.0 || wi.z == 0.0 {
        return None;
    }
    let sign = wo.z.signum();
    let (v, l) = (wo * sign, wi * sign);
    let wh = (v + Vec3::new(l.x, l.y, l.z.abs())).normalize_or_zero();
    Some((v, l, wh))
}
