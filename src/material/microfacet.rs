//! The GGX (Trowbridge–Reitz) and Beckmann microfacet distributions ([`Microfacet`]); GGX with
//! the Smith shadowing model (Walter et al. 2007, "Microfacet Models for Refraction through
//! Rough Surfaces") and sampling of the distribution of visible normals (Heitz 2018, "Sampling
//! the GGX Distribution of Visible Normals", JCGT 7(4)).
//!
//! Directions are in the local shading frame (macro-normal +z). Microfacet normals `wm` are
//! always taken on the +z side; a direction on the −z side sees the mirrored configuration
//! (D depends on cos²θₘ only).

use super::erf::{erf, erfc_parts, erfinv};
pub use super::smith::Smith;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// GGX with roughness `alpha_u` along the shading frame's first tangent (x) and `alpha_v` along
/// the second (y): slope-space widths; α = 0 would be a perfect mirror.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    pub alpha_u: f32,
    pub alpha_v: f32,
}

/// Smallest roughness used in the formulas: below it D overflows in `f32`.
pub const MIN_ALPHA: f32 = 1e-3;

impl Ggx {
    /// An isotropic distribution of roughness `alpha`, clamped to at least [`MIN_ALPHA`].
    pub fn new(alpha: f32) -> Self {
        Self {
            alpha_u: alpha.max(MIN_ALPHA),
            alpha_v: alpha.max(MIN_ALPHA),
        }
    }

    /// Normal distribution D(wm) in sr⁻¹ (normalised so that ∫ D(wm) cos θₘ dωₘ = 1 over the
    /// upper hemisphere); `wm` unit length. Written as 1 / (π α_u α_v (x²/α_u² + y²/α_v² + z²)²),
    /// the usual 1/(π α_u α_v cos⁴θₘ (1 + tan²θₘ (cos²φ/α_u² + sin²φ/α_v²))²) without the
    /// cancellation near the pole.
    #[inline]
    pub fn d(&self, wm: Vec3) -> f32 {
        if wm.z <= 0.0 {
            return 0.0;
        }
        let (x, y) = (wm.x / self.alpha_u, wm.y / self.alpha_v);
        let t = x * x + y * y + wm.z * wm.z;
        1.0 / (PI * self.alpha_u * self.alpha_v * t * t)
    }

    /// Smith's auxiliary function Λ(w) = (√(1 + α(φ)² tan²θ) − 1)/2 with α(φ)² tan²θ =
    /// (α_u² x² + α_v² y²)/z² (infinite at the horizon).
    #[inline]
    pub fn lambda(&self, w: Vec3) -> f32 {
        let cos2 = w.z * w.z;
        if cos2 == 0.0 {
            return f32::INFINITY;
        }
        let (x, y) = (self.alpha_u * w.x, self.alpha_v * w.y);
        0.5 * ((1.0 + (x * x + y * y) / cos2).sqrt() - 1.0)
    }

    /// Smith masking G1(w) = 1/(1 + Λ(w)).
    #[inline]
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated Smith masking–shadowing G(wo, wi) = 1/(1 + Λ(wo) + Λ(wi)) (Heitz 2014,
    /// "Understanding the Masking-Shadowing Function"); symmetric in its arguments.
    #[inline]
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Density of visible normals seen from `w`, D_w(wm) = G1(w)/|cos θ| · D(wm) · ⟨ŵ, wm⟩₊, in
    /// sr⁻¹ of `wm`, where ŵ is `w` flipped to the +z side. This is the density of
    /// [`Ggx::sample_visible_normal`].
    #[inline]
    pub fn visible_normal_pdf(&self, w: Vec3, wm: Vec3) -> f32 {
        visible_pdf(w, wm, |w| self.lambda(w), |wm| self.d(wm))
    }

    /// Samples a microfacet normal (on the +z side) from the distribution of normals visible from
    /// `w` (w on either side; the −z side is mirrored), following Heitz 2018: stretch the view
    /// into the α = 1 configuration, sample the projected hemisphere there, unstretch.
    #[inline]
    pub fn sample_visible_normal(&self, w: Vec3, u: Vec2) -> Vec3 {
        let (au, av) = (self.alpha_u, self.alpha_v);
        let mut vh = Vec3::new(au * w.x, av * w.y, w.z).normalize();
        if vh.z < 0.0 {
            vh = -vh;
        }
        // Orthonormal basis around the stretched view direction.
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
        } else {
            Vec3::X
        };
        let t2 = vh.cross(t1);
        // Uniform point on the unit disk, then squash the half of it that the view's
        // foreshortening hides.
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let mut p2 = r * phi.sin();
        let s = 0.5 * (1.0 + vh.z);
        p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
        // Lift onto the hemisphere around vh.
        let pz = (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
        let nh = p1 * t1 + p2 * t2 + pz * vh;
        // Unstretch.
        Vec3::new(au * nh.x, av * nh.y, nh.z.max(1e-6)).normalize()
    }
}

/// Which microfacet normal distribution a rough material uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Distribution {
    /// GGX (Trowbridge–Reitz), sampled through its visible normals ([`Ggx`]).
    #[default]
    Ggx,
    /// Beckmann (Walter et al. 2007, eqs. 25–27), sampled through its visible normals.
    Beckmann,
}

