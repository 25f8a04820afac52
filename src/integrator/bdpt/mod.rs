//! Spectral bidirectional path tracing (Veach 1997 ch. 10; Veach & Guibas 1995): a camera
//! subpath and a light subpath per camera sample, joined by every connection strategy (s light
//! vertices, t camera vertices) and combined by multiple importance sampling with the power
//! heuristic, its weights computed by the ratio-of-densities recurrence of Veach 1997 §10.2.1
//! (pbrt-v4 §13.3.6, `MISWeight`).
//!
//! - **Spectral.** Both subpaths carry the camera sample's hero wavelengths. A strategy whose
//!   vertices include a dispersive hit on either subpath keeps only the hero
//!   (`terminate_secondary`), as `path` does at such a hit; the others keep every wavelength.
//!   Every strategy that samples a given path uses all of its vertices, so all of them decide
//!   alike for it: each estimates the hero alone where the path is dispersive and every
//!   wavelength where it is not, and the MIS weights still sum to one. (Terminating the whole
//!   sample instead would cost a lit room its colour wherever a light subpath crossed a
//!   prism.) A sample whose camera subpath sees dispersion through delta lobes is split into
//!   its wavelengths (`split.rs`, with `Integrator::split_dispersion`).
//! - **Strategies.** s = 0: a camera subpath that hits an emitter (or leaves the scene toward
//!   the lights at infinity). s = 1: the light sampled from a camera vertex (`sample_li`, next
//!   event estimation). t = 1: a light vertex connected to the camera's lens (`Camera::connect`,
//!   pinhole or thin lens; none for an orthographic camera, whose lens vertex is a delta in
//!   direction), splatted at its raster position. Otherwise an edge between the two
//!   subpaths' last vertices. s = t = 1 (an emitter seen directly from a particle) is left to
//!   s = 0, t = 2, as in pbrt; delta lobes and delta lights take part where they can.
//! - **Transport.** Camera vertices evaluate f in radiance mode (with η² at refractions), light
//!   vertices in importance mode with the adjoint shading-normal correction (Veach 1997 §5.3).
//! - **Media.** In a scene with media the subpaths are `media.rs`'s walks: free flights by the
//!   hero's extinction, medium vertices with the phase function as their BSDF, `null` and
//!   sheet crossings that are not vertices. Every connection carries the transmittance between
//!   its ends (ratio tracking through heterogeneous media, reading its own sampler range), and
//!   each strategy divides by the average over the live wavelengths of its two subpaths'
//!   flight density ratios (the balance heuristic over hero choices, Miller, Georgiev and
//!   Jarosz 2019). The strategies' MIS weights leave the flights' densities out (`vertex.rs`).
//! - **Debugging.** A [`Strategy`] restricts a render to one (s, t), weighted or not: the
//!   weighted images of all strategies sum to the full render, and each unweighted one converges
//!   to the same image where it can sample the paths.

mod connect;
mod media;
mod polarised;
mod split;
mod strategies;
mod vertex;
mod walk;

use glam::Vec2;

use super::{Integrator, Splatted};
use crate::geometry::Ray;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use connect::Ends;
use strategies::{Keep, strategies};
use vertex::Vertex;

/// One connection strategy alone, for debugging and tests: `s` light vertices, `t` camera
/// vertices, with its MIS weight or without (then it is an unbiased estimator by itself of the
/// paths it can sample).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Strategy {
    pub s: u32,
    pub t: u32,
    pub weighted: bool,
}

/// The subpaths of one sample, kept between samples so that no sample allocates.
pub struct Scratch<'a, const N: usize> {
    camera: Vec<Vertex<'a, N>>,
    light: Vec<Vertex<'a, N>>,
    pol: polarised::Pol<N>,
}

