//! Light tracing in a scene with participating media: `light.rs`'s particle tracer with the
//! volumetric walk of `volpath/` (free flights through the particle's medium, `null` and
//! thin-sheet crossings that are not bounces) and camera connections from surface and medium
//! vertices whose shadow rays carry the transmittance through media and sheets.
//!
//! One technique per wavelength set, so the only weights are those of the hero choice: the
//! particle keeps `beta` = f/p₀ and the density ratios `r_u` (as `volpath`), and a connection
//! adds β·(connection value) / avg(r_u) (the balance heuristic over hero choices, Miller,
//! Georgiev and Jarosz 2019). A medium's own emission is not traced from (the camera side,
//! `path`, finds it).

use glam::{Vec2, Vec3};

use super::MAX_CROSSINGS;
use super::volpath::ShadowTarget;
use super::{Integrator, Splatted};
use crate::geometry::{Ray, spawn_ray};
use crate::material::{Material, TransportMode};
use crate::medium::live_average;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A particle between events.
struct Particle<const N: usize> {
    ray: Ray,
    beta: SampledSpectrum<N>,
    /// p_k/p₀ of the particle's path so far, per wavelength k.
    r_u: SampledSpectrum<N>,
    medium: Option<u32>,
    /// The starting weight's largest component, for roulette.
    beta0: f32,
    depth: u32,
    crossings: u32,
}

/// What the particle does after an event.
enum Next {
    Go,
    Stop,
}

/// As [`super::light::trace`], in a scene with media.
pub(super) fn trace<const N: usize>(
    it: &Integrator<'_>,
    margin: f32,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
    splat: &mut impl FnMut(Vec2, &SampledWavelengths<N>, Splatted<N>),
) {
    let scene = it.scene;
    let (u1, u2) = (s.get_2d(), s.get_2d());
    let Some((li, p_sel, u1x)) = it.lights.pick_reuse(u1.x) else {
        return;
    };
    let light = &scene.lights[li];
    let Some(e) = light.sample_le(
        &scene.shapes,
        scene.bounding_sphere(),
        w,
        Vec2::new(u1x, u1.y),
        u2,
    ) else {
        return;
    };
    // t = 1, s = 1: a point of an area light seen directly, through the media on the way
    let u_lens = s.get_2d();
    if e.n != Vec3::ZERO
        && let Some(c) = scene.camera.connect(e.o, u_lens, margin)
    {
        let le = light.emitted(e.n, c.wi, e.uv, w);
        if !le.is_zero() {
            let m0 = it.medium_at(e.o, e.o_error, e.n, c.wi);
            let tr = to_lens(it, (e.o, e.o_error, e.n, m0), c.p_lens, w, s);
            let cos = e.n.dot(c.wi).abs();
            splat(
                c.raster,
                w,
                Splatted::Radiance(le * tr * (cos * c.weight / (p_sel * e.pdf_pos))),
            );
        }
    }
    let beta = e.weight() * (1.0 / p_sel);
    if beta.is_zero() {
        return;
    }
    let mut pt = Particle {
        ray: if e.n == Vec3::ZERO {
            Ray::new(e.o, e.d)
        } else {
            spawn_ray(e.o, e.o_error, e.n, e.d)
        },
        beta,
        r_u: SampledSpectrum::splat(1.0),
        medium: it.medium_at(e.o, e.o_error, e.n, e.d),
        beta0: beta.max_component(),
        depth: 0,
        crossings: 0,
    };
    while pt.depth < it.max_depth {
        let hit = scene.accel.intersect(&scene.shapes, &pt.ray);
        // the medium up to the hit: a scattering event, connected to the camera
        if let Some(m) = pt.medium {
            let t_max = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
            let md = &scene.media[m as usize];
            let walk = md.walk(pt.ray.o, pt.ray.d, t_max, w, &mut || s.get_1d());
            pt.beta *= walk.beta;
            pt.r_u *= walk.r_u;
            if !pt.beta.is_finite() || pt.beta.is_zero() {
                return;
            }
            if let Some(t) = walk.t {
                pt.depth += 1;
                let p = pt.ray.at(t);
                let phase = md.phase();
                let wo = -pt.ray.d;
                let u_lens = s.get_2d();
                if let Some(c) = scene.camera.connect(p, u_lens, margin) {
                    let f = phase.eval(wo, c.wi);
                    let tr = to_lens(it, (p, Vec3::ZERO, Vec3::ZERO, pt.medium), c.p_lens, w, s);
                    let d = live_average(pt.r_u, w);
                    if d > 0.0 && !tr.is_zero() {
                        splat(
                            c.raster,
                            w,
                            Splatted::Radiance(pt.beta * tr * (f * c.weight / d)),
                        );
                    }
                }
                let ps = phase.sample(wo, s.get_2d());
                pt.ray = Ray::new(p, ps.wi);
                pt.crossings = 0;
                if !roulette(&mut pt, s) {
                    return;
                }
                continue;
            }
        }
        let Some(hit) = hit else {
            return;
        };
        if let Next::Stop = surface(it, &mut pt, &hit, margin, w, s, splat) {
            return;
        }
    }
}

