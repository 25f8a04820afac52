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

mod bdpt;

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
    /// `bdpt` only: one connection strategy alone (debugging).
    pub strategy: Option<crate::integrator::bdpt::Strategy>,
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
            strategy: None,
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
    #[error(
        "the `{0}` integrator connects paths to the camera's lens, which an orthographic camera \
         does not have; use a perspective or thin-lens camera"
    )]
    Camera(&'static str),
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
    let mut integrator = Integrator::new(scene, opts.integrator, opts.max_depth);
    integrator.strategy = opts.strategy;
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
    if opts.integrator == IntegratorKind::Bdpt {
        let film = film.into_inner().unwrap_or_else(|p| p.into_inner());
        let ctx = bdpt::Ctx {
            opts,
            integrator: &integrator,
            lambda: &lambda,
            pool: &pool,
            cancel,
            progress,
        };
        return Ok(bdpt::render(&ctx, film, &tiles, &passes, start));
    }
    if opts.integrator == IntegratorKind::Light {
        let film = film.into_inner().unwrap_or_else(|p| p.into_inner());
        if matches!(scene.camera, crate::geometry::Camera::Orthographic(_)) {
            return Err(RenderError::Camera("light"));
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
                                let (mut s, mut wl, ray) =
                                    camera_sample(scene, &lambda, &filter, opts.seed, x, y, i);
                                let l = integrator.radiance(ray, &mut wl, &mut s);
                                if !tile.add(x, y, &wl, &l, bins.as_ref()) {
                                    count_dropped(&wl, &l, &nan, &inf);
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

/// Camera sample `i` of pixel (x, y) under `seed`: the wavelengths, the filter offset and the
/// lens position read the sampler's first dimensions in that order; returns the sampler (for
/// the integrator's further dimensions), the wavelengths and the camera ray.
#[inline]
fn camera_sample(
    scene: &Scene,
    lambda: &WavelengthSampler,
    filter: &Filter,
    seed: u32,
    x: u32,
    y: u32,
    i: u32,
) -> (
    Sampler,
    SampledWavelengths<N_WAVELENGTHS>,
    crate::geometry::Ray,
) {
    let mut s = Sampler::new(seed, x, y, i);
    let wl = lambda.sample(s.get_1d());
    let offset = filter.sample(s.get_2d());
    let raster = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + offset;
    let ray = scene.camera.generate_ray(raster, s.get_2d());
    (s, wl, ray)
}

/// Counts a sample the film refused, as NaN or as infinite by its live values.
#[inline]
fn count_dropped<const N: usize>(
    wl: &SampledWavelengths<N>,
    l: &crate::spectrum::SampledSpectrum<N>,
    nan: &AtomicU64,
    inf: &AtomicU64,
) {
    let counter = if non_finite(wl, l) == Some(NonFinite::NaN) {
        nan
    } else {
        inf
    };
    counter.fetch_add(1, Ordering::Relaxed);
}

/// Spreads a light-tracing splat at `raster` (pixels) over the pixels of the filter's support,
/// each with the filter's normalised weight f(raster − centre)/∫∫f (px⁻², times the pixel's
/// unit area): the same reconstruction, ∫ L(x) f(x − centre) dx / ∫ f, that camera rays
/// realise by sampling their offsets from the filter (pbrt-v4 §5.4.3). Pixels outside the
/// image (`size`, pixels) are skipped; `to` takes image coordinates. Returns false, adding
/// nothing, if `l` is not finite.
fn splat_filtered<const N: usize>(
    to: &mut impl crate::film::Splat,
    size: (u32, u32),
    filter: &Filter,
    raster: Vec2,
    wl: &SampledWavelengths<N>,
    l: &crate::spectrum::SampledSpectrum<N>,
    bins: Option<&crate::film::Bins>,
) -> bool {
    let r = filter.radius;
    // pixels whose centre x + 0.5 lies within [raster − r, raster + r], one more on each side
    // for rounding; `Filter::weight` decides the half-open support exactly
    let lo = (raster - Vec2::splat(0.5 + r)).floor().max(Vec2::ZERO);
    let hi = ((raster + Vec2::splat(r - 0.5)).floor() + Vec2::ONE)
        .min(Vec2::new(size.0 as f32 - 1.0, size.1 as f32 - 1.0));
    if hi.x < lo.x || hi.y < lo.y {
        return non_finite(wl, l).is_none();
    }
    let (x0, y0, x1, y1) = (lo.x as u32, lo.y as u32, hi.x as u32, hi.y as u32);
    let pixels = (y0..=y1)
        .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
        .filter_map(|(x, y)| {
            let wgt = filter.weight(raster - Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            (wgt > 0.0).then_some((x, y, wgt))
        });
    to.splat_weighted(pixels, wl, l, bins)
}

/// Light paths per chunk of the light tracer: a chunk's splat list stays a few MB.
const LIGHT_CHUNK: u64 = 4096;

/// Light tracing: `spp × pixels` paths in chunks of [`LIGHT_CHUNK`] paths, each recording its
/// splats in a [`crate::film::SplatList`] (memory for its splats, not a full-image tile, so
/// there can be many chunks and every thread stays busy). Chunks are traced in batches of a few
/// per thread and their lists applied to the film in chunk order, so the image does not depend
/// on the number of threads.
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
    let (w, h) = (film.width, film.height);
    let pixels = w as u64 * h as u64;
    let total = pixels * opts.spp as u64;
    let bins = film.bins.clone();
    let filter = film.filter.clone();
    let done = AtomicU64::new(0);
    let (nan, inf) = (AtomicU64::new(0), AtomicU64::new(0));
    let chunks = total.div_ceil(LIGHT_CHUNK);
    // lists alive at once: two per thread (a few MB each), whatever the image size
    let batch = 2 * pool.current_num_threads().max(1) as u64;
    let mut paths = 0;
    let mut first = 0;
    while first < chunks && !cancel.load(Ordering::Relaxed) {
        let last = (first + batch).min(chunks);
        let lists: Vec<(crate::film::SplatList, u64)> = pool.install(|| {
            (first..last)
                .into_par_iter()
                .map(|c| {
                    let mut list = crate::film::SplatList::new(w);
                    let (lo, hi) = (c * LIGHT_CHUNK, ((c + 1) * LIGHT_CHUNK).min(total));
                    if cancel.load(Ordering::Relaxed) {
                        return (list, 0);
                    }
                    let n = done.fetch_add(hi - lo, Ordering::Relaxed);
                    progress(n, total);
                    let mut traced = 0;
                    for i in lo..hi {
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
                            filter.radius,
                            &mut wl,
                            &mut s,
                            &mut |raster, wl, l| {
                                let b = bins.as_ref();
                                let size = (w, h);
                                if !splat_filtered(&mut list, size, &filter, raster, wl, &l, b) {
                                    count_dropped(wl, &l, &nan, &inf);
                                }
                            },
                        );
                        traced += 1;
                    }
                    (list, traced)
                })
                .collect()
        });
        for (list, traced) in &lists {
            film.apply(list);
            paths += traced;
        }
        first = last;
    }
    film.set_path_count(paths.max(1));
    // Lights at infinity seen directly (sky, sun disk): camera rays with the filter's offsets,
    // as in `render`, each adding the escaped radiance; their per-pixel sums are scaled by
    // paths / spp so that the film's division by the path count leaves their mean.
    let mut cam_cancelled = false;
    if crate::integrator::light::has_visible_infinite_lights(integrator) && paths > 0 {
        let scene = integrator.scene;
        let filter = film.filter.clone();
        let rows: Vec<Option<crate::film::Tile>> = pool.install(|| {
            (0..h)
                .into_par_iter()
                .map(|y| {
                    if cancel.load(Ordering::Relaxed) {
                        return None;
                    }
                    let mut tile = film.tile(0, y, w, 1);
                    for x in 0..w {
                        for i in 0..opts.spp {
                            let seed = opts.seed ^ 0x534b_5900;
                            let (_, wl, ray) = camera_sample(scene, lambda, &filter, seed, x, y, i);
                            let l = crate::integrator::light::escaped(integrator, &ray, &wl);
                            if !tile.splat(x, y, &wl, &l, bins.as_ref()) {
                                count_dropped(&wl, &l, &nan, &inf);
                            }
                        }
                    }
                    Some(tile)
                })
                .collect()
        });
        let scale = paths as f64 / opts.spp.max(1) as f64;
        for row in &rows {
            match row {
                Some(t) => film.merge_scaled(t, scale),
                None => cam_cancelled = true,
            }
        }
    }
    let partial = paths < total || cam_cancelled || cancel.load(Ordering::Relaxed);
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
