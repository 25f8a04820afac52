//! The scheduler of bidirectional path tracing: camera samples by tiles and passes as for
//! `path`, each tile also recording the splats of its t = 1 strategies (light vertices seen by
//! the camera, which land anywhere in the image) in a [`SplatList`]. Tiles are traced in
//! batches and merged in tile order, their splat lists applied right after them, so the image
//! does not depend on the number of threads and memory holds only a batch's lists. A pass
//! accumulates in a film of its own, added to the image only when every tile finished it: a
//! splat's weight assumes every pixel took the pass's samples, so a render stopped early keeps
//! its completed passes only.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use super::control::ErrorEstimate;
use super::{Ctx, RenderStats, Snapshot, StopReason, camera_sample, count_dropped, splat_filtered};
use crate::film::{Film, Splat, SplatList, Tile};
use crate::integrator::bdpt::{Scratch, sample};
use crate::sampler::Sampler;
use crate::spectrum::N_WAVELENGTHS;

/// Key of the light subpaths' sampler streams (a stream per camera sample, apart from the
/// camera's).
const LIGHT_SEED: u32 = 0x4244_5054;

/// Renders `tiles` (x0, y0, width, height) in `passes` of sample indices [a, b), continuing
/// from `snap`.
///
/// Each pixel's value is the mean of its camera samples' t ≥ 2 strategies plus the splats of
/// the t = 1 strategies of all light subpaths (one per camera sample), whose estimator divides
/// by the number of light subpaths, pixels × spp: a splat's value is divided by the pixel
/// count here, so that the film's division by each pixel's sample count (spp) completes it.
pub(super) fn render(
    ctx: &Ctx<'_>,
    snap: Snapshot,
    tiles: &[(u32, u32, u32, u32)],
    passes: &[(u32, u32)],
) -> (Film, RenderStats) {
    let opts = ctx.opts;
    let mut film = snap.film;
    let (w, h) = (film.width, film.height);
    let first = opts.sample_range().0;
    let pass0 = (snap.pass as usize).min(passes.len());
    let pixels = w as u64 * h as u64;
    let done_before: u64 = passes[..pass0]
        .iter()
        .map(|(a, b)| (b - a) as u64 * pixels)
        .sum();
    let done = AtomicU64::new(done_before);
    let (nan, inf) = (
        AtomicU64::new(snap.nan_samples),
        AtomicU64::new(snap.inf_samples),
    );
    // tiles traced at once: a few per thread, each holding its pass's splats
    let batch = 4 * ctx.pool.current_num_threads().max(1);
    let mut spp_done = if pass0 > 0 {
        passes[pass0 - 1].1 - first
    } else {
        0
    };
    let mut stop = StopReason::Complete;
    let mut estimate = ErrorEstimate::default();
    let mut resumed = Some((snap.pass_film, snap.tiles_done));
    let snapshot = |film: &Film, pass_film: &Film, pass: usize, tiles_done: &[bool]| Snapshot {
        film: film.clone(),
        pass_film: Some(pass_film.clone()),
        pass: pass as u32,
        tiles_done: tiles_done.to_vec(),
        paths_done: 0,
        nan_samples: nan.load(Ordering::Relaxed),
        inf_samples: inf.load(Ordering::Relaxed),
        elapsed: ctx.budget.elapsed(),
    };
    let mut pass = pass0;
    let mut pass_film = film.empty_like();
    let mut tiles_done = vec![false; tiles.len()];
    'passes: while pass < passes.len() {
        let (a, b) = passes[pass];
        pass_film = film.empty_like();
        tiles_done = vec![false; tiles.len()];
        if let Some((pf, td)) = resumed.take()
            && let Some(pf) = pf
            && td.len() == tiles.len()
        {
            (pass_film, tiles_done) = (pf, td);
        }
        if ctx.budget.spent() {
            stop = StopReason::TimeLimit;
            break;
        }
        let t0 = Instant::now();
        let todo: Vec<usize> = (0..tiles.len()).filter(|&t| !tiles_done[t]).collect();
        for chunk in todo.chunks(batch) {
            if ctx.cancel.load(Ordering::Relaxed) {
                stop = StopReason::Cancelled;
                break 'passes;
            }
            let out: Vec<Option<(Tile, SplatList)>> = ctx.pool.install(|| {
                chunk
                    .par_iter()
                    .map(|&ti| trace_tile(ctx, &pass_film, tiles[ti], (a, b), (&nan, &inf), &done))
                    .collect()
            });
            let mut cancelled = false;
            for (&ti, r) in chunk.iter().zip(out) {
                match r {
                    Some((tile, list)) => {
                        pass_film.merge(&tile);
                        pass_film.apply(&list);
                        tiles_done[ti] = true;
                    }
                    None => cancelled = true,
                }
            }
            if cancelled {
                stop = StopReason::Cancelled;
                break 'passes;
            }
            if let Some(t) = &ctx.ticker
                && t.due()
            {
                t.write(&snapshot(&film, &pass_film, pass, &tiles_done));
            }
        }
        film.merge_film(&pass_film);
        pass_film = film.empty_like();
        tiles_done = vec![false; tiles.len()];
        spp_done = b - first;
        pass += 1;
        estimate.update(&film, spp_done);
        if let Some(why) = ctx.stop_after_pass(b - a, t0.elapsed(), passes.get(pass), estimate.last)
        {
            stop = why;
            break;
        }
    }
    ctx.final_checkpoint(&snapshot(&film, &pass_film, pass, &tiles_done));
    let stats = RenderStats {
        // the samples of completed passes, the only ones in the image
        samples: pixels * spp_done as u64,
        nan_samples: nan.load(Ordering::Relaxed),
        inf_samples: inf.load(Ordering::Relaxed),
        elapsed: ctx.budget.elapsed(),
        partial: stop == StopReason::Cancelled,
        spp_done,
        stop,
        rel_error: estimate.last,
    };
    (film, stats)
}

