//! Light tracing's scheduler: light paths in chunks, their splats recorded in lists and applied
//! in chunk order; then camera rays for the lights at infinity seen directly.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use super::{Ctx, RenderStats, Snapshot, StopReason, camera_sample, count_dropped, splat_filtered};
use crate::film::{Film, SplatList};
use crate::sampler::Sampler;

/// Light paths per chunk of the light tracer: a chunk's splat list stays a few MB.
const LIGHT_CHUNK: u64 = 4096;

/// Light tracing: `pixels` paths per sample index of the range [first, end), path `i` keyed
/// on pixel `i mod pixels` and sample `i / pixels` (global indices, so render parts trace
/// disjoint paths of the whole), in chunks of [`LIGHT_CHUNK`] paths, each recording its splats
/// in a [`SplatList`] (memory for its splats, not a full-image tile, so there can be many
/// chunks and every thread stays busy). Chunks are traced in batches of a few per thread; the
/// film's sums are exact, so the image does not depend on the number of threads, and a
/// checkpoint between batches resumes bit-exactly.
pub(super) fn render(ctx: &Ctx<'_>, snap: Snapshot) -> (Film, RenderStats) {
    let (opts, integrator) = (ctx.opts, ctx.integrator);
    let mut film = snap.film;
    let (w, h) = (film.width, film.height);
    let pixels = w as u64 * h as u64;
    let (first, end) = opts.sample_range();
    let (base, total) = (first as u64 * pixels, (end - first) as u64 * pixels);
    let bins = film.bins.clone();
    let filter = film.filter.clone();
    let done = AtomicU64::new(snap.paths_done);
    let (nan, inf) = (
        AtomicU64::new(snap.nan_samples),
        AtomicU64::new(snap.inf_samples),
    );
    let chunks = total.div_ceil(LIGHT_CHUNK);
    // lists alive at once: two per thread (a few MB each), whatever the image size
    let batch = 2 * ctx.pool.current_num_threads().max(1) as u64;
    let mut paths = snap.paths_done.min(total);
    let mut first_chunk = paths / LIGHT_CHUNK;
    let mut stop = StopReason::Complete;
    let snapshot = |film: &Film, paths: u64| Snapshot {
        film: film.clone(),
        pass_film: None,
        pass: 0,
        tiles_done: Vec::new(),
        paths_done: paths,
        nan_samples: nan.load(Ordering::Relaxed),
        inf_samples: inf.load(Ordering::Relaxed),
        elapsed: ctx.budget.elapsed(),
    };
    let mut last_batch: Option<(u64, std::time::Duration)> = None;
    while first_chunk < chunks {
        if ctx.cancel.load(Ordering::Relaxed) {
            stop = StopReason::Cancelled;
            break;
        }
        let last = (first_chunk + batch).min(chunks);
        let n_next = (last * LIGHT_CHUNK).min(total) - first_chunk * LIGHT_CHUNK;
        if ctx.budget.spent()
            || last_batch.is_some_and(|(n, took)| ctx.budget.would_exceed(n, took, n_next))
        {
            stop = StopReason::TimeLimit;
            break;
        }
        let t0 = Instant::now();
        let lists: Vec<(SplatList, u64)> = ctx.pool.install(|| {
            (first_chunk..last)
                .into_par_iter()
                .map(|c| {
                    let mut list = SplatList::new(w);
                    let (lo, hi) = (c * LIGHT_CHUNK, ((c + 1) * LIGHT_CHUNK).min(total));
                    if ctx.cancel.load(Ordering::Relaxed) {
                        return (list, 0);
                    }
                    let n = done.fetch_add(hi - lo, Ordering::Relaxed);
                    (ctx.progress)(n, ctx.total);
                    for i in base + lo..base + hi {
                        let px = i % pixels;
                        let mut s = Sampler::new(
                            opts.seed ^ 0x4c49_4748,
                            (px % w as u64) as u32,
                            (px / w as u64) as u32,
                            (i / pixels) as u32,
                        );
                        let mut wl = super::draw_wavelengths(ctx.lambda, &mut s);
                        crate::integrator::light::trace(
                            integrator,
                            filter.radius,
                            &mut wl,
                            &mut s,
                            &mut |raster, wl, l| {
                                let b = bins.as_ref();
                                let size = (w, h);
                                if !splat_filtered(&mut list, size, &filter, raster, wl, &l, b) {
                                    count_dropped(wl, l.radiance(), &nan, &inf);
                                }
                            },
                        );
                    }
                    (list, hi - lo)
                })
                .collect()
        });
        // a chunk cancelled before it started leaves a gap: keep only the chunks before it
        let complete = lists.iter().take_while(|(_, n)| *n > 0).count();
        for (list, traced) in &lists[..complete] {
            film.apply(list);
            paths += traced;
        }
        if complete < lists.len() {
            stop = StopReason::Cancelled;
            break;
        }
        last_batch = Some((n_next, t0.elapsed()));
        first_chunk = last;
        if let Some(t) = &ctx.ticker
            && t.due()
        {
            t.write(&snapshot(&film, paths));
        }
    }
    ctx.final_checkpoint(&snapshot(&film, paths));
    film.set_path_count(paths.max(1));
    let cam_cancelled = infinite_lights_pass(ctx, &mut film, paths, (&nan, &inf));
    if cam_cancelled {
        stop = StopReason::Cancelled;
    }
    let stats = RenderStats {
        samples: paths,
        nan_samples: nan.load(Ordering::Relaxed),
        inf_samples: inf.load(Ordering::Relaxed),
        elapsed: ctx.budget.elapsed(),
        partial: stop == StopReason::Cancelled,
        spp_done: (paths / pixels) as u32,
        stop,
        rel_error: None,
    };
    (film, stats)
}