impl<const N: usize> Scratch<'_, N> {
    pub fn new(max_depth: u32) -> Self {
        let n = (max_depth as usize).saturating_add(2).min(64);
        Self {
            camera: Vec::with_capacity(n),
            light: Vec::with_capacity(n),
            pol: polarised::Pol::default(),
        }
    }
}

/// First sampler dimension of the connections' samples (light choice and point for s = 1,
/// lens point for t = 1), four per subpath vertex after the walks' dimensions.
const CONNECT_DIMS: u32 = 1 << 16;

/// First sampler dimension of the connections' ratio tracking through heterogeneous media:
/// 1024 dimensions for each (s, t).
const TRACK_DIMS: u32 = 1 << 20;

/// What one BDPT sample's camera-side strategies (t ≥ 2) carry along its camera ray,
/// W·m⁻²·sr⁻¹·nm⁻¹: the strategies without a dispersive vertex at the sample's wavelengths, the
/// others at the hero alone (`hero_only`, the wavelengths with the secondaries terminated).
/// In a polarised render `stokes_all` and `stokes_hero` are the same sums as Stokes vectors
/// S0–S3 in the camera's frame (`all` and `hero` are then the unpolarised estimator's, which
/// the film does not use); zero otherwise.
pub struct Radiance<const N: usize> {
    pub all: SampledSpectrum<N>,
    pub hero: SampledSpectrum<N>,
    pub hero_only: SampledWavelengths<N>,
    pub stokes_all: [SampledSpectrum<N>; 4],
    pub stokes_hero: [SampledSpectrum<N>; 4],
}

impl<const N: usize> Radiance<N> {
    /// Nothing yet, for a sample at the wavelengths `w`.
    fn zero(w: &SampledWavelengths<N>) -> Self {
        let mut hero_only = *w;
        hero_only.terminate_secondary();
        Self {
            all: SampledSpectrum::zero(),
            hero: SampledSpectrum::zero(),
            hero_only,
            stokes_all: [SampledSpectrum::zero(); 4],
            stokes_hero: [SampledSpectrum::zero(); 4],
        }
    }
}

/// One BDPT sample at the wavelengths `w`, along `ray`. Returns the camera-side radiance, while
/// `splat(raster, w, value)` receives each t = 1 strategy's contribution at its raster
/// position with its wavelengths, `value` in the film's units times the pixel count (the
/// caller divides by it and spreads it over the filter, as for light tracing): a Stokes
/// vector in the camera's frame in a polarised render (`polarised.rs`). `s` is the
/// camera sample's stream (its camera dimensions read), `s_light` a stream of the same pixel
/// and index for the light subpath. `margin` is the filter radius, pixels.
///
/// With [`Integrator::split_dispersion`], a sample whose camera subpath meets a dispersive
/// interface through delta lobes only is traced again with each other wavelength as the hero
/// (`split.rs`); its camera-side radiance is then all in `all`, at `w`.
#[allow(clippy::too_many_arguments)]
pub fn sample<'a, const N: usize>(
    it: &'a Integrator<'a>,
    ray: Ray,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    s_light: &mut Sampler,
    margin: f32,
    scratch: &mut Scratch<'a, N>,
    splat: &mut impl FnMut(Vec2, &SampledWavelengths<N>, Splatted<N>),
) -> Radiance<N> {
    let conn = s.clone().at_dimension(CONNECT_DIMS);
    let again = it.split_dispersion.then(|| (s.clone(), s_light.clone()));
    let glow = walks(it, ray, w, s, s_light, scratch);
    // a medium's own emission, which only the camera walk finds
    let mut out = Radiance::zero(w);
    (out.all, out.hero) = (glow.all, glow.hero);
    // the camera sees dispersion through delta lobes only (the lens is vertex 0)
    let first = walk::first_dispersive(&scratch.camera);
    let camera_disperses =
        first < scratch.camera.len() && scratch.camera[1..first].iter().all(|v| v.delta);
    match again {
        Some(streams) if camera_disperses && !w.secondary_terminated() => {
            let sample = split::Sample {
                ray,
                w,
                conn: &conn,
                margin,
            };
            split::rotations(it, &sample, streams, scratch, splat, &mut out);
        }
        _ => {
            let keep = Keep::Every { dispersive: 1.0 };
            strategies(it, ray, w, &conn, margin, scratch, splat, keep, &mut out);
        }
    }
    out
}

