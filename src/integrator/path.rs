//! Unidirectional path tracing: next-event estimation with multiple importance sampling
//! (power heuristic, Veach 1997 §9.2), BSDF sampling, Russian roulette (pbrt-v4 §13.1.5), delta
//! lights and delta BSDFs handled exactly, lights chosen in proportion to their power.
//! Any hit on a dispersive interface terminates the secondary wavelengths, before a lobe is
//! chosen (Wilkie et al. 2014 §4.2; pbrt-v4 §14.1.3).
//!
//! The estimator is generic over what the path carries ([`Carrier`]): a spectrum of throughputs
//! ([`radiance`]) or a Mueller matrix per wavelength ([`stokes`], the polarised mode), each a
//! monomorphised copy of one loop, with the same samples and scalar weights.

use glam::Vec3;

use super::carrier::{Carrier, Polarised, to_camera_frame};
use super::{Integrator, MAX_CROSSINGS, Shading};
use crate::geometry::Ray;
use crate::geometry::shape::Intersection;
use crate::material::TransportMode;
use crate::sampler::Sampler;
use crate::sampling::power_heuristic;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Radiance along `ray`, W·m⁻²·sr⁻¹·nm⁻¹ at the wavelengths `w`.
pub(super) fn radiance<const N: usize>(
    it: &Integrator<'_>,
    ray: Ray,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
) -> SampledSpectrum<N> {
    trace::<N, SampledSpectrum<N>>(it, ray, w, s, None, &mut false)
}

/// [`radiance`], and whether the path's first dispersive hit was seen from the camera through
/// delta lobes only (directly, or in a mirror): where `split.rs` splits the sample.
pub(super) fn radiance_seen<const N: usize>(
    it: &Integrator<'_>,
    ray: Ray,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
) -> (SampledSpectrum<N>, bool) {
    let mut seen = false;
    let l = trace::<N, SampledSpectrum<N>>(it, ray, w, s, None, &mut seen);
    (l, seen)
}

/// The Stokes vector (S0, …, S3) of the light arriving along `ray`, per wavelength
/// (W·m⁻²·sr⁻¹·nm⁻¹), in the camera's frame: the basis vector `ray.d × up` (up the camera's
/// +y in world space; horizontal in the image), as Mitsuba 3's `stokes` integrator reports it,
/// so S1 > 0 is light polarised horizontally in the image.
pub(super) fn stokes<const N: usize>(
    it: &Integrator<'_>,
    ray: Ray,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
) -> [SampledSpectrum<N>; 4] {
    let d = ray.d;
    let sum = trace::<N, Polarised<N>>(it, ray, w, s, None, &mut false);
    // the path's Stokes vectors are in the implicit basis of the beam along −d
    to_camera_frame(it, d, &sum)
}

/// Radiance along `ray`, which a sampling step at `ray.o` (normal `n`) chose with density
/// `pdf` per sr against which light sampling there ([`Integrator::pick_light`] at `ray.o`,
/// `n`) is weighted (an irradiance meter's cosine-weighted direction): emission at the first
/// hit is MIS-weighted as after a BSDF sample.
pub(super) fn radiance_after_sample<const N: usize>(
    it: &Integrator<'_>,
    ray: Ray,
    pdf: f32,
    n: Vec3,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
) -> SampledSpectrum<N> {
    trace::<N, SampledSpectrum<N>>(it, ray, w, s, Some((pdf, n)), &mut false)
}

