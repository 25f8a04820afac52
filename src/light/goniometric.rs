//! A goniometric light: a point emitting a measured type C intensity distribution (an IES
//! LM-63 or EULUMDAT luminaire), I(λ, ω) = S(λ)·I_v(γ, C).
//!
//! - `S` is the spectral intensity per candela, W·sr⁻¹·nm⁻¹ per cd (the emission spectrum
//!   divided by its K_m ∫ S ȳ dλ, times the tilt factor and any scale), set by the build step.
//! - `I_v(γ, C)` is the file's table in cd, bilinear in the vertical angle γ (0° nadir, 180°
//!   zenith) and the horizontal angle C, so it is continuous and exact at every measured angle;
//!   the file's symmetry folds C into the stored planes; outside the stored γ range it is 0.
//! - Photometric frame: local −z is nadir, +x is C = 0°, +y is C = 90° (C counterclockwise
//!   seen from above, +z).
//!
//! Emission sampling (`sample_le`) is proportional to a conservative bound of I_v: the sphere
//! is cut into 256 × 512 cells of equal solid angle (uniform in cos γ and C), each weighted by
//! the maximum of I_v over the cell (exact: the table is piecewise bilinear, so the maximum is
//! at a corner of a piece, and every piece corner inside the cell is a candidate), and a
//! direction is uniform in solid angle within its cell. The bound is positive wherever I_v is,
//! so the estimator is unbiased; the weights follow I_v to within its variation over a cell.

use super::bounds::LightBounds;
use glam::{Mat3, Vec2, Vec3};

use super::distribution2d::Distribution2D;
use super::{EmissionPdf, EmissionSample, LightSample};
use crate::spectrum::{SampledWavelengths, Spectrum};

const ROWS: usize = 256;
const COLS: usize = 512;

/// How the stored horizontal angles extend to the full circle (see
/// `loader::photometric::Symmetry`, of which this is the render-side copy).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fold {
    /// One plane.
    Axial,
    /// 0–90° mirrored into four quadrants.
    Quadrant,
    /// 0–180° mirrored about the C0–C180 plane.
    Bilateral0To180,
    /// 90–270° mirrored about the C90–C270 plane.
    Bilateral90To270,
    /// The whole circle, wrapping from the last angle to the first + 360°.
    Full,
}

impl Fold {
    /// `c` in [0, 360) deg folded into the stored range.
    #[inline]
    fn apply(self, c: f32) -> f32 {
        match self {
            Fold::Axial | Fold::Full => c,
            Fold::Quadrant => {
                let c = if c > 180.0 { 360.0 - c } else { c };
                if c > 90.0 { 180.0 - c } else { c }
            }
            Fold::Bilateral0To180 => {
                if c > 180.0 {
                    360.0 - c
                } else {
                    c
                }
            }
            Fold::Bilateral90To270 => {
                if c < 90.0 {
                    180.0 - c
                } else if c > 270.0 {
                    540.0 - c
                } else {
                    c
                }
            }
        }
    }
}

/// A type C candela table in plain `f32` (degrees and cd).
#[derive(Clone, Debug)]
pub struct IntensityTable {
    /// Vertical angles γ, deg, ascending in [0, 180].
    pub vertical: Vec<f32>,
    /// Stored horizontal angles C, deg, ascending.
    pub horizontal: Vec<f32>,
    pub fold: Fold,
    /// Luminous intensity, cd, `cd[h * vertical.len() + v]`.
    pub cd: Vec<f32>,
}

/// The segment of ascending `xs` holding `x` and the fraction along it; `x` within the range.
#[inline]
fn segment(xs: &[f32], x: f32) -> (usize, f32) {
    if xs.len() == 1 {
        return (0, 0.0);
    }
    let i = xs.partition_point(|&a| a <= x).clamp(1, xs.len() - 1) - 1;
    let f = ((x - xs[i]) / (xs[i + 1] - xs[i])).clamp(0.0, 1.0);
    (i, f)
}

impl IntensityTable {
    /// I_v at vertical angle `gamma` and horizontal angle `c` (deg, c in [0, 360)), cd.
    pub fn eval(&self, gamma: f32, c: f32) -> f32 {
        let v = &self.vertical;
        if gamma < v[0] || gamma > v[v.len() - 1] {
            return 0.0;
        }
        let (j, tv) = segment(v, gamma);
        let j1 = (j + 1).min(v.len() - 1);
        let nv = v.len();
        let h = &self.horizontal;
        let c = self.fold.apply(c);
        let (i, i1, th) = if h.len() == 1 || self.fold == Fold::Axial {
            (0, 0, 0.0)
        } else if self.fold == Fold::Full && (c >= h[h.len() - 1] || c < h[0]) {
            // the wrap from the last stored angle to the first + 360°
            let last = h[h.len() - 1];
            let span = h[0] + 360.0 - last;
            let x = if c >= last {
                c - last
            } else {
                c + 360.0 - last
            };
            (h.len() - 1, 0, (x / span).clamp(0.0, 1.0))
        } else {
            let (i, t) = segment(h, c.clamp(h[0], h[h.len() - 1]));
            (i, (i + 1).min(h.len() - 1), t)
        };
        let at = |hi: usize, vi: usize| self.cd[hi * nv + vi];
        let lo = at(i, j) * (1.0 - tv) + at(i, j1) * tv;
        let hi = at(i1, j) * (1.0 - tv) + at(i1, j1) * tv;
        lo * (1.0 - th) + hi * th
    }

