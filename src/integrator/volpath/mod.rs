//! Volumetric path tracing: the path tracer of `path.rs` with participating media between the
//! surfaces, for scenes that have media (Mitsuba's `volpath` and `volpathmis`).
//!
//! Estimator (pbrt-v4 §14.2, `VolPathIntegrator`; Miller, Georgiev and Jarosz 2019 §5):
//! - Free flights are sampled by the hero wavelength's extinction (`medium`). The path keeps
//!   `beta` = f/p₀ (the path's value over its density with the hero as hero) and `r_u`, per
//!   wavelength k, p_k/p₀: the density the same path would have had with wavelength k as the
//!   hero. Dividing by the average of `r_u` over the live wavelengths is the balance heuristic
//!   over hero choices, so every wavelength is estimated without bias whatever σt(λ) does.
//! - Emitters are reached by two techniques, next-event estimation and the unidirectional
//!   walk, combined by the balance heuristic too: `r_l` holds, per wavelength, the density of
//!   next-event estimation for the same path over p₀, less the light's own density, which is
//!   multiplied in at the emitter.
//! - Shadow rays carry the exact transmittance of homogeneous media and cross `null` and
//!   `thindielectric` surfaces, times their undeviated transmission (Mitsuba's
//!   `eval_null_transmission`); any other surface blocks them.
//! - `null` surfaces and the transmission of `thindielectric` sheets are not scattering events:
//!   they change the ray's medium but not its depth (Mitsuba's `volpath`).
//! - Shapes change the medium of a ray crossing them ([`crate::medium::MediumInterface`]).
//!
//! Surface sampling densities are taken to be the same for every hero choice (every
//! non-dispersive material here samples by values that do not depend on which wavelength is
//! the hero); at a dispersive surface the secondary wavelengths end, as in `path.rs`.

use glam::Vec3;

use super::{Integrator, Shading};
use crate::geometry::shape::Intersection;
use crate::geometry::{Ray, spawn_ray};
use crate::material::{Material, TransportMode};
use crate::medium::live_average;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

use super::MAX_CROSSINGS;

mod nee;

pub(crate) use nee::ShadowTarget;

use nee::{Vertex, next_event};

/// The state of a camera path between vertices.
pub(super) struct Path<const N: usize> {
    beta: SampledSpectrum<N>,
    /// p_k/p₀ of the path so far, per wavelength k.
    r_u: SampledSpectrum<N>,
    /// Next-event estimation's density of the path so far over p₀, per wavelength, without
    /// the light's density at its end.
    r_l: SampledSpectrum<N>,
    /// The last scattering vertex (point, shading normal or zero in a medium), for the
    /// light-selection density of an emitter reached from it.
    prev_p: Vec3,
    prev_n: Vec3,
    /// Whether the last scattering event was a delta lobe (or the path is a camera ray):
    /// emitters reached are counted without MIS.
    specular: bool,
    medium: Option<u32>,
    depth: u32,
    eta_scale: f32,
    /// `null` and sheet crossings since the last scattering event.
    crossings: u32,
}

