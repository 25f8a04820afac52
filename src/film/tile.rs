//! A tile's sums, written by one thread, and one sample's contribution to a pixel
//! ([`SampleSums`], the module's estimator evaluated once per sample).

use super::*;

/// Accumulation for one rectangle of pixels (a tile), written by one thread.
#[derive(Clone, Debug)]
pub struct Tile {
    pub x0: u32,
    pub y0: u32,
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<PixelSums>,
    /// Σ per-bin estimates, `bins × pixels` (empty without spectral output).
    pub spectral: Vec<Exact>,
    nbins: usize,
    /// Σ estimates of S1, S2, S3 of a polarised render, `9 + 3 × bins` per pixel: their XYZ
    /// (cd/m²), then each one's spectral bins (W·m⁻²·sr⁻¹·nm⁻¹); empty otherwise (see
    /// [`Tile::add_stokes`]).
    pub stokes: Vec<Exact>,
}

impl Tile {
    pub fn new(x0: u32, y0: u32, width: u32, height: u32, nbins: usize) -> Self {
        let n = (width * height) as usize;
        Self {
            x0,
            y0,
            width,
            height,
            pixels: vec![PixelSums::default(); n],
            spectral: vec![Exact::ZERO; n * nbins],
            nbins,
            stokes: Vec::new(),
        }
    }

    /// The tile with room for the Stokes sums of a polarised render.
    pub fn with_stokes(mut self) -> Self {
        self.stokes = vec![Exact::ZERO; stokes_stride(self.nbins) * self.pixels.len()];
        self
    }

    /// Adds one polarised sample: its Stokes vector `st` (S0–S3 in the camera's frame,
    /// W·m⁻²·sr⁻¹·nm⁻¹ per wavelength), S0 as [`Tile::add`] adds radiance and S1–S3 as XYZ
    /// and spectral bins by the same estimator (their CIE-weighted sums, which may be
    /// negative). Returns false, adding nothing, if any component is NaN or infinite at a live
    /// wavelength.
    #[inline]
    pub fn add_stokes<const N: usize>(
        &mut self,
        x: u32,
        y: u32,
        w: &SampledWavelengths<N>,
        st: &[SampledSpectrum<N>; 4],
        bins: Option<&Bins>,
    ) -> bool {
        let Some(terms) = stokes_terms(w, st, bins) else {
            return false;
        };
        if !self.add(x, y, w, &st[0], bins) {
            return false;
        }
        self.add_stokes_terms(x, y, &terms, 1.0);
        true
    }

    /// Adds the S1–S3 sums `terms` times `wgt` to pixel (x, y) (image coordinates inside the
    /// tile).
    #[inline]
    fn add_stokes_terms<const N: usize>(
        &mut self,
        x: u32,
        y: u32,
        terms: &[SampleSums<N>; 3],
        wgt: f64,
    ) {
        let (nb, stride) = (self.nbins, stokes_stride(self.nbins));
        let i = ((y - self.y0) * self.width + (x - self.x0)) as usize;
        let px = &mut self.stokes[stride * i..stride * (i + 1)];
        for (k, v) in stokes_entries(terms, nb) {
            px[k].add_f64(v * wgt);
        }
    }

    /// Adds one sample's radiance (W·m⁻²·sr⁻¹·nm⁻¹ at each wavelength) to pixel (x, y) in image
    /// coordinates. Returns false, adding nothing, if a live wavelength's value is NaN or
    /// infinite ([`non_finite`]); a terminated wavelength's value (pdf 0) is never read.
    #[inline]
    pub fn add<const N: usize>(
        &mut self,
        x: u32,
        y: u32,
        w: &SampledWavelengths<N>,
        l: &SampledSpectrum<N>,
        bins: Option<&Bins>,
    ) -> bool {
        let Some(s) = SampleSums::new(w, l, bins) else {
            return false;
        };
        let p = self.accumulate(x, y, &s, 1.0);
        for k in 0..3 {
            p.xyz_sq[k].add_f64(s.xyz[k] * s.xyz[k]);
        }
        p.count += 1;
        true
    }