/// One tile of one pass: its camera samples' t ≥ 2 strategies in a tile of `pass_film`'s
/// pixels and their light subpaths' t = 1 splats in a list (None if cancelled before it
/// started).
fn trace_tile(
    ctx: &Ctx<'_>,
    pass_film: &Film,
    rect: (u32, u32, u32, u32),
    (a, b): (u32, u32),
    (nan, inf): (&AtomicU64, &AtomicU64),
    done: &AtomicU64,
) -> Option<(Tile, SplatList)> {
    let (opts, it) = (ctx.opts, ctx.integrator);
    let (w, h) = (pass_film.width, pass_film.height);
    let inv_pixels = 1.0 / (w as f32 * h as f32);
    let (filter, bins) = (&pass_film.filter, &pass_film.bins);
    let (x0, y0, tw, th) = rect;
    if ctx.cancel.load(Ordering::Relaxed) {
        return None;
    }
    let mut tile = pass_film.tile(x0, y0, tw, th);
    let mut list = SplatList::new(w);
    let mut scratch = Scratch::<N_WAVELENGTHS>::new(it.max_depth);
    let polarised = it.polarised();
    for y in y0..y0 + th {
        for x in x0..x0 + tw {
            for i in a..b {
                let (mut s, wl, ray, _) =
                    camera_sample(it.scene, ctx.lambda, filter, opts.seed, x, y, i);
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
                        let v = v.scaled(inv_pixels);
                        let b = bins.as_ref();
                        if !splat_filtered(&mut list, (w, h), filter, raster, wl, &v, b) {
                            count_dropped(wl, v.radiance(), nan, inf);
                        }
                    },
                );
                // the sample counts once; its hero-only part adds to it
                let b = bins.as_ref();
                let wh = &l.hero_only;
                if polarised {
                    if !tile.add_stokes(x, y, &wl, &l.stokes_all, b) {
                        count_dropped(&wl, &l.stokes_all[0], nan, inf);
                    }
                    let one = std::iter::once((x, y, 1.0));
                    let st = &l.stokes_hero;
                    if st.iter().any(|v| !v.is_zero())
                        && !tile.splat_stokes_weighted(one, wh, st, b)
                    {
                        count_dropped(wh, &st[0], nan, inf);
                    }
                    continue;
                }
                if !tile.add(x, y, &wl, &l.all, b) {
                    count_dropped(&wl, &l.all, nan, inf);
                }
                if !l.hero.is_zero() && !tile.splat(x, y, wh, &l.hero, b) {
                    count_dropped(wh, &l.hero, nan, inf);
                }
            }
        }
    }
    let n = (tw * th * (b - a)) as u64;
    (ctx.progress)(done.fetch_add(n, Ordering::Relaxed) + n, ctx.total);
    Some((tile, list))
}
