//! A piecewise-bilinear density on the unit square, optionally conditioned on up to three
//! parameters, with the marginal/conditional sample warp of Dupuy & Jakob 2018 ("An Adaptive
//! Parameterization for Efficient Material Acquisition and Rendering", §5 and its
//! supplementary code), as pbrt-v4 (`PiecewiseLinear2D`, util/sampling.h) and Mitsuba 3
//! (`Marginal2D`) implement it for measured BSDFs.
//!
//! The density is given at `nx × ny` nodes spaced evenly over [0, 1]² (x fastest), one such
//! slice per node of the parameter grid (the last parameter fastest). Between nodes it is
//! bilinear in (x, y); between parameter nodes the slices are blended linearly (each parameter
//! clamped to its grid's ends). With `normalize` each slice integrates to 1 over the square and
//! [`Warp2D::sample`] draws points with that density; without, [`Warp2D::eval`] returns the
//! values as stored (an interpolant only).

/// The parameter slices a query blends: up to 2³ slice indices and their weights.
struct Slices {
    at: [usize; 8],
    w: [f32; 8],
    n: usize,
}

/// A (conditional) piecewise-bilinear density on [0, 1]² (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Warp2D {
    nx: usize,
    ny: usize,
    /// Each parameter's grid (strictly increasing), in the order given.
    params: Vec<Vec<f32>>,
    /// Each parameter's stride in slices (0 for a one-node grid).
    strides: Vec<usize>,
    /// Node values, slice after slice (normalised if asked to).
    data: Vec<f32>,
    /// Per slice: the marginal CDF over rows (`ny`) and the conditional CDF within each row
    /// (`nx × ny`); empty for an interpolant only.
    marginal: Vec<f32>,
    conditional: Vec<f32>,
}

/// pbrt-v4's `FindInterval`: the largest i in [0, n − 2] with `pred(i)` (which must be true
/// up to some index and false after), else 0.
fn find_interval(n: usize, pred: impl Fn(usize) -> bool) -> usize {
    let (mut first, mut size) = (1usize, n.saturating_sub(2));
    while size > 0 {
        let half = size >> 1;
        let middle = first + half;
        if pred(middle) {
            first = middle + 1;
            size -= half + 1;
        } else {
            size = half;
        }
    }
    first.saturating_sub(1).min(n.saturating_sub(2))
}

/// The t in [0, 1] where the CDF of the linear density c0 + (c1 − c0)·t (unnormalised)
/// reaches `s`: the root of the quadratic, or s/mean for a near-constant density (pbrt-v4's
/// and Mitsuba's expression).
fn invert_linear(s: f32, c0: f32, c1: f32) -> f32 {
    if (c0 - c1).abs() < 1e-4 * (c0 + c1) {
        2.0 * s / (c0 + c1)
    } else {
        (c0 - (c0 * c0 - 2.0 * s * (c0 - c1)).max(0.0).sqrt()) / (c0 - c1)
    }
}

impl Warp2D {
    /// The density of `values` (`nx × ny` per slice, x fastest; slices in the order of the
    /// parameter grids `params`, the last fastest). With `normalize`, each slice is scaled to
    /// integrate to 1 and the CDFs for sampling are built. Err if a size does not match.
    pub fn new(
        values: &[f32],
        (nx, ny): (usize, usize),
        params: Vec<Vec<f32>>,
        normalize: bool,
    ) -> Result<Self, String> {
        if nx < 2 || ny < 2 {
            return Err(format!("a {nx} × {ny} table (at least 2 × 2 is needed)"));
        }
        if params.len() > 3 || params.iter().any(|p| p.is_empty()) {
            return Err("at most three parameters, each with at least one node".into());
        }
        let mut strides = vec![0; params.len()];
        let mut slices = 1;
        for (d, p) in params.iter().enumerate().rev() {
            strides[d] = if p.len() > 1 { slices } else { 0 };
            slices *= p.len();
        }
        let n = nx * ny;
        if values.len() != slices * n {
            return Err(format!(
                "{} values for {slices} slices of {nx} × {ny}",
                values.len()
            ));
        }
        let mut w = Warp2D {
            nx,
            ny,
            params,
            strides,
            data: values.to_vec(),
            marginal: Vec::new(),
            conditional: Vec::new(),
        };
        if normalize {
            w.marginal = vec![0.0; slices * ny];
            w.conditional = vec![0.0; slices * n];
            for s in 0..slices {
                w.build_cdfs(s)?;
            }
        } else {
            // stored over the patch area, as pbrt-v4 does, so that `eval` returns the values
            let patch = 1.0 / w.inv_patch();
            w.data.iter_mut().for_each(|v| *v *= patch);
        }
        Ok(w)
    }

