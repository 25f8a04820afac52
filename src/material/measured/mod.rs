//! A measured isotropic or anisotropic BRDF in the RGL format of Dupuy & Jakob 2018 ("An
//! Adaptive Parameterization for Efficient Material Acquisition and Rendering", TOG 37(6)),
//! evaluated and sampled as pbrt-v4's `MeasuredBxDF` (bxdfs.cpp) does; Mitsuba 3's `measured`
//! reads the same files the same way.
//!
//! Coordinates: a direction (θ, φ) maps to the unit square by u = (√(2θ/π), φ/2π + ½); for an
//! isotropic file the half vector's φ is taken relative to φ_o. The file holds
//! - `ndf` D(u_m) and `sigma` σ(u_o), the microfacet distribution and the projected area,
//!   interpolated bilinearly on u;
//! - `vndf`, the distribution of visible normals per (φ_o, θ_o), a [`Warp2D`] from a unit
//!   square of "sample" coordinates onto u_m;
//! - `luminance`, a [`Warp2D`] on the sample square (the reflectance's luminance there);
//! - `spectra`, the reflectance factor R on the sample square per (φ_o, θ_o, λ).
//!
//! f(ω_o, ω_i) = max(0, R(s, φ_o, θ_o, λ)) · D(u_m) / (4 σ(u_o) cos θ_i), sr⁻¹ without the
//! cosine, with s the sample coordinates of the half vector (`vndf` inverted). Sampling draws
//! s from `luminance`, u_m from `vndf`, and reflects ω_o about the half vector; its density in
//! sr⁻¹ of ω_i is p_lum(s) · p_vndf(u_m) / (4 (ω_o·m) · max(2π² u_m,x sin θ_m, 10⁻⁶)), the last
//! factor the Jacobian of u_m to solid angle of m (pbrt-v4's, with its floor). A file whose
//! `jacobian` flag is clear holds f·cos θ_i in R, which Mitsuba 3 reads as such
//! ([`Measured::jacobian`]). Like pbrt-v4's, f ignores the transport mode. Wavelengths
//! outside the file's range take its end values (as pbrt-v4). The surface is one-sided in
//! data but the shading frame faces the ray (a reflecting material), as pbrt-v4 flips ω_o.

mod warp;

pub use warp::Warp2D;

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::BsdfSample;
use super::fresnel::reflect;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A measured BRDF (see the module doc), its tables ready to interpolate and sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// D on (u_θ, u_φ) of the half vector (no parameters, not normalised).
    pub ndf: Warp2D,
    /// σ on (u_θ, u_φ) of ω_o (not normalised).
    pub sigma: Warp2D,
    /// Visible normals on u_m per (φ_o, θ_o) in radians (normalised).
    pub vndf: Warp2D,
    /// Luminance on the sample square per (φ_o, θ_o) (normalised).
    pub luminance: Warp2D,
    /// The reflectance factor on the sample square per (φ_o, θ_o, λ in nm).
    pub spectra: Warp2D,
    /// Whether the file is isotropic (φ of the half vector relative to φ_o).
    pub isotropic: bool,
    /// Whether R is multiplied by D/(4σ) (pbrt-v4 always; Mitsuba 3 when the file's
    /// `jacobian` flag is set); without, f = R / cos θ_i (R holds f·cos θ_i).
    pub jacobian: bool,
}

fn theta2u(theta: f32) -> f32 {
    (theta * (2.0 / PI)).max(0.0).sqrt()
}
fn phi2u(phi: f32) -> f32 {
    phi * (0.5 / PI) + 0.5
}

/// What `eval` and `pdf` share for a pair of directions (see [`Measured::half`]).
struct Half {
    /// (φ_o, θ_o), radians.
    o: (f32, f32),
    u_m: [f32; 2],
    s: [f32; 2],
    vndf_pdf: f32,
    jacobian: f32,
}

/// (θ, φ) of a unit vector, θ ∈ [0, π], φ ∈ (−π, π].
fn angles(v: Vec3) -> (f32, f32) {
    (v.z.clamp(-1.0, 1.0).acos(), v.y.atan2(v.x))
}

impl Measured {
    /// u_m of the half vector `m` seen from ω_o at azimuth `phi_o`.
    fn u_m(&self, m: Vec3, phi_o: f32) -> [f32; 2] {
        let (theta_m, phi_m) = angles(m);
        let y = phi2u(if self.isotropic { phi_m - phi_o } else { phi_m });
        [theta2u(theta_m), y - y.floor()]
    }

