//! The pieces of the Disney/Burley principled model that Mitsuba 3.9.1's `principled` and
//! `principledthin` share (`principledhelpers.h`): the parameters at a hit, Schlick's Fresnel,
//! Burley's diffuse, GTR1 for the clearcoat, and the microfacet side checks.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

use super::microfacet::Ggx;
use crate::spectrum::SampledSpectrum;

/// A principled material's parameters at one surface point (its textures looked up once per
/// hit); the base colour is the [`super::Bsdf`]'s `albedo`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DisneyAt {
    pub roughness: f32,
    /// GGX (α_u, α_v) of the main specular lobe.
    pub alpha: [f32; 2],
    /// Thin: the transmission lobe's (α_u, α_v), from roughness × (0.65η − 0.35). Solid: the
    /// clearcoat's GTR1 α in `[0]`.
    pub alpha_t: [f32; 2],
    pub spec_trans: f32,
    pub metallic: f32,
    pub clearcoat: f32,
    pub sheen: f32,
    pub sheen_tint: f32,
    pub flatness: f32,
    pub spec_tint: f32,
    /// Thin: diffuse transmission, halved to [0, 1].
    pub diff_trans: f32,
    /// Mitsuba's spectral "luminance" of the base colour, the mean of ȳ(λ)·base(λ) over the
    /// path's wavelengths (ȳ peaking at 1), for the tints; 1 when no tint is given.
    pub lum: f32,
}

/// GGX of (α_u, α_v).
#[inline]
pub(super) fn ggx(alpha: [f32; 2]) -> Ggx {
    Ggx {
        alpha_u: alpha[0],
        alpha_v: alpha[1],
    }
}

/// Mitsuba's `calc_dist_params`: α = roughness², stretched by √(1 − 0.9·anisotropic) along u
/// and squeezed along v when anisotropic; at least 0.001.
pub(super) fn dist_params(anisotropic: f32, roughness: f32, has_anisotropic: bool) -> [f32; 2] {
    let r2 = roughness * roughness;
    if !has_anisotropic {
        return [r2.max(0.001); 2];
    }
    let aspect = (1.0 - 0.9 * anisotropic).sqrt();
    [(r2 / aspect).max(0.001), (r2 * aspect).max(0.001)]
}

/// The half vector of a reflection (wo + wi) or a refraction (wo + η·wi), on the +z side;
/// zero when degenerate.
pub(super) fn half_vector(wo: Vec3, wi: Vec3, reflect: bool, eta_path: f32) -> Vec3 {
    let h = (wo + wi * if reflect { 1.0 } else { eta_path }).normalize_or_zero();
    if h.z < 0.0 { -h } else { h }
}

/// Mitsuba's `mac_mic_compatibility`: both directions on the microfacet's sides a reflection
/// (or a refraction) needs, the microfacet `m` turned to the side of `wo` (cos θ = `ci`).
pub(super) fn compatible(m: Vec3, wo: Vec3, wi: Vec3, ci: f32, reflection: bool) -> bool {
    let m = if ci < 0.0 { -m } else { m };
    wo.dot(m) > 0.0
        && if reflection {
            wi.dot(m) > 0.0
        } else {
            wi.dot(m) < 0.0
        }
}

