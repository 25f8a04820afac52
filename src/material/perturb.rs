//! Mitsuba's `normalmap` and `bumpmap`: a nested material evaluated in a perturbed shading
//! frame.
//!
//! The perturbed frame P is expressed in the hit's own local shading frame (normal +z), as
//! Mitsuba builds it: a normal map's texel (r, g, b) is the local normal 2·(r, g, b) − 1; a bump
//! map of height h (scaled) moves ∂p/∂u and ∂p/∂v along the normal by ∂h/∂u and ∂h/∂v, and P's
//! normal is their cross product, turned to the geometric normal's side. P's first tangent is
//! ∂p/∂u made perpendicular to its normal.
//!
//! Evaluation follows Mitsuba 3.9.1: the nested material sees directions in P, a direction
//! counts only where it lies on the same side of the unperturbed and the perturbed surface, and
//! values and sample weights carry the bump-terminator shadowing of Conty Estevez, Lecocq and
//! Stein 2019 ("A Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem",
//! Ray Tracing Gems ch. 12), G₁(ωᵢ) = 2/(1 + √(1 + α² tan²θᵢ)) with α² = clamp(tan²θ_d / 8,
//! 0, 1), θᵢ the angle of ωᵢ (toward the light) from the unperturbed normal and θ_d that of P's
//! normal (measured: Mitsuba 3.9.1's values are exactly this; the density is not shadowed).
//! Where the direction `wo` (toward the viewer, or the previous vertex) lies below P, P's normal
//! is mirrored about the unperturbed one, (x, y, z) → (−x, −y, z), as Mitsuba 3.9.1 does (also
//! measured), so that grazing views of a strongly tilted map still see a surface.
//! Mitsuba's BSDFs include the cosine, taken in P; spectrace's exclude it and the integrator
//! multiplies by |cos θᵢ| of the unperturbed frame, so the values here carry
//! |cos θᵢ in P| / |cos θᵢ|: the product is the same. Densities are per solid angle, the same in
//! any frame.
//!
//! That value is not symmetric in its directions. Particles (importance transport: `wo` toward
//! the light, `wi` toward the camera) need the adjoint, f*(wo, wi) = f(wi, wo) (Veach 1997
//! §3.7.6): the frame as seen from `wi`, the cosine ratio and shadowing on `wo`, the nested
//! material in its own importance mode. Light tracing and `bdpt` then estimate what `path`
//! does (measured on the `bumps` reference scene).

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample, Material, TransportMode};
use crate::geometry::Frame;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Mitsuba's `normalmap`: `map` holds raw triples (linear, not spectra), one local normal per
/// texel encoded as (n + 1)/2.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    pub map: crate::texture::Texture,
    pub inner: Material,
    /// Evaluate as pbrt-v4 evaluates its `normalmap` (see [`BumpMap::pbrt`]).
    pub pbrt: bool,
}

/// Mitsuba's `bumpmap`: a grey `height` texture (in m per unit of the height's value times
/// `scale`, relative to ∂p/∂u and ∂p/∂v) displacing the shading normal.
#[derive(Clone, Debug, PartialEq)]
pub struct BumpMap {
    pub height: crate::texture::Texture,
    pub scale: f32,
    pub inner: Material,
    /// Evaluate as pbrt-v4 evaluates its `displacement` (`BumpMap` and `BSDF::f` in
    /// `src/pbrt/materials.h`, `bsdf.h`): the nested material in P with the cosine taken in P,
    /// and nothing else: no bump-terminator shadowing, no mirrored normal, and a direction
    /// counts wherever P's material takes it, even below the unperturbed surface.
    pub pbrt: bool,
}

/// A hit's surface derivatives in its own local shading frame (normal +z), for the perturbed
/// frames: ∂p/∂u and ∂p/∂v in m per unit u and v, and the unit geometric normal; and where
/// the hit is on a mesh (triangle `prim`, barycentric weights `bary` of its stored corners),
/// for mesh attributes; and the hit's world position `p` (m), for textures mapped by position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalSurface {
    pub uv: Vec2,
    pub p: Vec3,
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    pub n_geom: Vec3,
    pub prim: u32,
    pub bary: [f32; 3],
}