/// The particle at a surface: crossed if index-matched (not a bounce), the sheet's mirror
/// reflection, or connected to the camera and scattered by the BSDF.
fn surface<const N: usize>(
    it: &Integrator<'_>,
    pt: &mut Particle<N>,
    hit: &crate::geometry::shape::Intersection,
    margin: f32,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
    splat: &mut impl FnMut(Vec2, &SampledWavelengths<N>, Splatted<N>),
) -> Next {
    let Some(sh) = it.shading(hit, pt.ray.d, w) else {
        return Next::Stop;
    };
    let ray = pt.ray;
    let pass = sh.bsdf.material.null_transmission(hit.n_shading.dot(ray.d));
    if pass > 0.0 && (matches!(sh.bsdf.material, Material::Null) || s.get_1d() < pass) {
        pt.crossings += 1;
        if pt.crossings > MAX_CROSSINGS {
            return Next::Stop;
        }
        pt.medium = it.medium_after(hit, ray.d, pt.medium);
        pt.ray = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(ray.d), ray.d);
        return Next::Go;
    }
    let wo = sh.frame.to_local(-ray.d);
    if pass > 0.0 {
        // the sheet's mirror reflection, a delta event of weight 1 (no connection)
        let n = hit.n_shading;
        let d = ray.d - 2.0 * ray.d.dot(n) * n;
        pt.medium = it.medium_after(hit, d, pt.medium);
        pt.ray = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(d), d);
    } else {
        if sh.bsdf.is_dispersive() && !sh.bsdf.is_specular() {
            w.terminate_secondary();
        }
        let u_lens = s.get_2d();
        if !sh.bsdf.is_specular()
            && let Some(c) = it.scene.camera.connect(hit.p, u_lens, margin)
        {
            let wc = sh.frame.to_local(c.wi);
            let f = sh.bsdf.eval(wo, wc, w, TransportMode::Importance);
            if !f.is_zero() {
                let m = it.medium_after(hit, c.wi, pt.medium);
                let origin = (hit.p, hit.p_error, sh.n_geom_toward(c.wi), m);
                let tr = to_lens(it, origin, c.p_lens, w, s);
                let corr = sh.adjoint_correction(wo, c.wi);
                let d = live_average(pt.r_u, w);
                if d > 0.0 && !tr.is_zero() {
                    splat(
                        c.raster,
                        w,
                        Splatted::Radiance(pt.beta * f * tr * (wc.z.abs() * corr * c.weight / d)),
                    );
                }
            }
        }
        let Some((_, next)) = sh.scatter(hit, wo, w, s, TransportMode::Importance, &mut pt.beta)
        else {
            return Next::Stop;
        };
        for j in 1..N {
            if w.pdf[j] == 0.0 {
                pt.beta[j] = 0.0;
            }
        }
        pt.medium = it.medium_after(hit, next.d, pt.medium);
        pt.ray = next;
    }
    pt.depth += 1;
    pt.crossings = 0;
    if roulette(pt, s) {
        Next::Go
    } else {
        Next::Stop
    }
}

/// The transmittance from `origin` to the lens point `p_lens`.
fn to_lens<const N: usize>(
    it: &Integrator<'_>,
    origin: (Vec3, Vec3, Vec3, Option<u32>),
    p_lens: Vec3,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
) -> SampledSpectrum<N> {
    let target = ShadowTarget::Point {
        p: p_lens,
        p_error: Vec3::ZERO,
        n: Vec3::ZERO,
    };
    it.shadow_transmittance(origin, target, w, s).0
}

/// Russian roulette on the throughput relative to the particle's starting weight (as
/// `light.rs`), from the third event on. False ends the particle.
fn roulette<const N: usize>(pt: &mut Particle<N>, s: &mut Sampler) -> bool {
    if pt.depth > 2 {
        let q = (1.0 - pt.beta.max_component() / pt.beta0).max(0.0);
        if s.get_1d() < q {
            return false;
        }
        pt.beta /= 1.0 - q;
    }
    true
}
