//! Bidirectional path tracing in a scene with participating media: the subpaths' random walk
//! with free flights between surfaces, and the transmittance of the connections.
//!
//! - **Walk** (pbrt-v3 §16.3.2's `RandomWalk` with media; the flights are `volpath`'s): in
//!   the ray's medium a free flight is sampled by the hero wavelength's extinction
//!   (`Medium::walk`); a scattering event becomes a medium vertex whose phase function is
//!   sampled next (value over density 1). The subpath's throughput keeps f/p₀ and each vertex
//!   the density ratios `r_u` of the flights so far, per wavelength (Miller, Georgiev and
//!   Jarosz 2019 §5), which the connection step divides by (see `mod.rs`).
//! - **Index-matched surfaces** (`null`) and a thin sheet's transmission are crossed, not
//!   vertices, as the connections' shadow rays cross them (`Integrator::shadow_transmittance`):
//!   a strategy must sample the same path space as the others. A sheet's mirror reflection is
//!   a delta vertex of weight 1, chosen with probability R.
//! - **A medium's own emission** is found by the camera walk alone (light subpaths start on
//!   lights, and no connection samples a point in a medium for its emission): it is added
//!   where the walk passes, as `volpath` adds it, with weight 1, into [`Glow`].
//! - **Sampler dimensions** are read in sequence (the number a flight reads is not fixed).

use glam::Vec3;

use super::vertex::{Kind, Vertex};
use super::walk::RR_DEPTH;
use crate::geometry::shape::Intersection;
use crate::geometry::{Ray, spawn_ray};
use crate::integrator::Integrator;
use crate::integrator::MAX_CROSSINGS;
use crate::integrator::volpath::ShadowTarget;
use crate::material::{Material, TransportMode};
use crate::medium::live_average;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// The media's own emission found by a camera subpath, W·m⁻²·sr⁻¹·nm⁻¹ along its camera ray:
/// from flights with no dispersive vertex behind them (every wavelength, `all`) and from those
/// after one (the hero alone, `hero`), as [`super::Radiance`] splits them.
pub(super) struct Glow<const N: usize> {
    pub all: SampledSpectrum<N>,
    pub hero: SampledSpectrum<N>,
}

/// What the walk carries between vertices.
struct State<const N: usize> {
    ray: Ray,
    beta: SampledSpectrum<N>,
    r_u: SampledSpectrum<N>,
    /// The density with which the last vertex chose `ray`'s direction (see `walk.rs`).
    pdf_dir: f32,
    medium: Option<u32>,
    eta_scale: f32,
    /// Whether a dispersive vertex lies behind.
    dispersive: bool,
    /// `null` and sheet crossings since the last vertex.
    crossings: u32,
    mode: TransportMode,
    max_vertices: usize,
    /// The starting throughput's largest component (light subpaths' roulette).
    beta0: f32,
}

/// What the walk does after a step.
enum Step {
    /// Trace the (new) ray.
    Next,
    /// Go on to the surface hit.
    On,
    /// The subpath ends.
    End,
}

/// As `walk.rs`'s walk (same arguments and contract), through media; a camera walk
/// (`TransportMode::Radiance`) adds the media's emission it passes to `glow`. The ray starts
/// in the medium of the last vertex of `path` toward it.
#[allow(clippy::too_many_arguments)]
pub(super) fn walk<'a, const N: usize>(
    it: &'a Integrator<'a>,
    ray: Ray,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    beta: SampledSpectrum<N>,
    pdf_dir: f32,
    mode: TransportMode,
    max_vertices: usize,
    path: &mut Vec<Vertex<'a, N>>,
    glow: &mut Glow<N>,
) {
    let scene = it.scene;
    let last = path.last().expect("a walk starts at a vertex");
    let mut st = State {
        medium: last.medium_toward(ray.d),
        ray,
        beta,
        r_u: last.r_u,
        pdf_dir,
        eta_scale: 1.0,
        dispersive: false,
        crossings: 0,
        mode,
        max_vertices,
        beta0: beta.max_component(),
    };
    while path.len() < max_vertices {
        let hit = scene.accel.intersect(&scene.shapes, &st.ray);
        // 1. The medium up to the hit: a medium vertex, or on to the hit.
        let t_max = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
        match flight(it, &mut st, t_max, w, s, path, glow) {
            Step::Next => continue,
            Step::End => return,
            Step::On => {}
        }
        let Some(hit) = hit else {
            // a camera ray leaving the scene ends on the lights at infinity
            if mode == TransportMode::Radiance && !scene.infinite_lights.is_empty() {
                let mut v = Vertex::new(Kind::Escaped, st.ray.o, st.beta, st.pdf_dir);
                v.d = st.ray.d;
                v.r_u = st.r_u;
                path.push(v);
            }
            return;
        };
        // 2. A surface: crossed, or a vertex.
        match surface(it, &mut st, &hit, w, s, path) {
            Step::Next | Step::On => {}
            Step::End => return,
        }
    }
}

