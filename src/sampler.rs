//! Owen-scrambled Sobol sampling, deterministic in (pixel, sample index, dimension).
//!
//! Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): every pair of dimensions
//! draws from the first two Sobol dimensions (van der Corput and x+1), with the sample index
//! shuffled by a nested uniform scramble and each coordinate Owen-scrambled by a hash, all seeded
//! by (seed, pixel, dimension). No state is shared between pixels, so an image does not depend
//! on the thread count or the tile order.

use glam::Vec2;

/// Integer hash (a 32-bit finaliser in the style of MurmurHash3), for seeding.
#[inline]
pub fn hash_u32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

#[inline]
fn hash_combine(a: u32, b: u32) -> u32 {
    hash_u32(
        a ^ b
            .wrapping_add(0x9e37_79b9)
            .wrapping_add(a << 6)
            .wrapping_add(a >> 2),
    )
}

/// Laine–Karras style hash permutation, which nests in the reversed-bit domain (Burley §3).
#[inline]
fn lk_permutation(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

/// Owen scramble of a 32-bit fixed-point value in [0, 1). The sampler applies it written out
/// (see [`Sampler::get_2d`]); the tests check that against this form.
#[cfg(test)]
fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    lk_permutation(x.reverse_bits(), seed).reverse_bits()
}

/// Second Sobol dimension (primitive polynomial x + 1): v₁ = 2³¹, vₖ = vₖ₋₁ ⊕ (vₖ₋₁ >> 1), the
/// result the XOR of vₖ over the set bits k − 1 of `index`. The definition, one step per bit;
/// [`sobol_dim1_rev`] is what sampling uses.
const fn sobol_dim1(mut index: u32) -> u32 {
    let mut v = 1u32 << 31;
    let mut r = 0;
    while index != 0 {
        if index & 1 != 0 {
            r ^= v;
        }
        index >>= 1;
        v ^= v >> 1;
    }
    r
}

/// `sobol_dim1(r.reverse_bits()).reverse_bits()` by bytes: the map is linear over GF(2), so it
/// is the XOR of one 256-entry table per byte of `r`, the tables built at compile time from
/// [`sobol_dim1`] itself. The bit-reversed domain is where the Owen scramble works (Burley §3),
/// so sampling reads the scrambled index this way without reversing it twice.
#[inline]
fn sobol_dim1_rev(r: u32) -> u32 {
    SOBOL1_REV[0][(r & 0xff) as usize]
        ^ SOBOL1_REV[1][((r >> 8) & 0xff) as usize]
        ^ SOBOL1_REV[2][((r >> 16) & 0xff) as usize]
        ^ SOBOL1_REV[3][(r >> 24) as usize]
}

/// `SOBOL1_REV[k][b]`: [`sobol_dim1_rev`] of byte `b` placed at byte `k` (4 KiB).
static SOBOL1_REV: [[u32; 256]; 4] = sobol1_rev_tables();

