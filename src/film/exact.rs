//! Exact sums: signed fixed-point numbers with 96 fractional bits in 192 bits.
//!
//! Why: the film's per-pixel sums must not depend on the order in which samples are added, so
//! that a render resumed from a checkpoint, or split into parts rendered on other machines and
//! merged, gives the same bits as one uninterrupted render (issue 12). Floating-point addition
//! is not associative; integer addition is. Every term is converted to a multiple of 2⁻⁹⁶ once
//! (truncated toward zero, a deterministic function of the f64 term), and from then on sums are
//! exact and order-free.
//!
//! Range and resolution: terms are multiples of 2⁻⁹⁶ ≈ 1.26·10⁻²⁹ in the sum's unit (cd/m²,
//! W·m⁻²·sr⁻¹ or W·m⁻²·sr⁻¹·nm⁻¹); a term's magnitude must stay below [`MAX_TERM`] = 2⁸⁸
//! ≈ 3.1·10²⁶, and a sum's below 2⁹⁵ ≈ 4·10²⁸ (128 maximal terms). The film refuses samples
//! whose terms exceed [`MAX_TERM`] as infinite; larger sums wrap (they would need more than 128
//! such samples in one pixel).

/// Largest magnitude of one term, 2⁸⁸: [`Exact::from_f64`] clamps to it.
pub const MAX_TERM: f64 = 309_485_009_821_345_068_724_781_056.0;

/// Fractional bits.
const FRAC: i32 = 96;

/// A signed fixed-point number: the integer `limbs` (little-endian, two's complement, 192 bits)
/// times 2⁻⁹⁶.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Exact(pub [u64; 3]);

impl Exact {
    pub const ZERO: Exact = Exact([0; 3]);

    /// `v` truncated toward zero to a multiple of 2⁻⁹⁶, its magnitude clamped to [`MAX_TERM`];
    /// NaN is 0 (callers drop NaN samples before).
    #[inline]
    pub fn from_f64(v: f64) -> Exact {
        let v = v.clamp(-MAX_TERM, MAX_TERM);
        let bits = v.to_bits();
        let biased = ((bits >> 52) & 0x7ff) as i32;
        if biased == 0 || v.is_nan() {
            // zero or subnormal (below 2⁻¹⁰²², far under the resolution)
            return Exact::ZERO;
        }
        let mant = (bits & ((1u64 << 52) - 1)) | (1u64 << 52);
        // |v| = mant · 2^(biased − 1075); the fixed-point integer is mant · 2^shift
        let shift = biased - 1075 + FRAC;
        let mut m = [0u64; 3];
        if shift <= -64 {
            return Exact::ZERO;
        } else if shift < 0 {
            m[0] = mant >> (-shift);
        } else {
            // shift ≤ 88 + 96 − 52 = 132 after the clamp: mant spans at most limbs k and k + 1
            let (k, b) = ((shift / 64) as usize, shift % 64);
            m[k] = mant << b;
            if b > 0 && k + 1 < 3 {
                m[k + 1] = mant >> (64 - b);
            }
        }
        let e = Exact(m);
        if v < 0.0 { e.negated() } else { e }
    }

    /// The two's complement negation.
    #[inline]
    pub fn negated(self) -> Exact {
        let mut out = [0u64; 3];
        let mut carry = 1u64;
        for (o, l) in out.iter_mut().zip(self.0) {
            let (s, c) = (!l).overflowing_add(carry);
            *o = s;
            carry = c as u64;
        }
        Exact(out)
    }

    /// Adds `other` (wrapping beyond ±2⁹⁵, see the module doc).
    #[inline]
    pub fn add(&mut self, other: Exact) {
        let mut carry = false;
        for (a, b) in self.0.iter_mut().zip(other.0) {
            let (s1, c1) = a.overflowing_add(b);
            let (s2, c2) = s1.overflowing_add(carry as u64);
            *a = s2;
            carry = c1 | c2;
        }
    }

    /// Adds the term `v` ([`Exact::from_f64`]).
    #[inline]
    pub fn add_f64(&mut self, v: f64) {
        self.add(Exact::from_f64(v));
    }

    pub fn is_negative(self) -> bool {
        (self.0[2] >> 63) == 1
    }

