//! The scheduler: renders a [`Scene`] into a [`Film`] on a rayon thread pool (the only module
//! that names rayon), in passes of samples per pixel so that a render stopped early is
//! uniformly converged. Progress is reported through a callback; checkpoints, resuming, render
//! parts and budgets are steered by a [`Control`] (see `control.rs`).
//!
//! Determinism: every sample draws from a [`Sampler`] keyed on (seed, pixel, sample index), and
//! the film's sums are exact, so the image is the same for any number of threads, for a render
//! resumed from a checkpoint, and for the merge of render parts.
//!
//! | file | what it holds |
//! | --- | --- |
//! | `mod.rs` | options, statistics, [`render_with`], camera samples and splats |
//! | `tiles.rs` | the camera-ray integrators (`path`, `whitted`, `direct`) by tiles and passes |
//! | `control.rs` | passes, budgets, the error estimate, [`Snapshot`] |
//! | `light.rs` | light tracing in chunks of light paths |
//! | `bdpt.rs` | bidirectional path tracing: tiles and their splat lists |

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::Vec2;

use crate::film::{Film, Filter, NonFinite, non_finite};
use crate::integrator::Integrator;
use crate::integrator::IntegratorKind;
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::spectrum::{N_WAVELENGTHS, SampledWavelengths, WavelengthSampler};

pub mod aov;
mod bdpt;
mod control;
mod error;

pub use error::RenderError;
use error::check_integrator;
mod light;
pub mod measure;
mod tiles;

use control::{Budget, Ticker, check_resume, passes};
pub use control::{Snapshot, StopReason};

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
    /// Render only part `i` of `n` (0-based): the sample indices [⌊i·spp/n⌋, ⌊(i+1)·spp/n⌋) of
    /// every pixel (light tracing: the light paths of those samples). Merged, the parts' sums
    /// are those of the whole render, bit for bit.
    pub part: Option<(u32, u32)>,
    /// Stop at the end of a pass when the next one would end past this render time (counted
    /// over resumed sessions; light tracing: between batches of light paths).
    pub time_limit: Option<Duration>,
    /// Stop at the end of the first pass whose estimated relative error of Y (see
    /// `control::ErrorEstimate`) is below this (dimensionless, e.g. 0.01).
    pub target_error: Option<f64>,
    /// Split camera samples at dispersion (the scene's `dispersion = "split"`; see
    /// `integrator::split`). Ignored with media and in polarised renders.
    pub split_dispersion: bool,
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
            part: None,
            time_limit: None,
            target_error: None,
            split_dispersion: scene.integrator.split_dispersion,
        }
    }

    /// The sample indices [first, end) of every pixel this render takes.
    pub fn sample_range(&self) -> (u32, u32) {
        match self.part {
            Some((i, n)) if n > 0 && i < n => {
                let at = |k: u32| (self.spp as u64 * k as u64 / n as u64) as u32;
                (at(i), at(i + 1))
            }
            _ => (0, self.spp),
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
    /// Render time, over every session of a resumed render.
    pub elapsed: Duration,
    /// Whether the render was cancelled before all samples were taken.
    pub partial: bool,
    /// Samples per pixel completed everywhere (counted in the sample range).
    pub spp_done: u32,
    pub stop: StopReason,
    /// The last estimated relative error of Y, if two passes ended.
    pub rel_error: Option<f64>,
}

/// Writes a checkpoint of the render's state (reports its own failures: the render goes on).
pub type CheckpointWriter<'a> = dyn Fn(&Snapshot) + Sync + 'a;

/// How a render is steered from outside.
pub struct Control<'a> {
    /// Set to stop the render between tiles.
    pub cancel: &'a AtomicBool,
    /// Called with (samples done, samples of the render) as tiles finish.
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
    /// Checkpoints: the writer is given the render's state between tiles at most once per
    /// interval, and once more when the render ends for any reason.
    pub checkpoint: Option<(Duration, &'a CheckpointWriter<'a>)>,
    /// A state to continue from, written by an earlier render of the same scene and options.
    pub resume: Option<Snapshot>,
}

