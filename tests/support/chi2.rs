//! χ² goodness-of-fit test of a direction sampler against its own density (the method of
//! Mitsuba's `chi2` test: bin sampled directions on a (cos θ, φ) grid, integrate the density
//! over each bin numerically for the expected counts, pool sparse bins, and turn the χ²
//! statistic into a p-value with the regularised incomplete gamma function).
//!
//! Declare it from a test with `#[path = "support/chi2.rs"] mod chi2;`.
#![allow(dead_code)]

use glam::Vec3;
use std::f64::consts::PI;

/// Bins in cos θ and φ. With `both_hemispheres` the cos θ bins span [−1, 1] (`n_cos` bins per
/// hemisphere), otherwise [0, 1].
#[derive(Clone, Copy, Debug)]
pub struct Grid {
    pub n_cos: usize,
    pub n_phi: usize,
    pub both_hemispheres: bool,
}

impl Grid {
    fn cos_bins(&self) -> usize {
        if self.both_hemispheres {
            2 * self.n_cos
        } else {
            self.n_cos
        }
    }
    fn z_min(&self) -> f64 {
        if self.both_hemispheres { -1.0 } else { 0.0 }
    }
    pub fn cells(&self) -> usize {
        self.cos_bins() * self.n_phi
    }
    /// Cell of a direction, or `None` if it is outside the grid (below the horizon of a
    /// one-hemisphere grid).
    pub fn cell(&self, d: Vec3) -> Option<usize> {
        let z = d.z as f64;
        if z < self.z_min() {
            return None;
        }
        let nz = self.cos_bins();
        let i = (((z - self.z_min()) / (1.0 - self.z_min()) * nz as f64) as usize).min(nz - 1);
        let mut phi = (d.y as f64).atan2(d.x as f64);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        let j = ((phi / (2.0 * PI) * self.n_phi as f64) as usize).min(self.n_phi - 1);
        Some(i * self.n_phi + j)
    }
    /// (z0, z1, φ0, φ1) of a cell.
    pub fn bounds(&self, c: usize) -> (f64, f64, f64, f64) {
        let (i, j) = (c / self.n_phi, c % self.n_phi);
        let dz = (1.0 - self.z_min()) / self.cos_bins() as f64;
        let dp = 2.0 * PI / self.n_phi as f64;
        let z0 = self.z_min() + i as f64 * dz;
        (z0, z0 + dz, j as f64 * dp, (j + 1) as f64 * dp)
    }
}

/// The outcome of one test.
#[derive(Clone, Debug)]
pub struct Chi2Outcome {
    pub chi2: f64,
    pub dof: usize,
    pub p_value: f64,
    /// ∫ pdf over the grid (the rest is the expected share of rejected samples).
    pub integral: f64,
    /// Samples the sampler rejected (`None`).
    pub rejected: usize,
    /// Samples that fell in a cell whose integrated density is 0.
    pub in_empty_cells: usize,
}

/// 1D adaptive Simpson on [a, b].
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, eps: f64, depth: u32) -> f64 {
    /// One panel: its ends (x, f(x)), the value at its midpoint, and its Simpson estimate.
    fn rec(
        f: &dyn Fn(f64) -> f64,
        (a, fa): (f64, f64),
        (b, fb): (f64, f64),
        fm: f64,
        whole: f64,
        eps: f64,
        depth: u32,
    ) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (f(lm), f(rm));
        let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
        let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
        let delta = left + right - whole;
        if depth == 0 || delta.abs() <= 15.0 * eps {
            return left + right + delta / 15.0;
        }
        rec(f, (a, fa), (m, fm), flm, left, 0.5 * eps, depth - 1)
            + rec(f, (m, fm), (b, fb), frm, right, 0.5 * eps, depth - 1)
    }
    // Start from 4 panels so that a narrow peak is not missed by the first estimate.
    let n = 4;
    let h = (b - a) / n as f64;
    (0..n)
        .map(|k| {
            let (x0, x1) = (a + k as f64 * h, a + (k + 1) as f64 * h);
            let xm = 0.5 * (x0 + x1);
            let (f0, fm, f1) = (f(x0), f(xm), f(x1));
            let whole = (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1);
            rec(f, (x0, f0), (x1, f1), fm, whole, eps / n as f64, depth)
        })
        .sum()
}