    /// The nearest f64 (within one rounding per limb: relative error below 10⁻¹⁵).
    pub fn to_f64(self) -> f64 {
        let (neg, m) = if self.is_negative() {
            (true, self.negated().0)
        } else {
            (false, self.0)
        };
        let v = m[2] as f64 * 2f64.powi(128 - FRAC)
            + m[1] as f64 * 2f64.powi(64 - FRAC)
            + m[0] as f64 * 2f64.powi(-FRAC);
        if neg { -v } else { v }
    }

    /// The six 32-bit words, least significant first (for files).
    pub fn to_words(self) -> [u32; 6] {
        let mut w = [0u32; 6];
        for (i, l) in self.0.iter().enumerate() {
            w[2 * i] = *l as u32;
            w[2 * i + 1] = (*l >> 32) as u32;
        }
        w
    }

    /// The inverse of [`Exact::to_words`].
    pub fn from_words(w: [u32; 6]) -> Exact {
        Exact([0, 1, 2].map(|i| w[2 * i] as u64 | (w[2 * i + 1] as u64) << 32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn max_term_is_two_to_the_88() {
        assert_eq!(MAX_TERM, 2f64.powi(88));
    }

    /// Conversions are exact for multiples of 2⁻⁹⁶ and truncate below; sums in any order agree
    /// bit for bit, and agree with the exact rational sum (checked in i128 units of 2⁻⁹⁶ for
    /// terms that fit).
    #[test]
    fn sums_are_exact_and_order_free() {
        for v in [0.0, 1.0, -1.0, 0.5, 3.25, -7.75e-3, 1e20, -2.5e25, 1e-28] {
            let e = Exact::from_f64(v);
            let back = e.to_f64();
            assert!(
                (back - v).abs() <= v.abs() * 1e-15 + 2f64.powi(-96),
                "{v} → {back}"
            );
        }
        assert_eq!(Exact::from_f64(1e-30), Exact::ZERO);
        assert_eq!(Exact::from_f64(f64::NAN), Exact::ZERO);
        assert_eq!(Exact::from_f64(1e300).to_f64(), MAX_TERM);
        assert_eq!(Exact::from_f64(-1e300).to_f64(), -MAX_TERM);
        // 2⁻⁹⁶ itself, and 1.5 · 2⁻⁹⁶ truncates to it
        assert_eq!(Exact::from_f64(2f64.powi(-96)).0, [1, 0, 0]);
        assert_eq!(Exact::from_f64(1.5 * 2f64.powi(-96)).0, [1, 0, 0]);
        assert_eq!(
            Exact::from_f64(-1.5 * 2f64.powi(-96)),
            Exact([1, 0, 0]).negated()
        );

        let mut k = 7u64;
        let terms: Vec<f64> = (0..2000)
            .map(|_| {
                k = k
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let m = (k >> 11) as f64 / (1u64 << 53) as f64;
                let e = ((k >> 3) % 60) as i32 - 40;
                if k & 1 == 0 {
                    m * 2f64.powi(e)
                } else {
                    -m * 2f64.powi(e)
                }
            })
            .collect();
        let mut fwd = Exact::ZERO;
        terms.iter().for_each(|&t| fwd.add_f64(t));
        let mut rev = Exact::ZERO;
        terms.iter().rev().for_each(|&t| rev.add_f64(t));
        let mut halves = (Exact::ZERO, Exact::ZERO);
        for (i, &t) in terms.iter().enumerate() {
            if i % 3 == 0 {
                halves.0.add_f64(t);
            } else {
                halves.1.add_f64(t);
            }
        }
        halves.0.add(halves.1);
        assert_eq!(fwd, rev);
        assert_eq!(fwd, halves.0);
        let f64_sum: f64 = terms.iter().sum();
        assert!((fwd.to_f64() - f64_sum).abs() < 1e-9 * f64_sum.abs().max(1.0));
        assert_eq!(Exact::from_words(fwd.to_words()), fwd);
        // in units of 2⁻⁹⁶, terms of magnitude < 2²⁰ fit in i128 exactly
        let mut units = 0i128;
        let mut ex = Exact::ZERO;
        for &t in terms.iter().filter(|t| t.abs() < 2f64.powi(20)) {
            let u = (t.abs() * 2f64.powi(96)).trunc() as i128;
            units += if t < 0.0 { -u } else { u };
            ex.add_f64(t);
        }
        let as_i128 = (ex.0[0] as u128 | (ex.0[1] as u128) << 64) as i128;
        assert_eq!(as_i128, units);
    }
}