/// Renders `scene`. `cancel` stops the render between tiles; `progress(done, total)` is called
/// with sample counts as tiles finish.
pub fn render(
    scene: &Scene,
    opts: &RenderOptions,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<(Film, RenderStats), RenderError> {
    render_with(
        scene,
        opts,
        Control {
            cancel,
            progress,
            checkpoint: None,
            resume: None,
        },
    )
}

/// What every scheduler reads.
struct Ctx<'a> {
    opts: &'a RenderOptions,
    integrator: &'a Integrator<'a>,
    lambda: &'a WavelengthSampler,
    pool: &'a rayon::ThreadPool,
    cancel: &'a AtomicBool,
    progress: &'a (dyn Fn(u64, u64) + Sync),
    ticker: Option<Ticker<'a>>,
    budget: Budget,
    /// Samples this render takes in all (pixels × samples per pixel of the range).
    total: u64,
}

impl Ctx<'_> {
    /// Why to stop after a pass of `n` samples per pixel that took `took`, if there is a next
    /// pass: it would end past the time limit, or the estimated error `error` met the target.
    fn stop_after_pass(
        &self,
        n: u32,
        took: Duration,
        next: Option<&(u32, u32)>,
        error: Option<f64>,
    ) -> Option<StopReason> {
        let next = next?;
        if self
            .budget
            .would_exceed(n as u64, took, (next.1 - next.0) as u64)
        {
            return Some(StopReason::TimeLimit);
        }
        match (self.opts.target_error, error) {
            (Some(target), Some(e)) if e <= target => Some(StopReason::TargetError),
            _ => None,
        }
    }

    /// Writes a final checkpoint, if checkpointing.
    fn final_checkpoint(&self, snap: &Snapshot) {
        if let Some(t) = &self.ticker {
            t.write(snap);
        }
    }
}

/// Renders `scene` under `ctl` (see [`Control`]).
pub fn render_with(
    scene: &Scene,
    opts: &RenderOptions,
    ctl: Control<'_>,
) -> Result<(Film, RenderStats), RenderError> {
    let start = Instant::now();
    check_integrator(scene, opts)?;
    let (w, h) = (scene.film.width, scene.film.height);
    let film = Film::new(
        w,
        h,
        scene.film.filter.clone(),
        scene.wavelengths,
        opts.spectral_bins,
    )
    .with_stokes(scene.integrator.polarised);
    let mut integrator = Integrator::new(scene, opts.integrator, opts.max_depth)
        .with_split_dispersion(opts.split_dispersion);
    integrator.strategy = opts.strategy;
    // a clamped render reproduces pbrt-v4's clamp, which depends on how its samples'
    // estimates are distributed: its wavelength density
    let lambda = match scene.film.max_component {
        Some(_) => WavelengthSampler::pbrt_visible(scene.wavelengths),
        None => WavelengthSampler::visible(scene.wavelengths),
    };
    let tiles: Vec<(u32, u32, u32, u32)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .map(|(x0, y0)| (x0, y0, TILE.min(w - x0), TILE.min(h - y0)))
        .collect();
    let (first, end) = opts.sample_range();
    let passes = passes(first, end);
    if let Some(snap) = &ctl.resume {
        check_resume(snap, &film, tiles.len(), passes.len()).map_err(RenderError::Resume)?;
    }
    let pool = thread_pool(opts.threads)?;
    let ctx = Ctx {
        opts,
        integrator: &integrator,
        lambda: &lambda,
        pool: &pool,
        cancel: ctl.cancel,
        progress: ctl.progress,
        ticker: ctl
            .checkpoint
            .map(|(every, write)| Ticker::new(every, write)),
        budget: Budget {
            limit: opts.time_limit,
            before: ctl.resume.as_ref().map_or(Duration::ZERO, |s| s.elapsed),
            start,
        },
        total: w as u64 * h as u64 * (end - first) as u64,
    };
    let snap = ctl.resume.unwrap_or_else(|| Snapshot {
        film,
        pass_film: None,
        pass: 0,
        tiles_done: Vec::new(),
        paths_done: 0,
        nan_samples: 0,
        inf_samples: 0,
        elapsed: Duration::ZERO,
    });
    match opts.integrator {
        IntegratorKind::Bdpt => Ok(bdpt::render(&ctx, snap, &tiles, &passes)),
        IntegratorKind::Light => {
            if matches!(scene.camera, crate::geometry::Camera::Orthographic(_)) {
                return Err(RenderError::Camera("light"));
            }
            if opts.target_error.is_some() {
                return Err(RenderError::TargetErrorLight);
            }
            Ok(light::render(&ctx, snap))
        }
        _ => Ok(tiles::render(&ctx, snap, &tiles, &passes)),
    }
}

