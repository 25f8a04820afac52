//! Light selection independent of position: a light chosen with probability proportional to
//! a weight (its emitted power, or a uniform sampling weight), with sample reuse.

/// Chooses lights with probability proportional to their emitted power.
#[derive(Clone, Debug)]
pub struct LightSelector {
    cdf: Vec<f64>,
    prob: Vec<f32>,
}

impl LightSelector {
    pub fn new(power: &[f64]) -> Self {
        let total: f64 = power.iter().map(|p| p.max(0.0)).sum();
        let n = power.len();
        let weights: Vec<f64> = if total > 0.0 {
            power.iter().map(|p| p.max(0.0) / total).collect()
        } else {
            vec![1.0 / n.max(1) as f64; n]
        };
        let mut cdf = Vec::with_capacity(n);
        let mut acc = 0.0;
        for w in &weights {
            acc += w;
            cdf.push(acc);
        }
        Self {
            cdf,
            prob: weights.iter().map(|&w| w as f32).collect(),
        }
    }

    /// A light index and its probability, from `u` in [0, 1); None if there are no lights.
    #[inline]
    pub fn pick(&self, u: f32) -> Option<(usize, f32)> {
        if self.cdf.is_empty() {
            return None;
        }
        let i = self
            .cdf
            .partition_point(|&c| c <= u as f64)
            .min(self.cdf.len() - 1);
        (self.prob[i] > 0.0).then_some((i, self.prob[i]))
    }

    /// [`LightSelector::pick`], and `u` rescaled within the chosen light's CDF interval to a
    /// fresh uniform number in [0, 1) ([`crate::sampling::reuse`]), so that one stratified
    /// coordinate both chooses the light and samples it.
    #[inline]
    pub fn pick_reuse(&self, u: f32) -> Option<(usize, f32, f32)> {
        let (i, p) = self.pick(u)?;
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] as f32 };
        Some((i, p, crate::sampling::reuse(u, lo, self.cdf[i] as f32)))
    }

    /// Probability of choosing light `i`.
    #[inline]
    pub fn prob(&self, i: usize) -> f32 {
        self.prob[i]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn selector_is_proportional_to_power() {
        let s = LightSelector::new(&[1.0, 3.0, 0.0]);
        assert_eq!(s.pick(0.1), Some((0, 0.25)));
        assert_eq!(s.pick(0.5), Some((1, 0.75)));
        assert_eq!(s.pick(0.999), Some((1, 0.75)));
        assert_eq!(s.prob(2), 0.0);
        assert!(LightSelector::new(&[]).pick(0.3).is_none());
        // reuse: the rest of u within the chosen interval, rescaled to [0, 1)
        assert_eq!(s.pick_reuse(0.125), Some((0, 0.25, 0.5)));
        assert_eq!(s.pick_reuse(0.625), Some((1, 0.75, 0.5)));
        assert_eq!(s.pick_reuse(0.25), Some((1, 0.75, 0.0)));
    }
}