    /// Adds the sums `s` times `wgt` to pixel (x, y) (image coordinates inside the tile), without
    /// counting a sample; returns the pixel's sums.
    #[inline]
    fn accumulate<const N: usize>(
        &mut self,
        x: u32,
        y: u32,
        s: &SampleSums<N>,
        wgt: f64,
    ) -> &mut PixelSums {
        let nb = self.nbins;
        let i = ((y - self.y0) * self.width + (x - self.x0)) as usize;
        let spectral = &mut self.spectral[i * nb..(i + 1) * nb];
        let p = &mut self.pixels[i];
        p.add_weighted(spectral, s.xyz, s.band, s.bins(), wgt);
        p
    }

    /// Adds a light-tracing splat to pixel (x, y) without counting a sample; the film divides
    /// by the number of light paths instead (see [`Film::set_path_count`]). Returns false,
    /// adding nothing, for NaN or infinite values at a live wavelength.
    #[inline]
    pub fn splat<const N: usize>(
        &mut self,
        x: u32,
        y: u32,
        w: &SampledWavelengths<N>,
        l: &SampledSpectrum<N>,
        bins: Option<&Bins>,
    ) -> bool {
        self.splat_scaled(x, y, w, l, bins, 1.0)
    }

    /// [`Tile::splat`] with the sample's estimate multiplied by `scale` (in f64, before the
    /// exact sum).
    #[inline]
    pub fn splat_scaled<const N: usize>(
        &mut self,
        x: u32,
        y: u32,
        w: &SampledWavelengths<N>,
        l: &SampledSpectrum<N>,
        bins: Option<&Bins>,
        scale: f64,
    ) -> bool {
        let Some(s) = SampleSums::new(w, l, bins) else {
            return false;
        };
        self.accumulate(x, y, &s, scale);
        true
    }
}

impl Splat for Tile {
    /// Adds one sample's estimate (the module's estimator, from `w` and `l`) to several pixels,
    /// pixel (x, y) with weight `wgt` for each `(x, y, wgt)` of `pixels` (image coordinates
    /// inside the tile), without counting samples; the estimate and its colour-matching
    /// functions are computed once. [`Tile::add`] and [`Tile::splat`] are its one-pixel cases.
    /// Returns false, adding nothing, for NaN or infinite values at a live wavelength
    /// ([`non_finite`]).
    #[inline]
    fn splat_weighted<const N: usize>(
        &mut self,
        pixels: impl Iterator<Item = (u32, u32, f32)>,
        w: &SampledWavelengths<N>,
        l: &SampledSpectrum<N>,
        bins: Option<&Bins>,
    ) -> bool {
        let Some(s) = SampleSums::new(w, l, bins) else {
            return false;
        };
        for (x, y, wgt) in pixels {
            self.accumulate(x, y, &s, wgt as f64);
        }
        true
    }

    #[inline]
    fn splat_stokes_weighted<const N: usize>(
        &mut self,
        pixels: impl Iterator<Item = (u32, u32, f32)> + Clone,
        w: &SampledWavelengths<N>,
        st: &[SampledSpectrum<N>; 4],
        bins: Option<&Bins>,
    ) -> bool {
        let Some(terms) = stokes_terms(w, st, bins) else {
            return false;
        };
        if !self.splat_weighted(pixels.clone(), w, &st[0], bins) {
            return false;
        }
        for (x, y, wgt) in pixels {
            self.add_stokes_terms(x, y, &terms, wgt as f64);
        }
        true
    }
}

/// The sums of S1, S2 and S3 of one sample (each by the module's estimator, which is linear,
/// so they may be negative); None if any is NaN or infinite at a live wavelength.
#[inline]
pub(crate) fn stokes_terms<const N: usize>(
    w: &SampledWavelengths<N>,
    st: &[SampledSpectrum<N>; 4],
    bins: Option<&Bins>,
) -> Option<[SampleSums<N>; 3]> {
    Some([
        SampleSums::new(w, &st[1], bins)?,
        SampleSums::new(w, &st[2], bins)?,
        SampleSums::new(w, &st[3], bins)?,
    ])
}