    /// ∫ I_v dω over the sphere, cd·sr = lm: exact for the piecewise-bilinear table (linear in
    /// C, so each stored cell averages its two planes; then ∫ (p + qγ) sin γ dγ in closed form),
    /// times the copies the symmetry makes.
    pub fn luminous_flux(&self) -> f64 {
        let v: Vec<f64> = self
            .vertical
            .iter()
            .map(|&x| (x as f64).to_radians())
            .collect();
        let nv = v.len();
        // ∫_{g0}^{g1} I sin γ dγ for I linear from a to b
        let strip = |a: f64, b: f64, g0: f64, g1: f64| {
            if g1 <= g0 {
                return 0.0;
            }
            let q = (b - a) / (g1 - g0);
            let p = a - q * g0;
            let prim = |g: f64| -p * g.cos() + q * (g.sin() - g * g.cos());
            prim(g1) - prim(g0)
        };
        // ∫ over γ of the plane with cd values `col` (len nv)
        let plane = |col: &dyn Fn(usize) -> f64| -> f64 {
            (0..nv.saturating_sub(1))
                .map(|j| strip(col(j), col(j + 1), v[j], v[j + 1]))
                .sum()
        };
        let cd = |h: usize, j: usize| self.cd[h * nv + j] as f64;
        let h: Vec<f64> = self
            .horizontal
            .iter()
            .map(|&x| (x as f64).to_radians())
            .collect();
        let two_pi = 2.0 * std::f64::consts::PI;
        if self.fold == Fold::Axial || h.len() == 1 {
            return two_pi * plane(&|j| cd(0, j));
        }
        let mut sum = 0.0;
        for i in 0..h.len() - 1 {
            sum += (h[i + 1] - h[i]) * plane(&|j| 0.5 * (cd(i, j) + cd(i + 1, j)));
        }
        let copies = match self.fold {
            Fold::Quadrant => 4.0,
            Fold::Bilateral0To180 | Fold::Bilateral90To270 => 2.0,
            Fold::Full | Fold::Axial => 1.0,
        };
        if self.fold == Fold::Full {
            let last = h.len() - 1;
            sum += (h[0] + two_pi - h[last]) * plane(&|j| 0.5 * (cd(last, j) + cd(0, j)));
        }
        copies * sum
    }

    /// Every C in [0, 360] where the folded table has a kink or a stored plane.
    fn breakpoints_c(&self) -> Vec<f32> {
        let mut out = vec![0.0, 90.0, 180.0, 270.0, 360.0];
        for &a in &self.horizontal {
            for c in [a, 180.0 - a, 180.0 + a, 360.0 - a, 540.0 - a] {
                let c = c.rem_euclid(360.0);
                out.push(c);
            }
        }
        out.sort_by(f32::total_cmp);
        out.dedup();
        out
    }
}

/// A point luminaire with a measured distribution (see the module doc).
#[derive(Clone, Debug)]
pub struct GoniometricLight {
    /// Position, m.
    pub position: Vec3,
    /// Columns: the photometric +x (C = 0°), +y (C = 90°) and +z (up: γ = 180°) in world space,
    /// orthonormal.
    pub frame: Mat3,
    /// Spectral intensity per candela of the table, W·sr⁻¹·nm⁻¹ per cd.
    pub spectrum: Spectrum,
    pub table: IntensityTable,
    /// Sampling of directions over (C/360°, (1 − cos γ)/2) ∈ [0, 1)².
    dist: Distribution2D,
}

impl GoniometricLight {
    /// Bounds for the light tree: an emitter at its position, of every direction
    /// (conservative: its distribution is not bounded more tightly), with `phi` the power, W,
    /// of which the tree takes 4π times the table's largest intensity
    /// ([`LightBounds::phi`]): φ · 4π·max(cd) / (the table's flux in lm-equivalent cd·sr).
    pub fn bounds(&self, phi: f32) -> LightBounds {
        // the solid angle the flux would fill at the peak intensity: flux / max(cd), sr
        let peak = self.table.cd.iter().fold(0.0f32, |m, &c| m.max(c)) as f64;
        let omega = (self.table.luminous_flux() / peak) as f32;
        LightBounds::point(self.position, LightBounds::phi_of(phi, omega))
    }