/// Radiance along `ray`, W·m⁻²·sr⁻¹·nm⁻¹ at the wavelengths `w`, the camera in the scene's
/// camera medium.
pub(super) fn radiance<const N: usize>(
    it: &Integrator<'_>,
    mut ray: Ray,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
) -> SampledSpectrum<N> {
    let scene = it.scene;
    let mut l = SampledSpectrum::<N>::zero();
    let mut path = Path {
        beta: SampledSpectrum::splat(1.0),
        r_u: SampledSpectrum::splat(1.0),
        r_l: SampledSpectrum::splat(1.0),
        prev_p: ray.o,
        prev_n: Vec3::ZERO,
        specular: true,
        medium: scene.camera_medium,
        depth: 0,
        eta_scale: 1.0,
        crossings: 0,
    };
    loop {
        let hit = scene.accel.intersect(&scene.shapes, &ray);
        // 1. The medium up to the hit: a scattering event or a pass (pbrt-v4 §14.2.1).
        let t_max = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
        match medium_step(it, &mut path, &mut ray, t_max, w, s, &mut l) {
            Step::Next => continue,
            Step::End => break,
            Step::On => {}
        }
        // 2. Escaped: the lights at infinity.
        let Some(hit) = hit else {
            for &i in &scene.infinite_lights {
                let light = &scene.lights[i as usize];
                let le = light.escaped(ray.d, w);
                if !le.is_zero() {
                    let p_light = it.light_prob(path.prev_p, path.prev_n, i as usize)
                        * light.pdf_li(&scene.shapes, path.prev_p, ray.d, Vec3::ZERO, Vec3::ZERO);
                    l += emitted(&path, le, p_light, w);
                }
            }
            break;
        };
        // 3. Emission at the hit.
        if let Some(li) = scene.surfaces[hit.shape as usize].light {
            let light = &scene.lights[li as usize];
            let le = light.emitted(hit.n_geom, -ray.d, hit.uv, w);
            if !le.is_zero() {
                let p_light = it.light_prob(path.prev_p, path.prev_n, li as usize)
                    * light.pdf_li(&scene.shapes, path.prev_p, ray.d, hit.p, hit.n_geom);
                l += emitted(&path, le, p_light, w);
            }
        }
        let Some(sh) = it.shading(&hit, ray.d, w) else {
            break;
        };
        // 4. Index-matched crossings and a thin sheet's mirror reflection.
        match cross_sheet(it, &mut path, &mut ray, &hit, &sh, w, s) {
            Step::Next => continue,
            Step::End => break,
            Step::On => {}
        }
        if path.depth == it.max_depth {
            break;
        }
        path.depth += 1;
        // 5. A scattering surface: next-event estimation and BSDF sampling as in `path.rs`.
        let wo = sh.frame.to_local(-ray.d);
        if sh.bsdf.is_dispersive() {
            w.terminate_secondary();
        }
        let u = s.get_2d();
        if !sh.bsdf.is_specular() {
            let v = Vertex::Surface {
                hit: &hit,
                sh: &sh,
                wo,
            };
            l += next_event(it, v, &path, w, u, s);
        }
        let Some((bs, next)) = sh.scatter(&hit, wo, w, s, TransportMode::Radiance, &mut path.beta)
        else {
            break;
        };
        // terminated wavelengths carry nothing (their values may be anything)
        for j in 1..N {
            if w.pdf[j] == 0.0 {
                path.beta[j] = 0.0;
            }
        }
        if bs.transmission {
            path.eta_scale *= bs.eta * bs.eta;
        }
        path.specular = bs.specular;
        path.r_l = path.r_u / bs.pdf;
        path.prev_p = hit.p;
        path.prev_n = sh.frame.n;
        path.medium = it.medium_after(&hit, next.d, path.medium);
        ray = next;
        path.crossings = 0;
        if !roulette(it, &mut path, w, s) {
            break;
        }
    }
    l
}

/// What the walk does after a step.
enum Step {
    /// Trace the (new) ray from the top of the loop.
    Next,
    /// The path ends.
    End,
    /// Go on with the surface hit.
    On,
}

/// The medium along `ray` up to `t_max`: a scattering event there (next-event estimation,
/// phase sampling, `Step::Next`) or a pass (`Step::On`), or the end of the path.
fn medium_step<const N: usize>(
    it: &Integrator<'_>,
    path: &mut Path<N>,
    ray: &mut Ray,
    t_max: f32,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
    l: &mut SampledSpectrum<N>,
) -> Step {
    let Some(m) = path.medium else {
        return Step::On;
    };
    let medium = &it.scene.media[m as usize];
    let walk = medium.walk(ray.o, ray.d, t_max, w, &mut || s.get_1d());
    // the medium's own emission, found by the walk alone
    if let Some((f, pdf)) = walk.emitted {
        let d = live_average(path.r_u * pdf, w);
        if d > 0.0 {
            *l += path.beta * f / d;
        }
    }
    path.beta *= walk.beta;
    path.r_u *= walk.r_u;
    if !path.beta.is_finite() || path.beta.is_zero() {
        return Step::End;
    }
    let Some(t) = walk.t else {
        path.r_l *= walk.r_l;
        return Step::On;
    };
    if path.depth == it.max_depth {
        return Step::End;
    }
    path.depth += 1;
    let p = ray.at(t);
    let phase = medium.phase();
    let wo = -ray.d;
    // next-event estimation from the medium point
    let u = s.get_2d();
    *l += next_event(it, Vertex::Medium { p, wo, phase }, path, w, u, s);
    // phase-function sampling (exact: value over pdf is 1)
    let ps = phase.sample(wo, s.get_2d());
    path.r_l = path.r_u / ps.pdf;
    path.prev_p = p;
    path.prev_n = Vec3::ZERO;
    path.specular = false;
    *ray = Ray::new(p, ps.wi);
    path.crossings = 0;
    if roulette(it, path, w, s) {
        Step::Next
    } else {
        Step::End
    }
}

