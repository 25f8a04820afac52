//! Participating media as the scene file describes them (see [`crate::medium`] for the
//! conventions): coefficients per metre as spectra over wavelength in nm.

use crate::medium::PhaseFunction;
use crate::spectrum::Spectrum;

use super::super::error::Loc;

/// A named medium that shapes refer to as their interior or exterior.
#[derive(Clone, Debug)]
pub struct MediumDesc {
    pub name: String,
    pub kind: MediumKind,
    pub loc: Loc,
}

#[derive(Clone, Debug)]
pub enum MediumKind {
    /// The same coefficients everywhere.
    Homogeneous {
        coefficients: Coefficients,
        phase: PhaseFunction,
    },
}

/// A homogeneous medium's coefficients, as the file gives them.
#[derive(Clone, Debug)]
pub enum Coefficients {
    /// Extinction σt(λ), m⁻¹, and single-scattering albedo σs/σt in [0, 1] (Mitsuba's
    /// `sigma_t` × `scale` and `albedo`).
    Extinction { sigma_t: Spectrum, albedo: Spectrum },
    /// Absorption σa(λ) and scattering σs(λ), m⁻¹.
    AbsorptionScattering {
        sigma_a: Spectrum,
        sigma_s: Spectrum,
    },
}