/// The path tracer; `first` is the density of the first direction and the normal at its
/// origin when it was sampled against light sampling (None: a camera ray, weighted 1).
/// `seen_dispersion` is set when the first dispersive hit is reached from a camera ray
/// through delta lobes only.
#[inline(always)]
fn trace<const N: usize, C: Carrier<N>>(
    it: &Integrator<'_>,
    mut ray: Ray,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
    first: Option<(f32, Vec3)>,
    seen_dispersion: &mut bool,
) -> C::Sum {
    let scene = it.scene;
    let mut l = C::zero_sum();
    let mut beta = C::one();
    // the previous vertex (point, shading normal, the BSDF sample's density), for MIS of
    // emitters hit by BSDF sampling
    let mut prev_p = ray.o;
    let (mut prev_pdf, mut prev_n) = first.unwrap_or((0.0, Vec3::ZERO));
    // the camera ray counts as "specular": no MIS
    let mut specular_bounce = first.is_none();
    // every scattering so far by a delta lobe (the camera ray counts as one)
    let mut all_specular = first.is_none();
    let (mut eta_scale, mut depth) = (1.0f32, 0u32);
    // `null` surfaces skipped since the last bounce, and whether the scene skips them
    let (mut crossings, skip_null) = (0u32, scene.integrator.skip_null);
    // Every bounce reads the same dimensions whatever happened before (pbrt-v4 §8.3: a fixed
    // layout keeps each bounce's samples stratified across the pixel's samples): light 2D
    // (its first coordinate also chooses the light and, on a mesh, the triangle, by sample
    // reuse, so the points on each light stay stratified), lobe choice 1D, direction 2D,
    // roulette 1D, each 1D read taking a pair: 8 dimensions per bounce from `base`.
    const BOUNCE_DIMS: u32 = 8;
    let base = s.dimension();
    loop {
        let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
            // Escaped: environment and sun disks, MIS-weighted against BSDF sampling.
            let prev = (!specular_bounce).then_some((prev_p, prev_n, prev_pdf));
            add_escaped(it, ray.d, prev, beta, w, &mut l);
            break;
        };
        // Emission at the hit, MIS-weighted against light sampling from the previous vertex.
        if let Some(li) = scene.surfaces[hit.shape as usize].light {
            let prev = (!specular_bounce).then_some((prev_p, prev_n, prev_pdf));
            add_emitted(it, li as usize, &hit, ray.d, prev, beta, w, &mut l);
        }
        // pbrt-v4's `interface`, skipped without a bounce (see `Integrator::skip_null`)
        if skip_null && let Some(next) = it.skip_null(&hit, ray.d) {
            crossings += 1;
            if crossings > MAX_CROSSINGS {
                break;
            }
            specular_bounce = true;
            ray = next;
            continue;
        }
        crossings = 0;
        if depth == it.max_depth {
            break;
        }
        debug_assert_eq!(
            s.dimension(),
            base + depth * BOUNCE_DIMS,
            "bounce {depth} starts at a shifted sampler dimension"
        );
        depth += 1;
        let Some(sh) = it.shading(&hit, ray.d, w) else {
            break;
        };
        let wo = sh.frame.to_local(-ray.d);
        // A dispersive interface (smooth or rough) keeps only the hero wavelength, decided at
        // the hit and before any lobe is chosen, so the decision does not depend on the hero's
        // Fresnel term (pbrt-v4 §14.1.3, `TerminateSecondary` on `BSDF::HasDispersion`
        // hits; Wilkie et al. 2014 §4.2). Terminating only when transmission is sampled with
        // probability 1 − F(λ₀) biases the secondaries.
        if sh.bsdf.is_dispersive() {
            *seen_dispersion |= all_specular && !w.secondary_terminated();
            w.terminate_secondary();
        }

        // Next-event estimation.
        if !sh.bsdf.is_specular() {
            add_next_event(it, &hit, &sh, wo, beta, w, s, &mut l);
        } else {
            // keep the dimension layout fixed
            s.get_2d();
        }

        // BSDF sampling.
        let mut wt = SampledSpectrum::splat(1.0);
        let Some((bs, next)) = sh.scatter(&hit, wo, w, s, TransportMode::Radiance, &mut wt) else {
            break;
        };
        beta = beta.scattered(&sh, (wo, bs.wi), w, wt);
        if bs.transmission {
            eta_scale *= bs.eta * bs.eta;
        }
        specular_bounce = bs.specular;
        all_specular &= bs.specular;
        prev_pdf = bs.pdf;
        prev_p = hit.p;
        prev_n = sh.frame.n;
        ray = next;

        // Russian roulette on the throughput, corrected for radiance scaling by η²
        // (pbrt-v4 §13.1.5), deciding whether hit depth + 1 is reached: only hits past
        // `rr_depth` may be cut (Mitsuba 3's `rr_depth`). Starting late costs time on long
        // paths but keeps the second and third bounces free of roulette noise, which in
        // scenes of low albedo lit by a sky cost more than the time saved (measured in
        // BENCHMARKS.md). Its dimension is read at every bounce, used or not.
        let u_rr = s.get_1d();
        let rr = (beta.scalar() * eta_scale).max_component();
        if rr < 1.0 && depth >= it.rr_depth {
            let q = (1.0 - rr).max(0.0);
            if u_rr < q {
                break;
            }
            beta = beta.divided(1.0 - q);
        }
        if beta.scalar().is_zero() {
            break;
        }
    }
    l
}

