//! The tile scheduler: renders a [`Scene`] into a [`Film`] on a rayon thread pool (the only
//! module that names rayon), in passes of samples per pixel so that a render stopped early is
//! uniformly converged. Progress is reported through a callback.
//!
//! Determinism: every sample draws from a [`Sampler`] keyed on (seed, pixel, sample index), and
//! every pixel belongs to one tile that adds its samples in index order, so the image is the
//! same for any number of threads.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::Vec2;
use rayon::prelude::*;

use crate::film::{Film, Filter, NonFinite, non_finite};
use crate::integrator::Integrator;
use crate::loader::desc::IntegratorKind;
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::spectrum::{N_WAVELENGTHS, SampledWavelengths, WavelengthSampler};

/// Tile side, pixels.
const TILE: u32 = 16;

/// What to render and how.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub spp: u32,
    /// Worker threads (None: every core).
    pub threads: Option<usize>,
    pub seed: u32,
    pub integrator: IntegratorKind,
    pub max_depth: u32,
    pub spectral_bins: u32,
}

impl RenderOptions {
    /// The scene's own settings.
    pub fn from_scene(scene: &Scene) -> Self {
        Self {
            spp: scene.film.spp,
            threads: None,
            seed: 0,
            integrator: scene.integrator.kind,
            max_depth: scene.integrator.max_depth,
            spectral_bins: scene.film.spectral_bins,
        }
    }
}

/// What happened during a render.
#[derive(Clone, Debug, Default)]
pub struct RenderStats {
    /// Samples added to the film.
    pub samples: u64,
    /// Samples dropped because their radiance was NaN.
    pub nan_samples: u64,
    /// Samples dropped because their radiance was infinite.
    pub inf_samples: u64,
    pub elapsed: Duration,
    /// Whether the render was stopped before all samples were taken.
    pub partial: bool,
    /// Samples per pixel completed everywhere.
    pub spp_done: u32,
}

/// Why a render could not start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("cannot start {threads} render threads: {message}")]
    Threads { threads: usize, message: String },
    #[error("the `light` integrator connects to a pinhole camera; use a perspective camera")]
    Camera,
}

/// Renders `scene`. `cancel` stops the render between tiles; `progress(done, total)` is called
/// with sample counts as tiles finish.
pub fn render(
    scene: &Scene,
    opts: &RenderOptions,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<(Film, RenderStats), RenderError> {
    let start = Instant::now();
    let (w, h) = (scene.film.width, scene.film.height);
    let film = Film::new(
        w,
        h,
        Filter::from_desc(&scene.film.filter),
        scene.wavelengths,
        opts.spectral_bins,
    );
    let (filter, bins) = (film.filter.clone(), film.bins.clone());
    let film = Mutex::new(film);
    let integrator = Integrator::new(scene, opts.integrator, opts.max_depth);
    let lambda = WavelengthSampler::visible(scene.wavelengths);
    let tiles: Vec<(u32, u32, u32, u32)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .map(|(x0, y0)| (x0, y0, TILE.min(w - x0), TILE.min(h - y0)))
        .collect();
    let total = w as u64 * h as u64 * opts.spp as u64;
    let done = AtomicU64::new(0);
    let nan = AtomicU64::new(0);
    let inf = AtomicU64::new(0);
    let threads = opts.threads.unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| RenderError::Threads {
            threads,
            message: e.to_string(),
        })?;
    // passes of doubling size: 1, 1, 2, 4, … samples per pixel, so an early stop has every
    // pixel at the same sample count
    let mut passes = Vec::new();
    let mut s0 = 0;
    while s0 < opts.spp {
        let n = s0.max(1).min(opts.spp - s0).min(64);
        passes.push((s0, s0 + n));
        s0 += n;
    }
    let mut spp_done = 0;
    let mut partial = false;
    if opts.integrator == IntegratorKind::Light {
        let film = film.into_inner().unwrap_or_else(|p| p.into_inner());
        if !matches!(scene.camera, crate::geometry::Camera::Perspective(_)) {
            return Err(RenderError::Camera);
        }
        return render_light(
            opts,
            film,
            &integrator,
            &lambda,
            &pool,
            cancel,
            progress,
            start,
        );
    }
    for (a, b) in passes {
        if cancel.load(Ordering::Relaxed) {
            partial = true;
            break;
        }
        let finished: Vec<bool> = pool.install(|| {
            tiles
                .par_iter()
                .map(|&(x0, y0, tw, th)| {
                    if cancel.load(Ordering::Relaxed) {
                        return false;
                    }
                    let mut tile = crate::film::Tile::new(
                        x0,
                        y0,
                        tw,
                        th,
                        bins.as_ref().map_or(0, |b| b.count),
                    );
                    for y in y0..y0 + th {
                        for x in x0..x0 + tw {
                            for i in a..b {
                                let mut s = Sampler::new(opts.seed, x, y, i);
                                let mut wl: SampledWavelengths<N_WAVELENGTHS> =
                                    lambda.sample(s.get_1d());
                                let offset = filter.sample(s.get_2d());
                                let raster = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + offset;
                                let ray = scene.camera.generate_ray(raster, s.get_2d());
                                let l = integrator.radiance(ray, &mut wl, &mut s);
                                if !tile.add(x, y, &wl, &l, bins.as_ref()) {
                                    if non_finite(&wl, &l) == Some(NonFinite::NaN) {
                                        nan.fetch_add(1, Ordering::Relaxed);
                                    } else {
                                        inf.fetch_add(1, Ordering::Relaxed);
                                    }
                                }
                            }
                        }
                    }
                    match film.lock() {
                        Ok(mut f) => f.merge(&tile),
                        Err(p) => p.into_inner().merge(&tile),
                    }
                    let n = done.fetch_add((tw * th * (b - a)) as u64, Ordering::Relaxed)
                        + (tw * th * (b - a)) as u64;
                    progress(n, total);
                    true
                })
                .collect()
        });
        if finished.iter().all(|&f| f) {
            spp_done = b;
        } else {
            partial = true;
            break;
        }
    }
    let film = film.into_inner().unwrap_or_else(|p| p.into_inner());
    let stats = RenderStats {
        samples: done.load(Ordering::Relaxed),
        nan_samples: nan.load(Ordering::Relaxed),
        inf_samples: inf.load(Ordering::Relaxed),
        elapsed: start.elapsed(),
        partial: partial || cancel.load(Ordering::Relaxed),
        spp_done,
    };
    Ok((film, stats))
}

