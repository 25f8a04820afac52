//! The camera-ray integrators' scheduler: passes of samples over 16×16 tiles, each tile summed
//! apart and added to the film, the tiles done recorded for checkpoints.

use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use super::control::ErrorEstimate;
use super::{Ctx, RenderStats, Snapshot, StopReason, camera_sample};
use crate::film::{Bins, Film, Filter, NonFinite, Tile, non_finite};

/// The state of a pass shared by the threads: the film and the tiles summed into it.
struct Shared {
    film: Film,
    tiles_done: Vec<bool>,
    nan: u64,
    inf: u64,
}

/// Camera-ray integrators (`path`, `whitted`, `direct`): each pass renders the tiles not yet
/// done, each tile summing its pixels' samples in a tile of its own and adding it to the film.
pub(super) fn render(
    ctx: &Ctx<'_>,
    snap: Snapshot,
    tiles: &[(u32, u32, u32, u32)],
    passes: &[(u32, u32)],
) -> (Film, RenderStats) {
    let opts = ctx.opts;
    let first = opts.sample_range().0;
    let (filter, bins) = (snap.film.filter.clone(), snap.film.bins.clone());
    let pixels = snap.film.width as u64 * snap.film.height as u64;
    let pass0 = (snap.pass as usize).min(passes.len());
    let done_before: u64 = passes[..pass0]
        .iter()
        .map(|(a, b)| (b - a) as u64 * pixels)
        .sum();
    let mut tiles_done = snap.tiles_done;
    if tiles_done.is_empty() {
        tiles_done = vec![false; tiles.len()];
    }
    let shared = Mutex::new(Shared {
        film: snap.film,
        tiles_done,
        nan: snap.nan_samples,
        inf: snap.inf_samples,
    });
    let lock = || shared.lock().unwrap_or_else(|p| p.into_inner());
    let done = AtomicU64::new(done_before);
    let snapshot = |s: &Shared, pass: usize| Snapshot {
        film: s.film.clone(),
        pass_film: None,
        pass: pass as u32,
        tiles_done: s.tiles_done.clone(),
        paths_done: 0,
        nan_samples: s.nan,
        inf_samples: s.inf,
        elapsed: ctx.budget.elapsed(),
    };
    let mut spp_done = if pass0 > 0 {
        passes[pass0 - 1].1 - first
    } else {
        0
    };
    let mut stop = StopReason::Complete;
    let mut estimate = ErrorEstimate::default();
    let mut pass = pass0;
    while pass < passes.len() {
        let (a, b) = passes[pass];
        if ctx.cancel.load(Ordering::Relaxed) {
            stop = StopReason::Cancelled;
            break;
        }
        if ctx.budget.spent() {
            stop = StopReason::TimeLimit;
            break;
        }
        let t0 = Instant::now();
        ctx.pool.install(|| {
            tiles
                .par_iter()
                .enumerate()
                .for_each(|(ti, &(x0, y0, tw, th))| {
                    if ctx.cancel.load(Ordering::Relaxed) || lock().tiles_done[ti] {
                        return;
                    }
                    let (tile, nan, inf) =
                        trace_tile(ctx, (x0, y0, tw, th), (a, b), &filter, bins.as_ref());
                    let n = (tw * th * (b - a)) as u64;
                    let mut s = lock();
                    s.film.merge(&tile);
                    s.tiles_done[ti] = true;
                    s.nan += nan;
                    s.inf += inf;
                    let due = ctx
                        .ticker
                        .as_ref()
                        .filter(|t| t.due())
                        .map(|_| snapshot(&s, pass));
                    drop(s);
                    if let (Some(t), Some(snap)) = (&ctx.ticker, due) {
                        t.write(&snap);
                    }
                    (ctx.progress)(done.fetch_add(n, Ordering::Relaxed) + n, ctx.total);
                })
        });
        let mut s = lock();
        if !s.tiles_done.iter().all(|&d| d) {
            stop = StopReason::Cancelled;
            break;
        }
        s.tiles_done.iter_mut().for_each(|d| *d = false);
        spp_done = b - first;
        pass += 1;
        estimate.update(&s.film, spp_done);
        drop(s);
        if let Some(why) = ctx.stop_after_pass(b - a, t0.elapsed(), passes.get(pass), estimate.last)
        {
            stop = why;
            break;
        }
    }
    let s = shared.into_inner().unwrap_or_else(|p| p.into_inner());
    ctx.final_checkpoint(&snapshot(&s, pass));
    let stats = RenderStats {
        samples: done.load(Ordering::Relaxed),
        nan_samples: s.nan,
        inf_samples: s.inf,
        elapsed: ctx.budget.elapsed(),
        partial: stop == StopReason::Cancelled,
        spp_done,
        stop,
        rel_error: estimate.last,
    };
    (s.film, stats)
}

/// One tile's samples [a, b) of every pixel, with the counts of samples dropped as NaN and as
/// infinite.
fn trace_tile(
    ctx: &Ctx<'_>,
    (x0, y0, tw, th): (u32, u32, u32, u32),
    (a, b): (u32, u32),
    filter: &Filter,
    bins: Option<&Bins>,
) -> (Tile, u64, u64) {
    let nb = bins.map_or(0, |b| b.count);
    let mut tile = crate::film::Tile::new(x0, y0, tw, th, nb);
    let polarised = ctx.integrator.polarised();
    if polarised {
        tile = tile.with_stokes();
    }
    let (mut nan, mut inf) = (0, 0);
    // pbrt-v4's firefly clamp, when the scene asks for it
    let max_component = ctx.integrator.scene.film.max_component;
    let clamp = |wl: &_, l| match max_component {
        Some(m) => crate::film::clamp_max_component(wl, l, m),
        None => l,
    };
    for y in y0..y0 + th {
        for x in x0..x0 + tw {
            for i in a..b {
                let (mut s, mut wl, ray, weight) = camera_sample(
                    ctx.integrator.scene,
                    ctx.lambda,
                    filter,
                    ctx.opts.seed,
                    x,
                    y,
                    i,
                );
                let (l, added) = if polarised {
                    let st = ctx.integrator.stokes(ray, &mut wl, &mut s);
                    (st[0], tile.add_stokes(x, y, &wl, &st, bins))
                } else if weight == 1.0 {
                    let l = ctx.integrator.radiance_split(ray, &mut wl, &mut s);
                    let l = clamp(&wl, l);
                    (l, tile.add(x, y, &wl, &l, bins))
                } else {
                    // a realistic camera's ray: weighted, or blocked by its lens (weight 0)
                    let l = if weight > 0.0 {
                        ctx.integrator.radiance_split(ray, &mut wl, &mut s) * weight
                    } else {
                        crate::spectrum::SampledSpectrum::zero()
                    };
                    let l = clamp(&wl, l);
                    (l, tile.add(x, y, &wl, &l, bins))
                };
                if !added {
                    match non_finite(&wl, &l) {
                        Some(NonFinite::NaN) => nan += 1,
                        _ => inf += 1,
                    }
                }
            }
        }
    }
    (tile, nan, inf)
}
