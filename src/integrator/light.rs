//! Light tracing (particle tracing): paths start at the lights, bounce through specular and
//! glossy interactions, and every diffuse or glossy vertex is connected to the camera (pinhole or
//! thin lens, through a lens point it samples: `Camera::connect`)
//! (Veach 1997 §10.2, the t = 1 strategies of bidirectional path tracing; pbrt-v4's
//! LightPathIntegrator). It renders
//! caustics that `path` cannot, such as a collimated beam refracted by a prism onto a screen.
//!
//! Every emitter is traced: area, point, spot and beam lights from their surfaces or positions;
//! lights at infinity (environment, directional with or without an angular diameter) from a
//! disk of the scene's bounding sphere (`sample_le`). A light at infinity seen directly by the
//! camera (the sky, a sun disk) cannot reach the lens from a particle; [`escaped`] adds it
//! along camera rays instead (see `render::render_light`). The camera must be perspective
//! (an orthographic camera is a delta in direction, which no particle can connect to).
//! Emission is each light's own `Light::sample_le`.
//!
//! Paths that reach the camera through a specular last bounce (an emitter seen in a mirror or
//! through glass) are not sampled by light tracing, for any light; use `path` or `bdpt`.

use glam::{Vec2, Vec3};

use super::carrier::{scatter_stokes, to_camera_frame};
use super::{Integrator, MAX_CROSSINGS, Splatted};
use crate::geometry::{Ray, spawn_ray, spawn_ray_to};
use crate::material::TransportMode;
use crate::polarisation::Stokes;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Traces one light path and calls `splat` for every camera connection, with the raster
/// position (pixels) of the connection, which may lie up to `margin` pixels outside the image
/// (the reconstruction filter's radius: the caller spreads each splat over the pixels of the
/// filter's support, see `render::render_light`).
///
/// In a polarised render the particle also carries a normalised Stokes vector per wavelength
/// (unpolarised at emission, in the implicit basis of its direction of travel), which each
/// scattering event multiplies by its normalised Mueller matrix (`carrier::scatter_stokes`,
/// with the physical directions: light arrives from the particle's past); its scalar weight is
/// the unpolarised estimator's, so S0 of an unpolarised scene is that render's, and a splat
/// is the Stokes vector in the camera's frame.
pub fn trace<const N: usize>(
    it: &Integrator<'_>,
    margin: f32,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
    splat: &mut impl FnMut(Vec2, &SampledWavelengths<N>, Splatted<N>),
) {
    if !it.scene.media.is_empty() {
        return super::light_media::trace(it, margin, w, s, splat);
    }
    let scene = it.scene;
    let (u1, u2) = (s.get_2d(), s.get_2d());
    // the light chosen with u1.x, reused for the point on it
    let Some((li, p_sel, u1x)) = it.lights.pick_reuse(u1.x) else {
        return;
    };
    let u1 = Vec2::new(u1x, u1.y);
    let camera = &scene.camera;
    // emission: the light's own sampling (`Light::sample_le`): u1 the origin, u2 the direction
    let light = &scene.lights[li];
    let Some(e) = light.sample_le(&scene.shapes, scene.bounding_sphere(), w, u1, u2) else {
        return;
    };
    // t = 1 with s = 1: a point of a light with a surface (an area light) seen directly by the
    // camera, Le·|cos θ| per unit area probability (the side the particle leaves does not
    // matter here)
    let u_lens = s.get_2d();
    if e.n != Vec3::ZERO
        && let Some(c) = camera.connect(e.o, u_lens, margin)
    {
        let le = light.emitted(e.n, c.wi, e.uv, w);
        if !le.is_zero() && !occluded_to_camera(it, e.o, e.o_error, e.n, c.p_lens) {
            let cos = e.n.dot(c.wi).abs();
            let l = le * (cos * c.weight / (p_sel * e.pdf_pos));
            splat(c.raster, w, unpolarised(it, l));
        }
    }
    let mut beta = e.weight() * (1.0 / p_sel);
    if beta.is_zero() {
        return;
    }
    let beta0 = beta.max_component();
    let polarised = it.polarised();
    let mut pol = [Stokes::unpolarised(1.0); N];
    let mut ray = if e.n == Vec3::ZERO {
        Ray::new(e.o, e.d)
    } else {
        spawn_ray(e.o, e.o_error, e.n, e.d)
    };
    let mut depth = 0;
    let mut crossings = 0;
    while depth < it.max_depth {
        let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
            break;
        };
        // a medium boundary pbrt-v4 skips (`interface`; pbrt-v4's `LightPathIntegrator`)
        if let Some(next) = it.skip_null(&hit, ray.d) {
            crossings += 1;
            if crossings > MAX_CROSSINGS {
                break;
            }
            ray = next;
            continue;
        }
        crossings = 0;
        let Some(sh) = it.shading(&hit, ray.d, w) else {
            break;
        };
        // wo points back toward where the light came from (pbrt's convention for importance)
        let wo = sh.frame.to_local(-ray.d);
        if sh.bsdf.is_dispersive() && !sh.bsdf.is_specular() {
            w.terminate_secondary();
        }
        let u_lens = s.get_2d();
        if !sh.bsdf.is_specular()
            && let Some(c) = camera.connect(hit.p, u_lens, margin)
        {
            let wc = sh.frame.to_local(c.wi);
            let f = sh.bsdf.eval(wo, wc, w, TransportMode::Importance);
            if !f.is_zero()
                && !occluded_to_camera(it, hit.p, hit.p_error, sh.n_geom_toward(c.wi), c.p_lens)
            {
                // β·f·|ns·wc|·(adjoint correction) = β·f·|ns·wo|·|ng·wc|/|ng·wo|:
                // the geometric cosine at the camera end, shading cosine at the light end
                // (Veach 1997 §5.3)
                let corr = sh.adjoint_correction(wo, c.wi);
                let l = beta * f * (wc.z.abs() * corr * c.weight);
                if polarised {
                    let st = scatter_stokes(&sh, (wc, wo), w, &pol);
                    let st: [Stokes; N] = std::array::from_fn(|j| st[j].scale(l[j]));
                    splat(
                        c.raster,
                        w,
                        Splatted::Stokes(to_camera_frame(it, -c.wi, &st)),
                    );
                } else {
                    splat(c.raster, w, Splatted::Radiance(l));
                }
            }
        }
        let Some((bs, next)) = sh.scatter(&hit, wo, w, s, TransportMode::Importance, &mut beta)
        else {
            break;
        };
        if polarised {
            pol = scatter_stokes(&sh, (bs.wi, wo), w, &pol);
        }
        ray = next;
        // Russian roulette on the throughput relative to the particle's starting weight
        if depth > 1 {
            let q = (1.0 - beta.max_component() / beta0).max(0.0);
            if s.get_1d() < q {
                break;
            }
            beta /= 1.0 - q;
        }
        depth += 1;
    }
}