/// Light tracing: `spp × pixels` paths in a fixed number of chunks, each splatting into its own
/// full-image tile; chunks are merged in order, so the image does not depend on the threads.
#[allow(clippy::too_many_arguments)]
fn render_light(
    opts: &RenderOptions,
    mut film: Film,
    integrator: &Integrator<'_>,
    lambda: &WavelengthSampler,
    pool: &rayon::ThreadPool,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64, u64) + Sync),
    start: Instant,
) -> Result<(Film, RenderStats), RenderError> {
    const CHUNKS: u64 = 8;
    let (w, h) = (film.width, film.height);
    let pixels = w as u64 * h as u64;
    let total = pixels * opts.spp as u64;
    let bins = film.bins.clone();
    let done = AtomicU64::new(0);
    let (nan, inf) = (AtomicU64::new(0), AtomicU64::new(0));
    let tiles: Vec<(crate::film::Tile, u64)> = pool.install(|| {
        (0..CHUNKS)
            .into_par_iter()
            .map(|c| {
                let mut tile = film.tile(0, 0, w, h);
                let (lo, hi) = (total * c / CHUNKS, total * (c + 1) / CHUNKS);
                let mut traced = 0;
                for i in lo..hi {
                    if (i - lo) % 4096 == 0 {
                        if cancel.load(Ordering::Relaxed) {
                            break;
                        }
                        let n = done.fetch_add(4096.min(hi - i), Ordering::Relaxed);
                        progress(n, total);
                    }
                    let px = i % pixels;
                    let mut s = Sampler::new(
                        opts.seed ^ 0x4c49_4748,
                        (px % w as u64) as u32,
                        (px / w as u64) as u32,
                        (i / pixels) as u32,
                    );
                    let mut wl: SampledWavelengths<N_WAVELENGTHS> = lambda.sample(s.get_1d());
                    crate::integrator::light::trace(
                        integrator,
                        &mut wl,
                        &mut s,
                        &mut |raster, wl, l| {
                            let (x, y) =
                                ((raster.x as u32).min(w - 1), (raster.y as u32).min(h - 1));
                            if !tile.splat(x, y, wl, &l, bins.as_ref()) {
                                let counter = if non_finite(wl, &l) == Some(NonFinite::NaN) {
                                    &nan
                                } else {
                                    &inf
                                };
                                counter.fetch_add(1, Ordering::Relaxed);
                            }
                        },
                    );
                    traced += 1;
                }
                (tile, traced)
            })
            .collect()
    });
    let mut paths = 0;
    for (tile, traced) in &tiles {
        film.merge(tile);
        paths += traced;
    }
    film.set_path_count(paths.max(1));
    let partial = paths < total || cancel.load(Ordering::Relaxed);
    let stats = RenderStats {
        samples: paths,
        nan_samples: nan.load(Ordering::Relaxed),
        inf_samples: inf.load(Ordering::Relaxed),
        elapsed: start.elapsed(),
        partial,
        spp_done: (paths / pixels) as u32,
    };
    Ok((film, stats))
}
