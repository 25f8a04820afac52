//! Irradiance meters: E(p, n) = ∫ L_i(p, ω) cos θ dω over the hemisphere around `n`, the
//! quantity Radiance's `rtrace -I` computes, estimated as the path tracer estimates light
//! reflected by a white Lambertian surface at p (of radiance E/π):
//!
//! 1. one light sample (next-event estimation): L·cos θ / p_light, MIS-weighted by the power
//!    heuristic against the cosine density (Veach 1997 §9.2); delta lights weight 1;
//! 2. one cosine-weighted direction (pdf cos θ/π per sr): π × the path-traced radiance along it,
//!    its first emitter hit MIS-weighted against step 1 (`path::radiance_after_sample`), so
//!    indirect light of every order is included.
//!
//! The meter is a point in space, not a surface: its rays start a hair (relative 2⁻²⁰ of the
//! coordinates, at least 1 µm) off p along ±n, so a meter lying on a floor sees the room above
//! it and not the floor.

use glam::{Vec2, Vec3};

use super::Integrator;
use crate::geometry::{Frame, spawn_ray, spawn_ray_to};
use crate::sampler::Sampler;
use crate::sampling::{cosine_hemisphere, power_heuristic};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Spectral irradiance at `p` (m) on the side of the unit normal `n`, W·m⁻²·nm⁻¹ at the
/// wavelengths `w` (which may be terminated to the hero by a dispersive hit). Reads two 2D
/// dimensions (light, direction), then the path tracer's.
pub fn irradiance<const N: usize>(
    it: &Integrator<'_>,
    p: Vec3,
    n: Vec3,
    w: &mut SampledWavelengths<N>,
    s: &mut Sampler,
) -> SampledSpectrum<N> {
    let scene = it.scene;
    let p_error = Vec3::splat(p.abs().max_element() * (1.0 / (1u32 << 20) as f32) + 1e-6);
    let mut e = SampledSpectrum::<N>::zero();

    // 1. Next-event estimation.
    let u = s.get_2d();
    if let Some((li, p_sel, ux)) = it.pick_light(p, n, u.x) {
        let light = &scene.lights[li];
        if let Some(ls) = light.sample_li(&scene.shapes, p, w, Vec2::new(ux, u.y)) {
            let cos = ls.wi.dot(n);
            if cos > 0.0 && !ls.li.is_zero() {
                let ray = if ls.distance.is_finite() {
                    spawn_ray_to(p, p_error, n, ls.p, ls.p_error, ls.n)
                } else {
                    spawn_ray(p, p_error, n, ls.wi)
                };
                if !scene.accel.occluded(&scene.shapes, &ray) {
                    let p_light = p_sel * ls.pdf;
                    let wgt = if ls.delta {
                        1.0
                    } else {
                        power_heuristic(1.0, p_light, 1.0, cos * std::f32::consts::FRAC_1_PI)
                    };
                    e += ls.li * (cos * wgt / p_light);
                }
            }
        }
    }

    // 2. A cosine-weighted direction and the radiance arriving along it.
    let local = cosine_hemisphere(s.get_2d());
    let pdf = local.z * std::f32::consts::FRAC_1_PI;
    if pdf > 0.0 {
        let d = Frame::from_normal(n).to_world(local);
        let ray = spawn_ray(p, p_error, n, d);
        let l = super::path::radiance_after_sample(it, ray, pdf, n, w, s);
        e += l * std::f32::consts::PI;
    }
    e
}