/// Lights at infinity seen directly (sky, sun disk): camera rays with the filter's offsets,
/// each adding the escaped radiance times paths / (samples per pixel), so that the film's
/// division by the path count leaves their mean (the factor is the pixel count when every
/// path was traced). True if cancelled part-way.
fn infinite_lights_pass(
    ctx: &Ctx<'_>,
    film: &mut Film,
    paths: u64,
    (nan, inf): (&AtomicU64, &AtomicU64),
) -> bool {
    let (opts, integrator) = (ctx.opts, ctx.integrator);
    if !(crate::integrator::light::has_visible_infinite_lights(integrator) && paths > 0) {
        return false;
    }
    let (w, h) = (film.width, film.height);
    let (first, end) = opts.sample_range();
    let (bins, filter) = (film.bins.clone(), film.filter.clone());
    let mut cam_cancelled = false;
    let scene = integrator.scene;
    let scale = paths as f64 / (end - first).max(1) as f64;
    let rows: Vec<Option<crate::film::Tile>> = ctx.pool.install(|| {
        (0..h)
            .into_par_iter()
            .map(|y| {
                if ctx.cancel.load(Ordering::Relaxed) {
                    return None;
                }
                let mut tile = film.tile(0, y, w, 1);
                for x in 0..w {
                    for i in first..end {
                        let seed = opts.seed ^ 0x534b_5900;
                        let (_, wl, ray, _) =
                            camera_sample(scene, ctx.lambda, &filter, seed, x, y, i);
                        let l = crate::integrator::light::escaped(integrator, &ray, &wl);
                        if !tile.splat_scaled(x, y, &wl, &l, bins.as_ref(), scale) {
                            count_dropped(&wl, &l, nan, inf);
                        }
                    }
                }
                Some(tile)
            })
            .collect()
    });
    for row in &rows {
        match row {
            Some(t) => film.merge(t),
            None => cam_cancelled = true,
        }
    }
    cam_cancelled
}
