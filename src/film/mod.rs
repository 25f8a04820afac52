//! The film: turns spectral radiance samples into CIE XYZ (Y in cd/m²), linear sRGB on the
//! same absolute scale, band radiance L (W·m⁻²·sr⁻¹) and optional spectral bins
//! (W·m⁻²·sr⁻¹·nm⁻¹), per pixel.
//!
//! Estimator (`../shared/PHYSICS.md`, "Monte Carlo estimate"): a sample with wavelengths λ_j of
//! pdf p_j and radiance L_j contributes XYZ = K_m · (1/N) Σ_j L_j (x̄, ȳ, z̄)(λ_j) / p_j and
//! L = (1/N) Σ_j L_j / p_j; wavelengths with p_j = 0 (terminated secondaries) are dropped, and
//! the hero's pdf was divided by N when they were terminated, so the estimate stays unbiased.
//!
//! Sums are exact ([`Exact`], fixed point): each term is rounded once, and sums do not depend
//! on the order of additions, so threads, checkpoints and render parts cannot change a bit.

mod exact;
pub mod filter;
mod splats;
mod state;
mod tile;

pub use exact::{Exact, MAX_TERM};
pub use filter::{Filter, FilterDesc};
pub use splats::{Splat, SplatList};
pub use state::STATE_PREFIX;
pub(crate) use tile::SampleSums;
pub use tile::Tile;
pub use tile::clamp_max_component;

use crate::colour::cie::{K_M, cmf};
use crate::colour::spaces::xyz_to_srgb;
use crate::spectrum::{SampledSpectrum, SampledWavelengths, WavelengthRange};

/// Why a sample was dropped: a NaN or an infinite value at a live wavelength.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NonFinite {
    NaN,
    Inf,
}

/// Whether the sample's radiance is NaN (first) or infinite at a live wavelength (pdf > 0).
/// Terminated secondaries (pdf 0) do not count: the film drops them anyway, so whatever they
/// hold must not discard the hero's valid estimate.
#[inline]
pub fn non_finite<const N: usize>(
    w: &SampledWavelengths<N>,
    l: &SampledSpectrum<N>,
) -> Option<NonFinite> {
    let live = || (0..N).filter(|&j| w.pdf[j] != 0.0);
    if live().any(|j| l[j].is_nan()) {
        Some(NonFinite::NaN)
    } else if live().any(|j| l[j].is_infinite()) {
        Some(NonFinite::Inf)
    } else {
        None
    }
}

/// The number of Stokes sums per pixel of a polarised film with `nbins` spectral bins: the XYZ
/// of S1, S2, S3, then S1's bins, S2's, S3's.
pub(crate) fn stokes_stride(nbins: usize) -> usize {
    9 + 3 * nbins
}

/// Per-pixel sums of sample estimates, exact ([`Exact`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PixelSums {
    /// Σ XYZ estimates, cd/m².
    pub xyz: [Exact; 3],
    /// Σ band radiance estimates, W·m⁻²·sr⁻¹.
    pub band: Exact,
    /// Σ of the squared XYZ estimates of camera samples, (cd/m²)², for second moments (each
    /// square clamped to [`MAX_TERM`]).
    pub xyz_sq: [Exact; 3],
    /// Number of samples that reached the pixel (NaN/∞ samples are not counted); for light
    /// tracing, the number of light paths traced in all.
    pub count: u64,
}

impl PixelSums {
    /// Adds one sample's sums (XYZ, band radiance, and (bin, value) pairs into `spectral`,
    /// this pixel's bins) times the filter weight `wgt`, without counting a sample: the one
    /// accumulation step of tiles and of applied splat lists.
    #[inline]
    fn add_weighted(
        &mut self,
        spectral: &mut [Exact],
        xyz: [f64; 3],
        band: f64,
        bins: &[(usize, f64)],
        wgt: f64,
    ) {
        for (a, c) in self.xyz.iter_mut().zip(xyz) {
            a.add_f64(c * wgt);
        }
        self.band.add_f64(band * wgt);
        for &(k, v) in bins {
            spectral[k].add_f64(v * wgt);
        }
    }

    /// Adds another pixel's sums and count.
    fn add_sums(&mut self, b: &PixelSums) {
        for k in 0..3 {
            self.xyz[k].add(b.xyz[k]);
            self.xyz_sq[k].add(b.xyz_sq[k]);
        }
        self.band.add(b.band);
        self.count += b.count;
    }
}

