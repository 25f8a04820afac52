//! The optimiser that builds the RGB → spectrum coefficient table.
//!
//! Jakob & Hanika, "A Low-Dimensional Function Space for Efficient Spectral Upsampling"
//! (Computer Graphics Forum 38(2), 2019), §3–4: a reflectance is modelled as
//! s(c₀λ'² + c₁λ' + c₂) with the sigmoid s(x) = ½ + x / (2√(1+x²)) and λ' the wavelength mapped
//! to [0, 1] over 360–830 nm. For a target linear RGB the coefficients minimise the CIELAB
//! distance between the target and the reflectance's colour under the space's white illuminant,
//! found by Gauss–Newton iteration (§4.1). The table samples RGB as (max component, two ratios)
//! and is filled by continuation from a neighbouring, already-solved entry (§4.2).

use glam::{DMat3, DVec3};

use crate::colour::cie::{CIE_MAX_NM, CIE_MIN_NM, cmf};
use crate::colour::lab::xyz_to_lab;
use crate::colour::spaces::RgbSpace;
use crate::spectrum::curve::Spectrum;

use super::{Table, sigmoid};

/// The colour-matching integrals the optimiser needs, weighted by the white illuminant.
pub struct Fitter {
    /// Normalised wavelength λ' in [0, 1] of each 1 nm sample.
    lambda_n: Vec<f64>,
    /// Trapezoid weight × (x̄, ȳ, z̄) × illuminant / (∫ȳ·illuminant), per sample.
    weighted_cmf: Vec<DVec3>,
    xyz_to_rgb: DMat3,
    rgb_to_xyz: DMat3,
    white_xyz: [f64; 3],
}

/// Result of fitting one RGB.
#[derive(Clone, Copy, Debug)]
pub struct Fit {
    /// Coefficients for the normalised wavelength λ'.
    pub coeffs: [f64; 3],
    /// Final CIELAB residual norm.
    pub residual: f64,
}

impl Fitter {
    /// Fitter for `space`, whose white is given as the illuminant spectrum `illuminant`
    /// (relative SPD).
    pub fn new(space: &RgbSpace, illuminant: &Spectrum) -> Self {
        let c = cmf();
        let n = c.len();
        let mut lambda_n = Vec::with_capacity(n);
        let mut weighted_cmf = Vec::with_capacity(n);
        let mut y_white = 0.0;
        for i in 0..n {
            let l = CIE_MIN_NM + i as f32;
            let w = if i == 0 || i == n - 1 { 0.5 } else { 1.0 };
            let [x, y, z] = c.at_index(i);
            let e = illuminant.eval(l) as f64 * w;
            weighted_cmf.push(DVec3::new(x as f64, y as f64, z as f64) * e);
            y_white += y as f64 * e;
            lambda_n.push((l - CIE_MIN_NM) as f64 / (CIE_MAX_NM - CIE_MIN_NM) as f64);
        }
        for v in &mut weighted_cmf {
            *v /= y_white;
        }
        let white: DVec3 = weighted_cmf.iter().sum();
        Self {
            lambda_n,
            weighted_cmf,
            xyz_to_rgb: space.xyz_to_rgb(),
            rgb_to_xyz: space.rgb_to_xyz(),
            white_xyz: white.to_array(),
        }
    }

    /// XYZ (white Y = 1) of the reflectance with normalised coefficients `c`.
    pub fn xyz(&self, c: [f64; 3]) -> [f64; 3] {
        let mut acc = DVec3::ZERO;
        for (l, w) in self.lambda_n.iter().zip(&self.weighted_cmf) {
            let x = (c[0] * l + c[1]) * l + c[2];
            acc += *w * sigmoid(x);
        }
        acc.to_array()
    }

    /// Linear RGB of the reflectance with normalised coefficients `c`.
    pub fn rgb(&self, c: [f64; 3]) -> [f64; 3] {
        (self.xyz_to_rgb * DVec3::from(self.xyz(c))).to_array()
    }

    fn residual(&self, c: [f64; 3], target_lab: [f64; 3]) -> DVec3 {
        let lab = xyz_to_lab(self.xyz(c), self.white_xyz);
        DVec3::from(target_lab) - DVec3::from(lab)
    }

