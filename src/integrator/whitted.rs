//! The lecture notes' model, evaluated literally per wavelength (Whitted 1980): at each hit,
//! ambient + Σ over lights (diffuse + specular, with a shadow ray) + perfect specular reflection
//! and refraction traced recursively, weighted by the exact Fresnel terms and Snell's law.
//!
//! - Ambient k_a·I_a: each uniform environment light of radiance I_a contributes k_d·I_a at a
//!   diffuse or Phong surface (k_a = k_d, no occlusion, as in the notes).
//! - Diffuse and specular from each light: f·L_i·cos θ with the material's BRDF (for Phong the
//!   normalised k_d/π + k_s(n+2)/(2π)cosⁿα), one light sample per light.
//! - Reflection and refraction: both lobes of a smooth dielectric are traced (F and 1 − F), a
//!   smooth conductor's mirror lobe with its complex Fresnel term, a smooth plastic's coating
//!   (F) on top of its diffuse base's direct lighting.

use super::Integrator;
use crate::geometry::{Ray, spawn_ray};
use crate::light::Light;
use crate::material::{Material, TransportMode};
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

pub(super) fn radiance<const N: usize>(
    it: &Integrator<'_>,
    ray: Ray,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
    depth: u32,
) -> SampledSpectrum<N> {
    let scene = it.scene;
    let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
        let mut l = SampledSpectrum::zero();
        for &i in &scene.infinite_lights {
            l += scene.lights[i as usize].escaped(ray.d, w);
        }
        return l;
    };
    let surf = scene.surfaces[hit.shape as usize];
    let mut l = match surf.light {
        Some(li) => scene.lights[li as usize].emitted(hit.n_geom, -ray.d, hit.uv, w),
        None => SampledSpectrum::zero(),
    };
    let Some(sh) = it.shading(&hit, ray.d, w) else {
        return l;
    };
    let wo = sh.frame.to_local(-ray.d);

    if sh.bsdf.is_specular() {
        if depth >= it.max_depth {
            return l;
        }
        if sh.bsdf.is_dispersive() {
            w.terminate_secondary();
        }
        // Both lobes, each once: uc = 0 picks reflection when F > 0, uc → 1 picks transmission
        // when F < 1. With F = 0 (index-matched) both draws give transmission, with F = 1 (total
        // internal reflection) both give reflection: a lobe already traced is skipped.
        let (mut done_reflection, mut done_transmission) = (false, false);
        for uc in [0.0, 1.0 - f32::EPSILON] {
            let Some(bs) =
                sh.bsdf
                    .sample(wo, w, uc, glam::Vec2::splat(0.5), TransportMode::Radiance)
            else {
                continue;
            };
            let done = if bs.transmission {
                &mut done_transmission
            } else {
                &mut done_reflection
            };
            if *done {
                continue;
            }
            *done = true;
            let wi = sh.frame.to_world(bs.wi);
            let next = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(wi), wi);
            // weight f·|cos θ| (the lobe's Fresnel factor), not divided by the lobe probability
            l += bs.f * bs.wi.z.abs() * radiance(it, next, w, s, depth + 1);
        }
        return l;
    }

    // ambient: k_d · I_a for every uniform environment light
    let kd = match sh.bsdf.material {
        Material::Diffuse(_) => Some(sh.bsdf.albedo),
        Material::Phong(m) => Some(m.kd.sample(w)),
        _ => None,
    };
    for light in &scene.lights {
        if let (Light::Environment(env), Some(kd)) = (light, kd) {
            l += kd * env.radiance.sample(w);
        }
    }
    // diffuse + specular from each light, with a shadow ray
    for light in &scene.lights {
        if matches!(light, Light::Environment(_)) {
            continue;
        }
        let Some(ls) = light.sample_li(&scene.shapes, hit.p, w, s.get_2d()) else {
            continue;
        };
        let wi = sh.frame.to_local(ls.wi);
        let f = sh.bsdf.eval(wo, wi, w, TransportMode::Radiance) * wi.z.abs();
        if f.is_zero() || it.occluded(&hit, sh.n_geom_toward(ls.wi), &ls) {
            continue;
        }
        l += f * ls.li * (1.0 / ls.pdf);
    }
    // a smooth plastic's coating reflects like a mirror, weight F·specular: traced as the
    // specular lobes above are (uc = 0 chooses the coating whenever it reflects at all)
    if let Material::Plastic(p) = sh.bsdf.material
        && p.rough.is_none()
        && depth < it.max_depth
        && let Some(bs) =
            sh.bsdf
                .sample(wo, w, 0.0, glam::Vec2::splat(0.5), TransportMode::Radiance)
        && bs.specular
    {
        let wi = sh.frame.to_world(bs.wi);
        let next = spawn_ray(hit.p, hit.p_error, sh.n_geom_toward(wi), wi);
        l += bs.f * bs.wi.z.abs() * radiance(it, next, w, s, depth + 1);
    }
    l
}