/// Spectral bins of the film's wavelength range.
#[derive(Clone, Debug)]
pub struct Bins {
    pub range: WavelengthRange,
    pub count: usize,
}

impl Bins {
    pub fn width(&self) -> f32 {
        self.range.width() / self.count as f32
    }
    /// Bin of `lambda_nm`, if inside the range.
    #[inline]
    pub fn index(&self, lambda_nm: f32) -> Option<usize> {
        let t = (lambda_nm - self.range.min_nm) / self.width();
        (t >= 0.0 && lambda_nm <= self.range.max_nm).then(|| (t as usize).min(self.count - 1))
    }
    /// Centre wavelength of bin `i`, nm.
    pub fn centre(&self, i: usize) -> f32 {
        self.range.min_nm + (i as f32 + 0.5) * self.width()
    }
}

/// A finished image: per-pixel means, row-major, top row first.
#[derive(Clone, Debug)]
pub struct Image {
    pub width: usize,
    pub height: usize,
    /// CIE 1931 XYZ, Y = luminance in cd/m².
    pub xyz: Vec<[f32; 3]>,
    /// Linear sRGB (D65), same absolute scale as XYZ.
    pub rgb: Vec<[f32; 3]>,
    /// Radiance integrated over the film's wavelength range, W·m⁻²·sr⁻¹.
    pub band: Vec<f32>,
    /// Mean spectral radiance per bin, W·m⁻²·sr⁻¹·nm⁻¹: `spectral[b][pixel]`.
    pub spectral: Vec<Vec<f32>>,
    pub bins: Option<Bins>,
    /// Second moment of the camera samples' XYZ, the mean of their squares, (cd/m²)² (zero
    /// for light-tracing splats); its excess over the squared mean is the sample variance.
    pub xyz_m2: Vec<[f32; 3]>,
    /// A polarised render's Stokes components S1, S2, S3 per pixel as CIE XYZ (cd/m², the
    /// same estimator as `xyz`, which is S0), in the camera's frame (S1 > 0: polarised
    /// horizontally in the image; Mitsuba 3's `stokes` conventions); empty otherwise.
    pub stokes: Vec<[[f32; 3]; 3]>,
    /// A polarised render's S1, S2, S3 per spectral bin, W·m⁻²·sr⁻¹·nm⁻¹:
    /// `stokes_spectral[k·bins + b][pixel]` for S(k+1) in bin b; empty without both.
    pub stokes_spectral: Vec<Vec<f32>>,
}

/// The whole film: settings and the accumulated sums of every pixel.
#[derive(Clone, Debug)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    pub filter: Filter,
    pub range: WavelengthRange,
    pub bins: Option<Bins>,
    sums: Vec<PixelSums>,
    spectral: Vec<Exact>,
    /// Σ of S1, S2, S3, [`stokes_stride`] per pixel (a polarised render; empty otherwise).
    stokes: Vec<Exact>,
}

impl Film {
    pub fn new(
        width: u32,
        height: u32,
        filter: Filter,
        range: WavelengthRange,
        spectral_bins: u32,
    ) -> Self {
        let n = (width * height) as usize;
        let bins = (spectral_bins > 0).then_some(Bins {
            range,
            count: spectral_bins as usize,
        });
        let nb = bins.as_ref().map_or(0, |b| b.count);
        Self {
            width,
            height,
            filter,
            range,
            bins,
            sums: vec![PixelSums::default(); n],
            spectral: vec![Exact::ZERO; n * nb],
            stokes: Vec::new(),
        }
    }

    /// The film with Stokes sums (S1–S3) when `polarised`, for a polarised render.
    pub fn with_stokes(mut self, polarised: bool) -> Self {
        let nb = self.bins.as_ref().map_or(0, |b| b.count);
        self.stokes = if polarised {
            vec![Exact::ZERO; stokes_stride(nb) * self.sums.len()]
        } else {
            Vec::new()
        };
        self
    }

    /// Whether the film holds Stokes sums.
    pub fn polarised(&self) -> bool {
        !self.stokes.is_empty()
    }

    /// An empty tile for the rectangle at (x0, y0) of the given size.
    pub fn tile(&self, x0: u32, y0: u32, width: u32, height: u32) -> Tile {
        let t = Tile::new(
            x0,
            y0,
            width,
            height,
            self.bins.as_ref().map_or(0, |b| b.count),
        );
        if self.polarised() { t.with_stokes() } else { t }
    }