    /// Slice `s`'s CDFs (trapezoid sums in f64) and its values scaled to integrate to 1; Err
    /// if it has a negative value or integrates to 0 (no density to sample).
    fn build_cdfs(&mut self, s: usize) -> Result<(), String> {
        let (nx, ny) = (self.nx, self.ny);
        let data = &mut self.data[s * nx * ny..(s + 1) * nx * ny];
        let cond = &mut self.conditional[s * nx * ny..(s + 1) * nx * ny];
        let marg = &mut self.marginal[s * ny..(s + 1) * ny];
        for y in 0..ny {
            let mut sum = 0.0f64;
            cond[y * nx] = 0.0;
            for x in 0..nx - 1 {
                let i = y * nx + x;
                sum += 0.5 * (data[i] as f64 + data[i + 1] as f64);
                cond[i + 1] = sum as f32;
            }
        }
        let mut sum = 0.0f64;
        marg[0] = 0.0;
        for y in 0..ny - 1 {
            sum += 0.5 * (cond[(y + 1) * nx - 1] as f64 + cond[(y + 2) * nx - 1] as f64);
            marg[y + 1] = sum as f32;
        }
        if data.iter().any(|&v| v < 0.0) || !(marg[ny - 1] > 0.0) {
            return Err(format!(
                "slice {s} is negative somewhere or zero everywhere: not a density"
            ));
        }
        let norm = 1.0 / marg[ny - 1];
        cond.iter_mut().for_each(|v| *v *= norm);
        marg.iter_mut().for_each(|v| *v *= norm);
        data.iter_mut().for_each(|v| *v *= norm);
        Ok(())
    }

    /// The slices blended at `param` and their weights (pbrt-v4's `param_weight`).
    fn slices(&self, param: &[f32]) -> Slices {
        let mut out = Slices {
            at: [0; 8],
            w: [0.0; 8],
            n: 1,
        };
        out.w[0] = 1.0;
        for (d, grid) in self.params.iter().enumerate() {
            let p = param.get(d).copied().unwrap_or(0.0);
            let (i, t) = if grid.len() == 1 {
                (0, 0.0)
            } else {
                let i = find_interval(grid.len(), |k| grid[k] <= p);
                (i, ((p - grid[i]) / (grid[i + 1] - grid[i])).clamp(0.0, 1.0))
            };
            let n = out.n;
            for k in 0..n {
                let base = out.at[k] + self.strides[d] * i;
                let wk = out.w[k];
                out.at[k] = base;
                out.w[k] = wk * (1.0 - t);
                out.at[k + n] = base + self.strides[d];
                out.w[k + n] = wk * t;
            }
            out.n = 2 * n;
        }
        out
    }

    /// `table`[i] of each blended slice (slices of `size` values), blended.
    #[inline]
    fn lookup(table: &[f32], s: &Slices, size: usize, i: usize) -> f32 {
        (0..s.n)
            .filter(|&k| s.w[k] != 0.0)
            .map(|k| s.w[k] * table[s.at[k] * size + i])
            .sum()
    }

    /// 1/(patch width × patch height): the factor from stored node values to densities.
    fn inv_patch(&self) -> f32 {
        ((self.nx - 1) * (self.ny - 1)) as f32
    }