/// The (index within a pixel's [`stokes_stride`] sums, value) pairs of `terms`: the XYZ of S1,
/// S2, S3, then their spectral bins (`nb` bins each).
#[inline]
pub(crate) fn stokes_entries<const N: usize>(
    terms: &[SampleSums<N>; 3],
    nb: usize,
) -> impl Iterator<Item = (usize, f64)> + '_ {
    terms.iter().enumerate().flat_map(move |(k, s)| {
        let xyz = s
            .xyz
            .into_iter()
            .enumerate()
            .map(move |(c, v)| (3 * k + c, v));
        let bins = s.bins().iter().map(move |&(b, v)| (9 + k * nb + b, v));
        xyz.chain(bins)
    })
}

/// One sample's contribution to a pixel before its filter weight: XYZ (Y in cd/m²), band
/// radiance (W·m⁻²·sr⁻¹) and, per live wavelength inside a spectral bin, that bin and the
/// value per nm (W·m⁻²·sr⁻¹·nm⁻¹), from the module's estimator (1/N)·Σ L(λⱼ)/p(λⱼ)·….
pub(crate) struct SampleSums<const N: usize> {
    pub xyz: [f64; 3],
    pub band: f64,
    /// (bin, value per nm); the first `nbins` entries are used.
    per_bin: [(usize, f64); N],
    nbins: usize,
}

/// pbrt-v4's firefly clamp (`RGBFilm::AddSample` with `maxcomponentvalue`): the sample's
/// estimate `l` scaled down, whole, so that none of its X, Y, Z (cd/m², the film's estimate
/// K_m·mean of x̄ᵢLᵢ/pᵢ over the live wavelengths) exceeds `max`; unchanged when none does.
/// Biased, as pbrt-v4's is.
#[inline]
pub fn clamp_max_component<const N: usize>(
    w: &SampledWavelengths<N>,
    l: SampledSpectrum<N>,
    max: f32,
) -> SampledSpectrum<N> {
    let mut xyz = [0.0f64; 3];
    for j in 0..N {
        if w.pdf[j] == 0.0 {
            continue;
        }
        let v = l[j] as f64 / w.pdf[j] as f64 / N as f64;
        let c = cmf().eval(w.lambda[j]);
        for k in 0..3 {
            xyz[k] += K_M * v * c[k] as f64;
        }
    }
    let m = xyz.into_iter().fold(0.0f64, f64::max);
    if m > max as f64 {
        l * (max as f64 / m) as f32
    } else {
        l
    }
}

impl<const N: usize> SampleSums<N> {
    /// None for NaN or infinite values at a live wavelength ([`non_finite`]), and for sums
    /// too large to add exactly (XYZ or band radiance of magnitude [`MAX_TERM`] ≈ 3·10²⁶ or
    /// more: the caller counts them as infinite).
    #[inline]
    pub fn new(
        w: &SampledWavelengths<N>,
        l: &SampledSpectrum<N>,
        bins: Option<&Bins>,
    ) -> Option<Self> {
        if non_finite(w, l).is_some() {
            return None;
        }
        let inv_n = 1.0 / N as f64;
        let (mut xyz, mut band) = ([0.0f64; 3], 0.0f64);
        let (mut per_bin, mut nbins) = ([(0, 0.0f64); N], 0);
        for j in 0..N {
            if w.pdf[j] == 0.0 {
                continue;
            }
            let v = l[j] as f64 / w.pdf[j] as f64 * inv_n;
            let c = cmf().eval(w.lambda[j]);
            for k in 0..3 {
                xyz[k] += K_M * v * c[k] as f64;
            }
            band += v;
            if let Some(b) = bins
                && let Some(k) = b.index(w.lambda[j])
            {
                per_bin[nbins] = (k, v / b.width() as f64);
                nbins += 1;
            }
        }
        let fits = |v: f64| v.abs() < MAX_TERM;
        if !(xyz.iter().all(|&v| fits(v)) && fits(band)) {
            return None;
        }
        Some(Self {
            xyz,
            band,
            per_bin,
            nbins,
        })
    }

    /// (bin, value per nm) of each live wavelength inside a spectral bin.
    #[inline]
    pub fn bins(&self) -> &[(usize, f64)] {
        &self.per_bin[..self.nbins]
    }
}
