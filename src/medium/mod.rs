//! Participating media: what a ray meets between surfaces (issue 27).
//!
//! Conventions. Coefficients are per metre (m⁻¹) at a wavelength in nm: absorption σa,
//! scattering σs, extinction σt = σa + σs, single-scattering albedo σs/σt. Transmittance over
//! `t` metres is Beer–Lambert, exp(−σt t). A free flight is sampled by the hero wavelength's
//! σt and returns, for every wavelength of the path, both the value of the sampled event and
//! the density the event would have had with that wavelength as the hero, so that an
//! integrator can weigh whole paths by the balance heuristic over the wavelengths (spectral
//! MIS, Miller, Georgiev and Jarosz 2019 §5; pbrt-v4 §14.2.2's `r_u`). Phase functions follow
//! [`phase`]'s conventions (both directions away from the scattering point).
//!
//! Boundaries: every shape may name the medium inside it and the one outside it
//! ([`MediumInterface`]); a ray crossing the shape enters the one on the side it goes to,
//! decided by the geometric normal (Mitsuba 3's `target_medium`). A shape that names neither
//! leaves the ray's medium unchanged.

pub mod grid;
pub mod heterogeneous;
pub mod homogeneous;
pub mod phase;

pub use grid::{Grid, Volume, Wrap};
pub use heterogeneous::{Heterogeneous, Walk};
pub use homogeneous::{Flight, Homogeneous};
pub use phase::{PhaseFunction, PhaseSample};

use glam::Vec3;

use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A render-ready medium (closed: the integrators match on it).
#[derive(Clone, Debug)]
pub enum Medium {
    Homogeneous(Homogeneous),
    Heterogeneous(Heterogeneous),
}

impl Medium {
    /// Samples a free flight along `o + t d` (d unit) of at most `t_max` metres, with uniform
    /// numbers from `u` (see [`Walk`]).
    #[inline]
    pub fn walk<const N: usize>(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        w: &SampledWavelengths<N>,
        u: &mut impl FnMut() -> f32,
    ) -> Walk<N> {
        match self {
            Medium::Homogeneous(m) => {
                let flight = m.sample_flight(u(), o, d, t_max, w);
                let emitted = m.emitted(&flight, o, d, t_max, w);
                match flight {
                    Flight::Scatter { t, f, pdf } => Walk {
                        t: Some(t),
                        beta: f / pdf[0],
                        r_u: pdf / pdf[0],
                        r_l: SampledSpectrum::splat(1.0),
                        emitted,
                    },
                    // the walk's density of passing is Tr; next-event estimation's has no
                    // such factor (it evaluates Tr exactly)
                    Flight::Pass { tr, pdf } => Walk {
                        t: None,
                        beta: tr / pdf[0],
                        r_u: pdf / pdf[0],
                        r_l: SampledSpectrum::splat(1.0 / pdf[0]),
                        emitted,
                    },
                }
            }
            Medium::Heterogeneous(m) => m.walk(o, d, t_max, w, u),
        }
    }

    /// The transmittance over `o + t d`, t in [0, `t_max`] metres (exact for a homogeneous
    /// medium, an unbiased ratio-tracking estimate from `u` for a heterogeneous one), and, per
    /// wavelength, the density with which [`Medium::walk`] crosses the same segment with that
    /// wavelength as the hero, which next-event estimation's MIS weight needs: the
    /// transmittance itself, or 1 where no distance is sampled (a medium that only absorbs).
    #[inline]
    pub fn transmittance<const N: usize>(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        w: &SampledWavelengths<N>,
        u: &mut impl FnMut() -> f32,
    ) -> (SampledSpectrum<N>, SampledSpectrum<N>) {
        match self {
            Medium::Homogeneous(m) => {
                let tr = m.transmittance(t_max, w);
                if m.absorbs_only() {
                    (tr, SampledSpectrum::splat(1.0))
                } else {
                    (tr, tr)
                }
            }
            Medium::Heterogeneous(m) => {
                let tr = m.transmittance(o, d, t_max, w, u);
                (tr, tr)
            }
        }
    }

    /// The phase function of the medium's scattering.
    #[inline]
    pub fn phase(&self) -> PhaseFunction {
        match self {
            Medium::Homogeneous(m) => m.phase,
            Medium::Heterogeneous(m) => m.phase,
        }
    }
}

/// The media on either side of a shape: indices into [`crate::scene::Scene::media`], None
/// for vacuum.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MediumInterface {
    /// The side the geometric normal points away from.
    pub interior: Option<u32>,
    /// The side the geometric normal points to.
    pub exterior: Option<u32>,
}

impl MediumInterface {
    /// Whether the shape names any medium; a shape that does not leaves a ray's medium as it
    /// was.
    #[inline]
    pub fn is_transition(&self) -> bool {
        self.interior.is_some() || self.exterior.is_some()
    }

    /// The medium a ray leaving the surface (geometric normal `n`) in direction `d` travels
    /// in, given the one it arrived in (`current`).
    #[inline]
    pub fn target(&self, n: Vec3, d: Vec3, current: Option<u32>) -> Option<u32> {
        if !self.is_transition() {
            current
        } else if n.dot(d) > 0.0 {
            self.exterior
        } else {
            self.interior
        }
    }
}

/// The average of `x` over the wavelengths still alive (pdf > 0): the balance heuristic's
/// denominator over hero choices (a terminated wavelength is no longer a technique).
#[inline]
pub fn live_average<const N: usize>(x: SampledSpectrum<N>, w: &SampledWavelengths<N>) -> f32 {
    let (mut sum, mut n) = (0.0, 0);
    for j in 0..N {
        if w.pdf[j] > 0.0 {
            sum += x[j];
            n += 1;
        }
    }
    if n == 0 { x[0] } else { sum / n as f32 }
}
