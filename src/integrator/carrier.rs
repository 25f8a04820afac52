//! What a camera path carries from vertex to vertex: the path tracer (`path.rs`) is generic
//! over it and monomorphised for each, so the unpolarised loop stays as it was and the
//! polarised one adds only its matrix products (issue 28).
//!
//! - [`SampledSpectrum`]: the throughput per wavelength (dimensionless), radiance summed.
//! - [`Polarised`]: a Mueller matrix per wavelength (dimensionless), mapping the Stokes vector
//!   of light arriving at the current vertex (in the implicit basis of its direction,
//!   [`crate::polarisation::stokes_basis`]) to the one reaching the camera (in the implicit
//!   basis of −camera ray); Stokes vectors summed. Emitters are unpolarised, so each emission
//!   adds the first column of the throughput times its radiance.
//!
//! The scalar weights (f·|cos θ|/pdf, MIS weights, roulette) are the unpolarised estimator's;
//! a scattering event multiplies them by its normalised Mueller matrix
//! ([`crate::material::Polarising`], P₀₀ = 1).

use glam::Vec3;

use super::Integrator;
use super::Shading;
use crate::material::Polarising;
use crate::polarisation::{Mueller, Stokes, rotate_stokes_basis, stokes_basis};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A path's throughput: see the module doc.
pub(super) trait Carrier<const N: usize>: Copy {
    /// What the path sums: radiance (W·m⁻²·sr⁻¹·nm⁻¹) or Stokes vectors in that unit.
    type Sum: Copy;
    /// The throughput of a camera ray: 1, or identity matrices.
    fn one() -> Self;
    /// Nothing summed yet.
    fn zero_sum() -> Self::Sum;
    /// Adds the throughput times unpolarised light `l` (per wavelength) arriving here.
    fn add_unpolarised(&self, sum: &mut Self::Sum, l: SampledSpectrum<N>);
    /// Adds the throughput times the scattering event at `sh` (light arriving along −`wi`,
    /// leaving along `wo`, local) times unpolarised light `l`: next-event estimation.
    fn add_scattered(
        &self,
        sum: &mut Self::Sum,
        sh: &Shading<'_, N>,
        dirs: (Vec3, Vec3),
        w: &SampledWavelengths<N>,
        l: SampledSpectrum<N>,
    );
    /// The throughput after the scattering event at `sh` (as above) of scalar weight `wt`
    /// (f·|cos θ|/pdf per wavelength).
    fn scattered(
        &self,
        sh: &Shading<'_, N>,
        dirs: (Vec3, Vec3),
        w: &SampledWavelengths<N>,
        wt: SampledSpectrum<N>,
    ) -> Self;
    /// The throughput for unpolarised light, per wavelength: Russian roulette's measure.
    fn scalar(&self) -> SampledSpectrum<N>;
    /// The throughput divided by `x` (a roulette survival probability).
    fn divided(&self, x: f32) -> Self;
}

impl<const N: usize> Carrier<N> for SampledSpectrum<N> {
    type Sum = SampledSpectrum<N>;

    #[inline(always)]
    fn one() -> Self {
        SampledSpectrum::splat(1.0)
    }
    #[inline(always)]
    fn zero_sum() -> Self::Sum {
        SampledSpectrum::zero()
    }
    #[inline(always)]
    fn add_unpolarised(&self, sum: &mut Self::Sum, l: SampledSpectrum<N>) {
        *sum += *self * l;
    }
    #[inline(always)]
    fn add_scattered(
        &self,
        sum: &mut Self::Sum,
        _: &Shading<'_, N>,
        _: (Vec3, Vec3),
        _: &SampledWavelengths<N>,
        l: SampledSpectrum<N>,
    ) {
        *sum += *self * l;
    }
    #[inline(always)]
    fn scattered(
        &self,
        _: &Shading<'_, N>,
        _: (Vec3, Vec3),
        _: &SampledWavelengths<N>,
        wt: SampledSpectrum<N>,
    ) -> Self {
        *self * wt
    }
    #[inline(always)]
    fn scalar(&self) -> SampledSpectrum<N> {
        *self
    }
    #[inline(always)]
    fn divided(&self, x: f32) -> Self {
        *self / x
    }
}

/// A polarised path's throughput: a Mueller matrix per wavelength (see the module doc).
#[derive(Clone, Copy, Debug)]
pub(super) struct Polarised<const N: usize>(pub [Mueller; N]);

impl<const N: usize> Carrier<N> for Polarised<N> {
    type Sum = [Stokes; N];

