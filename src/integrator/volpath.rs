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
use crate::geometry::{Ray, spawn_ray, spawn_ray_to};
use crate::light::LightSample;
use crate::material::{Material, TransportMode};
use crate::medium::live_average;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Surfaces a shadow ray or a run of `null` crossings may pass before it is given up (a ray
/// caught between coincident surfaces must end).
const MAX_CROSSINGS: u32 = 256;

/// The state of a camera path between vertices.
struct Path<const N: usize> {
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
    };
    let mut crossings = 0;
    loop {
        let hit = scene.accel.intersect(&scene.shapes, &ray);
        // 1. The medium up to the hit: a scattering event or a pass (pbrt-v4 §14.2.1).
        if let Some(m) = path.medium {
            let t_max = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
            let medium = &scene.media[m as usize];
            let walk = medium.walk(ray.o, ray.d, t_max, w, &mut || s.get_1d());
            path.beta *= walk.beta;
            path.r_u *= walk.r_u;
            if !path.beta.is_finite() || path.beta.is_zero() {
                break;
            }
            if let Some(t) = walk.t {
                if path.depth == it.max_depth {
                    break;
                }
                path.depth += 1;
                let p = ray.at(t);
                let phase = medium.phase();
                let wo = -ray.d;
                // next-event estimation from the medium point
                let u = s.get_2d();
                l += next_event(it, Vertex::Medium { p, wo, phase }, &path, w, u, s);
                // phase-function sampling (exact: value over pdf is 1)
                let ps = phase.sample(wo, s.get_2d());
                path.r_l = path.r_u / ps.pdf;
                path.prev_p = p;
                path.prev_n = Vec3::ZERO;
                path.specular = false;
                ray = Ray::new(p, ps.wi);
                crossings = 0;
                if !roulette(it, &mut path, w, s) {
                    break;
                }
                continue;
            }
            path.r_l *= walk.r_l;
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
        let surf = scene.surfaces[hit.shape as usize];
        if let Some(li) = surf.light {
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
        // 4. Index-matched crossings (`null`, a thin sheet's transmission): not a scattering
        // event; the ray goes on in the medium on the other side.
        // the sheet's R at the shading normal's incidence, as shadow rays evaluate it
        let pass = sh.bsdf.material.null_transmission(hit.n_shading.dot(ray.d));
        if pass > 0.0 {
            // a thin sheet: transmission with probability 1 − R (weight 1; next-event
            // estimation's density has no such factor), else its mirror reflection, a delta
            // scattering event of weight 1
            let cross = matches!(sh.bsdf.material, Material::Null) || s.get_1d() < pass;
            if cross {
                if pass < 1.0 {
                    path.r_l /= pass;
                }
                crossings += 1;
                if crossings > MAX_CROSSINGS {
                    break;
                }
                path.medium = it.medium_after(&hit, ray.d, path.medium);
                ray = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(ray.d), ray.d);
                continue;
            }
            if path.depth == it.max_depth {
                break;
            }
            path.depth += 1;
            path.specular = true;
            let n = hit.n_shading;
            let d = ray.d - 2.0 * ray.d.dot(n) * n;
            path.medium = it.medium_after(&hit, d, path.medium);
            ray = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(d), d);
            crossings = 0;
            if !roulette(it, &mut path, w, s) {
                break;
            }
            continue;
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
        crossings = 0;
        if !roulette(it, &mut path, w, s) {
            break;
        }
    }
    l
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

/// A vertex from which light is sampled.
enum Vertex<'a, 'b, const N: usize> {
    Surface {
        hit: &'a Intersection,
        sh: &'a Shading<'b, N>,
        /// Toward the previous vertex, in the shading frame.
        wo: Vec3,
    },
    Medium {
        p: Vec3,
        /// Toward the previous vertex, world space.
        wo: Vec3,
        phase: crate::medium::PhaseFunction,
    },
}

/// Next-event estimation (pbrt-v4 §14.2.4, `SampleLd`): a light chosen and sampled from the
/// 2D sample `u`, its radiance times the scattering value and the transmittance of the
/// shadow ray, weighted by the balance heuristic against the walk reaching it (whose density
/// includes that transmittance, the probability of crossing the media and sheets unscattered).
fn next_event<const N: usize>(
    it: &Integrator<'_>,
    v: Vertex<'_, '_, N>,
    path: &Path<N>,
    w: &SampledWavelengths<N>,
    u: glam::Vec2,
    s: &mut Sampler,
) -> SampledSpectrum<N> {
    let scene = it.scene;
    let zero = SampledSpectrum::zero();
    let (p, n) = match &v {
        Vertex::Surface { hit, sh, .. } => (hit.p, sh.frame.n),
        Vertex::Medium { p, .. } => (*p, Vec3::ZERO),
    };
    let Some((li, p_sel, ux)) = it.pick_light(p, n, u.x) else {
        return zero;
    };
    let light = &scene.lights[li];
    let Some(ls) = light.sample_li(&scene.shapes, p, w, glam::Vec2::new(ux, u.y)) else {
        return zero;
    };
    if ls.li.is_zero() {
        return zero;
    }
    let (f, scatter_pdf, origin) = match &v {
        Vertex::Surface { hit, sh, wo } => {
            let wi = sh.frame.to_local(ls.wi);
            let (f, pdf) = sh.bsdf.eval_pdf(*wo, wi, w, TransportMode::Radiance);
            let medium = it.medium_after(hit, ls.wi, path.medium);
            (
                f * wi.z.abs(),
                pdf,
                (hit.p, hit.p_error, sh.n_geom_toward(ls.wi), medium),
            )
        }
        Vertex::Medium { p, wo, phase } => {
            let pdf = phase.eval(*wo, ls.wi);
            (
                SampledSpectrum::splat(pdf),
                pdf,
                (*p, Vec3::ZERO, Vec3::ZERO, path.medium),
            )
        }
    };
    if f.is_zero() {
        return zero;
    }
    let (tr, pass) = it.shadow_transmittance(origin, &ls, w, s);
    if tr.is_zero() {
        return zero;
    }
    let p_light = p_sel * ls.pdf;
    let d = if ls.delta {
        live_average(path.r_u * p_light, w)
    } else {
        live_average(
            path.r_u * (pass * scatter_pdf + SampledSpectrum::splat(p_light)),
            w,
        )
    };
    if d > 0.0 {
        path.beta * f * tr * ls.li / d
    } else {
        zero
    }
}

impl Integrator<'_> {
    /// The medium a ray leaving `hit` in direction `d` travels in, given the one it arrived
    /// in.
    #[inline]
    pub(crate) fn medium_after(
        &self,
        hit: &Intersection,
        d: Vec3,
        current: Option<u32>,
    ) -> Option<u32> {
        match self.scene.medium_interfaces.get(hit.shape as usize) {
            Some(mi) => mi.target(hit.n_geom, d, current),
            None => current,
        }
    }

    /// The transmittance from `origin` (point, error bound, offset normal, the medium the
    /// shadow ray starts in) to the light sample `ls`, per wavelength: Beer–Lambert through
    /// every homogeneous medium on the way, ratio tracking (numbers from `s`) through every
    /// heterogeneous one, times the undeviated transmission of the `null` and
    /// `thindielectric` surfaces it crosses; 0 if any other surface is in the way. Second,
    /// per wavelength, the density with which the walk would cross the same way (the
    /// media's densities of passing, see [`crate::medium::Medium::transmittance`], times
    /// the sheets' transmission).
    pub(crate) fn shadow_transmittance<const N: usize>(
        &self,
        origin: (Vec3, Vec3, Vec3, Option<u32>),
        ls: &LightSample<N>,
        w: &SampledWavelengths<N>,
        s: &mut Sampler,
    ) -> (SampledSpectrum<N>, SampledSpectrum<N>) {
        let scene = self.scene;
        let (p, p_error, n, mut medium) = origin;
        let toward = |p: Vec3, p_error: Vec3, n: Vec3| {
            if ls.distance.is_finite() {
                spawn_ray_to(p, p_error, n, ls.p, ls.p_error, ls.n)
            } else {
                spawn_ray(p, p_error, n, ls.wi)
            }
        };
        let mut ray = toward(p, p_error, n);
        let mut tr = SampledSpectrum::splat(1.0);
        let mut pass = SampledSpectrum::splat(1.0);
        let zero = (SampledSpectrum::zero(), SampledSpectrum::zero());
        for _ in 0..MAX_CROSSINGS {
            let hit = scene.accel.intersect(&scene.shapes, &ray);
            if let Some(m) = medium {
                let t = hit.as_ref().map_or(ray.t_max, |h| h.t);
                let (t_seg, p_seg) =
                    scene.media[m as usize].transmittance(ray.o, ray.d, t, w, &mut || s.get_1d());
                tr *= t_seg;
                pass *= p_seg;
            }
            let Some(hit) = hit else {
                return (tr, pass);
            };
            let sheet = match scene.surfaces[hit.shape as usize].material {
                Some(mat) => {
                    scene.materials[mat as usize].null_transmission(hit.n_shading.dot(ray.d))
                }
                None => 0.0,
            };
            tr *= sheet;
            pass *= sheet;
            if tr.is_zero() {
                return zero;
            }
            medium = self.medium_after(&hit, ray.d, medium);
            let n = if hit.n_geom.dot(ray.d) < 0.0 {
                -hit.n_geom
            } else {
                hit.n_geom
            };
            ray = toward(hit.p, hit.p_error, n);
        }
        zero
    }
}
