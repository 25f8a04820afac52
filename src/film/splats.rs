//! Light-tracing splats recorded in order and applied to the film later: how a chunk of light
//! paths contributes without a full-image tile of its own. Memory grows with the splats a chunk
//! makes, not with the image, so chunks can be small and many (one per few thousand paths),
//! which keeps every thread busy; applying the chunks' lists in chunk order makes the image
//! independent of which thread traced which chunk.

use super::tile::{stokes_entries, stokes_terms};
use super::{Bins, Film, SampleSums, stokes_stride};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Where a sample's filtered splat goes: a tile (summed at once) or a [`SplatList`] (recorded).
pub trait Splat {
    /// Adds one sample's estimate to pixel (x, y) with weight `wgt` for each `(x, y, wgt)` of
    /// `pixels` (image coordinates). Returns false, adding nothing, for NaN or infinite values
    /// at a live wavelength.
    fn splat_weighted<const N: usize>(
        &mut self,
        pixels: impl Iterator<Item = (u32, u32, f32)>,
        w: &SampledWavelengths<N>,
        l: &SampledSpectrum<N>,
        bins: Option<&Bins>,
    ) -> bool;

    /// As [`Splat::splat_weighted`] for a polarised sample: its Stokes vector `st` (S0–S3 in
    /// the camera's frame, W·m⁻²·sr⁻¹·nm⁻¹ per wavelength), S0 as radiance and S1–S3 into the
    /// film's Stokes sums. Returns false, adding nothing, if any is NaN or infinite at a live
    /// wavelength.
    fn splat_stokes_weighted<const N: usize>(
        &mut self,
        pixels: impl Iterator<Item = (u32, u32, f32)> + Clone,
        w: &SampledWavelengths<N>,
        st: &[SampledSpectrum<N>; 4],
        bins: Option<&Bins>,
    ) -> bool;
}

/// One recorded sample: its sums and where its pixels and bins end in the list's arrays.
#[derive(Clone, Copy, Debug)]
struct Recorded {
    xyz: [f64; 3],
    band: f64,
    pixels_end: u32,
    bins_end: u32,
    stokes_end: u32,
}

/// Splats of a whole image, in the order they were made.
#[derive(Clone, Debug)]
pub struct SplatList {
    width: u32,
    samples: Vec<Recorded>,
    /// (pixel index y·width + x, filter weight) of every splat, by sample.
    pixels: Vec<(u32, f32)>,
    /// (spectral bin, value per nm) of every sample that has bins.
    bins: Vec<(usize, f64)>,
    /// (index within a pixel's Stokes sums, value) of every polarised sample.
    stokes: Vec<(usize, f64)>,
}

impl SplatList {
    /// An empty list for an image `width` pixels wide.
    pub fn new(width: u32) -> Self {
        Self {
            width,
            samples: Vec::new(),
            pixels: Vec::new(),
            bins: Vec::new(),
            stokes: Vec::new(),
        }
    }

    /// Number of samples recorded.
    pub fn len(&self) -> usize {
        self.samples.len()
    }

    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }
}

impl Splat for SplatList {
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
        let width = self.width;
        self.pixels
            .extend(pixels.map(|(x, y, wgt)| (y * width + x, wgt)));
        self.bins.extend_from_slice(s.bins());
        self.samples.push(Recorded {
            xyz: s.xyz,
            band: s.band,
            pixels_end: self.pixels.len() as u32,
            bins_end: self.bins.len() as u32,
            stokes_end: self.stokes.len() as u32,
        });
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
        let (nb, before) = (bins.map_or(0, |b| b.count), self.stokes.len());
        self.stokes.extend(stokes_entries(&terms, nb));
        if !self.splat_weighted(pixels, w, &st[0], bins) {
            self.stokes.truncate(before);
            return false;
        }
        true
    }
}

