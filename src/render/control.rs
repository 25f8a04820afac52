//! What steers a render besides the scene: passes, budgets (time, target error), checkpoints
//! and resuming from them.
//!
//! Resuming is bit-exact because nothing the image depends on is left to chance: the passes
//! follow from the sample range alone ([`passes`]), every sample draws from a sampler keyed on
//! (seed, pixel, sample index), and the film's sums are exact ([`crate::film::Exact`]), so a
//! tile summed before a stop and the tiles summed after it add to the very bits of an
//! uninterrupted render.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::film::Film;

/// Why a render ended.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum StopReason {
    /// Every sample was taken.
    #[default]
    Complete,
    /// The next pass would have ended past `RenderOptions::time_limit`.
    TimeLimit,
    /// The estimated relative error of Y fell below `RenderOptions::target_error`.
    TargetError,
    /// Cancelled (Ctrl-C): the image holds the passes (or light paths) completed.
    Cancelled,
}

impl StopReason {
    /// The name written to EXR headers.
    pub fn name(self) -> &'static str {
        match self {
            StopReason::Complete => "complete",
            StopReason::TimeLimit => "time limit",
            StopReason::TargetError => "target error",
            StopReason::Cancelled => "cancelled",
        }
    }
}

/// A render's state between tiles: enough to continue it bit-exactly (see the module doc).
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// Sums of the completed passes; for camera-ray integrators also those of the tiles of
    /// the current pass already done (light tracing: of the light paths traced).
    pub film: Film,
    /// `bdpt`: the sums of the current pass's tiles already done, kept apart because its
    /// splats are complete only when the whole pass is.
    pub pass_film: Option<Film>,
    /// Index of the pass in progress in `passes` (all done: the number of passes).
    pub pass: u32,
    /// Tiles of that pass already summed, in the scheduler's tile order.
    pub tiles_done: Vec<bool>,
    /// Light tracing: light paths traced, counted from the sample range's first.
    pub paths_done: u64,
    pub nan_samples: u64,
    pub inf_samples: u64,
    /// Render time spent before (over every earlier session).
    pub elapsed: Duration,
}

/// Where a resumed render must start, checked against the scene and options.
pub(super) fn check_resume(
    snap: &Snapshot,
    film: &Film,
    tiles: usize,
    passes: usize,
) -> Result<(), String> {
    let size = |f: &Film| (f.width, f.height, f.bins.as_ref().map_or(0, |b| b.count));
    if size(&snap.film) != size(film) {
        let (w, h, b) = size(&snap.film);
        let (w2, h2, b2) = size(film);
        return Err(format!(
            "the checkpoint holds a {w}×{h} film with {b} spectral bins, the render a {w2}×{h2} film with {b2}"
        ));
    }
    if snap.pass as usize > passes {
        return Err(format!(
            "the checkpoint is at pass {} of a render with {passes} passes",
            snap.pass
        ));
    }
    if !snap.tiles_done.is_empty() && snap.tiles_done.len() != tiles {
        return Err(format!(
            "the checkpoint lists {} tiles, the render has {tiles}",
            snap.tiles_done.len()
        ));
    }
    Ok(())
}

/// Passes over the sample indices [first, end) of every pixel: 1, 1, 2, 4, … samples (at most
/// 64 each), so that a render stopped between passes has every pixel at the same count.
pub(super) fn passes(first: u32, end: u32) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    let mut s0 = first;
    while s0 < end {
        let n = (s0 - first).max(1).min(end - s0).min(64);
        out.push((s0, s0 + n));
        s0 += n;
    }
    out
}

/// Calls the checkpoint writer at most once per `every`, one call at a time.
pub(super) struct Ticker<'a> {
    every: Duration,
    last: Mutex<Instant>,
    /// Held while a checkpoint is written: one writer at a time, and the last one written
    /// is the newest state.
    writing: Mutex<()>,
    /// Set by the caller of [`Ticker::due`] that will write.
    claimed: AtomicBool,
    write: &'a (dyn Fn(&Snapshot) + Sync),
}

impl<'a> Ticker<'a> {
    pub fn new(every: Duration, write: &'a (dyn Fn(&Snapshot) + Sync)) -> Self {
        Self {
            every,
            last: Mutex::new(Instant::now()),
            writing: Mutex::new(()),
            claimed: AtomicBool::new(false),
            write,
        }
    }

    /// Whether a checkpoint is due: `every` has passed since the last one was written, and
    /// none is being written (the interval counts from the end of a write, so that slow
    /// writes never take over the render).
    /// A true answer claims the checkpoint: the caller must call [`Ticker::write`].
    pub fn due(&self) -> bool {
        let last = self.last.lock().unwrap_or_else(|p| p.into_inner());
        last.elapsed() >= self.every && !self.claimed.swap(true, Ordering::AcqRel)
    }

    /// Writes `snap` (after any write in progress) and restarts the interval.
    pub fn write(&self, snap: &Snapshot) {
        let _one = self.writing.lock().unwrap_or_else(|p| p.into_inner());
        (self.write)(snap);
        *self.last.lock().unwrap_or_else(|p| p.into_inner()) = Instant::now();
        self.claimed.store(false, Ordering::Release);
    }
}

