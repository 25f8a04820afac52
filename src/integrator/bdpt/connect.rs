//! The connections of bidirectional path tracing: what strategy (s, t) contributes before its
//! MIS weight, for t = 1 (a light vertex seen through the lens), s = 1 (next-event estimation)
//! and s, t ≥ 2 (an edge between the subpaths' ends), with the visibility or, in a scene with
//! media, the transmittance between the two ends.

use glam::{Vec2, Vec3};

use super::media;
use super::vertex::{Kind, Vertex};
use crate::geometry::{spawn_ray, spawn_ray_to};
use crate::integrator::{Integrator, MAX_CROSSINGS};
use crate::material::TransportMode;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// The two subpaths and a strategy's use of them, for the connections below.
pub(super) struct Ends<'b, 'a, const N: usize> {
    pub light: &'b [Vertex<'a, N>],
    pub camera: &'b [Vertex<'a, N>],
    pub s: usize,
    pub t: usize,
    pub w: &'b SampledWavelengths<N>,
}

impl<'a, const N: usize> Ends<'_, 'a, N> {
    /// t = 1: the light subpath's last vertex seen by the camera through the lens point it
    /// samples from `u`: the contribution (W·m⁻²·sr⁻¹·nm⁻¹ times the pixel count), the lens
    /// vertex, and the raster position.
    pub fn to_lens(
        &self,
        it: &Integrator<'_>,
        u: Vec2,
        margin: f32,
        track: &mut Sampler,
    ) -> Option<(SampledSpectrum<N>, Vertex<'a, N>, Vec2)> {
        let qs = &self.light[self.s - 1];
        if !qs.connectible(it) {
            return None;
        }
        let c = it.scene.camera.connect(qs.p, u, margin)?;
        let mut v = Vertex::new(
            Kind::Camera,
            c.p_lens,
            SampledSpectrum::splat(c.weight),
            0.0,
        );
        v.medium = it.scene.camera_medium;
        let l = qs.beta
            * qs.f(c.wi, self.w, TransportMode::Importance)
            * (qs.cos_shading(c.wi) * c.weight);
        if l.is_zero() {
            return None;
        }
        let tr = reach(it, qs, &v, self.w, track)?;
        Some((l * tr, v, c.raster))
    }

    /// s = 1: next-event estimation from the camera subpath's last vertex with the light
    /// point it samples from `u`: the contribution and the light vertex.
    pub fn to_light(
        &self,
        it: &Integrator<'_>,
        u: Vec2,
        track: &mut Sampler,
    ) -> Option<(SampledSpectrum<N>, Vertex<'a, N>)> {
        let (scene, w) = (it.scene, self.w);
        let pt = &self.camera[self.t - 1];
        if !pt.connectible(it) {
            return None;
        }
        let (li, p_sel, ux) = it.lights.pick_reuse(u.x)?;
        let light = &scene.lights[li];
        let ls = light.sample_li(&scene.shapes, pt.p, w, Vec2::new(ux, u.y))?;
        if ls.li.is_zero() || !(ls.pdf > 0.0) {
            return None;
        }
        let mut v = Vertex::new(
            Kind::Light { light: li as u32 },
            ls.p,
            ls.li * (1.0 / (p_sel * ls.pdf)),
            0.0,
        );
        v.p_error = ls.p_error;
        v.ng = if ls.distance.is_finite() {
            ls.n
        } else {
            Vec3::ZERO
        };
        v.d = ls.wi;
        v.pdf_fwd = v.pdf_light_origin(it, pt);
        let l = pt.beta * pt.f(ls.wi, w, TransportMode::Radiance) * v.beta * pt.cos_shading(ls.wi);
        if l.is_zero() {
            return None;
        }
        let tr = reach(it, pt, &v, w, track)?;
        Some((l * tr, v))
    }

    /// s, t ≥ 2: an edge between the two subpaths' last vertices.
    pub fn edge(&self, it: &Integrator<'_>, track: &mut Sampler) -> Option<SampledSpectrum<N>> {
        let (qs, pt) = (&self.light[self.s - 1], &self.camera[self.t - 1]);
        if !qs.connectible(it) || !pt.connectible(it) {
            return None;
        }
        let d = qs.p - pt.p;
        let d2 = d.length_squared();
        if !(d2 > 0.0) {
            return None;
        }
        let wi = d / d2.sqrt();
        let g = pt.cos_shading(wi) * qs.cos_shading(wi) / d2;
        let l = qs.beta
            * qs.f(-wi, self.w, TransportMode::Importance)
            * pt.f(wi, self.w, TransportMode::Radiance)
            * pt.beta
            * g;
        if l.is_zero() {
            return None;
        }
        Some(l * reach(it, pt, qs, self.w, track)?)
    }
}

/// What reaches `b` from `a` along the segment between them, per wavelength: 1 where nothing
/// blocks it in a scene without media; with media, the transmittance through them and the
/// `null` and sheet surfaces on the way (`media::transmittance`). None if blocked.
fn reach<const N: usize>(
    it: &Integrator<'_>,
    a: &Vertex<'_, N>,
    b: &Vertex<'_, N>,
    w: &SampledWavelengths<N>,
    track: &mut Sampler,
) -> Option<SampledSpectrum<N>> {
    if it.scene.media.is_empty() {
        return visible(it, a, b).then(|| SampledSpectrum::splat(1.0));
    }
    let tr = media::transmittance(it, a, b, w, track);
    (!tr.is_zero()).then_some(tr)
}

/// Whether nothing blocks the segment between `a` and `b` (either may be at infinity, but not
/// both). Where the scene skips `null` surfaces ([`Integrator::skip_null`]) they do not block
/// it, as pbrt-v4's `Integrator::Tr` lets its connections through `interface` surfaces.
fn visible<const N: usize>(it: &Integrator<'_>, a: &Vertex<'_, N>, b: &Vertex<'_, N>) -> bool {
    let scene = it.scene;
    // the segment from (p, p_error, ng) on toward the far end
    let (from, to) = if a.at_infinity(it) { (b, a) } else { (a, b) };
    let ray_from = |p, p_error, n| {
        if to.at_infinity(it) {
            spawn_ray(p, p_error, n, to.d)
        } else {
            spawn_ray_to(p, p_error, n, to.p, to.p_error, to.ng)
        }
    };
    let mut ray = ray_from(from.p, from.p_error, from.ng);
    if !scene.integrator.skip_null {
        return !scene.accel.occluded(&scene.shapes, &ray);
    }
    for _ in 0..MAX_CROSSINGS {
        let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
            return true;
        };
        if it.skip_null(&hit, ray.d).is_none() {
            return false;
        }
        ray = ray_from(hit.p, hit.p_error, hit.n_geom_toward(ray.d));
    }
    false
}
