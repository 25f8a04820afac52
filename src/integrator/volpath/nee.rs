//! Next-event estimation in a scene with media (pbrt-v4 §14.2.4, `SampleLd`), the shadow rays'
//! transmittance through media and index-matched surfaces, and the medium a ray enters.

use glam::Vec3;

use super::{MAX_CROSSINGS, Path};
use crate::geometry::shape::Intersection;
use crate::geometry::{spawn_ray, spawn_ray_to};
use crate::integrator::{Integrator, Shading};
use crate::light::LightSample;
use crate::material::TransportMode;
use crate::medium::live_average;
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A vertex from which light is sampled.
pub(super) enum Vertex<'a, 'b, const N: usize> {
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
pub(super) fn next_event<const N: usize>(
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
    let (tr, pass) = it.shadow_transmittance(origin, ShadowTarget::light(&ls), w, s);
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

/// Where a shadow ray goes: a point (on a surface with its error bound and normal, or zero
/// for a point in space) or a direction to infinity.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ShadowTarget {
    Point { p: Vec3, p_error: Vec3, n: Vec3 },
    Direction(Vec3),
}

impl ShadowTarget {
    /// The light sample's point, or its direction for a light at infinity.
    pub(crate) fn light<const N: usize>(ls: &LightSample<N>) -> Self {
        if ls.distance.is_finite() {
            ShadowTarget::Point {
                p: ls.p,
                p_error: ls.p_error,
                n: ls.n,
            }
        } else {
            ShadowTarget::Direction(ls.wi)
        }
    }
}

impl Integrator<'_> {
    /// The medium at the point `p` (found along the ray from `p` in direction `d`: the side
    /// facing `p` of the first shape that bounds a medium; vacuum if none does). For points
    /// whose medium no path state tells, such as a light's.
    pub(crate) fn medium_at(&self, p: Vec3, p_error: Vec3, n: Vec3, d: Vec3) -> Option<u32> {
        let scene = self.scene;
        let mut ray = spawn_ray(p, p_error, n, d);
        for _ in 0..MAX_CROSSINGS {
            let hit = scene.accel.intersect(&scene.shapes, &ray)?;
            if let Some(mi) = scene.medium_interfaces.get(hit.shape as usize)
                && mi.is_transition()
            {
                return if hit.n_geom.dot(ray.d) > 0.0 {
                    mi.interior
                } else {
                    mi.exterior
                };
            }
            let n = hit.n_geom_toward(ray.d);
            ray = spawn_ray(hit.p, hit.p_error, n, ray.d);
        }
        None
    }

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
        target: ShadowTarget,
        w: &SampledWavelengths<N>,
        s: &mut Sampler,
    ) -> (SampledSpectrum<N>, SampledSpectrum<N>) {
        let scene = self.scene;
        let (p, p_error, n, mut medium) = origin;
        let toward = |p: Vec3, p_error: Vec3, n: Vec3| match target {
            ShadowTarget::Point {
                p: q,
                p_error: e,
                n: m,
            } => spawn_ray_to(p, p_error, n, q, e, m),
            ShadowTarget::Direction(d) => spawn_ray(p, p_error, n, d),
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
            let n = hit.n_geom_toward(ray.d);
            ray = toward(hit.p, hit.p_error, n);
        }
        zero
    }
}