/// The free flight through the ray's medium up to `t_max`: a medium vertex whose phase
/// function gives the next ray (`Step::Next`), on to the hit (`Step::On`), or the end.
fn flight<'a, const N: usize>(
    it: &Integrator<'_>,
    st: &mut State<N>,
    t_max: f32,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    path: &mut Vec<Vertex<'a, N>>,
    glow: &mut Glow<N>,
) -> Step {
    let Some(m) = st.medium else {
        return Step::On;
    };
    let md = &it.scene.media[m as usize];
    let flight = md.walk(st.ray.o, st.ray.d, t_max, w, &mut || s.get_1d());
    if let (Some((f, pdf)), TransportMode::Radiance) = (flight.emitted, st.mode) {
        add_glow(it, glow, st, f, pdf, w, path.len() + 1);
    }
    st.beta *= flight.beta;
    st.r_u *= flight.r_u;
    if !st.beta.is_finite() || st.beta.is_zero() {
        return Step::End;
    }
    let Some(t) = flight.t else {
        return Step::On;
    };
    let phase = md.phase();
    let mut v = Vertex::new(Kind::Medium { phase }, st.ray.at(t), st.beta, 0.0);
    v.wo = -st.ray.d;
    v.medium = st.medium;
    push(it, path, v, st);
    if path.len() == st.max_vertices {
        return Step::End;
    }
    let ps = phase.sample(v.wo, s.get_2d());
    let cur = path.len() - 1;
    let rev = phase.eval(ps.wi, v.wo);
    path[cur - 1].pdf_rev = v.convert(it, rev, &path[cur - 1]);
    st.pdf_dir = ps.pdf;
    st.ray = Ray::new(v.p, ps.wi);
    st.crossings = 0;
    if roulette(it, st, path.len(), w, s) {
        Step::Next
    } else {
        Step::End
    }
}

/// The surface at `hit`: an index-matched surface or a sheet's transmission crossed (not a
/// vertex), else a surface vertex, scattered by a sheet's mirror reflection (a delta vertex of
/// weight 1) or by its BSDF. `Step::Next` goes on with the new ray.
fn surface<'a, const N: usize>(
    it: &'a Integrator<'a>,
    st: &mut State<N>,
    hit: &Intersection,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    path: &mut Vec<Vertex<'a, N>>,
) -> Step {
    let scene = it.scene;
    let shading = it.shading(hit, st.ray.d, w);
    let pass = shading.as_ref().map_or(0.0, |sh| {
        sh.bsdf
            .material
            .null_transmission(hit.n_shading.dot(st.ray.d))
    });
    if let Some(sh) = &shading
        && pass > 0.0
        && (matches!(sh.bsdf.material, Material::Null) || s.get_1d() < pass)
    {
        st.crossings += 1;
        if st.crossings > MAX_CROSSINGS {
            return Step::End;
        }
        st.medium = it.medium_after(hit, st.ray.d, st.medium);
        let n = sh.n_geom_toward(st.ray.d);
        st.ray = spawn_ray(hit.p, hit.p_error, n, st.ray.d);
        return Step::Next;
    }
    let mut v = Vertex::new(
        Kind::Surface {
            emitter: scene.surfaces[hit.shape as usize].light,
        },
        hit.p,
        st.beta,
        0.0,
    );
    v.p_error = hit.p_error;
    v.ng = hit.n_geom;
    v.uv = hit.uv;
    v.wo = -st.ray.d;
    v.shading = shading;
    v.medium = st.medium;
    v.interface = scene
        .medium_interfaces
        .get(hit.shape as usize)
        .copied()
        .unwrap_or_default();
    push(it, path, v, st);
    let Some(sh) = v.shading else {
        return Step::End;
    };
    if path.len() == st.max_vertices {
        return Step::End;
    }
    let cur = path.len() - 1;
    if pass > 0.0 {
        // the sheet's mirror reflection
        path[cur].delta = true;
        path[cur - 1].pdf_rev = 0.0;
        st.pdf_dir = 0.0;
        let n = hit.n_shading;
        let d = st.ray.d - 2.0 * st.ray.d.dot(n) * n;
        st.ray = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(d), d);
    } else {
        let wo = sh.frame.to_local(-st.ray.d);
        // a dispersive hit samples with the hero alone (see `walk.rs`)
        st.dispersive |= sh.bsdf.is_dispersive();
        let mut wl = *w;
        let Some((bs, next)) = sh.scatter(hit, wo, &mut wl, s, st.mode, &mut st.beta) else {
            return Step::End;
        };
        let (fwd, rev) = if bs.specular {
            path[cur].delta = true;
            (0.0, 0.0)
        } else {
            (bs.pdf, sh.bsdf.pdf(bs.wi, wo, w, TransportMode::Radiance))
        };
        st.pdf_dir = fwd;
        path[cur - 1].pdf_rev = v.convert(it, rev, &path[cur - 1]);
        if bs.transmission {
            st.eta_scale *= bs.eta * bs.eta;
        }
        st.ray = next;
    }
    st.medium = it.medium_after(hit, st.ray.d, st.medium);
    st.crossings = 0;
    if roulette(it, st, path.len(), w, s) {
        Step::Next
    } else {
        Step::End
    }
}