/// The density of normals visible from `w` (either side, ŵ its +z image) for a distribution
/// of Smith Λ `lambda` and normals `d`: D_w(wm) = G1(w)/cos θ̂ · D(wm) · ⟨ŵ, wm⟩₊ with
/// G1 = 1/(1 + Λ), sr⁻¹ of `wm` (Heitz 2018, eq. 1).
#[inline]
fn visible_pdf(w: Vec3, wm: Vec3, lambda: impl Fn(Vec3) -> f32, d: impl Fn(Vec3) -> f32) -> f32 {
    if w.z == 0.0 {
        return 0.0;
    }
    let wu = if w.z < 0.0 { -w } else { w };
    let c = wu.dot(wm);
    if c <= 0.0 {
        return 0.0;
    }
    1.0 / (1.0 + lambda(w)) / wu.z * d(wm) * c
}

/// Slopes (x̃, ỹ) of the α = 1 Beckmann surface's microfacets visible from a direction at
/// cos θ = `cos_t` (> 0) in the x–z plane: density ∝ (cos θ − x̃ sin θ)₊ e^{−x̃²−ỹ²}/π
/// (Heitz & d'Eon 2014, §4 and its Beckmann case). ỹ is Gaussian, ỹ = erf⁻¹(2u₂ − 1); x̃ inverts
/// the CDF ½(1 + erf x̃) + tan θ·e^{−x̃²}/(2√π) over x̃ < cot θ (normalised by its value 1 + Λ
/// at cot θ) by Newton steps on X = erf x̃, safeguarded by bisection (the scheme of Jakob 2014,
/// "An Improved Visible Normal Sampling Routine for the Beckmann Distribution").
fn beckmann_visible_slopes(cos_t: f64, u: Vec2) -> (f64, f64) {
    let ux = (u.x as f64).clamp(1e-7, 1.0 - 1e-7);
    let uy = (u.y as f64).clamp(1e-7, 1.0 - 1e-7);
    let y = erfinv(2.0 * uy - 1.0);
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    if sin_t < 1e-7 {
        return (erfinv(2.0 * ux - 1.0), y);
    }
    let tan_t = sin_t / cos_t;
    let cot_t = cos_t / sin_t;
    let k = tan_t / std::f64::consts::PI.sqrt();
    let hi0 = erf(cot_t);
    let norm = 1.0 / (1.0 + hi0 + k * (-cot_t * cot_t).exp());
    let (mut lo, mut hi) = (-1.0f64, hi0);
    // start from the CDF without the tan θ term
    let mut xx = (2.0 * ux - 1.0).clamp(lo, hi);
    for _ in 0..40 {
        if !(xx > lo && xx < hi) {
            xx = 0.5 * (lo + hi);
        }
        let s = erfinv(xx);
        let value = norm * (1.0 + xx + k * (-s * s).exp()) - ux;
        if value.abs() < 1e-9 {
            break;
        }
        if value > 0.0 {
            hi = xx;
        } else {
            lo = xx;
        }
        let deriv = norm * (1.0 - tan_t * s);
        xx -= value / deriv;
    }
    (erfinv(xx.clamp(-1.0 + 1e-15, hi0)), y)
}

/// A microfacet distribution of roughness `alpha_u` along the shading frame's first tangent
/// (x, Mitsuba's ∂p/∂u) and `alpha_v` along the second (y), each at least [`MIN_ALPHA`], with
/// the Smith G of its own Λ (`smith`); local directions, `wm` on the +z side (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    pub alpha_u: f32,
    pub alpha_v: f32,
    pub kind: Distribution,
    pub smith: Smith,
}

impl Microfacet {
    /// An isotropic distribution.
    pub fn new(alpha: f32, kind: Distribution) -> Self {
        Self::anisotropic(alpha, alpha, kind)
    }

    /// Roughness `alpha_u` along x and `alpha_v` along y.
    pub fn anisotropic(alpha_u: f32, alpha_v: f32, kind: Distribution) -> Self {
        Self {
            alpha_u: alpha_u.max(MIN_ALPHA),
            alpha_v: alpha_v.max(MIN_ALPHA),
            kind,
            smith: Smith::HeightCorrelated,
        }
    }

