//! The two subpaths of bidirectional path tracing: a camera subpath from the lens and a light
//! subpath from a light's own emission sampling (`Light::sample_le`), each a random walk that
//! records forward and reverse densities at its vertices (Veach 1997 §10.2; pbrt-v4 §13.3.2).
//! The walks never terminate the wavelengths themselves: a dispersive vertex samples its
//! direction with the hero, and [`first_dispersive`] tells which strategies pass through one.

use glam::Vec2;

use super::media::{self, Glow};
use super::vertex::{Kind, Vertex};
use crate::geometry::{Ray, spawn_ray};
use crate::integrator::{Integrator, MAX_CROSSINGS};
use crate::material::TransportMode;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Sampler dimensions each bounce of a walk reads: lobe choice 1D, direction 2D, roulette 1D,
/// each read taking a pair (a fixed layout keeps each bounce stratified, as in `path`).
const BOUNCE_DIMS: u32 = 8;

/// The bounce from which Russian roulette may end a light subpath (unless the scene's
/// `rr_depth` is smaller; camera subpaths start at `rr_depth`, as `path` does). Every vertex of
/// a light subpath pays for a connection to each camera vertex, so long low-power particles
/// cost more than they bring: on the Cornell box, roulette from the second bounce of both
/// subpaths took 26 % less time per sample than from the fifth, for 5 % more variance, but on a
/// sky-lit diffuse scene (`tests/reference/constant_env`) the camera side's early roulette
/// doubled the noise; on the light side alone it keeps the gain there and the noise here
/// (`scripts/bench_bdpt.py`, `scripts/derive_thresholds.py --integrator bdpt`).
pub(super) const RR_DEPTH: u32 = 2;

/// The camera subpath for `ray` (already sampled by the caller with its lens point): the lens
/// vertex, then up to `max_vertices − 1` surface hits, ending at an escaped ray (lights at
/// infinity) if the walk leaves the scene. W_e/p = 1 for a camera ray sampled by importance,
/// so the throughput starts at 1. In a scene with media the walk is `media.rs`'s, and the
/// media's own emission it passes goes to `glow`.
pub(super) fn camera_subpath<'a, const N: usize>(
    it: &'a Integrator<'a>,
    ray: Ray,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    max_vertices: usize,
    path: &mut Vec<Vertex<'a, N>>,
    glow: &mut Glow<N>,
) {
    path.clear();
    if max_vertices == 0 {
        return;
    }
    let beta = SampledSpectrum::splat(1.0);
    let mut v = Vertex::new(Kind::Camera, ray.o, beta, 1.0);
    // an orthographic camera is a delta in direction: no t = 1 strategy can reach it, and MIS
    // must not count one
    v.delta = matches!(it.scene.camera, crate::geometry::Camera::Orthographic(_));
    v.medium = it.scene.camera_medium;
    path.push(v);
    let pdf_dir = it.scene.camera.pdf_we(ray.o, ray.d);
    if !it.scene.media.is_empty() {
        let mode = TransportMode::Radiance;
        media::walk(it, ray, w, s, beta, pdf_dir, mode, max_vertices, path, glow);
        return;
    }
    walk(
        it,
        ray,
        w,
        s,
        beta,
        pdf_dir,
        TransportMode::Radiance,
        max_vertices,
        path,
    );
}

/// The light subpath: a light chosen by the integrator's selector, a particle from its
/// `sample_le`, then up to `max_vertices − 1` surface hits. Empty if there is no light or the
/// particle carries nothing.
pub(super) fn light_subpath<'a, const N: usize>(
    it: &'a Integrator<'a>,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    max_vertices: usize,
    path: &mut Vec<Vertex<'a, N>>,
) {
    path.clear();
    if max_vertices == 0 {
        return;
    }
    let scene = it.scene;
    let (u_pos, u_dir) = (s.get_2d(), s.get_2d());
    let Some((li, p_sel, ux)) = it.lights.pick_reuse(u_pos.x) else {
        return;
    };
    let light = &scene.lights[li];
    let Some(e) = light.sample_le(
        &scene.shapes,
        scene.bounding_sphere(),
        w,
        Vec2::new(ux, u_pos.y),
        u_dir,
    ) else {
        return;
    };
    let parallel = light.emits_parallel();
    // the light vertex: chosen with p_sel × (position density, or for parallel light the
    // direction density), its throughput Le / that
    let pdf_origin = p_sel * if parallel { e.pdf_dir } else { e.pdf_pos };
    let mut v = Vertex::new(
        Kind::Light { light: li as u32 },
        e.o,
        e.le * (1.0 / pdf_origin),
        pdf_origin,
    );
    v.p_error = e.o_error;
    v.ng = if light.is_at_infinity() {
        glam::Vec3::ZERO
    } else {
        e.n
    };
    v.d = -e.d;
    v.uv = e.uv;
    if !scene.media.is_empty() {
        v.medium = it.medium_at(e.o, e.o_error, e.n, e.d);
    }
    path.push(v);
    let beta = e.weight() * (1.0 / p_sel);
    if beta.is_zero() {
        return;
    }
    let ray = if e.n == glam::Vec3::ZERO {
        Ray::new(e.o, e.d)
    } else {
        spawn_ray(e.o, e.o_error, e.n, e.d)
    };
    // the density of the first hit: per area across the direction for parallel light
    // (converted by |cos θ| at the hit in `walk` through `Vertex::pdf_light`), else the
    // direction's solid-angle density
    let pdf_dir = if parallel { e.pdf_pos } else { e.pdf_dir };
    if !scene.media.is_empty() {
        let mut glow = Glow {
            all: SampledSpectrum::zero(),
            hero: SampledSpectrum::zero(),
        };
        let mode = TransportMode::Importance;
        media::walk(
            it,
            ray,
            w,
            s,
            beta,
            pdf_dir,
            mode,
            max_vertices,
            path,
            &mut glow,
        );
        return;
    }
    walk(
        it,
        ray,
        w,
        s,
        beta,
        pdf_dir,
        TransportMode::Importance,
        max_vertices,
        path,
    );
}

