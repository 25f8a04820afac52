//! A film's exact sums as planes of 32-bit words: what checkpoints and render parts store (as
//! unsigned-integer EXR channels beside the image) so that a resumed or merged render continues
//! from the very bits it stopped at.
//!
//! Channels, each `width × height` words, row-major: `<prefix>X.w0` … `<prefix>X.w5` (the six
//! words of an [`Exact`], least significant first) for the sums `X`, `Y`, `Z` (cd/m²), `L`
//! (W·m⁻²·sr⁻¹), `m2X`, `m2Y`, `m2Z` ((cd/m²)²), `S<k>` (bin k, W·m⁻²·sr⁻¹·nm⁻¹), a polarised
//! film's `s1X` … `s3Z` (the XYZ of Stokes S1–S3, cd/m²) and `s1S<k>` … `s3S<k>` (their bins),
//! and
//! `<prefix>count.w0`, `.w1` (the sample count, a u64). Files use the prefix [`STATE_PREFIX`]
//! for a film's sums (and `spectrace.pass.` for a `bdpt` checkpoint's unfinished pass).

use super::{Exact, Film};

/// Prefix of the state channels' names.
pub const STATE_PREFIX: &str = "spectrace.sum.";

/// Names of the sums, in order: X, Y, Z, L, m2X, m2Y, m2Z, the bins, then (a polarised
/// film) the Stokes components' XYZ `s1X` … `s3Z` and bins `s1S<k>` … `s3S<k>`.
fn sum_names(nbins: usize, stokes: bool) -> Vec<String> {
    let mut v: Vec<String> = ["X", "Y", "Z", "L", "m2X", "m2Y", "m2Z"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    v.extend((0..nbins).map(|k| format!("S{k}")));
    if stokes {
        for c in 1..=3 {
            v.extend(["X", "Y", "Z"].map(|a| format!("s{c}{a}")));
        }
        for c in 1..=3 {
            v.extend((0..nbins).map(|k| format!("s{c}S{k}")));
        }
    }
    v
}

impl Film {
    fn nbins(&self) -> usize {
        self.bins.as_ref().map_or(0, |b| b.count)
    }

    /// The exact value of sum `q` (index into [`sum_names`]) at pixel `i`.
    fn sum(&self, q: usize, i: usize) -> Exact {
        let p = &self.sums[i];
        match q {
            0..=2 => p.xyz[q],
            3 => p.band,
            4..=6 => p.xyz_sq[q - 4],
            _ if q < 7 + self.nbins() => self.spectral[i * self.nbins() + q - 7],
            _ => self.stokes[i * super::stokes_stride(self.nbins()) + q - 7 - self.nbins()],
        }
    }

    fn sum_mut(&mut self, q: usize, i: usize) -> &mut Exact {
        let nb = self.nbins();
        let p = &mut self.sums[i];
        match q {
            0..=2 => &mut p.xyz[q],
            3 => &mut p.band,
            4..=6 => &mut p.xyz_sq[q - 4],
            _ if q < 7 + nb => &mut self.spectral[i * nb + q - 7],
            _ => &mut self.stokes[i * super::stokes_stride(nb) + q - 7 - nb],
        }
    }

    /// The state channels (see the module doc) with names starting `prefix`, sorted by name.
    pub fn state_channels(&self, prefix: &str) -> Vec<(String, Vec<u32>)> {
        let n = (self.width * self.height) as usize;
        let mut out = Vec::new();
        for (q, name) in sum_names(self.nbins(), self.polarised()).iter().enumerate() {
            let mut planes: Vec<Vec<u32>> = (0..6).map(|_| Vec::with_capacity(n)).collect();
            for i in 0..n {
                for (plane, w) in planes.iter_mut().zip(self.sum(q, i).to_words()) {
                    plane.push(w);
                }
            }
            for (k, plane) in planes.into_iter().enumerate() {
                out.push((format!("{prefix}{name}.w{k}"), plane));
            }
        }
        let counts = |shift: u32| {
            self.sums
                .iter()
                .map(|p| (p.count >> shift) as u32)
                .collect()
        };
        out.push((format!("{prefix}count.w0"), counts(0)));
        out.push((format!("{prefix}count.w1"), counts(32)));
        out.sort_by(|a, b| a.0.cmp(&b.0));
        out
    }

    /// Adds the sums and counts stored in the channels named `prefix…` of `channels` (as
    /// [`Film::state_channels`] writes them for a film of this size and bin count). Fails,
    /// naming it, if a channel is missing or holds a wrong number of words, adding nothing;
    /// other channels are ignored.
    pub fn add_state_channels(
        &mut self,
        prefix: &str,
        channels: &[(String, Vec<u32>)],
    ) -> Result<(), String> {
        let n = (self.width * self.height) as usize;
        let find = |name: String| -> Result<&[u32], String> {
            match channels.iter().find(|(c, _)| *c == name) {
                Some((_, d)) if d.len() == n => Ok(d.as_slice()),
                Some((_, d)) => Err(format!(
                    "channel `{name}` holds {} values for {n} pixels",
                    d.len()
                )),
                None => Err(format!("channel `{name}` is missing")),
            }
        };
        let mut planes = Vec::new();
        for name in sum_names(self.nbins(), self.polarised()) {
            let words: Vec<&[u32]> = (0..6)
                .map(|k| find(format!("{prefix}{name}.w{k}")))
                .collect::<Result<_, _>>()?;
            planes.push(words);
        }
        let lo = find(format!("{prefix}count.w0"))?;
        let hi = find(format!("{prefix}count.w1"))?;
        for (q, words) in planes.iter().enumerate() {
            (0..n).for_each(|i| {
                let e = Exact::from_words(std::array::from_fn(|k| words[k][i]));
                self.sum_mut(q, i).add(e);
            });
        }
        for (i, p) in self.sums.iter_mut().enumerate() {
            p.count += lo[i] as u64 | (hi[i] as u64) << 32;
        }
        Ok(())
    }

    /// Whether two films hold the same sums and counts, bit for bit.
    #[cfg(test)]
    pub fn same_sums(&self, other: &Film) -> bool {
        self.sums == other.sums && self.spectral == other.spectral && self.stokes == other.stokes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Filter;
    use crate::film::FilterDesc;
    use crate::spectrum::{SampledSpectrum, SampledWavelengths, WavelengthRange};

    /// Channels written and added back into an empty film give the same sums; adding them to
    /// a film twice doubles its sums.
    #[test]
    fn state_channels_round_trip() {
        let f = Filter::from_desc(&FilterDesc::BOX);
        let mut a = Film::new(5, 3, f, WavelengthRange::default(), 4);
        let mut tile = a.tile(0, 0, 5, 3);
        let bins = a.bins.clone();
        for s in 0..40u32 {
            let w = SampledWavelengths::<4> {
                lambda: [400.0, 480.0, 560.0, 650.0].map(|l| l + s as f32),
                pdf: [0.003; 4],
            };
            let l = SampledSpectrum([0.1, 2.0, 1e-9, 3e5].map(|v| v * (1 + s % 3) as f32));
            assert!(tile.add(s % 5, s % 3, &w, &l, bins.as_ref()));
        }
        a.merge(&tile);
        let ch = a.state_channels(STATE_PREFIX);
        assert_eq!(ch.len(), 6 * (7 + 4) + 2);
        let mut b = a.empty_like();
        b.add_state_channels(STATE_PREFIX, &ch).unwrap();
        assert!(a.same_sums(&b));
        b.add_state_channels(STATE_PREFIX, &ch).unwrap();
        let mut a2 = a.clone();
        a2.merge_film(&a);
        assert!(a2.same_sums(&b));
        assert!(!a.same_sums(&b));
        let mut short = ch.clone();
        short.retain(|(n, _)| !n.ends_with("S3.w2"));
        let err = a
            .empty_like()
            .add_state_channels(STATE_PREFIX, &short)
            .unwrap_err();
        assert!(err.contains("S3.w2") && err.contains("missing"), "{err}");
    }

    /// A polarised film's Stokes sums (XYZ and bins of S1–S3) round-trip too, and a film
    /// without them refuses nothing it does not need.
    #[test]
    fn polarised_state_channels_round_trip() {
        let f = Filter::from_desc(&FilterDesc::BOX);
        let mut a = Film::new(4, 2, f, WavelengthRange::default(), 3).with_stokes(true);
        let mut tile = a.tile(0, 0, 4, 2);
        let bins = a.bins.clone();
        for s in 0..30u32 {
            let w = SampledWavelengths::<4> {
                lambda: [420.0, 500.0, 580.0, 660.0].map(|l| l + s as f32),
                pdf: [0.003; 4],
            };
            let k = (1 + s % 3) as f32;
            let st = [
                SampledSpectrum([1.0, 2.0, 3.0, 4.0].map(|v| v * k)),
                SampledSpectrum([0.5, -1.0, 0.25, 2.0].map(|v| v * k)),
                SampledSpectrum([-0.3, 0.1, 0.2, -1.0].map(|v| v * k)),
                SampledSpectrum([0.01, 0.0, -0.02, 0.03].map(|v| v * k)),
            ];
            assert!(tile.add_stokes(s % 4, s % 2, &w, &st, bins.as_ref()));
        }
        a.merge(&tile);
        let ch = a.state_channels(STATE_PREFIX);
        assert_eq!(ch.len(), 6 * (7 + 3 + 9 + 9) + 2);
        let mut b = a.empty_like();
        assert!(b.polarised());
        b.add_state_channels(STATE_PREFIX, &ch).unwrap();
        assert!(a.same_sums(&b));
        let img = b.image();
        assert_eq!((img.stokes.len(), img.stokes_spectral.len()), (8, 9));
        assert!(img.stokes.iter().any(|p| p[0][1] != 0.0));
    }
}