    /// The same distribution with masking–shadowing `smith`.
    pub fn with_smith(self, smith: Smith) -> Self {
        Self { smith, ..self }
    }

    #[inline]
    fn ggx(&self) -> Ggx {
        Ggx {
            alpha_u: self.alpha_u,
            alpha_v: self.alpha_v,
        }
    }

    /// Normal distribution D(wm) in sr⁻¹, ∫ D cos θₘ dωₘ = 1 over the upper hemisphere.
    /// Beckmann: exp(−(x²/α_u² + y²/α_v²)/z²) / (π α_u α_v z⁴) for wm = (x, y, z).
    #[inline]
    pub fn d(&self, wm: Vec3) -> f32 {
        match self.kind {
            Distribution::Ggx => self.ggx().d(wm),
            Distribution::Beckmann => {
                if wm.z <= 0.0 {
                    return 0.0;
                }
                let cos2 = wm.z * wm.z;
                let (x, y) = (wm.x / self.alpha_u, wm.y / self.alpha_v);
                (-(x * x + y * y) / cos2).exp() / (PI * self.alpha_u * self.alpha_v * cos2 * cos2)
            }
        }
    }

    /// Smith's Λ(w). Beckmann (Walter et al. 2007, eq. 27 before its rational fit), with
    /// a = 1/(α(φ) tan θ), α(φ) tan θ = √(α_u² x² + α_v² y²)/|z|:
    /// Λ = (erf(a) − 1)/2 + e^{−a²}/(2a√π); 0 at the pole, ∞ at the horizon.
    #[inline]
    pub fn lambda(&self, w: Vec3) -> f32 {
        match self.kind {
            Distribution::Ggx => self.ggx().lambda(w),
            Distribution::Beckmann => {
                let cos2 = (w.z * w.z) as f64;
                if cos2 == 0.0 {
                    return f32::INFINITY;
                }
                let (x, y) = ((self.alpha_u * w.x) as f64, (self.alpha_v * w.y) as f64);
                let at = ((x * x + y * y) / cos2).sqrt();
                if at == 0.0 {
                    return 0.0;
                }
                let a = 1.0 / at;
                let (p, e) = erfc_parts(a);
                // (−erfc(a) + e^{−a²}/(a√π)) / 2
                (0.5 * e * (1.0 / (a * std::f64::consts::PI.sqrt()) - p)).max(0.0) as f32
            }
        }
    }