    /// The density (or, without normalisation, the interpolated value) at `pos` ∈ [0, 1]².
    pub fn eval(&self, pos: [f32; 2], param: &[f32]) -> f32 {
        let s = self.slices(param);
        let (nx, ny) = (self.nx, self.ny);
        let x = pos[0].max(0.0) * (nx - 1) as f32;
        let y = pos[1].max(0.0) * (ny - 1) as f32;
        let (ix, iy) = ((x as usize).min(nx - 2), (y as usize).min(ny - 2));
        let (wx, wy) = (x - ix as f32, y - iy as f32);
        let i = ix + iy * nx;
        let size = nx * ny;
        let v = |o: usize| Self::lookup(&self.data, &s, size, i + o);
        let (v00, v10, v01, v11) = (v(0), v(1), v(nx), v(nx + 1));
        let row0 = (1.0 - wx) * v00 + wx * v10;
        let row1 = (1.0 - wx) * v01 + wx * v11;
        ((1.0 - wy) * row0 + wy * row1) * self.inv_patch()
    }

    /// A point of [0, 1]² drawn with the density at `param` from the uniform `u`, and its
    /// density (pbrt-v4's `Sample`): the row from the marginal, then the column in it.
    /// Needs `normalize`.
    pub fn sample(&self, u: [f32; 2], param: &[f32]) -> ([f32; 2], f32) {
        const ONE_MINUS_EPS: f32 = 1.0 - f32::EPSILON / 2.0;
        let mut sx = u[0].clamp(1.0 - ONE_MINUS_EPS, ONE_MINUS_EPS);
        let mut sy = u[1].clamp(1.0 - ONE_MINUS_EPS, ONE_MINUS_EPS);
        let s = self.slices(param);
        let (nx, ny) = (self.nx, self.ny);
        let size = nx * ny;
        let marg = |i: usize| Self::lookup(&self.marginal, &s, ny, i);
        let row = find_interval(ny, |i| marg(i) < sy);
        sy -= marg(row);
        let off = row * nx;
        let cond = |i: usize| Self::lookup(&self.conditional, &s, size, i);
        let (r0, r1) = (cond(off + nx - 1), cond(off + 2 * nx - 1));
        sy = invert_linear(sy, r0, r1);
        sx *= (1.0 - sy) * r0 + sy * r1;
        let cond_at = |i: usize| (1.0 - sy) * cond(off + i) + sy * cond(off + nx + i);
        let col = find_interval(nx, |i| cond_at(i) < sx);
        sx -= cond_at(col);
        let i = off + col;
        let v = |o: usize| Self::lookup(&self.data, &s, size, i + o);
        let c0 = (1.0 - sy) * v(0) + sy * v(nx);
        let c1 = (1.0 - sy) * v(1) + sy * v(nx + 1);
        sx = invert_linear(sx, c0, c1);
        let p = [
            (col as f32 + sx) / (nx - 1) as f32,
            (row as f32 + sy) / (ny - 1) as f32,
        ];
        (p, ((1.0 - sx) * c0 + sx * c1) * self.inv_patch())
    }