impl LocalSurface {
    /// A flat surface parameterised along the frame's axes, for lookups without geometry.
    pub fn flat(uv: Vec2) -> Self {
        Self {
            uv,
            p: Vec3::ZERO,
            dpdu: Vec3::X,
            dpdv: Vec3::Y,
            n_geom: Vec3::Z,
            prim: 0,
            bary: [1.0, 0.0, 0.0],
        }
    }
}

/// The frame with normal `n` (local, need not be unit) and first tangent ∂p/∂u made
/// perpendicular to it; the unperturbed frame where `n` is degenerate.
fn frame(n: Vec3, dpdu: Vec3) -> Frame {
    match n.try_normalize() {
        Some(n) => Frame::from_normal_tangent(n, dpdu),
        None => Frame::from_normal(Vec3::Z),
    }
}

/// The bump-terminator shadowing G₁ (see the module docs) for P's normal at cos θ_d =
/// `cos_d` from the unperturbed one and a direction at cos θᵢ = `cos_i` from it; in (0, 1].
#[inline]
pub fn shadowing(cos_d: f32, cos_i: f32) -> f32 {
    let cd2 = cos_d.abs().min(1.0).powi(2);
    let alpha2 = (0.125 * (1.0 - cd2) / cd2).clamp(0.0, 1.0);
    let ci2 = cos_i.abs().max(1e-6).powi(2);
    let tan2_i = (1.0 - ci2) / ci2;
    2.0 / (1.0 + (1.0 + alpha2 * tan2_i).sqrt())
}

impl NormalMap {
    /// P at `s`: normal 2·texel − 1.
    #[inline]
    pub(super) fn frame(&self, s: &LocalSurface) -> Frame {
        frame(self.map.vector(s.uv) * 2.0 - Vec3::ONE, s.dpdu)
    }
}

impl BumpMap {
    /// P at `s`: ∂p/∂u′ = ∂p/∂u + n·(scale·∂h/∂u − n·∂p/∂u), likewise for v, normal
    /// ∂p/∂u′ × ∂p/∂v′ on the geometric normal's side (Mitsuba's `bumpmap`).
    #[inline]
    pub(super) fn frame(&self, s: &LocalSurface) -> Frame {
        let g = self.height.gradient(s.uv) * self.scale;
        let du = Vec3::new(s.dpdu.x, s.dpdu.y, g.x);
        let dv = Vec3::new(s.dpdv.x, s.dpdv.y, g.y);
        let mut n = du.cross(dv);
        if n.dot(s.n_geom) < 0.0 {
            n = -n;
        }
        frame(n, s.dpdu)
    }
}