/// Schlick's weight (1 − cos)⁵, the cosine clamped to [0, 1].
#[inline]
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Mitsuba's `calc_schlick`: Schlick's Fresnel from `r0` at cos θ = `cos_i` (negative inside
/// the index `eta`); seen from the optically less dense side, with the transmitted cosine.
pub(super) fn schlick(r0: f32, cos_i: f32, eta: f32) -> f32 {
    let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
    let w = if eta_it > 1.0 {
        schlick_weight(cos_i.abs())
    } else {
        let cos_t2 = 1.0 - (1.0 - cos_i * cos_i) / (eta_it * eta_it);
        schlick_weight(cos_t2.max(0.0).sqrt())
    };
    r0 + (1.0 - r0) * w
}

/// The Fresnel reflectance at normal incidence of index ratio `eta`.
#[inline]
pub(super) fn r0_eta(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// The tint colour base/lum (1 where lum ≤ 0).
#[inline]
pub(super) fn tint<const N: usize>(base: SampledSpectrum<N>, lum: f32) -> SampledSpectrum<N> {
    if lum > 0.0 {
        base * (1.0 / lum)
    } else {
        SampledSpectrum::splat(1.0)
    }
}

/// Burley's diffuse with retro-reflection, lerped to the flattened term by `flatness` if
/// given (the factor of base/π; cos θ's are |cos|, `cos_d` the half angle's with wi).
pub(super) fn burley_diffuse(p: &DisneyAt, ci: f32, co: f32, cos_d: f32, flat: bool) -> f32 {
    let (fo, fi) = (schlick_weight(co), schlick_weight(ci));
    let f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    let rr = 2.0 * p.roughness * cos_d * cos_d;
    let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    if !flat {
        return f_diff + f_retro;
    }
    let fss90 = rr / 2.0;
    let fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
    let f_ss = 1.25 * (fss * (1.0 / (co + ci) - 0.5) + 0.5);
    (f_diff + f_retro) + (f_ss - (f_diff + f_retro)) * p.flatness
}

/// Lobe probabilities divided by their sum (all 0 if it is not positive).
pub(super) fn normalised(p: [f32; 4]) -> [f32; 4] {
    let total: f32 = p.iter().sum();
    if total > 0.0 {
        p.map(|x| x / total)
    } else {
        [0.0; 4]
    }
}

/// GTR1's D(m) = (α² − 1)/(π ln α² (1 + (α² − 1) cos²θₘ)) in sr⁻¹ (Burley 2012, eq. 4).
pub(super) fn gtr1_d(alpha: f32, m: Vec3) -> f32 {
    let a2 = alpha * alpha;
    let r = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * m.z * m.z));
    if r * m.z > 1e-20 { r } else { 0.0 }
}

/// Density of [`gtr1_sample`], D(m)·cos θₘ per sr of m.
pub(super) fn gtr1_pdf(alpha: f32, m: Vec3) -> f32 {
    if m.z < 0.0 {
        0.0
    } else {
        m.z * gtr1_d(alpha, m)
    }
}

/// A GTR1 normal: cos²θ = (1 − α^(2(1−u_y)))/(1 − α²), φ = 2π u_x.
pub(super) fn gtr1_sample(alpha: f32, u: Vec2) -> Vec3 {
    let a2 = alpha * alpha;
    let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
    let (sin_t, cos_t) = ((1.0 - cos2).max(0.0).sqrt(), cos2.max(0.0).sqrt());
    let (s, c) = (2.0 * PI * u.x).sin_cos();
    Vec3::new(c * sin_t, s * sin_t, cos_t)
}

/// Mitsuba's `smith_ggx1` for the clearcoat: 2/(1 + √(1 + α² tan²θ)), 1 at the pole, 0 when
/// `v` sees the back of `wh`.
pub(super) fn smith_ggx1(v: Vec3, wh: Vec3, alpha: f32) -> f32 {
    if v.dot(wh) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let c2 = v.z * v.z;
    2.0 / (1.0 + (1.0 + alpha * alpha * (1.0 - c2) / c2).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gtr1_samples_follow_their_pdf() {
        // ∫ pdf dω = 1 by midpoint quadrature in (cos θ, φ)
        let alpha = 0.05;
        let n = 20000;
        let mut s = 0.0f64;
        for i in 0..n {
            let c = (i as f64 + 0.5) / n as f64;
            let m = Vec3::new((1.0 - c * c).sqrt() as f32, 0.0, c as f32);
            s += gtr1_pdf(alpha, m) as f64 * 2.0 * std::f64::consts::PI / n as f64;
        }
        assert!((s - 1.0).abs() < 2e-3, "{s}");
        // the inverse CDF: cos θ of u_y = 0.5 has half the mass above it
        let m = gtr1_sample(alpha, Vec2::new(0.3, 0.5));
        let mut above = 0.0f64;
        for i in 0..n {
            let c = m.z as f64 + (1.0 - m.z as f64) * (i as f64 + 0.5) / n as f64;
            let v = Vec3::new((1.0 - c * c).sqrt() as f32, 0.0, c as f32);
            above += gtr1_pdf(alpha, v) as f64 * 2.0 * std::f64::consts::PI * (1.0 - m.z as f64)
                / n as f64;
        }
        assert!((above - 0.5).abs() < 5e-3, "{above}");
    }

    #[test]
    fn schlick_is_r0_at_normal_incidence_and_1_at_grazing() {
        assert!((schlick(0.04, 1.0, 1.5) - 0.04).abs() < 1e-7);
        assert!((schlick(0.04, 0.0, 1.5) - 1.0).abs() < 1e-6);
        // from inside past the critical angle: total reflection
        assert!((schlick(0.04, -0.1, 1.5) - 1.0).abs() < 1e-6);
    }
}
