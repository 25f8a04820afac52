//! A material's directional-hemispherical reflectance and transmittance: the fraction of the
//! power arriving from one direction that it sends back into the hemisphere it came from, and
//! through into the other (both in [0, 1]; their sum is 1 minus what it absorbs).
//!
//! ρ(ωᵢ) = ∫ f(ωᵢ, ωₒ)|cos θₒ| dωₒ over a hemisphere, estimated from the material's own
//! sampling in [`TransportMode::Importance`] (power, so transmission carries no 1/η² radiance
//! scaling): each sample's weight f·|cos θₒ|/pdf counted as reflection or transmission by its
//! side. For materials with delta lobes only (smooth dielectrics, conductors, sheets, films)
//! each lobe is taken once, exactly.

use glam::{Vec2, Vec3};

use super::{Material, TransportMode};
use crate::sampler::Sampler;
use crate::spectrum::SampledWavelengths;

/// ρ and τ at one wavelength, with their standard errors (0 when exact).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Albedo {
    /// Wavelength in vacuum, nm.
    pub lambda_nm: f32,
    /// Directional-hemispherical reflectance, dimensionless.
    pub reflectance: f64,
    /// Directional-hemispherical transmittance, dimensionless.
    pub transmittance: f64,
    /// Standard errors of the two (0 for an exact value).
    pub reflectance_se: f64,
    pub transmittance_se: f64,
    /// Whether the values are exact (delta lobes only) rather than estimated.
    pub exact: bool,
}

/// ρ and τ of `m` for light arriving at polar angle `theta_rad` from the normal (from the
/// outside, the side the normal points to) at `lambda_nm`, from `samples` samples where the
/// material is not purely specular (seeded by `seed`: the same inputs give the same values).
pub fn albedo(m: &Material, theta_rad: f32, lambda_nm: f32, samples: u32, seed: u32) -> Albedo {
    let wo = Vec3::new(theta_rad.sin(), 0.0, theta_rad.cos());
    let w = SampledWavelengths::<1> {
        lambda: [lambda_nm],
        pdf: [1.0],
    };
    let bsdf = m.at(Vec2::splat(0.5), &w);
    let mode = TransportMode::Importance;
    if m.is_specular() {
        // each delta lobe once: uc = 0 picks the first lobe that has weight, uc → 1 the last
        let (mut r, mut t) = (None, None);
        for uc in [0.0, 1.0 - f32::EPSILON] {
            if let Some(s) = bsdf.sample(wo, &w, uc, Vec2::splat(0.5), mode) {
                let v = (s.f[0] * s.wi.z.abs()) as f64;
                if s.wi.z > 0.0 {
                    r.get_or_insert(v);
                } else {
                    t.get_or_insert(v);
                }
            }
        }
        return Albedo {
            lambda_nm,
            reflectance: r.unwrap_or(0.0),
            transmittance: t.unwrap_or(0.0),
            reflectance_se: 0.0,
            transmittance_se: 0.0,
            exact: true,
        };
    }
    let n = samples.max(2);
    let (mut sr, mut sr2, mut st, mut st2) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for i in 0..n {
        let mut s = Sampler::new(seed, 0, 0, i);
        let uc = s.get_1d();
        let u = s.get_2d();
        let Some(b) = bsdf.sample(wo, &w, uc, u, mode) else {
            continue;
        };
        if !(b.pdf > 0.0) {
            continue;
        }
        // the sample weight f·|cos θₒ|/pdf (delta lobes too: module docs of `material`)
        let v = (b.f[0] * b.wi.z.abs() / b.pdf) as f64;
        if !v.is_finite() {
            continue;
        }
        if b.wi.z > 0.0 {
            sr += v;
            sr2 += v * v;
        } else {
            st += v;
            st2 += v * v;
        }
    }
    let nf = n as f64;
    let se = |s: f64, s2: f64| ((s2 / nf - (s / nf).powi(2)).max(0.0) / (nf - 1.0)).sqrt();
    Albedo {
        lambda_nm,
        reflectance: sr / nf,
        transmittance: st / nf,
        reflectance_se: se(sr, sr2),
        transmittance_se: se(st, st2),
        exact: false,
    }
}