/// Both subpaths of a sample at `w` into `scratch` (and the polarised factors' cache);
/// returns a medium's emission the camera walk found.
fn walks<'a, const N: usize>(
    it: &'a Integrator<'a>,
    ray: Ray,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    s_light: &mut Sampler,
    scratch: &mut Scratch<'a, N>,
) -> media::Glow<N> {
    let max_depth = it.max_depth as usize;
    let mut glow = media::Glow {
        all: SampledSpectrum::zero(),
        hero: SampledSpectrum::zero(),
    };
    walk::camera_subpath(
        it,
        ray,
        w,
        s,
        max_depth.saturating_add(2),
        &mut scratch.camera,
        &mut glow,
    );
    walk::light_subpath(
        it,
        w,
        s_light,
        max_depth.saturating_add(1),
        &mut scratch.light,
    );
    if it.polarised() {
        scratch.pol.build(it, &scratch.camera, &scratch.light, w);
    }
    glow
}

/// The contribution of strategy (s, t), MIS-weighted if `weighted`, for t = 1 the raster
/// position where it lands, and for s = 1 or t = 1 the vertex it sampled. None when the
/// strategy yields nothing for these subpaths.
#[allow(clippy::too_many_arguments)]
fn connect<'a, const N: usize>(
    it: &Integrator<'_>,
    light: &[Vertex<'a, N>],
    camera: &[Vertex<'a, N>],
    s: usize,
    t: usize,
    w: &SampledWavelengths<N>,
    conn: &Sampler,
    margin: f32,
    weighted: bool,
) -> Option<(SampledSpectrum<N>, Option<Vec2>, Option<Vertex<'a, N>>)> {
    // the connection's own ratio tracking reads a range of its own
    let mut track = conn
        .clone()
        .at_dimension(TRACK_DIMS + (((s as u32) * 128 + t as u32) << 10));
    let ends = Ends {
        light,
        camera,
        s,
        t,
        w,
    };
    let (l, sampled, raster) = if s == 0 {
        // the camera subpath's last vertex is on an emitter
        let pt = &camera[t - 1];
        (pt.beta * pt.le(it, &camera[t - 2], w), None, None)
    } else if t == 1 {
        let u = conn
            .clone()
            .at_dimension(CONNECT_DIMS + 4 * s as u32 + 2)
            .get_2d();
        let (l, v, raster) = ends.to_lens(it, u, margin, &mut track)?;
        (l, Some(v), Some(raster))
    } else if s == 1 {
        let u = conn
            .clone()
            .at_dimension(CONNECT_DIMS + 4 * t as u32)
            .get_2d();
        let (l, v) = ends.to_light(it, u, &mut track)?;
        (l, Some(v), None)
    } else {
        (ends.edge(it, &mut track)?, None, None)
    };
    if l.is_zero() {
        return None;
    }
    // the balance heuristic over hero choices of both subpaths' free flights (1 without media)
    let spectral = if it.scene.media.is_empty() {
        1.0
    } else {
        let r_camera = sampled
            .filter(|_| t == 1)
            .map_or(camera[t - 1].r_u, |v| v.r_u);
        let r_light = match (s, sampled) {
            (0, _) => SampledSpectrum::splat(1.0),
            (1, Some(v)) => v.r_u,
            _ => light[s - 1].r_u,
        };
        let d = crate::medium::live_average(r_camera * r_light, w);
        if !(d > 0.0) {
            return None;
        }
        1.0 / d
    };
    let mis = if weighted {
        mis_weight(it, light, camera, sampled.as_ref(), s, t, w)
    } else {
        1.0
    };
    Some((l * (mis * spectral), raster, sampled))
}

/// The power-heuristic MIS weight of strategy (s, t) for the path it built, by the
/// ratio-of-densities recurrence (Veach 1997 §10.2.1, eqs. 10.9–10.10; pbrt-v4 §13.3.6): with
/// pᵢ the density of the same path sampled with i light vertices, pᵢ₊₁/pᵢ and pᵢ₋₁/pᵢ are
/// products of reverse over forward vertex densities, w = p_s² / Σᵢ pᵢ² = 1 / (1 + Σ (pᵢ/p_s)²)
/// over the strategies that can sample the path (none ends on a delta vertex or a delta
/// light). The connection's endpoints and their neighbours get the reverse densities this
/// connection implies; `sampled` is the vertex an s = 1 or t = 1 strategy sampled in place of
/// the subpath's own. A zero density (a delta) counts as 1 in the ratios, so that delta
/// vertices cancel.
fn mis_weight<const N: usize>(
    it: &Integrator<'_>,
    light: &[Vertex<'_, N>],
    camera: &[Vertex<'_, N>],
    sampled: Option<&Vertex<'_, N>>,
    s: usize,
    t: usize,
    w: &SampledWavelengths<N>,
) -> f32 {
    if s + t == 2 {
        return 1.0;
    }
    let remap = |x: f32| if x != 0.0 { x } else { 1.0 };
    let pt = match (t, sampled) {
        (1, Some(v)) => v,
        _ => &camera[t - 1],
    };
    let qs = match (s, sampled) {
        (0, _) => None,
        (1, Some(v)) => Some(v),
        _ => Some(&light[s - 1]),
    };
    let pt_minus = (t >= 2).then(|| &camera[t - 2]);
    let qs_minus = (s >= 2).then(|| &light[s - 2]);
    // reverse densities implied by the connection
    let pt_rev = match qs {
        Some(q) => q.pdf(it, qs_minus, pt, w),
        None => pt_minus.map_or(0.0, |pm| pt.pdf_light_origin(it, pm)),
    };
    let pt_minus_rev = pt_minus.map_or(0.0, |pm| match qs {
        Some(q) => pt.pdf(it, Some(q), pm, w),
        None => pt.pdf_light(it, pm),
    });
    let qs_rev = qs.map_or(0.0, |q| pt.pdf(it, pt_minus, q, w));
    let qs_minus_rev = match (qs, qs_minus) {
        (Some(q), Some(qm)) => q.pdf(it, Some(pt), qm, w),
        _ => 0.0,
    };
    let mut sum = 0.0f32;
    // hypothetical strategies with fewer camera vertices
    let mut ri = 1.0f32;
    for i in (1..t).rev() {
        let v = &camera[i];
        let rev = if i == t - 1 {
            pt_rev
        } else if i + 2 == t {
            pt_minus_rev
        } else {
            v.pdf_rev
        };
        ri *= remap(rev) / remap(v.pdf_fwd);
        let delta = i != t - 1 && v.delta;
        if !delta && !camera[i - 1].delta {
            sum += ri * ri;
        }
    }
    // hypothetical strategies with fewer light vertices
    let mut ri = 1.0f32;
    for i in (0..s).rev() {
        let v = match (i, s, sampled) {
            (0, 1, Some(sv)) => sv,
            _ => &light[i],
        };
        let rev = if i == s - 1 {
            qs_rev
        } else if i + 2 == s {
            qs_minus_rev
        } else {
            v.pdf_rev
        };
        ri *= remap(rev) / remap(v.pdf_fwd);
        let delta = i != s - 1 && v.delta;
        let delta_before = if i > 0 {
            light[i - 1].delta
        } else {
            v.is_delta_light(it)
        };
        if !delta && !delta_before {
            sum += ri * ri;
        }
    }
    1.0 / (1.0 + sum)
}
