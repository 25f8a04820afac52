//! Measuring irradiance and illuminance at meter points (`spectrace measure`): each point's
//! samples are split into [`REPLICAS`] independently scrambled replicas (the sampler keyed on
//! (seed, point, replica, sample, dimension)), whose means are independent, unbiased estimates;
//! the reading is their mean and its standard error the replicas' standard deviation / √R
//! (randomised quasi-Monte Carlo, Owen 1997; L'Ecuyer & Lemieux 2002). Results do not depend
//! on the thread count.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use rayon::prelude::*;

use super::RenderError;
use crate::film::{Bins, SampleSums};
use crate::integrator::IntegratorKind;
use crate::integrator::{Integrator, meter};
use crate::sampler::Sampler;
use crate::scene::{MeterPoint, Scene};
use crate::spectrum::WavelengthSampler;

/// Independent replicas per point.
pub const REPLICAS: u32 = 16;

/// What to measure with.
#[derive(Clone, Debug)]
pub struct MeasureOptions {
    /// Samples per point (rounded up to a multiple of [`REPLICAS`]).
    pub samples: u32,
    /// Worker threads (None: every core).
    pub threads: Option<usize>,
    pub seed: u32,
    /// Path length bound as the path tracer reads it (hits after the meter's own rays).
    pub max_depth: u32,
    /// Spectral bins over the film's wavelength range (0: none).
    pub spectral_bins: u32,
}

/// A meter's reading.
#[derive(Clone, Debug, Default)]
pub struct Reading {
    /// Illuminance E_v = K_m ∫ E(λ) ȳ(λ) dλ, lx, and its standard error, lx.
    pub illuminance_lx: f64,
    pub illuminance_se_lx: f64,
    /// Irradiance ∫ E(λ) dλ over the film's wavelength range, W/m², and its standard error.
    pub irradiance_w_m2: f64,
    pub irradiance_se_w_m2: f64,
    /// Mean spectral irradiance in each bin, W·m⁻²·nm⁻¹ (empty without bins).
    pub spectral_w_m2_nm: Vec<f64>,
    /// Samples refused as NaN or infinite (counted as zero in the mean).
    pub dropped: u64,
}

/// Per-replica sums of one point.
#[derive(Clone, Default)]
struct Sums {
    y: f64,
    band: f64,
    bins: Vec<f64>,
    dropped: u64,
}

/// A point's reading from its replicas' sums (`per` samples each).
fn reading(reps: &[Sums], per: u32) -> Reading {
    let r = reps.len() as f64;
    let mean_se = |f: &dyn Fn(&Sums) -> f64| {
        let m: Vec<f64> = reps.iter().map(|s| f(s) / per as f64).collect();
        let mean = m.iter().sum::<f64>() / r;
        let var = m.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (r - 1.0);
        (mean, (var / r).sqrt())
    };
    let (ev, ev_se) = mean_se(&|s| s.y);
    let (ee, ee_se) = mean_se(&|s| s.band);
    let nb = reps[0].bins.len();
    Reading {
        illuminance_lx: ev,
        illuminance_se_lx: ev_se,
        irradiance_w_m2: ee,
        irradiance_se_w_m2: ee_se,
        spectral_w_m2_nm: (0..nb)
            .map(|b| reps.iter().map(|s| s.bins[b]).sum::<f64>() / (r * per as f64))
            .collect(),
        dropped: reps.iter().map(|s| s.dropped).sum(),
    }
}

/// Measures every point; `progress` receives the number of (point, replica) jobs done, out of
/// `points.len() × REPLICAS`. When `cancel` is set, the points not finished read None.
pub fn measure(
    scene: &Scene,
    points: &[MeterPoint],
    opts: &MeasureOptions,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<Option<Reading>>, RenderError> {
    let integrator = Integrator::new(scene, IntegratorKind::Path, opts.max_depth);
    let lambda = WavelengthSampler::visible(scene.wavelengths);
    let bins = (opts.spectral_bins > 0).then_some(Bins {
        range: scene.wavelengths,
        count: opts.spectral_bins as usize,
    });
    let per = opts.samples.div_ceil(REPLICAS).max(1);
    let pool = super::thread_pool(opts.threads)?;
    let done = AtomicU64::new(0);
    let nb = bins.as_ref().map_or(0, |b| b.count);
    // one point at a time per thread, its replicas in turn, reduced to its reading at once
    // (memory per point, not per replica)
    let readings: Vec<Option<Reading>> = pool.install(|| {
        points
            .par_iter()
            .enumerate()
            .map(|(i, &mp)| {
                let mut reps = Vec::with_capacity(REPLICAS as usize);
                for k in 0..REPLICAS {
                    let mut out = Sums {
                        bins: vec![0.0; nb],
                        ..Sums::default()
                    };
                    for j in 0..per {
                        if cancel.load(Ordering::Relaxed) {
                            return None;
                        }
                        let mut s = Sampler::new(opts.seed, i as u32, k, j);
                        let mut w = super::draw_wavelengths(&lambda, &mut s);
                        let e = meter::irradiance(&integrator, mp.p, mp.n, &mut w, &mut s);
                        match SampleSums::new(&w, &e, bins.as_ref()) {
                            Some(ss) => {
                                out.y += ss.xyz[1];
                                out.band += ss.band;
                                for &(b, v) in ss.bins() {
                                    out.bins[b] += v;
                                }
                            }
                            None => out.dropped += 1,
                        }
                    }
                    progress(done.fetch_add(1, Ordering::Relaxed) + 1);
                    reps.push(out);
                }
                Some(reading(&reps, per))
            })
            .collect()
    });
    Ok(readings)
}

/// Illuminance at the surface each pixel sees, lx, row-major from the top row (Radiance's
/// `rpict -i`): per sample a camera ray through the pixel (jittered by the film's filter), its
/// first hit, and the irradiance there on the side facing the camera (the geometric normal),
/// estimated as at a meter; 0 where the ray escapes. `progress` receives rows done.
pub fn illuminance_image(
    scene: &Scene,
    spp: u32,
    opts: &MeasureOptions,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<f32>, RenderError> {
    let integrator = Integrator::new(scene, IntegratorKind::Path, opts.max_depth);
    let lambda = WavelengthSampler::visible(scene.wavelengths);
    let filter = scene.film.filter.clone();
    let (w, h) = (scene.film.width, scene.film.height);
    let pool = super::thread_pool(opts.threads)?;
    let done = AtomicU64::new(0);
    let rows: Vec<Vec<f32>> = pool.install(|| {
        (0..h)
            .into_par_iter()
            .map(|y| {
                let mut row = vec![0.0f32; w as usize];
                for x in 0..w {
                    if cancel.load(Ordering::Relaxed) {
                        break;
                    }
                    let mut sum = 0.0f64;
                    for i in 0..spp {
                        let (mut s, mut wl, ray, _) =
                            super::camera_sample(scene, &lambda, &filter, opts.seed, x, y, i);
                        let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
                            continue;
                        };
                        let n = if hit.n_geom.dot(ray.d) > 0.0 {
                            -hit.n_geom
                        } else {
                            hit.n_geom
                        };
                        let e = meter::irradiance(&integrator, hit.p, n, &mut wl, &mut s);
                        if let Some(ss) = SampleSums::new(&wl, &e, None) {
                            sum += ss.xyz[1];
                        }
                    }
                    row[x as usize] = (sum / spp.max(1) as f64) as f32;
                }
                progress(done.fetch_add(1, Ordering::Relaxed) + 1);
                row
            })
            .collect()
    });
    Ok(rows.concat())
}