    /// Smith G(wo, wi) as `smith` defines it (see [`Smith`]).
    #[inline]
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (lo, li) = (self.lambda(wo), self.lambda(wi));
        match self.smith {
            Smith::HeightCorrelated => 1.0 / (1.0 + lo + li),
            Smith::Separable => 1.0 / ((1.0 + lo) * (1.0 + li)),
        }
    }

    /// Samples a microfacet normal on the +z side from the distribution of normals visible from
    /// `w` (either side; the −z side is mirrored). GGX: [`Ggx::sample_visible_normal`];
    /// Beckmann: stretch the view to α = 1, sample the visible slopes there (the slope CDF
    /// inverted by Newton steps in the erf domain), turn them to the view's azimuth, unstretch (Heitz & d'Eon
    /// 2014, §4; Mitsuba 3 samples Beckmann's visible normals by default too).
    #[inline]
    pub fn sample_normal(&self, w: Vec3, u: Vec2) -> Vec3 {
        match self.kind {
            Distribution::Ggx => self.ggx().sample_visible_normal(w, u),
            Distribution::Beckmann => {
                let (au, av) = (self.alpha_u as f64, self.alpha_v as f64);
                let (wx, wy, wz) = (w.x as f64, w.y as f64, w.z as f64);
                let (mut sx, mut sy, mut sz) = (au * wx, av * wy, wz);
                let len = (sx * sx + sy * sy + sz * sz).sqrt();
                (sx, sy, sz) = (sx / len, sy / len, sz / len);
                if sz < 0.0 {
                    (sx, sy, sz) = (-sx, -sy, -sz);
                }
                let (x, y) = beckmann_visible_slopes(sz, u);
                let r = (sx * sx + sy * sy).sqrt();
                let (c, s) = if r > 1e-12 {
                    (sx / r, sy / r)
                } else {
                    (1.0, 0.0)
                };
                let (rx, ry) = (c * x - s * y, s * x + c * y);
                let (mx, my) = (-rx * au, -ry * av);
                let len = (mx * mx + my * my + 1.0).sqrt();
                Vec3::new((mx / len) as f32, (my / len) as f32, (1.0 / len) as f32)
            }
        }
    }

    /// Density of [`Microfacet::sample_normal`] in sr⁻¹ of `wm`: the visible normals' D_w(wm) =
    /// G1(w)/|cos θ| · D(wm) · ⟨ŵ, wm⟩₊, ŵ being `w` flipped to the +z side.
    #[inline]
    pub fn normal_pdf(&self, w: Vec3, wm: Vec3) -> f32 {
        match self.kind {
            Distribution::Ggx => self.ggx().visible_normal_pdf(w, wm),
            Distribution::Beckmann => visible_pdf(w, wm, |w| self.lambda(w), |wm| self.d(wm)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Midpoint quadrature over the upper hemisphere in (cos θ, φ): calls `f(wm, dω)` for
    /// 4000 × 64 cells, with cos θ = 1 − s² to resolve the peak at the pole.
    fn hemisphere(mut f: impl FnMut(Vec3, f64)) {
        let (nc, np) = (4000, 64);
        for i in 0..nc {
            let s = (i as f64 + 0.5) / nc as f64;
            let c = 1.0 - s * s;
            let jac = 2.0 * s / nc as f64;
            let st = (1.0 - c * c).max(0.0).sqrt();
            for j in 0..np {
                let p = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / np as f64;
                let wm = Vec3::new((st * p.cos()) as f32, (st * p.sin()) as f32, c as f32);
                f(wm, jac * 2.0 * std::f64::consts::PI / np as f64);
            }
        }
    }

    /// Beckmann: ∫ D cos θₘ dωₘ = 1, the sampler's density integrates to 1, and the Smith Λ
    /// satisfies the projected-area identity ∫ D(wm) ⟨w, wm⟩₊ dωₘ = (1 + Λ(w)) cos θ (Heitz 2014,
    /// eq. 7 with G1 = 1/(1 + Λ)), which checks Λ independently of its formula.
    #[test]
    fn beckmann_is_normalised_and_lambda_matches_projected_area() {
        let cases = [
            (0.05f32, 0.05f32),
            (0.3, 0.3),
            (1.0, 1.0),
            (0.1, 0.4),
            (0.6, 0.15),
        ];
        for kind in [Distribution::Beckmann, Distribution::Ggx] {
            for (au, av) in cases {
                projected_area_identity(Microfacet::anisotropic(au, av, kind));
            }
        }
    }

    fn projected_area_identity(m: Microfacet) {
        let alpha = (m.alpha_u, m.alpha_v, m.kind);
        for (theta, phi_o) in [(0.0f64, 0.0f64), (45.0, 0.0), (80.0, 0.0), (60.0, 50.0)] {
            let (t, po) = (theta.to_radians(), phi_o.to_radians());
            let w = Vec3::new(
                (t.sin() * po.cos()) as f32,
                (t.sin() * po.sin()) as f32,
                t.cos() as f32,
            );
            let (mut sd, mut sp, mut proj) = (0.0f64, 0.0f64, 0.0f64);
            hemisphere(|wm, dw| {
                sd += m.d(wm) as f64 * wm.z as f64 * dw;
                sp += m.normal_pdf(w, wm) as f64 * dw;
                proj += m.d(wm) as f64 * (w.dot(wm) as f64).max(0.0) * dw;
            });
            let want = (1.0 + m.lambda(w) as f64) * w.z as f64;
            assert!((sd - 1.0).abs() < 2e-3, "{alpha:?}: ∫D cos = {sd}");
            assert!((sp - 1.0).abs() < 2e-3, "{alpha:?} θ {theta}: ∫pdf = {sp}");
            assert!(
                (proj / want - 1.0).abs() < 3e-3,
                "{alpha:?} θ {theta} φ {phi_o}: ∫D⟨w,wm⟩ = {proj}, (1 + Λ) cos θ = {want}"
            );
        }
    }

    /// ∫ D(wm) cos θₘ dωₘ = 1 and ∫ D_w(wm) dωₘ = 1, by the midpoint rule in (cos θ, φ).
    #[test]
    fn distributions_are_normalised() {
        for alpha in [0.05f32, 0.3, 1.0] {
            let g = Ggx::new(alpha);
            let w = Vec3::new(0.6, 0.0, 0.8);
            let (mut sd, mut sv) = (0.0f64, 0.0f64);
            hemisphere(|wm, dw| {
                sd += g.d(wm) as f64 * wm.z as f64 * dw;
                sv += g.visible_normal_pdf(w, wm) as f64 * dw;
            });
            assert!((sd - 1.0).abs() < 2e-3, "alpha {alpha}: ∫D cos = {sd}");
            assert!((sv - 1.0).abs() < 2e-3, "alpha {alpha}: ∫D_w = {sv}");
        }
    }
}