/// ∫ pdf dω over a cell: dω = d(cos θ) dφ.
pub fn integrate_cell(pdf: &dyn Fn(Vec3) -> f64, b: (f64, f64, f64, f64), eps: f64) -> f64 {
    let (z0, z1, p0, p1) = b;
    let inner = |z: f64| {
        let s = (1.0 - z * z).max(0.0).sqrt();
        let g = |phi: f64| {
            let d = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
            pdf(d)
        };
        simpson(&g, p0, p1, eps / (z1 - z0), 8)
    };
    simpson(&inner, z0, z1, eps, 8)
}

/// Draws `n_samples` directions from `sample` (`None` = rejected sample), bins them on `grid`,
/// and compares with the expected counts from `pdf` (sr⁻¹). Cells expecting fewer than 5
/// samples are pooled; the expected number of rejected samples, n·(1 − ∫pdf), is one more
/// category.
pub fn chi2_test(
    grid: Grid,
    n_samples: usize,
    mut sample: impl FnMut() -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64,
) -> Chi2Outcome {
    let cells = grid.cells();
    let mut observed = vec![0u64; cells + 1]; // last: rejected or off-grid
    for _ in 0..n_samples {
        match sample().and_then(|d| grid.cell(d)) {
            Some(c) => observed[c] += 1,
            None => observed[cells] += 1,
        }
    }
    let mut expected = vec![0.0f64; cells + 1];
    for (c, e) in expected.iter_mut().enumerate().take(cells) {
        // Tolerance: an error of at most ~0.01 expected samples per cell.
        *e = integrate_cell(&pdf, grid.bounds(c), 0.01 / n_samples as f64) * n_samples as f64;
    }
    let integral = expected[..cells].iter().sum::<f64>() / n_samples as f64;
    expected[cells] = (1.0 - integral).max(0.0) * n_samples as f64;

    let in_empty_cells = (0..cells)
        .filter(|&c| expected[c] == 0.0)
        .map(|c| observed[c] as usize)
        .sum();

    // Pool the sparse cells; a pool still below 5 joins the smallest regular cell.
    let mut kept: Vec<(f64, f64)> = Vec::new();
    let (mut pool_o, mut pool_e) = (0.0f64, 0.0f64);
    for c in 0..=cells {
        let (o, e) = (observed[c] as f64, expected[c]);
        if e < 5.0 {
            pool_o += o;
            pool_e += e;
        } else {
            kept.push((o, e));
        }
    }
    let mut chi2 = 0.0;
    if pool_e == 0.0 && pool_o > 0.0 {
        chi2 = f64::INFINITY; // samples where the density integrates to 0
    } else if pool_e >= 5.0 || kept.is_empty() {
        kept.push((pool_o, pool_e));
    } else if pool_e > 0.0 {
        let smallest = (0..kept.len())
            .min_by(|&a, &b| kept[a].1.total_cmp(&kept[b].1))
            .unwrap();
        kept[smallest].0 += pool_o;
        kept[smallest].1 += pool_e;
    }
    let k = kept.len();
    chi2 += kept
        .iter()
        .map(|&(o, e)| (o - e) * (o - e) / e)
        .sum::<f64>();
    let dof = k.saturating_sub(1).max(1);
    let p_value = if chi2.is_finite() {
        gamma_q(0.5 * dof as f64, 0.5 * chi2)
    } else {
        0.0
    };
    Chi2Outcome {
        chi2,
        dof,
        p_value,
        integral,
        rejected: observed[cells] as usize,
        in_empty_cells,
    }
}

/// Per-test significance for `m` tests at family-wise level `alpha` (Šidák correction).
pub fn sidak(alpha: f64, m: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / m as f64)
}

/// ln Γ(x) for x > 0 (Lanczos approximation, g = 7, 9 terms; relative error ~1e-15).
pub fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Γ(x)Γ(1 − x) = π / sin(πx).
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, &c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularised upper incomplete gamma Q(a, x) = Γ(a, x)/Γ(a): the χ² survival function is
/// Q(dof/2, χ²/2). Series for x < a + 1, continued fraction (modified Lentz) otherwise.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    assert!(a > 0.0 && x >= 0.0, "gamma_q({a}, {x})");
    if x == 0.0 {
        return 1.0;
    }
    let log_prefactor = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        // P(a, x) = x^a e^{−x} / Γ(a+1) · Σ_n x^n / ((a+1)…(a+n))
        let (mut term, mut sum, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        (1.0 - sum * log_prefactor.exp()).max(0.0)
    } else {
        // Q(a, x) = x^a e^{−x}/Γ(a) · 1/(x + 1 − a − 1·(1 − a)/(x + 3 − a − 2(2 − a)/(x + 5 − a − …)))
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (log_prefactor.exp() * h).clamp(0.0, 1.0)
    }
}
