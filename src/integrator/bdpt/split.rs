//! A BDPT sample split at dispersion (`crate::integrator::split` argues why the average of
//! the hero's rotations is unbiased): when the camera subpath meets a dispersive interface,
//! the sample's subpaths are walked again from the same sampler streams with each other
//! wavelength as the hero, and each rotation's dispersive strategies (the ones that keep the
//! hero alone) are added at 1/N. The strategies without a dispersive vertex estimate every
//! wavelength already and are taken from the first rotation only: they would be the same in
//! every rotation, since nothing before a subpath's first dispersive vertex depends on the
//! hero. Camera-side values are brought back to the sample's own wavelengths
//! (`split::to_original`), so the sample's radiance is all in `Radiance::all`; t = 1 splats
//! keep their rotation's wavelengths and land where that rotation's path leads.

use glam::Vec2;

use super::{Keep, Radiance, Scratch, strategies, walks};
use crate::geometry::Ray;
use crate::integrator::split::to_original;
use crate::integrator::{Integrator, Splatted};
use crate::sampler::Sampler;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// What every rotation of a sample shares.
pub(super) struct Sample<'b, const N: usize> {
    pub ray: Ray,
    /// The sample's own wavelengths (the first rotation's).
    pub w: &'b SampledWavelengths<N>,
    /// The connections' stream.
    pub conn: &'b Sampler,
    /// Filter radius, pixels.
    pub margin: f32,
}

/// The `N` rotations of a sample whose subpaths are in `scratch` (the first rotation's),
/// `streams` the camera and light streams as they were before the walks. Adds to `out.all`.
pub(super) fn rotations<'a, const N: usize>(
    it: &'a Integrator<'a>,
    sample: &Sample<'_, N>,
    streams: (Sampler, Sampler),
    scratch: &mut Scratch<'a, N>,
    splat: &mut impl FnMut(Vec2, &SampledWavelengths<N>, Splatted<N>),
    out: &mut Radiance<N>,
) {
    let scale = 1.0 / N as f32;
    let (ray, w, conn, margin) = (sample.ray, sample.w, sample.conn, sample.margin);
    let keep = Keep::Every { dispersive: scale };
    strategies(it, ray, w, conn, margin, scratch, splat, keep, out);
    out.all += to_original(w, 0, &out.hero_only, &out.hero);
    out.hero = SampledSpectrum::zero();
    for j in 1..N {
        let wj = w.rotated(j);
        let (mut s, mut sl) = (streams.0.clone(), streams.1.clone());
        let glow = walks(it, ray, &wj, &mut s, &mut sl, scratch);
        debug_assert!(
            glow.all.is_zero() && glow.hero.is_zero(),
            "no media when split"
        );
        let mut part = Radiance::zero(&wj);
        let keep = Keep::Dispersive { scale };
        strategies(it, ray, &wj, conn, margin, scratch, splat, keep, &mut part);
        out.all += to_original(w, j, &part.hero_only, &part.hero);
    }
}