    #[inline]
    fn one() -> Self {
        Polarised([Mueller::IDENTITY; N])
    }
    #[inline]
    fn zero_sum() -> Self::Sum {
        [Stokes([0.0; 4]); N]
    }
    #[inline]
    fn add_unpolarised(&self, sum: &mut Self::Sum, l: SampledSpectrum<N>) {
        for (j, s) in sum.iter_mut().enumerate() {
            let m = &self.0[j].0;
            for (k, v) in s.0.iter_mut().enumerate() {
                *v += m[k][0] * l[j];
            }
        }
    }
    #[inline]
    fn add_scattered(
        &self,
        sum: &mut Self::Sum,
        sh: &Shading<'_, N>,
        dirs: (Vec3, Vec3),
        w: &SampledWavelengths<N>,
        l: SampledSpectrum<N>,
    ) {
        let p = match sh.bsdf.mueller(&sh.frame, dirs.0, dirs.1, w) {
            Polarising::Depolarise | Polarising::Keep => return self.add_unpolarised(sum, l),
            Polarising::Matrix(p) => p,
        };
        // only the first column of the throughput times P: P's first column, transformed
        for (j, s) in sum.iter_mut().enumerate() {
            let col = Stokes(std::array::from_fn(|k| p[j].0[k][0] * l[j]));
            let t = self.0[j] * col;
            for (v, x) in s.0.iter_mut().zip(t.0) {
                *v += x;
            }
        }
    }
    #[inline]
    fn scattered(
        &self,
        sh: &Shading<'_, N>,
        dirs: (Vec3, Vec3),
        w: &SampledWavelengths<N>,
        wt: SampledSpectrum<N>,
    ) -> Self {
        let mut out = *self;
        match sh.bsdf.mueller(&sh.frame, dirs.0, dirs.1, w) {
            Polarising::Keep => {}
            // light leaves unpolarised: only the first column stays
            Polarising::Depolarise => {
                for m in &mut out.0 {
                    for row in &mut m.0 {
                        row[1] = 0.0;
                        row[2] = 0.0;
                        row[3] = 0.0;
                    }
                }
            }
            Polarising::Matrix(p) => {
                for (m, pj) in out.0.iter_mut().zip(p) {
                    *m = *m * pj;
                }
            }
        }
        for (m, &x) in out.0.iter_mut().zip(wt.0.iter()) {
            *m = m.scale(x);
        }
        out
    }
    #[inline]
    fn scalar(&self) -> SampledSpectrum<N> {
        SampledSpectrum(std::array::from_fn(|j| self.0[j].0[0][0]))
    }
    #[inline]
    fn divided(&self, x: f32) -> Self {
        Polarised(self.0.map(|m| m.scale(1.0 / x)))
    }
}

/// The Stokes vectors `st` (per wavelength, in the implicit basis of light arriving at `sh`
/// along −`wi`) after the scattering event at `sh` that sends it along `wo` (both local),
/// times its normalised Mueller matrix (P₀₀ = 1; the scalar weight is the caller's): the
/// light subpaths' and particles' counterpart of [`Carrier::scattered`].
#[inline]
pub(super) fn scatter_stokes<const N: usize>(
    sh: &Shading<'_, N>,
    (wo, wi): (Vec3, Vec3),
    w: &SampledWavelengths<N>,
    st: &[Stokes; N],
) -> [Stokes; N] {
    match sh.bsdf.mueller(&sh.frame, wo, wi, w) {
        Polarising::Keep => *st,
        Polarising::Depolarise => st.map(|v| Stokes::unpolarised(v.0[0])),
        Polarising::Matrix(p) => std::array::from_fn(|j| p[j] * st[j]),
    }
}

/// Stokes vectors `st` (per wavelength, W·m⁻²·sr⁻¹·nm⁻¹) of light reaching the camera
/// travelling along −`d`, in its implicit basis, re-expressed in the camera's frame for the
/// camera ray direction `d` (the basis vector `d × up`, see [`super::path::stokes`]) and
/// returned as S0…S3 spectra.
pub(super) fn to_camera_frame<const N: usize>(
    it: &Integrator<'_>,
    d: Vec3,
    st: &[Stokes; N],
) -> [SampledSpectrum<N>; 4] {
    let d = d.normalize();
    let target = d.cross(it.scene.camera.up()).try_normalize();
    let r = target.map(|t| rotate_stokes_basis(-d, stokes_basis(-d), t));
    let mut out = [SampledSpectrum::<N>::zero(); 4];
    for (j, v) in st.iter().enumerate() {
        let v: Stokes = match &r {
            Some(r) => *r * *v,
            None => *v,
        };
        for (k, o) in out.iter_mut().enumerate() {
            o[j] = v.0[k];
        }
    }
    out
}