/// The worker pool: `threads` threads, or every core for None.
fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, RenderError> {
    let threads = threads.unwrap_or(0);
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| RenderError::Threads {
            threads,
            message: e.to_string(),
        })
}

/// The wavelengths of a path from the next pair of `s`'s dimensions: the first number places
/// them within their strata, the second picks the hero's stratum ([`WavelengthSampler::sample`]).
#[inline]
pub(super) fn draw_wavelengths(
    lambda: &WavelengthSampler,
    s: &mut Sampler,
) -> SampledWavelengths<N_WAVELENGTHS> {
    let u = s.get_2d();
    lambda.sample(u.x, u.y)
}

/// Camera sample `i` of pixel (x, y) under `seed`: the wavelengths, the filter offset and the
/// lens position read the sampler's first dimensions in that order; returns the sampler (for
/// the integrator's further dimensions), the wavelengths, the camera ray and its weight
/// (1 but for a realistic camera, whose pupil sampling weighs its rays; 0 where its lens blocks
/// the ray, which then must not be traced). A camera ray through dispersive lens glass keeps its
/// hero wavelength only.
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
    f32,
) {
    let mut s = Sampler::new(seed, x, y, i);
    let mut wl = draw_wavelengths(lambda, &mut s);
    let offset = filter.sample(s.get_2d());
    let raster = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + offset;
    let u_lens = s.get_2d();
    if !matches!(scene.camera, crate::geometry::Camera::Realistic(_)) {
        let ray = scene.camera.generate_ray(raster, u_lens);
        return (s, wl, ray, 1.0);
    }
    if scene.camera.disperses() {
        wl.terminate_secondary();
    }
    match scene.camera.generate_ray_at(raster, u_lens, wl.hero()) {
        Some((ray, w)) => (s, wl, ray, w),
        None => (s, wl, scene.camera.generate_ray(raster, u_lens), 0.0),
    }
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
    l: &crate::integrator::Splatted<N>,
    bins: Option<&crate::film::Bins>,
) -> bool {
    use crate::integrator::Splatted;
    let r = filter.radius;
    // pixels whose centre x + 0.5 lies within [raster − r, raster + r], one more on each side
    // for rounding; `Filter::weight` decides the half-open support exactly
    let lo = (raster - Vec2::splat(0.5 + r)).floor().max(Vec2::ZERO);
    let hi = ((raster + Vec2::splat(r - 0.5)).floor() + Vec2::ONE)
        .min(Vec2::new(size.0 as f32 - 1.0, size.1 as f32 - 1.0));
    if hi.x < lo.x || hi.y < lo.y {
        return match l {
            Splatted::Radiance(l) => non_finite(wl, l).is_none(),
            Splatted::Stokes(st) => st.iter().all(|l| non_finite(wl, l).is_none()),
        };
    }
    let (x0, y0, x1, y1) = (lo.x as u32, lo.y as u32, hi.x as u32, hi.y as u32);
    let pixels = (y0..=y1)
        .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
        .filter_map(|(x, y)| {
            let wgt = filter.weight(raster - Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            (wgt > 0.0).then_some((x, y, wgt))
        });
    match l {
        Splatted::Radiance(l) => to.splat_weighted(pixels, wl, l, bins),
        Splatted::Stokes(st) => to.splat_stokes_weighted(pixels, wl, st, bins),
    }
}