/// Appends `v` (its kind, position, normal and medium set) with the walk's ratios and its
/// forward density from the previous vertex.
fn push<'a, const N: usize>(
    it: &Integrator<'_>,
    path: &mut Vec<Vertex<'a, N>>,
    mut v: Vertex<'a, N>,
    st: &State<N>,
) {
    let prev = &path[path.len() - 1];
    v.r_u = st.r_u;
    v.pdf_fwd = if prev.kind_is_parallel_light(it) {
        // per area across the beam, projected onto a surface (a medium point has no cosine)
        if v.ng == Vec3::ZERO {
            st.pdf_dir
        } else {
            st.pdf_dir * v.ng.dot(st.ray.d).abs()
        }
    } else {
        prev.convert(it, st.pdf_dir, &v)
    };
    path.push(v);
}

/// Adds the emission `f` a flight collected, with its densities `pdf` per hero choice, to the
/// camera walk's glow, as the single strategy (s = 0, t = `t`) that samples it.
fn add_glow<const N: usize>(
    it: &Integrator<'_>,
    glow: &mut Glow<N>,
    st: &State<N>,
    f: SampledSpectrum<N>,
    pdf: SampledSpectrum<N>,
    w: &SampledWavelengths<N>,
    t: usize,
) {
    if let Some(only) = it.strategy
        && (only.s, only.t as usize) != (0, t)
    {
        return;
    }
    let mut hero = *w;
    hero.terminate_secondary();
    let wl = if st.dispersive { &hero } else { w };
    let d = live_average(st.r_u * pdf, wl);
    if d > 0.0 {
        let c = st.beta * f / d;
        if st.dispersive {
            glow.hero += c;
        } else {
            glow.all += c;
        }
    }
}

/// Russian roulette as in `walk.rs`, on the throughput over the average density ratio of the
/// flights (as `volpath`), `vertices` the subpath's length so far. False ends the walk.
fn roulette<const N: usize>(
    it: &Integrator<'_>,
    st: &mut State<N>,
    vertices: usize,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
) -> bool {
    let u = s.get_1d();
    if st.beta.is_zero() {
        return false;
    }
    let avg = live_average(st.r_u, w);
    let (rr, start) = match st.mode {
        TransportMode::Radiance => ((st.beta * st.eta_scale).max_component() / avg, it.rr_depth),
        TransportMode::Importance => (
            st.beta.max_component() / (st.beta0 * avg),
            it.rr_depth.min(RR_DEPTH),
        ),
    };
    // bounces so far: the vertices past the first
    if rr < 1.0 && (vertices as u32).saturating_sub(1) >= start {
        let q = (1.0 - rr).max(0.0);
        if u < q {
            return false;
        }
        st.beta /= 1.0 - q;
    }
    true
}

/// The transmittance of the connection from `a` (a surface or medium vertex, the end of a
/// subpath) to `b`, per wavelength: through the media and the `null` and sheet surfaces
/// between them (`Integrator::shadow_transmittance`, its ratio tracking reading `s`), 0 if
/// anything else is in the way.
pub(super) fn transmittance<const N: usize>(
    it: &Integrator<'_>,
    a: &Vertex<'_, N>,
    b: &Vertex<'_, N>,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
) -> SampledSpectrum<N> {
    let d = a.dir_to(it, b);
    let n = if a.ng.dot(d) < 0.0 { -a.ng } else { a.ng };
    let origin = (a.p, a.p_error, n, a.medium_toward(d));
    let target = if b.at_infinity(it) {
        ShadowTarget::Direction(b.d)
    } else {
        ShadowTarget::Point {
            p: b.p,
            p_error: b.p_error,
            n: b.ng,
        }
    };
    it.shadow_transmittance(origin, target, w, s).0
}