/// A `null` surface or a thin sheet at `hit`: crossed (not a scattering event; the ray goes
/// on in the medium on the other side, `Step::Next`), or the sheet's mirror reflection, a
/// delta scattering event of weight 1 (`Step::Next`); any other material `Step::On`.
fn cross_sheet<const N: usize>(
    it: &Integrator<'_>,
    path: &mut Path<N>,
    ray: &mut Ray,
    hit: &Intersection,
    sh: &Shading<'_, N>,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
) -> Step {
    // the sheet's R at the shading normal's incidence, as shadow rays evaluate it
    let pass = sh.bsdf.material.null_transmission(hit.n_shading.dot(ray.d));
    if pass <= 0.0 {
        return Step::On;
    }
    // a thin sheet's transmission is chosen with probability 1 − R (weight 1), a density
    // next-event estimation does not have
    let cross = matches!(sh.bsdf.material, Material::Null) || s.get_1d() < pass;
    if cross {
        if pass < 1.0 {
            path.r_l /= pass;
        }
        path.crossings += 1;
        if path.crossings > MAX_CROSSINGS {
            return Step::End;
        }
        path.medium = it.medium_after(hit, ray.d, path.medium);
        *ray = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(ray.d), ray.d);
        return Step::Next;
    }
    if path.depth == it.max_depth {
        return Step::End;
    }
    path.depth += 1;
    path.specular = true;
    let n = hit.n_shading;
    let d = ray.d - 2.0 * ray.d.dot(n) * n;
    path.medium = it.medium_after(hit, d, path.medium);
    *ray = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(d), d);
    path.crossings = 0;
    if roulette(it, path, w, s) {
        Step::Next
    } else {
        Step::End
    }
}

/// Emission `le` reached by the walk, with the light's density `p_light` (selection times
/// solid angle) from the last scattering vertex: weighted by the balance heuristic against
/// next-event estimation, or alone after a delta lobe.
#[inline]
fn emitted<const N: usize>(
    path: &Path<N>,
    le: SampledSpectrum<N>,
    p_light: f32,
    w: &SampledWavelengths<N>,
) -> SampledSpectrum<N> {
    let d = if path.specular || p_light <= 0.0 {
        live_average(path.r_u, w)
    } else {
        live_average(path.r_u + path.r_l * p_light, w)
    };
    if d > 0.0 {
        path.beta * le / d
    } else {
        SampledSpectrum::zero()
    }
}

/// Russian roulette on the throughput over the average density ratio, corrected for radiance
/// scaling by η² (pbrt-v4 §14.2.3), past `rr_depth` scattering events. False ends the path.
#[inline]
fn roulette<const N: usize>(
    it: &Integrator<'_>,
    path: &mut Path<N>,
    w: &SampledWavelengths<N>,
    s: &mut Sampler,
) -> bool {
    let u = s.get_1d();
    if path.beta.is_zero() {
        return false;
    }
    let avg = live_average(path.r_u, w);
    let rr = (path.beta * path.eta_scale).max_component() / avg;
    if rr < 1.0 && path.depth >= it.rr_depth {
        let q = (1.0 - rr).max(0.0);
        if u < q {
            return false;
        }
        path.beta /= 1.0 - q;
    }
    true
}