impl Film {
    /// Adds every splat of `list`, in its order, as a tile adds splats (sums × filter weight,
    /// in f64), without counting samples.
    pub fn apply(&mut self, list: &SplatList) {
        debug_assert_eq!(list.width, self.width);
        let nb = self.bins.as_ref().map_or(0, |b| b.count);
        let stride = stokes_stride(nb);
        let (mut p0, mut b0, mut s0) = (0usize, 0usize, 0usize);
        for s in &list.samples {
            let (p1, b1) = (s.pixels_end as usize, s.bins_end as usize);
            let s1 = s.stokes_end as usize;
            for &(i, wgt) in &list.pixels[p0..p1] {
                let i = i as usize;
                let spectral = &mut self.spectral[i * nb..(i + 1) * nb];
                self.sums[i].add_weighted(spectral, s.xyz, s.band, &list.bins[b0..b1], wgt as f64);
                if !self.stokes.is_empty() {
                    for &(k, v) in &list.stokes[s0..s1] {
                        self.stokes[i * stride + k].add_f64(v * wgt as f64);
                    }
                }
            }
            (p0, b0, s0) = (p1, b1, s1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Filter;
    use crate::film::FilterDesc;
    use crate::spectrum::WavelengthRange;

    /// A list applied to the film adds what the same splats add through a full-image tile
    /// merged into the film (to f64 rounding: the tile sums first, then adds), bins included,
    /// and a dropped (non-finite) sample adds nothing either way.
    #[test]
    fn applied_list_equals_tile_and_merge() {
        let new_film = || {
            let f = Filter::from_desc(&FilterDesc::BOX);
            Film::new(7, 5, f, WavelengthRange::default(), 6)
        };
        let (mut a, mut b) = (new_film(), new_film());
        let mut tile = a.tile(0, 0, 7, 5);
        let mut list = SplatList::new(7);
        let bins = a.bins.clone();
        let mut k = 1u32;
        let mut rnd = || {
            k = k.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (k >> 8) as f32 / (1u32 << 24) as f32
        };
        for s in 0..300 {
            let w = SampledWavelengths::<4> {
                lambda: [0.0; 4].map(|_| 380.0 + 400.0 * rnd()),
                pdf: [0.0; 4].map(|_| 0.001 + 0.01 * rnd()),
            };
            let mut l = SampledSpectrum([0.0; 4].map(|_| rnd()));
            if s % 50 == 7 {
                l.0[2] = f32::NAN;
            }
            let px: Vec<(u32, u32, f32)> = (0..1 + s % 4)
                .map(|_| ((rnd() * 7.0) as u32, (rnd() * 5.0) as u32, rnd()))
                .collect();
            let kept = tile.splat_weighted(px.iter().copied(), &w, &l, bins.as_ref());
            let recorded = Splat::splat_weighted(&mut list, px.into_iter(), &w, &l, bins.as_ref());
            assert_eq!(kept, recorded);
            assert_eq!(kept, s % 50 != 7);
        }
        a.merge(&tile);
        b.apply(&list);
        assert_eq!(list.len(), 294);
        a.set_path_count(300);
        b.set_path_count(300);
        let (ia, ib) = (a.image(), b.image());
        let close = |x: f32, y: f32| (x - y).abs() <= 1e-6 * x.abs().max(y.abs()).max(1e-20);
        for (x, y) in ia.xyz.iter().zip(&ib.xyz) {
            assert!((0..3).all(|c| close(x[c], y[c])), "{x:?} vs {y:?}");
        }
        for (x, y) in ia.band.iter().zip(&ib.band) {
            assert!(close(*x, *y), "{x} vs {y}");
        }
        for (bx, by) in ia.spectral.iter().zip(&ib.spectral) {
            assert!(bx.iter().zip(by).all(|(x, y)| close(*x, *y)));
        }
        assert!(ia.xyz.iter().any(|x| x[1] > 0.0));
        assert!(ia.spectral.iter().flatten().any(|&x| x > 0.0));
    }
}