    /// max(0, R) per wavelength at sample coordinates `s` seen from (φ_o, θ_o), times
    /// D(u_m)/(4 σ(u_o) cos θ_i).
    fn value<const N: usize>(
        &self,
        s: [f32; 2],
        (phi_o, theta_o): (f32, f32),
        (u_m, cos_i): ([f32; 2], f32),
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let u_o = [theta2u(theta_o), phi2u(phi_o)];
        let scale = if self.jacobian {
            self.ndf.eval(u_m, &[]) / (4.0 * self.sigma.eval(u_o, &[]) * cos_i)
        } else {
            1.0 / cos_i
        };
        if !scale.is_finite() {
            return SampledSpectrum::zero();
        }
        SampledSpectrum(std::array::from_fn(|j| {
            let r = self.spectra.eval(s, &[phi_o, theta_o, w.lambda[j]]);
            r.max(0.0) * scale
        }))
    }

    /// The half vector's sample coordinates for the pair (wo, wi): (φ_o, θ_o), u_m, the sample
    /// coordinates s (`vndf` inverted) and the VNDF's density there, and the Jacobian to sr⁻¹
    /// of wi; None unless both are above the surface.
    #[inline]
    fn half(&self, wo: Vec3, wi: Vec3) -> Option<Half> {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return None;
        }
        let m = (wo + wi).try_normalize()?;
        let (theta_o, phi_o) = angles(wo);
        let u_m = self.u_m(m, phi_o);
        let (s, vndf_pdf) = self.vndf.invert(u_m, &[phi_o, theta_o]);
        let jacobian = Self::jacobian(wo, m, u_m);
        Some(Half {
            o: (phi_o, theta_o),
            u_m,
            s,
            vndf_pdf,
            jacobian,
        })
    }

    /// The density (sr⁻¹ of wi) of [`Measured::sample`] at the pair `h` describes.
    #[inline]
    fn density(&self, h: &Half) -> f32 {
        let lum_pdf = self.luminance.eval(h.s, &[h.o.0, h.o.1]);
        h.vndf_pdf * lum_pdf / h.jacobian
    }

    /// f(wo, wi) per wavelength, sr⁻¹ without the cosine; 0 unless both are above the surface.
    pub fn eval<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        self.half(wo, wi).map_or(SampledSpectrum::zero(), |h| {
            self.value(h.s, h.o, (h.u_m, wi.z), w)
        })
    }

    /// The Jacobian 4 (ω_o·m) · max(2π² u_m,x sin θ_m, 10⁻⁶) from density on u_m to density
    /// in sr⁻¹ of ω_i.
    fn jacobian(wo: Vec3, m: Vec3, u_m: [f32; 2]) -> f32 {
        let sin_m = (m.x * m.x + m.y * m.y).sqrt();
        4.0 * wo.dot(m) * (2.0 * PI * PI * u_m[0] * sin_m).max(1e-6)
    }

    /// Density (sr⁻¹ of `wi`) of [`Measured::sample`] from `wo`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.half(wo, wi).map_or(0.0, |h| self.density(&h))
    }

    /// [`Measured::eval`] and [`Measured::pdf`] together, the VNDF inverted once.
    pub fn eval_pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> (SampledSpectrum<N>, f32) {
        self.half(wo, wi)
            .map_or((SampledSpectrum::zero(), 0.0), |h| {
                (self.value(h.s, h.o, (h.u_m, wi.z), w), self.density(&h))
            })
    }

    /// Samples `wi` from `wo` with the direction sample `u` (see the module doc); None when
    /// the reflected direction is below the surface.
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        u: Vec2,
        w: &SampledWavelengths<N>,
    ) -> Option<BsdfSample<N>> {
        if wo.z <= 0.0 {
            return None;
        }
        let (theta_o, phi_o) = angles(wo);
        let (s, lum_pdf) = self.luminance.sample(u.to_array(), &[phi_o, theta_o]);
        let (u_m, vndf_pdf) = self.vndf.sample(s, &[phi_o, theta_o]);
        let theta_m = u_m[0] * u_m[0] * (PI / 2.0);
        let phi_m = (2.0 * u_m[1] - 1.0) * PI + if self.isotropic { phi_o } else { 0.0 };
        let (sin_t, cos_t) = theta_m.sin_cos();
        let (sin_p, cos_p) = phi_m.sin_cos();
        let m = Vec3::new(sin_t * cos_p, sin_t * sin_p, cos_t);
        let wi = reflect(wo, m);
        if wi.z <= 0.0 {
            return None;
        }
        let f = self.value(s, (phi_o, theta_o), (u_m, wi.z), w);
        let pdf = vndf_pdf * lum_pdf / Self::jacobian(wo, m, u_m);
        if !(pdf > 0.0) || !pdf.is_finite() {
            return None;
        }
        Some(BsdfSample::reflection(f, wi, pdf))
    }
}
