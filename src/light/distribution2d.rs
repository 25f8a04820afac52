//! A piecewise-constant density on [0, 1)² over a grid of cells (pbrt-v4 §A.5.6,
//! `PiecewiseConstant2D`): a row is chosen from the marginal distribution of the rows, then a
//! column from that row's conditional distribution, each inverted with a guide table so a
//! sample costs O(1) on average.

use glam::Vec2;

use crate::sampling::CdfGuide;

#[derive(Clone, Debug)]
pub struct Distribution2D {
    cols: usize,
    rows: usize,
    /// Per row: the CDF over its columns, `cols + 1` entries from 0 to 1.
    cond_cdf: Vec<f32>,
    cond_guide: Vec<CdfGuide>,
    /// The CDF over rows, `rows + 1` entries.
    marg_cdf: Vec<f32>,
    marg_guide: CdfGuide,
    /// Cell weights divided by their mean: the density on [0, 1)² in each cell.
    density: Vec<f32>,
}

impl Distribution2D {
    /// From non-negative weights, row-major, `cols × rows`. None if every weight is 0 or one is
    /// negative or not finite.
    pub fn new(weights: &[f32], cols: usize, rows: usize) -> Option<Self> {
        if cols == 0 || rows == 0 || weights.len() != cols * rows {
            return None;
        }
        if weights.iter().any(|w| !(w.is_finite() && *w >= 0.0)) {
            return None;
        }
        let total: f64 = weights.iter().map(|&w| w as f64).sum();
        if !(total > 0.0) {
            return None;
        }
        let mut cond_cdf = Vec::with_capacity(rows * (cols + 1));
        let mut cond_guide = Vec::with_capacity(rows);
        let mut row_sums = Vec::with_capacity(rows);
        for r in 0..rows {
            let row = &weights[r * cols..(r + 1) * cols];
            let sum: f64 = row.iter().map(|&w| w as f64).sum();
            row_sums.push(sum);
            let start = cond_cdf.len();
            let mut acc = 0.0;
            cond_cdf.push(0.0);
            for &w in row {
                acc += w as f64;
                // an empty row is never chosen; give it a uniform CDF anyway
                cond_cdf.push(if sum > 0.0 { (acc / sum) as f32 } else { 0.0 });
            }
            if sum <= 0.0 {
                for (c, v) in cond_cdf[start..].iter_mut().enumerate() {
                    *v = c as f32 / cols as f32;
                }
            }
            cond_cdf[start + cols] = 1.0;
            cond_guide.push(CdfGuide::new(&cond_cdf[start..], cols));
        }
        let mut marg_cdf = Vec::with_capacity(rows + 1);
        let mut acc = 0.0;
        marg_cdf.push(0.0);
        for s in &row_sums {
            acc += s;
            marg_cdf.push((acc / total) as f32);
        }
        marg_cdf[rows] = 1.0;
        let marg_guide = CdfGuide::new(&marg_cdf, rows);
        let mean = total / (cols * rows) as f64;
        let density = weights.iter().map(|&w| (w as f64 / mean) as f32).collect();
        Some(Self {
            cols,
            rows,
            cond_cdf,
            cond_guide,
            marg_cdf,
            marg_guide,
            density,
        })
    }

    /// A point in [0, 1)² from `u` uniform in [0, 1)², with its density on [0, 1)².
    #[inline]
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let r = self.marg_guide.cell(&self.marg_cdf, u.y as f64);
        let (m0, m1) = (self.marg_cdf[r], self.marg_cdf[r + 1]);
        let fy = if m1 > m0 { (u.y - m0) / (m1 - m0) } else { 0.5 };
        let cdf = &self.cond_cdf[r * (self.cols + 1)..(r + 1) * (self.cols + 1)];
        let c = self.cond_guide[r].cell(cdf, u.x as f64);
        let (c0, c1) = (cdf[c], cdf[c + 1]);
        let fx = if c1 > c0 { (u.x - c0) / (c1 - c0) } else { 0.5 };
        let p = Vec2::new(
            ((c as f32 + fx.clamp(0.0, 1.0)) / self.cols as f32).min(1.0 - f32::EPSILON / 2.0),
            ((r as f32 + fy.clamp(0.0, 1.0)) / self.rows as f32).min(1.0 - f32::EPSILON / 2.0),
        );
        (p, self.density[r * self.cols + c])
    }

    /// The density on [0, 1)² in cell (column `c`, row `r`).
    #[inline]
    pub fn pdf_cell(&self, c: usize, r: usize) -> f32 {
        self.density[r.min(self.rows - 1) * self.cols + c.min(self.cols - 1)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sampling follows the weights: cell frequencies match weight / total, and the returned
    /// density is the cell's weight over the mean weight.
    #[test]
    fn frequencies_follow_weights() {
        let w = [1.0, 0.0, 3.0, 2.0, 2.0, 0.0];
        let d = Distribution2D::new(&w, 3, 2).unwrap();
        let n = 300;
        let mut counts = [0usize; 6];
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let (p, pdf) = d.sample(u);
                let cell = (p.y * 2.0) as usize * 3 + (p.x * 3.0) as usize;
                counts[cell] += 1;
                assert_eq!(pdf, d.pdf_cell((p.x * 3.0) as usize, (p.y * 2.0) as usize));
                assert!((pdf - w[cell] / (8.0 / 6.0)).abs() < 1e-5);
            }
        }
        for (c, &k) in counts.iter().enumerate() {
            let f = k as f64 / (n * n) as f64;
            assert!((f - w[c] as f64 / 8.0).abs() < 2e-3, "cell {c}: {f}");
        }
        assert!(Distribution2D::new(&[0.0; 4], 2, 2).is_none());
    }
}