    /// None if the table is zero everywhere.
    pub fn new(
        position: Vec3,
        frame: Mat3,
        spectrum: Spectrum,
        table: IntensityTable,
    ) -> Option<Self> {
        let cs = table.breakpoints_c();
        let vs = &table.vertical;
        let mut weights = vec![0.0f32; ROWS * COLS];
        let mut gammas = Vec::new();
        let mut cvals = Vec::new();
        for r in 0..ROWS {
            let g0 = gamma_of(r as f32 / ROWS as f32);
            let g1 = gamma_of((r + 1) as f32 / ROWS as f32);
            gammas.clear();
            gammas.extend([g0, g1]);
            gammas.extend(vs.iter().copied().filter(|&g| g > g0 && g < g1));
            for c in 0..COLS {
                let c0 = 360.0 * c as f32 / COLS as f32;
                let c1 = 360.0 * (c + 1) as f32 / COLS as f32;
                cvals.clear();
                cvals.extend([c0, c1.min(359.9999)]);
                // the sorted breakpoints strictly inside the column
                let (a, b) = (
                    cs.partition_point(|&x| x <= c0),
                    cs.partition_point(|&x| x < c1),
                );
                cvals.extend_from_slice(&cs[a..b.max(a)]);
                let mut m = 0.0f32;
                for &g in &gammas {
                    for &cc in &cvals {
                        m = m.max(table.eval(g, cc));
                    }
                }
                weights[r * COLS + c] = m;
            }
        }
        let dist = Distribution2D::new(&weights, COLS, ROWS)?;
        Some(Self {
            position,
            frame,
            spectrum,
            table,
            dist,
        })
    }

    /// I_v toward `dir` (unit, world, from the light), cd.
    #[inline]
    pub fn candela(&self, dir: Vec3) -> f32 {
        let l = self.frame.transpose() * dir;
        let (gamma, c) = angles(l);
        self.table.eval(gamma, c)
    }

    /// li = S·I_v(−wi)/r², delta; None where the luminaire sends no light.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        super::point_like_sample(self.position, p, |wi| {
            let cd = self.candela(-wi);
            (cd > 0.0).then(|| self.spectrum.sample(w) * cd)
        })
    }

    /// A particle: a direction from the tabulated bound, pdf_dir = density/(4π) sr⁻¹.
    pub fn sample_le<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> EmissionSample<N> {
        let (st, density) = self.dist.sample(u);
        let cos_g = 1.0 - 2.0 * st.y;
        let sin_g = (1.0 - cos_g * cos_g).max(0.0).sqrt();
        let phi = 2.0 * std::f32::consts::PI * st.x;
        let local = Vec3::new(sin_g * phi.cos(), sin_g * phi.sin(), -cos_g);
        let d = (self.frame * local).normalize();
        let le = self.spectrum.sample(w) * self.candela(d);
        EmissionSample::from_point(
            self.position,
            d,
            le,
            density * crate::sampling::UNIFORM_SPHERE_PDF,
        )
    }

    /// Densities of [`GoniometricLight::sample_le`] for the direction `d` (unit).
    pub fn pdf_le(&self, d: Vec3) -> EmissionPdf {
        let l = self.frame.transpose() * d;
        let t = ((1.0 + l.z) * 0.5).clamp(0.0, 1.0);
        let (_, c) = angles(l);
        let col = ((c / 360.0) * COLS as f32) as usize;
        let row = (t * ROWS as f32) as usize;
        EmissionPdf {
            pos: 0.0,
            dir: self.dist.pdf_cell(col, row) * crate::sampling::UNIFORM_SPHERE_PDF,
        }
    }

    /// Band power over `band_per_cd` = ∫ S dλ (W·sr⁻¹ per cd): ∫ I_v dω × that, W.
    pub fn power(&self, band_per_cd: f64) -> f64 {
        self.table.luminous_flux() * band_per_cd
    }
}

/// γ (deg from nadir) at t = (1 − cos γ)/2.
fn gamma_of(t: f32) -> f32 {
    (1.0 - 2.0 * t).clamp(-1.0, 1.0).acos().to_degrees()
}

/// (γ, C) in degrees of a unit local direction: γ from −z, C counterclockwise from +x about +z,
/// in [0, 360).
#[inline]
fn angles(l: Vec3) -> (f32, f32) {
    let gamma = (-l.z).clamp(-1.0, 1.0).acos().to_degrees();
    let mut c = l.y.atan2(l.x).to_degrees();
    if c < 0.0 {
        c += 360.0;
    }
    if c >= 360.0 {
        c = 0.0;
    }
    (gamma, c)
}

pub mod equal_area;

#[cfg(test)]
mod tests;