    /// Adds a tile's sums and sample counts into the film. Sums are exact, so the order of
    /// merges never matters.
    pub fn merge(&mut self, t: &Tile) {
        let nb = self.bins.as_ref().map_or(0, |b| b.count);
        for ty in 0..t.height {
            for tx in 0..t.width {
                let src = (ty * t.width + tx) as usize;
                let dst = ((t.y0 + ty) * self.width + t.x0 + tx) as usize;
                self.sums[dst].add_sums(&t.pixels[src]);
                for k in 0..nb {
                    self.spectral[dst * nb + k].add(t.spectral[src * nb + k]);
                }
                if !self.stokes.is_empty() && !t.stokes.is_empty() {
                    let st = stokes_stride(nb);
                    for k in 0..st {
                        self.stokes[dst * st + k].add(t.stokes[src * st + k]);
                    }
                }
            }
        }
    }

    /// An empty film with the same size, filter, range and bins.
    pub fn empty_like(&self) -> Film {
        Film::new(
            self.width,
            self.height,
            self.filter.clone(),
            self.range,
            self.bins.as_ref().map_or(0, |b| b.count as u32),
        )
        .with_stokes(self.polarised())
    }

    /// Adds another film's sums and sample counts (same size and bins) into this one.
    pub fn merge_film(&mut self, other: &Film) {
        debug_assert_eq!((self.width, self.height), (other.width, other.height));
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            a.add_sums(b);
        }
        for (a, b) in self.spectral.iter_mut().zip(&other.spectral) {
            a.add(*b);
        }
        for (a, b) in self.stokes.iter_mut().zip(&other.stokes) {
            a.add(*b);
        }
    }

    /// Sets every pixel's sample count to the number of light paths traced, so that splatted
    /// sums become radiance estimates.
    pub fn set_path_count(&mut self, paths: u64) {
        for p in &mut self.sums {
            p.count = paths;
        }
    }

    /// Number of samples in pixel (x, y).
    pub fn samples_at(&self, x: u32, y: u32) -> u64 {
        self.sums[(y * self.width + x) as usize].count
    }

    /// Per-pixel mean luminance Y, cd/m² (0 without samples).
    pub fn mean_luminance(&self) -> Vec<f64> {
        self.sums
            .iter()
            .map(|s| {
                if s.count > 0 {
                    s.xyz[1].to_f64() / s.count as f64
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// Per-pixel means. Pixels without samples (a render stopped early) are 0, never NaN.
    pub fn image(&self) -> Image {
        let n = (self.width * self.height) as usize;
        let nb = self.bins.as_ref().map_or(0, |b| b.count);
        let mut xyz = Vec::with_capacity(n);
        let mut rgb = Vec::with_capacity(n);
        let mut band = Vec::with_capacity(n);
        let mut xyz_m2 = Vec::with_capacity(n);
        let mut spectral = vec![Vec::with_capacity(n); nb];
        let mut stokes = Vec::with_capacity(if self.polarised() { n } else { 0 });
        let st = stokes_stride(nb);
        let mut stokes_spectral = if self.polarised() {
            vec![Vec::with_capacity(n); 3 * nb]
        } else {
            Vec::new()
        };
        for (i, s) in self.sums.iter().enumerate() {
            let inv = if s.count > 0 {
                1.0 / s.count as f64
            } else {
                0.0
            };
            let m = s.xyz.map(|v| v.to_f64() * inv);
            xyz.push(m.map(|v| v as f32));
            rgb.push(xyz_to_srgb(m).map(|v| v as f32));
            band.push((s.band.to_f64() * inv) as f32);
            xyz_m2.push(s.xyz_sq.map(|v| (v.to_f64() * inv) as f32));
            for (k, sp) in spectral.iter_mut().enumerate() {
                sp.push((self.spectral[i * nb + k].to_f64() * inv) as f32);
            }
            if self.polarised() {
                let e = |k: usize| (self.stokes[i * st + k].to_f64() * inv) as f32;
                for (k, plane) in stokes_spectral.iter_mut().enumerate() {
                    plane.push(e(9 + k));
                }
                stokes.push(std::array::from_fn(|c| {
                    std::array::from_fn(|a| e(3 * c + a))
                }));
            }
        }
        Image {
            width: self.width as usize,
            height: self.height as usize,
            xyz,
            rgb,
            band,
            spectral,
            bins: self.bins.clone(),
            xyz_m2,
            stokes,
            stokes_spectral,
        }
    }
}