/// Adds the radiance of the lights at infinity in direction `d` to `l`, times `beta`; `prev`
/// (the previous vertex's point, shading normal and BSDF density) MIS-weights it against
/// light sampling there (None after a specular bounce or for a camera ray: weight 1).
#[inline(always)]
fn add_escaped<const N: usize, C: Carrier<N>>(
    it: &Integrator<'_>,
    d: Vec3,
    prev: Option<(Vec3, Vec3, f32)>,
    beta: C,
    w: &SampledWavelengths<N>,
    l: &mut C::Sum,
) {
    let scene = it.scene;
    for &i in &scene.infinite_lights {
        let i = i as usize;
        let light = &scene.lights[i];
        let le = light.escaped(d, w);
        if le.is_zero() {
            continue;
        }
        let wgt = emission_weight(it, prev, i, d, (Vec3::ZERO, Vec3::ZERO));
        beta.add_unpolarised(l, le * wgt);
    }
}

/// The power-heuristic weight of emission from light `li` reached along `d` by BSDF sampling
/// at `prev` (point, shading normal, the sample's density per sr; None: weight 1) against
/// light sampling there, for the emitting point and normal `at` (zero for lights at infinity).
#[inline(always)]
fn emission_weight(
    it: &Integrator<'_>,
    prev: Option<(Vec3, Vec3, f32)>,
    li: usize,
    d: Vec3,
    at: (Vec3, Vec3),
) -> f32 {
    let Some((prev_p, prev_n, prev_pdf)) = prev else {
        return 1.0;
    };
    let light = &it.scene.lights[li];
    let pl =
        it.light_prob(prev_p, prev_n, li) * light.pdf_li(&it.scene.shapes, prev_p, d, at.0, at.1);
    power_heuristic(1.0, prev_pdf, 1.0, pl)
}

/// Adds the radiance the hit's area light `li` sends back along `d` to `l`, times `beta`,
/// MIS-weighted against light sampling at `prev` as [`add_escaped`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn add_emitted<const N: usize, C: Carrier<N>>(
    it: &Integrator<'_>,
    li: usize,
    hit: &Intersection,
    d: Vec3,
    prev: Option<(Vec3, Vec3, f32)>,
    beta: C,
    w: &SampledWavelengths<N>,
    l: &mut C::Sum,
) {
    let le = it.scene.lights[li].emitted(hit.n_geom, -d, hit.uv, w);
    if le.is_zero() {
        return;
    }
    let wgt = emission_weight(it, prev, li, d, (hit.p, hit.n_geom));
    beta.add_unpolarised(l, le * wgt);
}

/// Next-event estimation at a non-specular hit (Veach 1997 §9.2; pbrt-v4 §13.4): a light
/// chosen by the integrator's light selection, a point on it, its radiance times f·|cos θ|,
/// MIS-weighted against BSDF sampling by the power heuristic, added to `l` times `beta`.
/// Reads one 2D sample (the light choice reuses its first coordinate).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn add_next_event<const N: usize, C: Carrier<N>>(
    it: &Integrator<'_>,
    hit: &Intersection,
    sh: &Shading<'_, N>,
    wo: Vec3,
    beta: C,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    l: &mut C::Sum,
) {
    let scene = it.scene;
    let u = s.get_2d();
    if let Some((li, p_sel, ux)) = it.pick_light(hit.p, sh.frame.n, u.x) {
        let light = &scene.lights[li];
        let u = glam::Vec2::new(ux, u.y);
        if let Some(ls) = light.sample_li(&scene.shapes, hit.p, w, u) {
            let wi = sh.frame.to_local(ls.wi);
            let (f, bsdf_pdf) = sh.bsdf.eval_pdf(wo, wi, w, TransportMode::Radiance);
            let f = f * wi.z.abs();
            if !f.is_zero() && !ls.li.is_zero() && !it.occluded(hit, sh.n_geom_toward(ls.wi), &ls) {
                let p_light = p_sel * ls.pdf;
                let wgt = if ls.delta {
                    1.0
                } else {
                    power_heuristic(1.0, p_light, 1.0, bsdf_pdf)
                };
                beta.add_scattered(l, sh, (wo, wi), w, f * ls.li * (wgt / p_light));
            }
        }
    }
}