/// Unpolarised light `l` as a splat: radiance, or S0 alone in a polarised render.
fn unpolarised<const N: usize>(it: &Integrator<'_>, l: SampledSpectrum<N>) -> Splatted<N> {
    if it.polarised() {
        let z = SampledSpectrum::zero();
        Splatted::Stokes([l, z, z, z])
    } else {
        Splatted::Radiance(l)
    }
}

fn occluded_to_camera(it: &Integrator<'_>, p: Vec3, p_error: Vec3, n: Vec3, eye: Vec3) -> bool {
    let ray = spawn_ray_to(p, p_error, n, eye, Vec3::ZERO, Vec3::ZERO);
    it.scene.accel.occluded(&it.scene.shapes, &ray)
}

/// Whether the scene has a light at infinity that a camera ray can see directly (an
/// environment, or a directional light with an angular diameter): light tracing then adds
/// [`escaped`] along camera rays.
pub fn has_visible_infinite_lights(it: &Integrator<'_>) -> bool {
    // at infinity and not collimated: an environment, or a sun with a disk
    it.scene
        .lights
        .iter()
        .any(|l| l.is_at_infinity() && !l.is_delta())
}

/// Radiance seen directly along a camera ray from the lights at infinity, W·m⁻²·sr⁻¹·nm⁻¹:
/// the sum of their `escaped` radiance if the ray leaves the scene, else 0. This is the path
/// tracer's zero-bounce term for those lights (the particles of `trace` cannot reach the lens
/// directly from infinity).
pub fn escaped<const N: usize>(
    it: &Integrator<'_>,
    ray: &Ray,
    w: &SampledWavelengths<N>,
) -> SampledSpectrum<N> {
    let scene = it.scene;
    if !scene.media.is_empty() {
        // through the camera's medium and any index-matched surfaces on the way; ratio
        // tracking's numbers keyed on the ray (this function takes no sampler)
        let key = ray.d.x.to_bits()
            ^ ray.d.y.to_bits().rotate_left(11)
            ^ ray.d.z.to_bits().rotate_left(22);
        let mut s = crate::sampler::Sampler::new(key, ray.o.x.to_bits(), ray.o.y.to_bits(), 0);
        let origin = (ray.o, Vec3::ZERO, Vec3::ZERO, scene.camera_medium);
        let target = super::volpath::ShadowTarget::Direction(ray.d);
        let (tr, _) = it.shadow_transmittance(origin, target, w, &mut s);
        let mut l = SampledSpectrum::zero();
        for &i in &scene.infinite_lights {
            l += scene.lights[i as usize].escaped(ray.d, w);
        }
        return l * tr;
    }
    // only whether the ray leaves the scene matters: an any-hit query
    if scene.accel.occluded(&scene.shapes, ray) {
        return SampledSpectrum::zero();
    }
    let mut l = SampledSpectrum::zero();
    for &i in &scene.infinite_lights {
        l += scene.lights[i as usize].escaped(ray.d, w);
    }
    l
}