impl<const N: usize> Bsdf<'_, N> {
    /// The nested material of a normal or bump map, evaluated in [`Bsdf::perturb`].
    #[inline]
    fn perturbed_inner(&self) -> Bsdf<'_, N> {
        let inner = match self.material {
            Material::NormalMap(m) => &m.inner,
            Material::BumpMap(m) => &m.inner,
            other => other,
        };
        Bsdf {
            perturb: Frame::from_normal(Vec3::Z),
            ..self.with_material(inner)
        }
    }

    /// Whether this is a pbrt-v4 bump or normal map ([`BumpMap::pbrt`]).
    #[inline]
    fn pbrt_bump(&self) -> bool {
        match self.material {
            Material::BumpMap(m) => m.pbrt,
            Material::NormalMap(m) => m.pbrt,
            _ => false,
        }
    }

    /// P as seen from `wo`: [`Bsdf::perturb`], or its normal mirrored about the unperturbed one
    /// where `wo` lies below it (see the module docs; pbrt-v4 never mirrors it).
    #[inline]
    fn frame_for(&self, wo: Vec3) -> Frame {
        let p = self.perturb;
        if p.n.dot(wo) >= 0.0 || self.pbrt_bump() {
            p
        } else {
            Frame::from_normal_tangent(Vec3::new(-p.n.x, -p.n.y, p.n.z), p.s)
        }
    }

    /// |cos θ in P| / |cos θ| · G₁(wi) for `wi` (local) and its image `pi` in P (normal `n`),
    /// or None where they lie on opposite sides (or at the unperturbed horizon). pbrt-v4's bump
    /// map: the ratio alone, on either side.
    #[inline]
    fn cos_ratio(&self, n: Vec3, wi: Vec3, pi: Vec3) -> Option<f32> {
        if self.pbrt_bump() {
            return (wi.z.abs() > 1e-7).then(|| pi.z.abs() / wi.z.abs());
        }
        (wi.z * pi.z > 0.0 && wi.z.abs() > 1e-7)
            .then(|| pi.z.abs() / wi.z.abs() * shadowing(n.z, wi.z))
    }

    #[inline]
    pub(super) fn perturbed_eval_pdf(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> (SampledSpectrum<N>, f32) {
        let p = self.frame_for(wo);
        let (po, pi) = (p.to_local(wo), p.to_local(wi));
        let inner = self.perturbed_inner();
        if mode == TransportMode::Importance {
            // the adjoint: f(wi, wo) of radiance transport, with the density of sampling wi
            return (
                self.perturbed_adjoint(wo, wi, w),
                inner.pdf(po, pi, w, mode),
            );
        }
        let Some(c) = self.cos_ratio(p.n, wi, pi) else {
            return (SampledSpectrum::zero(), 0.0);
        };
        let (f, pdf) = inner.eval_pdf(po, pi, w, mode);
        (f * c, pdf)
    }

    /// The importance-transport value f*(wo, wi) = f(wi, wo): P as seen from `wi` (the camera
    /// side), the nested material in importance mode (its own adjoint), the cosine ratio and
    /// shadowing on `wo` (the light side).
    #[inline]
    fn perturbed_adjoint(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let p = self.frame_for(wi);
        let (po, pi) = (p.to_local(wo), p.to_local(wi));
        match self.cos_ratio(p.n, wo, po) {
            Some(c) => {
                self.perturbed_inner()
                    .eval(po, pi, w, TransportMode::Importance)
                    * c
            }
            None => SampledSpectrum::zero(),
        }
    }

    #[inline]
    pub(super) fn perturbed_sample(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        let p = self.frame_for(wo);
        let mut bs = self
            .perturbed_inner()
            .sample(p.to_local(wo), w, uc, u, mode)?;
        let wi = p.to_world(bs.wi);
        if mode == TransportMode::Importance {
            // the adjoint value (see `perturbed_eval_pdf`); a delta lobe cannot be evaluated
            // again, so it takes the cosine ratio of `wo` in the frame it was sampled in
            bs.f = if bs.specular {
                bs.f * self.cos_ratio(p.n, wo, p.to_local(wo))?
            } else {
                self.perturbed_adjoint(wo, wi, w)
            };
        } else {
            bs.f *= self.cos_ratio(p.n, wi, bs.wi)?;
        }
        if bs.f.is_zero() {
            return None;
        }
        bs.wi = wi;
        bs.transmission = (wi.z > 0.0) != (wo.z > 0.0);
        Some(bs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// G₁ against values Mitsuba 3.9.1's `normalmap` returns (eval over the unshadowed model)
    /// for a normal tilted by 30.03° (a 1 × 1 PNG of bytes (191, 128, 238)) and light at θᵢ.
    #[test]
    fn shadowing_matches_mitsuba() {
        let n = Vec3::new(191.0, 128.0, 238.0) / 255.0 * 2.0 - Vec3::ONE;
        let cd = n.normalize().z;
        for (deg, want) in [
            (30.0f32, 0.996583),
            (60.0, 0.970820),
            (80.0, 0.791859),
            (85.0, 0.566802),
            (89.0, 0.157690),
        ] {
            let g = shadowing(cd, deg.to_radians().cos());
            assert!((g - want).abs() < 2e-4, "θ {deg}: {g}, Mitsuba {want}");
        }
        assert_eq!(
            shadowing(1.0, 0.01),
            1.0,
            "an unperturbed normal shadows nothing"
        );
        assert!(shadowing(0.0, 0.0) > 0.0 && shadowing(0.0, 0.0).is_finite());
    }
}
