//! The scheduler of bidirectional path tracing: camera samples by tiles and passes as for
//! `path`, each tile also recording the splats of its t = 1 strategies (light vertices seen by
//! the camera, which land anywhere in the image) in a [`SplatList`]. Tiles are traced in
//! batches and merged in tile order, their splat lists applied right after them, so the image
//! does not depend on the number of threads and memory holds only a batch's lists. A pass
//! accumulates in a film of its own, added to the image only when every tile finished it: a
//! splat's weight assumes every pixel took the pass's samples, so a render stopped early keeps
//! its completed passes only.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use super::{RenderOptions, RenderStats, camera_sample, count_dropped, splat_filtered};
use crate::film::{Film, SplatList, Tile};
use crate::integrator::Integrator;
use crate::integrator::bdpt::{Scratch, sample};
use crate::sampler::Sampler;
use crate::spectrum::{N_WAVELENGTHS, WavelengthSampler};

/// What a BDPT render reads.
pub(super) struct Ctx<'a> {
    pub opts: &'a RenderOptions,
    pub integrator: &'a Integrator<'a>,
    pub lambda: &'a WavelengthSampler,
    pub pool: &'a rayon::ThreadPool,
    pub cancel: &'a AtomicBool,
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
}

/// Key of the light subpaths' sampler streams (a stream per camera sample, apart from the
/// camera's).
const LIGHT_SEED: u32 = 0x4244_5054;

/// Renders `tiles` (x0, y0, width, height) in `passes` of sample indices [a, b).
///
/// Each pixel's value is the mean of its camera samples' t ≥ 2 strategies plus the splats of
/// the t = 1 strategies of all light subpaths (one per camera sample), whose estimator divides
/// by the number of light subpaths, pixels × spp: a splat's value is divided by the pixel
/// count here, so that the film's division by each pixel's sample count (spp) completes it.
pub(super) fn render(
    ctx: &Ctx<'_>,
    mut film: Film,
    tiles: &[(u32, u32, u32, u32)],
    passes: &[(u32, u32)],
    start: Instant,
) -> (Film, RenderStats) {
    let (opts, it) = (ctx.opts, ctx.integrator);
    let (w, h) = (film.width, film.height);
    let inv_pixels = 1.0 / (w as f32 * h as f32);
    let total = w as u64 * h as u64 * opts.spp as u64;
    let (filter, bins) = (film.filter.clone(), film.bins.clone());
    let done = AtomicU64::new(0);
    let (nan, inf) = (AtomicU64::new(0), AtomicU64::new(0));
    // tiles traced at once: a few per thread, each holding its pass's splats
    let batch = 4 * ctx.pool.current_num_threads().max(1);
    let mut spp_done = 0;
    let mut partial = false;
    'passes: for &(a, b) in passes {
        let mut pass = film.empty_like();
        for chunk in tiles.chunks(batch) {
            if ctx.cancel.load(Ordering::Relaxed) {
                partial = true;
                break 'passes;
            }
            let out: Vec<Option<(Tile, SplatList)>> = ctx.pool.install(|| {
                chunk
                    .par_iter()
                    .map(|&(x0, y0, tw, th)| {
                        if ctx.cancel.load(Ordering::Relaxed) {
                            return None;
                        }
                        let mut tile = pass.tile(x0, y0, tw, th);
                        let mut list = SplatList::new(w);
                        let mut scratch = Scratch::<N_WAVELENGTHS>::new(it.max_depth);
                        for y in y0..y0 + th {
                            for x in x0..x0 + tw {
                                for i in a..b {
                                    let (mut s, wl, ray) = camera_sample(
                                        it.scene, ctx.lambda, &filter, opts.seed, x, y, i,
                                    );
                                    let mut sl = Sampler::new(opts.seed ^ LIGHT_SEED, x, y, i);
                                    let l = sample(
                                        it,
                                        ray,
                                        &wl,
                                        &mut s,
                                        &mut sl,
                                        filter.radius,
                                        &mut scratch,
                                        &mut |raster, wl, v| {
                                            let v = v * inv_pixels;
                                            let b = bins.as_ref();
                                            if !splat_filtered(
                                                &mut list,
                                                (w, h),
                                                &filter,
                                                raster,
                                                wl,
                                                &v,
                                                b,
                                            ) {
                                                count_dropped(wl, &v, &nan, &inf);
                                            }
                                        },
                                    );
                                    // the sample counts once; its hero-only part adds to it
                                    let b = bins.as_ref();
                                    if !tile.add(x, y, &wl, &l.all, b) {
                                        count_dropped(&wl, &l.all, &nan, &inf);
                                    }
                                    let wh = &l.hero_only;
                                    if !l.hero.is_zero() && !tile.splat(x, y, wh, &l.hero, b) {
                                        count_dropped(wh, &l.hero, &nan, &inf);
                                    }
                                }
                            }
                        }
                        let n = (tw * th * (b - a)) as u64;
                        (ctx.progress)(done.fetch_add(n, Ordering::Relaxed) + n, total);
                        Some((tile, list))
                    })
                    .collect()
            });
            for r in out {
                match r {
                    Some((tile, list)) => {
                        pass.merge(&tile);
                        pass.apply(&list);
                    }
                    None => partial = true,
                }
            }
            if partial {
                break 'passes;
            }
        }
        film.merge_film(&pass);
        spp_done = b;
    }
    let stats = RenderStats {
        // the samples of completed passes, the only ones in the image
        samples: w as u64 * h as u64 * spp_done as u64,
        nan_samples: nan.load(Ordering::Relaxed),
        inf_samples: inf.load(Ordering::Relaxed),
        elapsed: start.elapsed(),
        partial: partial || ctx.cancel.load(Ordering::Relaxed),
        spp_done,
    };
    (film, stats)
}
