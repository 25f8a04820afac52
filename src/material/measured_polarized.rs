//! Mitsuba 3's `measured_polarized` (src/bsdfs/measured_polarized.cpp, 3.9.1): a measured
//! polarimetric BRDF (the pBRDF data of Baek et al. 2020, "Image-Based Acquisition and
//! Modeling of Polarimetric Reflectance"), a table of Mueller matrices on Rusinkiewicz's
//! half/difference angles, read from a `.pbsdf` file (`loader::mitsuba::tensor`).
//!
//! For the light direction ω_L and the view direction ω_V (local, both above the surface):
//! h = (ω_L + ω_V)/|…|, θ_h = acos h_z, θ_d = acos(h·ω_L), and φ_d the azimuth of ω_L about h
//! in the frame b = z × h, t = b × h (Rusinkiewicz 1998), in [−π, π]. The table is
//! interpolated multilinearly in (φ_d, θ_d, θ_h, λ), each coordinate clamped to its grid's ends
//! (no wrapping of φ_d, as Mitsuba). f = max(0, M₀₀) in sr⁻¹ without the cosine (the table
//! holds the BRDF); a NaN M₀₀ (the data's invalid configurations) is 0. In radiance transport
//! the light is `wi`, in importance transport `wo` (the data need not be reciprocal).
//!
//! Sampling, as Mitsuba: with probability 0.1 the cosine-weighted hemisphere, else the GGX
//! visible normals of roughness `alpha_sample` seen from `wo`, reflected; the pdf (sr⁻¹ of
//! `wi`) is the mixture. The Mueller matrix (`polarised.rs`) acts in the basis s = ω_L × ω_V
//! on both beams.

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::Polarising;
use super::fresnel::reflect;
use super::microfacet::Ggx;
use super::{BsdfSample, TransportMode};
use crate::geometry::Frame;
use crate::polarisation::Mueller;
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// The probability of sampling the cosine-weighted hemisphere (Mitsuba's
/// `COSINE_HEMISPHERE_PDF_WEIGHT`).
const COSINE_WEIGHT: f32 = 0.1;

/// A measured pBRDF (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct MeasuredPolarized {
    /// Grid of φ_d, θ_d, θ_h (radians, strictly increasing) and of wavelengths (nm).
    pub phi_d: Vec<f32>,
    pub theta_d: Vec<f32>,
    pub theta_h: Vec<f32>,
    pub wavelengths: Vec<f32>,
    /// Mueller matrices of the BRDF (sr⁻¹), φ_d × θ_d × θ_h × λ × 4 × 4 in C order.
    pub m: Arc<Vec<f32>>,
    /// The sampling distribution (GGX, isotropic).
    pub sampling: Ggx,
    /// A wavelength (nm) used for every wavelength, or None.
    pub wavelength: Option<f32>,
}

/// Where a query falls in the table: per coordinate (φ_d, θ_d, θ_h) the lower grid index, the
/// weight of the upper one, and the flat stride.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cell {
    base: usize,
    steps: [usize; 3],
    t: [f32; 3],
}

/// The interval of `grid` holding `x` (clamped to the ends) and the upper node's weight.
fn interval(grid: &[f32], x: f32) -> (usize, f32, bool) {
    let n = grid.len();
    if n < 2 {
        return (0, 0.0, false);
    }
    let i = grid
        .partition_point(|&g| g <= x)
        .saturating_sub(1)
        .min(n - 2);
    let t = ((x - grid[i]) / (grid[i + 1] - grid[i])).clamp(0.0, 1.0);
    (i, if t.is_nan() { 0.0 } else { t }, true)
}

/// (φ_d, θ_d, θ_h) of the light direction `l` and view direction `v` (local, unit).
pub(super) fn rusinkiewicz(l: Vec3, v: Vec3) -> Option<[f32; 3]> {
    let h = (l + v).try_normalize()?;
    let theta_h = h.z.clamp(-1.0, 1.0).acos();
    let theta_d = h.dot(l).clamp(-1.0, 1.0).acos();
    // b = z × h; at h = z (the mirror configuration, measure zero) any axis across h
    let b = Vec3::new(-h.y, h.x, 0.0).try_normalize().unwrap_or(Vec3::Y);
    let t = b.cross(h);
    let lp = l - h * h.dot(l);
    let phi_d = lp.dot(b).atan2(lp.dot(t));
    Some([phi_d, theta_d, theta_h])
}

impl MeasuredPolarized {
    /// The cell of the angles `a` (φ_d, θ_d, θ_h).
    pub(super) fn cell(&self, a: [f32; 3]) -> Cell {
        let nl = self.wavelengths.len();
        let (nh, nd) = (self.theta_h.len(), self.theta_d.len());
        let strides = [nd * nh * nl * 16, nh * nl * 16, nl * 16];
        let grids = [&self.phi_d, &self.theta_d, &self.theta_h];
        let (mut base, mut steps, mut t) = (0, [0; 3], [0.0; 3]);
        for k in 0..3 {
            let (i, w, two) = interval(grids[k], a[k]);
            base += i * strides[k];
            steps[k] = if two { strides[k] } else { 0 };
            t[k] = w;
        }
        Cell { base, steps, t }
    }