/// Extends `path` (whose last vertex emitted `ray`) by hits until `max_vertices` vertices, a
/// miss, an absorbed sample or Russian roulette. `pdf_dir` is the density with which the
/// last vertex chose `ray`'s direction (sr⁻¹; for a parallel-light vertex, m⁻² across the
/// beam). Each hit records its forward density, and the vertex before it its reverse density
/// (pbrt-v4 §13.3.2, `RandomWalk`). A dispersive hit keeps only the hero wavelength.
#[allow(clippy::too_many_arguments)]
fn walk<'a, const N: usize>(
    it: &'a Integrator<'a>,
    mut ray: Ray,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    mut beta: SampledSpectrum<N>,
    mut pdf_dir: f32,
    mode: TransportMode,
    max_vertices: usize,
    path: &mut Vec<Vertex<'a, N>>,
) {
    let scene = it.scene;
    let beta0 = beta.max_component();
    let mut eta_scale = 1.0f32;
    let base = s.dimension();
    let mut bounce = 0u32;
    let mut crossings = 0u32;
    while path.len() < max_vertices {
        let prev = path.len() - 1;
        let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
            // a camera ray leaving the scene ends on the lights at infinity
            if mode == TransportMode::Radiance && !scene.infinite_lights.is_empty() {
                let mut v = Vertex::new(Kind::Escaped, ray.o, beta, pdf_dir);
                v.d = ray.d;
                path.push(v);
            }
            return;
        };
        // a medium boundary pbrt-v4 skips (`interface`): no vertex (pbrt-v4's `RandomWalk`);
        // the next hit's density is still `pdf_dir`, its direction unchanged
        if let Some(next) = it.skip_null(&hit, ray.d) {
            crossings += 1;
            if crossings > MAX_CROSSINGS {
                return;
            }
            ray = next;
            continue;
        }
        crossings = 0;
        let surf = &scene.surfaces[hit.shape as usize];
        let shading = it.shading(&hit, ray.d, w);
        let mut v = Vertex::new(
            Kind::Surface {
                emitter: surf.light,
            },
            hit.p,
            beta,
            0.0,
        );
        v.p_error = hit.p_error;
        v.ng = hit.n_geom;
        v.uv = hit.uv;
        v.wo = -ray.d;
        v.shading = shading;
        v.pdf_fwd = if path[prev].kind_is_parallel_light(it) {
            pdf_dir * hit.n_geom.dot(ray.d).abs()
        } else {
            path[prev].convert(it, pdf_dir, &v)
        };
        path.push(v);
        let Some(sh) = v.shading else {
            return;
        };
        if path.len() == max_vertices {
            return;
        }
        *s = s.clone().at_dimension(base + bounce * BOUNCE_DIMS);
        bounce += 1;
        let wo = sh.frame.to_local(-ray.d);
        // a dispersive hit samples with the hero wavelength alone: `scatter` terminates a copy,
        // and the strategies through this vertex use the terminated set (`first_dispersive`)
        let mut wl = *w;
        let Some((bs, next)) = sh.scatter(&hit, wo, &mut wl, s, mode, &mut beta) else {
            return;
        };
        let cur = path.len() - 1;
        let (fwd, rev) = if bs.specular {
            path[cur].delta = true;
            (0.0, 0.0)
        } else {
            (bs.pdf, sh.bsdf.pdf(bs.wi, wo, w, TransportMode::Radiance))
        };
        pdf_dir = fwd;
        let (before, after) = path.split_at_mut(cur);
        before[cur - 1].pdf_rev = after[0].convert(it, rev, &before[cur - 1]);
        if bs.transmission {
            eta_scale *= bs.eta * bs.eta;
        }
        ray = next;
        // Russian roulette past `rr_depth` bounces for camera subpaths, on the throughput
        // (η²-corrected as in `path`); from bounce RR_DEPTH for light subpaths, relative to the
        // particle's starting weight (as `light`); its dimension is read at every bounce
        let u_rr = s.get_1d();
        let rr = match mode {
            TransportMode::Radiance => (beta * eta_scale).max_component(),
            TransportMode::Importance => beta.max_component() / beta0,
        };
        let start = match mode {
            TransportMode::Radiance => it.rr_depth,
            TransportMode::Importance => it.rr_depth.min(RR_DEPTH),
        };
        if rr < 1.0 && bounce >= start {
            let q = (1.0 - rr).max(0.0);
            if u_rr < q {
                return;
            }
            beta /= 1.0 - q;
        }
        if beta.is_zero() {
            return;
        }
    }
}

/// Index of the first vertex of `path` whose material is dispersive (`path.len()` if none):
/// every strategy using that many vertices of this subpath or more keeps only the hero
/// wavelength, as `path` does at a dispersive hit; strategies using fewer keep them all.
pub(super) fn first_dispersive<const N: usize>(path: &[Vertex<'_, N>]) -> usize {
    path.iter()
        .position(|v| v.shading.is_some_and(|sh| sh.bsdf.is_dispersive()))
        .unwrap_or(path.len())
}