/// The time budget: whether to start another pass.
pub(super) struct Budget {
    pub limit: Option<Duration>,
    /// Render time before this session.
    pub before: Duration,
    pub start: Instant,
}

impl Budget {
    /// Render time so far, over all sessions.
    pub fn elapsed(&self) -> Duration {
        self.before + self.start.elapsed()
    }

    /// Whether earlier sessions of a resumed render used all its time (otherwise a session
    /// renders at least one pass).
    pub fn spent(&self) -> bool {
        self.limit.is_some_and(|l| self.before >= l)
    }

    /// Whether `next` samples (per pixel, or light paths), after `last` that took `took`,
    /// would end past the limit.
    pub fn would_exceed(&self, last: u64, took: Duration, next: u64) -> bool {
        let Some(limit) = self.limit else {
            return false;
        };
        let predicted = took.as_secs_f64() * next as f64 / last.max(1) as f64;
        self.elapsed().as_secs_f64() + predicted > limit.as_secs_f64()
    }
}

/// The estimated relative error of the image's luminance, from successive passes.
///
/// After a pass ends with mean Y₂ over n₂ samples per pixel, following a state Y₁ over n₁, the
/// pass alone is an independent estimate Yₚ = (n₂Y₂ − n₁Y₁)/(n₂ − n₁) over n₂ − n₁ samples,
/// and E[(Yₚ − Y₁)²] = σ²·(1/(n₂ − n₁) + 1/n₁) gives each pixel's per-sample variance σ² and
/// so the variance σ²/n₂ of its current mean. The figure is the relative RMS error
/// √(mean over pixels of σ²/n₂) / (mean over pixels of Y₂): one number for the image, the
/// error of a typical pixel relative to the typical luminance.
#[derive(Default)]
pub(super) struct ErrorEstimate {
    prev: Option<(Vec<f64>, u32)>,
    pub last: Option<f64>,
}

impl ErrorEstimate {
    /// Records the film after a pass ending at `n` samples per pixel (counted in this
    /// render's sample range); returns the estimate once two states are known.
    pub fn update(&mut self, film: &Film, n: u32) -> Option<f64> {
        let y = film.mean_luminance();
        if let Some((y1, n1)) = &self.prev
            && n > *n1
            && *n1 > 0
        {
            let (n1f, n2f) = (*n1 as f64, n as f64);
            let np = n2f - n1f;
            let k = 1.0 / np + 1.0 / n1f;
            let (mut var, mut mean) = (0.0, 0.0);
            for (a, b) in y1.iter().zip(&y) {
                let yp = (n2f * b - n1f * a) / np;
                var += (yp - a) * (yp - a) / k / n2f;
                mean += b;
            }
            let m = y.len().max(1) as f64;
            self.last = (mean > 0.0).then(|| (var / m).sqrt() / (mean / m));
        }
        self.prev = Some((y, n));
        self.last
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_double_from_the_first_sample_and_cover_the_range() {
        assert_eq!(passes(0, 5), vec![(0, 1), (1, 2), (2, 4), (4, 5)]);
        assert_eq!(passes(10, 13), vec![(10, 11), (11, 12), (12, 13)]);
        assert!(passes(3, 3).is_empty());
        let p = passes(0, 1000);
        assert!(p.windows(2).all(|w| w[0].1 == w[1].0));
        assert!(p.iter().all(|(a, b)| b - a <= 64));
        assert_eq!(p.last().unwrap().1, 1000);
    }

    /// Pixels whose samples are Gaussian with known σ: the estimate matches σ/√n / mean.
    #[test]
    fn error_estimate_matches_a_known_variance() {
        use crate::film::Filter;
        use crate::film::FilterDesc;
        use crate::spectrum::{SampledSpectrum, SampledWavelengths, WavelengthRange};
        let (w, h) = (64u32, 64u32);
        let mut film = Film::new(
            w,
            h,
            Filter::from_desc(&FilterDesc::BOX),
            WavelengthRange::default(),
            0,
        );
        let mut est = ErrorEstimate::default();
        let mut k = 99u64;
        let mut gauss = || {
            let mut u = || {
                k = k
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((k >> 11) as f64 + 0.5) / (1u64 << 53) as f64
            };
            let (a, b) = (u(), u());
            (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        };
        // a flat spectrum at 555 nm with pdf 1: Y = K_m·ȳ(555)·L/N … scaled by its own mean
        let wl = SampledWavelengths::<1> {
            lambda: [555.0],
            pdf: [1.0],
        };
        let mut n = 0;
        let mut got = None;
        for (a, b) in passes(0, 64) {
            let mut tile = film.tile(0, 0, w, h);
            for y in 0..h {
                for x in 0..w {
                    for _ in a..b {
                        let l = SampledSpectrum([(1.0 + 0.3 * gauss()) as f32]);
                        tile.add(x, y, &wl, &l, None);
                    }
                }
            }
            film.merge(&tile);
            n = b;
            got = est.update(&film, n);
        }
        let want = 0.3 / (n as f64).sqrt();
        let got = got.unwrap();
        assert!((got / want - 1.0).abs() < 0.05, "{got} vs {want}");
    }
}