    /// Gauss–Newton from the start `c`, at most `iters` steps, stopping when the CIELAB residual
    /// falls below 1e-6.
    pub fn fit(&self, rgb: [f64; 3], mut c: [f64; 3], iters: usize) -> Fit {
        let target_lab = xyz_to_lab(
            (self.rgb_to_xyz * DVec3::from(rgb)).to_array(),
            self.white_xyz,
        );
        let mut r = self.residual(c, target_lab);
        for _ in 0..iters {
            if r.length() < 1e-6 {
                break;
            }
            // Jacobian of the residual by central differences.
            let mut jac = [DVec3::ZERO; 3];
            for (k, col) in jac.iter_mut().enumerate() {
                let h = 1e-5;
                let (mut cp, mut cm) = (c, c);
                cp[k] += h;
                cm[k] -= h;
                *col = (self.residual(cp, target_lab) - self.residual(cm, target_lab)) / (2.0 * h);
            }
            let j = DMat3::from_cols(jac[0], jac[1], jac[2]);
            if j.determinant().abs() < 1e-30 {
                break;
            }
            let step = j.inverse() * r;
            // Damped step: halve until the residual decreases (keeps extreme colours stable).
            let mut t = 1.0;
            loop {
                let cn = [c[0] - t * step.x, c[1] - t * step.y, c[2] - t * step.z];
                let rn = self.residual(cn, target_lab);
                if rn.length() < r.length() || t < 1e-4 {
                    c = cn;
                    r = rn;
                    break;
                }
                t *= 0.5;
            }
            // Very large coefficients mean the sigmoid saturates; stop growing them.
            let m = c.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if m > 300.0 {
                let s = 300.0 / m;
                c = c.map(|v| v * s);
                r = self.residual(c, target_lab);
            }
        }
        Fit {
            coeffs: c,
            residual: r.length(),
        }
    }
}

/// The z (max-component) nodes: smoothstep(smoothstep(k/(res−1))), denser near 0 and 1.
pub fn z_nodes(res: usize) -> Vec<f32> {
    let ss = |x: f64| x * x * (3.0 - 2.0 * x);
    (0..res)
        .map(|k| ss(ss(k as f64 / (res - 1) as f64)) as f32)
        .collect()
}

/// Builds the full table at resolution `res` on `threads` threads.
pub fn build_table(fitter: &Fitter, res: usize, threads: usize) -> Table {
    let z = z_nodes(res);
    let mut coeffs = vec![[0.0f32; 3]; 3 * res * res * res];
    // One work item per (max component l, y index j): a column over z and x.
    let jobs: Vec<(usize, usize)> = (0..3).flat_map(|l| (0..res).map(move |j| (l, j))).collect();
    let chunk = jobs.len().div_ceil(threads.max(1));
    let results: Vec<Vec<(usize, [f32; 3])>> = std::thread::scope(|s| {
        let handles: Vec<_> = jobs
            .chunks(chunk)
            .map(|part| {
                let z = &z;
                s.spawn(move || {
                    let mut out = Vec::new();
                    for &(l, j) in part {
                        for i in 0..res {
                            solve_column(fitter, res, z, l, j, i, &mut out);
                        }
                    }
                    out
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_default())
            .collect()
    });
    for (idx, c) in results.into_iter().flatten() {
        coeffs[idx] = c;
    }
    Table {
        res,
        z_nodes: z,
        coeffs,
    }
}

/// Solves all z entries for fixed (l, j, i), starting at z index res/5 and continuing outward.
fn solve_column(
    fitter: &Fitter,
    res: usize,
    z: &[f32],
    l: usize,
    j: usize,
    i: usize,
    out: &mut Vec<(usize, [f32; 3])>,
) {
    let x = i as f64 / (res - 1) as f64;
    let y = j as f64 / (res - 1) as f64;
    let start = res / 5;
    let mut solve = |k: usize, c: [f64; 3]| {
        let zk = z[k] as f64;
        let mut rgb = [0.0; 3];
        rgb[l] = zk;
        rgb[(l + 1) % 3] = x * zk;
        rgb[(l + 2) % 3] = y * zk;
        let fit = fitter.fit(rgb, c, 30);
        let idx = ((l * res + k) * res + j) * res + i;
        out.push((idx, fit.coeffs.map(|v| v as f32)));
        fit.coeffs
    };
    let mut c = [0.0; 3];
    let mut c_start = None;
    for k in start..res {
        c = solve(k, c);
        c_start.get_or_insert(c);
    }
    let mut c = c_start.unwrap_or([0.0; 3]);
    for k in (0..start).rev() {
        c = solve(k, c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_nodes_span_unit_interval() {
        let z = z_nodes(16);
        assert_eq!((z[0], z[15]), (0.0, 1.0));
        assert!(z.windows(2).all(|w| w[1] > w[0]));
    }
}
