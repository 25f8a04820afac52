//! Every connection strategy (s, t) of one sample's subpaths: which ones a sample (or a
//! rotation of a split sample, `split.rs`) evaluates, and where each contribution goes: t = 1
//! splats to the caller, the others into the camera-side sums, at every wavelength or at the
//! hero alone where a dispersive vertex takes part.

use glam::Vec2;

use super::{Radiance, Scratch, connect, walk};
use crate::geometry::Ray;
use crate::integrator::carrier::to_camera_frame;
use crate::integrator::{Integrator, Splatted};
use crate::polarisation::Stokes;
use crate::sampler::Sampler;
use crate::spectrum::SampledWavelengths;

/// Which strategies [`strategies`] evaluates, and the factor on the hero-only ones.
#[derive(Clone, Copy)]
pub(super) enum Keep {
    /// All of them, the dispersive ones times `dispersive` (1, or 1/N in the first rotation
    /// of a split sample).
    Every { dispersive: f32 },
    /// The dispersive ones only, times `scale` (the other rotations of a split sample:
    /// `split.rs`).
    Dispersive { scale: f32 },
}

/// Every connection strategy of the subpaths in `scratch` at the wavelengths `w`: t = 1 ones
/// to `splat`, the others added to `out` (`all`, or `hero` at `out.hero_only` where a
/// dispersive vertex takes part), as `keep` says.
#[allow(clippy::too_many_arguments)]
pub(super) fn strategies<'a, const N: usize>(
    it: &'a Integrator<'a>,
    ray: Ray,
    w: &SampledWavelengths<N>,
    conn: &Sampler,
    margin: f32,
    scratch: &Scratch<'a, N>,
    splat: &mut impl FnMut(Vec2, &SampledWavelengths<N>, Splatted<N>),
    keep: Keep,
    out: &mut Radiance<N>,
) {
    let max_depth = it.max_depth as usize;
    let polarised = it.polarised();
    let (camera, light, pol) = (&scratch.camera, &scratch.light, &scratch.pol);
    // the camera side's Stokes sums (a polarised render), in the implicit basis of light
    // travelling along −ray.d
    let zero = [Stokes([0.0; 4]); N];
    let (mut st_all, mut st_hero) = (zero, zero);
    let (disp_c, disp_l) = (
        walk::first_dispersive(camera),
        walk::first_dispersive(light),
    );
    let hero_only = out.hero_only;
    for t in 1..=camera.len() {
        for s in 0..=light.len() {
            // depth = interior vertices of the full path = s + t − 2
            if (s == 1 && t == 1) || s + t < 2 || s + t - 2 > max_depth {
                continue;
            }
            if let Some(only) = it.strategy
                && (only.s as usize, only.t as usize) != (s, t)
            {
                continue;
            }
            let weighted = it.strategy.is_none_or(|o| o.weighted);
            let dispersive = s > disp_l || t > disp_c;
            let scale = match (keep, dispersive) {
                (Keep::Dispersive { .. }, false) => continue,
                (Keep::Dispersive { scale }, true) | (Keep::Every { dispersive: scale }, true) => {
                    scale
                }
                (Keep::Every { .. }, false) => 1.0,
            };
            let wl = if dispersive { &hero_only } else { w };
            let Some((c, raster, sampled)) =
                connect(it, light, camera, s, t, wl, conn, margin, weighted)
            else {
                continue;
            };
            let c = c * scale;
            if polarised {
                let (p, travel) =
                    pol.factor(it, light, camera, (s, t), sampled.as_ref(), ray.d, wl);
                let st: [Stokes; N] = std::array::from_fn(|j| p[j].scale(c[j]));
                match (raster, dispersive) {
                    (Some(r), _) => {
                        splat(r, wl, Splatted::Stokes(to_camera_frame(it, -travel, &st)))
                    }
                    (None, false) => add_stokes(&mut st_all, &st),
                    (None, true) => add_stokes(&mut st_hero, &st),
                }
                continue;
            }
            match (raster, dispersive) {
                (Some(r), _) => splat(r, wl, Splatted::Radiance(c)),
                (None, false) => out.all += c,
                (None, true) => out.hero += c,
            }
        }
    }
    if polarised {
        out.stokes_all = to_camera_frame(it, ray.d, &st_all);
        out.stokes_hero = to_camera_frame(it, ray.d, &st_hero);
        // a medium's glow (no polarised render has media) is unpolarised
        out.stokes_all[0] += out.all;
        out.stokes_hero[0] += out.hero;
    }
}

/// `sum` += `st`, per wavelength.
fn add_stokes<const N: usize>(sum: &mut [Stokes; N], st: &[Stokes; N]) {
    for (a, b) in sum.iter_mut().zip(st) {
        for (x, y) in a.0.iter_mut().zip(b.0) {
            *x += y;
        }
    }
}
