//! Direct illumination as Mitsuba 3's `direct` integrator computes it (src/integrators/
//! direct.cpp): the emission seen along the camera ray, plus at its first hit `emitter_samples`
//! light samples and `bsdf_samples` BSDF samples, each weighted by the power heuristic with the
//! sample counts as fractions (Veach 1997 §9.2.4: with n_l light and n_b BSDF samples, a light
//! sample of density p_l is weighted (n_l p_l)² / ((n_l p_l)² + (n_b p_b)²), and the estimate is
//! the sum over all samples of f·L·cos θ / (n p) times the weight). Light paths of one bounce
//! only: the same expectation as `path` with one bounce, with Mitsuba's sample counts.

use glam::Vec3;

use super::Integrator;
use crate::geometry::Ray;
use crate::material::TransportMode;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// The power heuristic for a sample of density `a` against the other strategy's `b`, both
/// already multiplied by their sample counts; 1 when `b` is 0.
#[inline]
fn weight(a: f32, b: f32) -> f32 {
    if b <= 0.0 {
        return 1.0;
    }
    let (a2, b2) = (a * a, b * b);
    if a2.is_infinite() {
        return 1.0;
    }
    a2 / (a2 + b2)
}

/// Radiance along `ray`, W·m⁻²·sr⁻¹·nm⁻¹, from emission seen directly and direct lighting at
/// the first hit.
pub(super) fn radiance<const N: usize>(
    it: &Integrator<'_>,
    ray: Ray,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
    emitter_samples: u32,
    bsdf_samples: u32,
) -> SampledSpectrum<N> {
    let scene = it.scene;
    let mut l = SampledSpectrum::<N>::zero();
    let (nl, nb) = (emitter_samples as f32, bsdf_samples as f32);
    let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
        for &i in &scene.infinite_lights {
            l += scene.lights[i as usize].escaped(ray.d, w);
        }
        return l;
    };
    if let Some(li) = scene.surfaces[hit.shape as usize].light {
        l += scene.lights[li as usize].emitted(hit.n_geom, -ray.d, hit.uv, w);
    }
    let Some(sh) = it.shading(&hit, ray.d, w) else {
        return l;
    };
    let wo = sh.frame.to_local(-ray.d);
    if sh.bsdf.is_dispersive() {
        w.terminate_secondary();
    }
    // light samples
    for _ in 0..emitter_samples {
        let u = s.get_2d();
        if sh.bsdf.is_specular() {
            continue;
        }
        let Some((li, p_sel, ux)) = it.pick_light(hit.p, sh.frame.n, u.x) else {
            continue;
        };
        let light = &scene.lights[li];
        let Some(ls) = light.sample_li(&scene.shapes, hit.p, w, glam::Vec2::new(ux, u.y)) else {
            continue;
        };
        let wi = sh.frame.to_local(ls.wi);
        let (f, bsdf_pdf) = sh.bsdf.eval_pdf(wo, wi, w, TransportMode::Radiance);
        let f = f * wi.z.abs();
        if f.is_zero() || ls.li.is_zero() || it.occluded(&hit, sh.n_geom_toward(ls.wi), &ls) {
            continue;
        }
        let p_light = p_sel * ls.pdf;
        let wgt = if ls.delta {
            1.0
        } else {
            weight(nl * p_light, nb * bsdf_pdf)
        };
        l += f * ls.li * (wgt / (p_light * nl));
    }
    // BSDF samples
    for _ in 0..bsdf_samples {
        let mut beta = SampledSpectrum::<N>::splat(1.0);
        let Some((bs, next)) = sh.scatter(&hit, wo, w, s, TransportMode::Radiance, &mut beta)
        else {
            continue;
        };
        // the density of reaching the same point by light sampling, times the light count
        let pl = |li: usize, p: Vec3, n: Vec3| {
            it.light_prob(hit.p, sh.frame.n, li)
                * scene.lights[li].pdf_li(&scene.shapes, hit.p, next.d, p, n)
        };
        match scene.accel.intersect(&scene.shapes, &next) {
            Some(h2) => {
                if let Some(li) = scene.surfaces[h2.shape as usize].light {
                    let le = scene.lights[li as usize].emitted(h2.n_geom, -next.d, h2.uv, w);
                    if !le.is_zero() {
                        let wgt = if bs.specular {
                            1.0
                        } else {
                            weight(nb * bs.pdf, nl * pl(li as usize, h2.p, h2.n_geom))
                        };
                        l += beta * le * (wgt / nb);
                    }
                }
            }
            None => {
                for &i in &scene.infinite_lights {
                    let le = scene.lights[i as usize].escaped(next.d, w);
                    if le.is_zero() {
                        continue;
                    }
                    let wgt = if bs.specular {
                        1.0
                    } else {
                        weight(nb * bs.pdf, nl * pl(i as usize, Vec3::ZERO, Vec3::ZERO))
                    };
                    l += beta * le * (wgt / nb);
                }
            }
        }
    }
    l
}