    /// The lower table index of `lambda` nm (the fixed wavelength if one is set) among the
    /// wavelengths, the upper one's weight and the step to it.
    fn lambda_at(&self, lambda: f32) -> (usize, f32, usize) {
        let (i, t, two) = interval(&self.wavelengths, self.wavelength.unwrap_or(lambda));
        (i, t, if two { 16 } else { 0 })
    }

    /// The interpolated element (r, c) = `rc` of the table in `cell` at the wavelength
    /// position `l` ([`MeasuredPolarized::lambda_at`]).
    fn element(&self, cell: &Cell, (il, tl, step_l): (usize, f32, usize), rc: usize) -> f32 {
        let mut v = 0.0;
        for corner in 0..16u32 {
            let mut wgt = 1.0;
            let mut at = cell.base + il * 16 + rc;
            for k in 0..3 {
                if corner & (1 << k) != 0 {
                    wgt *= cell.t[k];
                    at += cell.steps[k];
                } else {
                    wgt *= 1.0 - cell.t[k];
                }
            }
            if corner & 8 != 0 {
                wgt *= tl;
                at += step_l;
            } else {
                wgt *= 1.0 - tl;
            }
            if wgt != 0.0 {
                v += wgt * self.m[at];
            }
        }
        v
    }

    /// The interpolated Mueller matrix (sr⁻¹, in the table's s basis) in `cell` at `lambda`.
    pub(super) fn matrix(&self, cell: &Cell, lambda: f32) -> Mueller {
        let l = self.lambda_at(lambda);
        Mueller(std::array::from_fn(|r| {
            std::array::from_fn(|c| self.element(cell, l, 4 * r + c))
        }))
    }

    /// f(wo, wi) per wavelength, sr⁻¹ without the cosine: max(0, M₀₀), 0 where NaN.
    pub fn eval<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> SampledSpectrum<N> {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return SampledSpectrum::zero();
        }
        let (l, v) = match mode {
            TransportMode::Radiance => (wi, wo),
            TransportMode::Importance => (wo, wi),
        };
        let Some(a) = rusinkiewicz(l, v) else {
            return SampledSpectrum::zero();
        };
        let cell = self.cell(a);
        SampledSpectrum(std::array::from_fn(|j| {
            let f = self.element(&cell, self.lambda_at(w.lambda[j]), 0);
            if f > 0.0 { f } else { 0.0 }
        }))
    }

    /// Density (sr⁻¹ of `wi`) of [`MeasuredPolarized::sample`] from `wo`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let cosine = COSINE_WEIGHT * cosine_hemisphere_pdf(wi.z);
        let Some(h) = (wo + wi).try_normalize() else {
            return cosine;
        };
        let d = wi.dot(h);
        let glossy = if d > 0.0 {
            self.sampling.visible_normal_pdf(wo, h) / (4.0 * d)
        } else {
            0.0
        };
        cosine + (1.0 - COSINE_WEIGHT) * glossy
    }

    /// Samples `wi` from `wo` (see the module doc) with the lobe choice `uc` and direction
    /// sample `u`; None below the surface.
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        uc: f32,
        u: Vec2,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = if uc < COSINE_WEIGHT {
            cosine_hemisphere(u)
        } else {
            reflect(wo, self.sampling.sample_visible_normal(wo, u))
        };
        let pdf = self.pdf(wo, wi);
        if !(pdf > 0.0) || wi.z <= 0.0 {
            return None;
        }
        Some(BsdfSample::reflection(self.eval(wo, wi, w, mode), wi, pdf))
    }

    /// The normalised Mueller matrix (`polarised.rs`): the interpolated table
    /// at each wavelength, in the basis s = ω_L × ω_V of both beams (light arriving from `wi`,
    /// seen from `wo`), normalised; depolarising where M₀₀ is not positive or any element is not
    /// finite (the data's invalid configurations).
    pub(super) fn mueller<const N: usize>(
        &self,
        frame: &Frame,
        (wo, wi): (Vec3, Vec3),
        w: &SampledWavelengths<N>,
    ) -> Polarising<N> {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Polarising::Depolarise;
        }
        let Some(a) = rusinkiewicz(wi, wo) else {
            return Polarising::Depolarise;
        };
        let cell = self.cell(a);
        let s = wi
            .cross(wo)
            .try_normalize()
            .unwrap_or_else(|| Frame::from_normal(wo).s);
        let mut out = [Mueller::IDENTITY; N];
        for (j, o) in out.iter_mut().enumerate() {
            let mj = self.matrix(&cell, w.lambda[j]);
            let a = mj.0[0][0];
            if !(a > 0.0) || mj.0.iter().flatten().any(|v| !v.is_finite()) {
                return Polarising::Depolarise;
            }
            *o = super::polarised::to_world(frame, &mj.scale(1.0 / a), wo, wi, s, s);
        }
        Polarising::Matrix(out)
    }
}