const fn sobol1_rev_tables() -> [[u32; 256]; 4] {
    let mut t = [[0u32; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut b = 0;
        while b < 256 {
            let r = (b as u32) << (8 * k);
            t[k][b] = sobol_dim1(r.reverse_bits()).reverse_bits();
            b += 1;
        }
        k += 1;
    }
    t
}

#[inline]
fn to_unit(x: u32) -> f32 {
    // 24 significant bits so that the result is < 1 in f32
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// A sample stream for one (pixel, sample index). Each call consumes the next dimension.
#[derive(Clone, Debug)]
pub struct Sampler {
    pixel_seed: u32,
    /// The sample index with its bits reversed (the domain of the scramble).
    index_rev: u32,
    dim: u32,
}

impl Sampler {
    /// The stream of sample `index` of pixel (x, y) under global `seed`.
    #[inline]
    pub fn new(seed: u32, x: u32, y: u32, index: u32) -> Self {
        Self {
            pixel_seed: hash_combine(hash_combine(hash_u32(seed), x), y),
            index_rev: index.reverse_bits(),
            dim: 0,
        }
    }

    /// Continues the stream at dimension `dim` (for integrators that reserve ranges).
    #[inline]
    pub fn at_dimension(mut self, dim: u32) -> Self {
        self.dim = dim;
        self
    }

    /// The next dimension this stream will read (each `get_2d` and `get_1d` reads two).
    #[inline]
    pub fn dimension(&self) -> u32 {
        self.dim
    }

    /// The next two dimensions as a point in [0, 1)².
    #[inline]
    pub fn get_2d(&mut self) -> Vec2 {
        let seed = hash_combine(self.pixel_seed, self.dim);
        self.dim += 2;
        // The shuffled index i = nested_uniform_scramble(index) = r reversed, then each
        // coordinate's Owen scramble: x = nested_uniform_scramble(i reversed) (the van der
        // Corput point of i), y = nested_uniform_scramble(sobol_dim1(i)). Written out, the
        // reversals that cancel are left out: 3 reversals instead of 8, and the second
        // dimension by table ([`sobol_dim1_rev`]) instead of one step per bit of i.
        let r = lk_permutation(self.index_rev, seed);
        let x = lk_permutation(r.reverse_bits(), hash_u32(seed ^ 0xa511_e9b3)).reverse_bits();
        let y = lk_permutation(sobol_dim1_rev(r), hash_u32(seed ^ 0x63d8_3595)).reverse_bits();
        Vec2::new(to_unit(x), to_unit(y))
    }

    /// The next dimension in [0, 1): the first coordinate of the pair [`Sampler::get_2d`] would
    /// return (the same value, so layouts stay the same), computed alone. Uses one pair.
    #[inline]
    pub fn get_1d(&mut self) -> f32 {
        let seed = hash_combine(self.pixel_seed, self.dim);
        self.dim += 2;
        let r = lk_permutation(self.index_rev, seed);
        to_unit(lk_permutation(r.reverse_bits(), hash_u32(seed ^ 0xa511_e9b3)).reverse_bits())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sobol_dim1_matches_known_sequence() {
        // Sobol dimension 2 in index (not Gray-code) order: x_i = XOR of v_k over the set bits
        // of i, with v = 1/2, 3/4, 5/8, …: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8
        let want = [0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875];
        for (i, w) in want.iter().enumerate() {
            assert_eq!(sobol_dim1(i as u32) as f64 / 2f64.powi(32), *w, "index {i}");
        }
    }

    /// The sampler as first written (Burley 2020, listing 2 with the pair of Sobol dimensions):
    /// three nested uniform scrambles and the second dimension one step per bit.
    fn reference_get_2d(seed: u32, x: u32, y: u32, index: u32, dim: u32) -> (u32, u32) {
        let pixel_seed = hash_combine(hash_combine(hash_u32(seed), x), y);
        let seed = hash_combine(pixel_seed, dim);
        let i = nested_uniform_scramble(index, seed);
        let x = nested_uniform_scramble(i.reverse_bits(), hash_u32(seed ^ 0xa511_e9b3));
        let y = nested_uniform_scramble(sobol_dim1(i), hash_u32(seed ^ 0x63d8_3595));
        (x, y)
    }

    #[test]
    fn tables_give_the_bits_of_the_definition() {
        // the byte tables against the bit-serial definition, on random and edge words
        let mut h = 1u32;
        let mut words = vec![0, 1, u32::MAX, 1 << 31, 0xff, 0xff00_0000];
        for _ in 0..20_000 {
            h = hash_u32(h.wrapping_add(0x9e37_79b9));
            words.push(h);
        }
        for r in words {
            assert_eq!(
                sobol_dim1_rev(r),
                sobol_dim1(r.reverse_bits()).reverse_bits(),
                "r = {r:#010x}"
            );
        }
        // and whole points against the sampler as first written, in every 1D and 2D read
        for (seed, px, py) in [
            (0u32, 0u32, 0u32),
            (7, 3, 4),
            (123, 511, 77),
            (9, 65_535, 1),
        ] {
            for index in (0..300).chain([1 << 20, u32::MAX - 1]) {
                for dim in (0..24).step_by(2) {
                    let (x, y) = reference_get_2d(seed, px, py, index, dim);
                    let s = Sampler::new(seed, px, py, index).at_dimension(dim);
                    assert_eq!(s.clone().get_2d(), Vec2::new(to_unit(x), to_unit(y)));
                    assert_eq!(s.clone().get_1d(), to_unit(x));
                }
            }
        }
    }

    #[test]
    fn deterministic_and_stratified() {
        let a: Vec<Vec2> = (0..64)
            .map(|i| Sampler::new(7, 3, 4, i).at_dimension(6).get_2d())
            .collect();
        let b: Vec<Vec2> = (0..64)
            .map(|i| Sampler::new(7, 3, 4, i).at_dimension(6).get_2d())
            .collect();
        assert_eq!(a, b);
        // (0,2)-sequence property survives Owen scrambling: 64 points, one per 8×8 cell
        let mut cells = [0u32; 64];
        for p in &a {
            assert!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
            cells[(p.y * 8.0) as usize * 8 + (p.x * 8.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
        // and each 1D projection is stratified into 64 intervals
        let mut xs = [0u32; 64];
        for p in &a {
            xs[(p.x * 64.0) as usize] += 1;
        }
        assert!(xs.iter().all(|&c| c == 1));
        // different pixels and dimensions decorrelate
        assert_ne!(
            Sampler::new(7, 3, 4, 0).get_2d(),
            Sampler::new(7, 4, 4, 0).get_2d()
        );
        assert_ne!(
            Sampler::new(7, 3, 4, 0).get_2d(),
            Sampler::new(7, 3, 4, 0).at_dimension(2).get_2d()
        );
    }

    /// Every 2D projection the integrators read (each dimension pair, in any pixel) is a
    /// (0, 2)-sequence: for every power of two n = 2^m ≤ 4096, each aligned block of n
    /// consecutive samples puts exactly one point in every elementary interval of area 1/n,
    /// [i/2^a, (i+1)/2^a) × [j/2^b, (j+1)/2^b) with a + b = m (Niederreiter 1992, §4.1; Owen
    /// scrambling preserves it, Owen 1995). 1D reads are the pair's first coordinate, so they
    /// are stratified into n intervals by the case a = m.
    #[test]
    fn every_pair_is_stratified_at_every_power_of_two() {
        const M: u32 = 12;
        for (seed, px, py) in [(0u32, 0u32, 0u32), (7, 3, 4), (123, 511, 77)] {
            for dim in (0..40).step_by(2) {
                // 2·4096 samples: the prefixes and the second aligned block of each size
                let pts: Vec<(u32, u32)> = (0..2u32 << M)
                    .map(|i| {
                        let p = Sampler::new(seed, px, py, i).at_dimension(dim).get_2d();
                        // the 24-bit fixed-point coordinates, exact
                        (
                            (p.x * (1 << 24) as f32) as u32,
                            (p.y * (1 << 24) as f32) as u32,
                        )
                    })
                    .collect();
                for m in 0..=M {
                    let n = 1usize << m;
                    for block in [&pts[..n], &pts[n..2 * n]] {
                        for a in 0..=m {
                            let b = m - a;
                            let mut seen = vec![false; n];
                            for &(x, y) in block {
                                let cell = ((x >> (24 - a)) << b | (y >> (24 - b))) as usize;
                                assert!(
                                    !seen[cell],
                                    "seed {seed}, pixel ({px}, {py}), dims {dim}–{}: two of {n} \
                                     points in one {}×{} interval",
                                    dim + 1,
                                    1 << a,
                                    1 << b
                                );
                                seen[cell] = true;
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn get_1d_is_the_first_coordinate_of_get_2d() {
        for i in 0..256 {
            let mut a = Sampler::new(3, 5, 7, i).at_dimension(4);
            let mut b = a.clone();
            assert_eq!(a.get_1d(), b.get_2d().x);
            assert_eq!(a.dimension(), b.dimension());
        }
    }

    #[test]
    fn mean_is_unbiased() {
        let n = 1 << 14;
        let mut s = 0.0f64;
        for px in 0..4 {
            for i in 0..n {
                s += Sampler::new(1, px, 0, i).get_1d() as f64;
            }
        }
        let mean = s / (4 * n) as f64;
        assert!((mean - 0.5).abs() < 1e-3, "{mean}");
    }
}