    /// The uniform sample [`Warp2D::sample`] maps to `p`, and the density at `p` (pbrt-v4's
    /// `Invert`). Needs `normalize`.
    pub fn invert(&self, p: [f32; 2], param: &[f32]) -> ([f32; 2], f32) {
        let s = self.slices(param);
        let (nx, ny) = (self.nx, self.ny);
        let size = nx * ny;
        let x = p[0].max(0.0) * (nx - 1) as f32;
        let y = p[1].max(0.0) * (ny - 1) as f32;
        let (ix, iy) = ((x as usize).min(nx - 2), (y as usize).min(ny - 2));
        let (mut sx, mut sy) = (x - ix as f32, y - iy as f32);
        let i = ix + iy * nx;
        let v = |o: usize| Self::lookup(&self.data, &s, size, i + o);
        let c0 = (1.0 - sy) * v(0) + sy * v(nx);
        let c1 = (1.0 - sy) * v(1) + sy * v(nx + 1);
        let pdf = (1.0 - sx) * c0 + sx * c1;
        sx *= c0 + 0.5 * sx * (c1 - c0);
        let cond = |i: usize| Self::lookup(&self.conditional, &s, size, i);
        sx += (1.0 - sy) * cond(i) + sy * cond(i + nx);
        let off = iy * nx;
        let (r0, r1) = (cond(off + nx - 1), cond(off + 2 * nx - 1));
        sx /= (1.0 - sy) * r0 + sy * r1;
        sy *= r0 + 0.5 * sy * (r1 - r0);
        sy += Self::lookup(&self.marginal, &s, ny, iy);
        ([sx, sy], pdf * self.inv_patch())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 5 × 4 density per slice over two parameters (3 and 2 nodes): positive, uneven.
    fn warp() -> Warp2D {
        let (nx, ny, slices) = (5, 4, 6);
        let v: Vec<f32> = (0..nx * ny * slices)
            .map(|i| 0.2 + ((i * 7919) % 13) as f32 / 5.0)
            .collect();
        Warp2D::new(
            &v,
            (nx, ny),
            vec![vec![0.0, 1.0, 3.0], vec![0.5, 2.0]],
            true,
        )
        .unwrap()
    }

    /// Sampling and inverting are inverse maps, and the density sampling reports is the one
    /// `eval` and `invert` report, also between parameter nodes.
    #[test]
    fn sample_and_invert_agree() {
        let w = warp();
        for param in [[0.0, 0.5], [0.4, 1.1], [2.9, 3.0], [-1.0, 0.7]] {
            for k in 0..50 {
                let u = [
                    (k as f32 + 0.37) / 50.0,
                    ((k * 31) % 50) as f32 / 50.0 + 0.01,
                ];
                let (p, pdf) = w.sample(u, &param);
                let (back, pdf_inv) = w.invert(p, &param);
                assert!((back[0] - u[0]).abs() < 1e-4 && (back[1] - u[1]).abs() < 1e-4);
                let e = w.eval(p, &param);
                assert!((pdf - e).abs() < 1e-4 * e && (pdf_inv - e).abs() < 1e-4 * e);
            }
        }
    }

    /// A normalised slice integrates to 1 (midpoint rule on a fine grid), between nodes too.
    #[test]
    fn normalised_density_integrates_to_one() {
        let w = warp();
        let n = 400;
        let mut sum = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let p = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                sum += w.eval(p, &[1.7, 1.2]) as f64;
            }
        }
        let integral = sum / (n * n) as f64;
        assert!((integral - 1.0).abs() < 1e-3, "{integral}");
    }

    /// A table that cannot be a density (a slice zero everywhere, or negative somewhere) and
    /// sizes that do not match are refused with the reason, not normalised into NaNs.
    #[test]
    fn tables_that_are_no_density_are_refused() {
        let zero = Warp2D::new(&[0.0; 8], (2, 2), vec![vec![1.0, 2.0]], true).unwrap_err();
        assert!(zero.contains("zero everywhere"), "{zero}");
        let neg = Warp2D::new(&[1.0, -1.0, 1.0, 1.0], (2, 2), vec![], true).unwrap_err();
        assert!(neg.contains("negative"), "{neg}");
        assert!(Warp2D::new(&[1.0; 5], (2, 2), vec![], true).is_err());
        assert!(Warp2D::new(&[1.0; 2], (1, 2), vec![], false).is_err());
    }

    /// Without normalisation the interpolant returns the stored values at the nodes and is
    /// bilinear between them, blending slices linearly in a parameter.
    #[test]
    fn interpolant_is_multilinear() {
        let v: Vec<f32> = (0..8).map(|i| i as f32).collect();
        let w = Warp2D::new(&v, (2, 2), vec![vec![10.0, 20.0]], false).unwrap();
        assert_eq!(w.eval([1.0, 0.0], &[10.0]), 1.0);
        assert_eq!(w.eval([0.0, 1.0], &[20.0]), 6.0);
        assert!((w.eval([0.5, 0.5], &[15.0]) - 3.5).abs() < 1e-6);
        // clamped to the grid's ends
        assert_eq!(w.eval([1.0, 1.0], &[99.0]), 7.0);
    }
}
