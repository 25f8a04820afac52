//! Participating media as the scene file describes them (see [`crate::medium`] for the
//! conventions): coefficients per metre as spectra over wavelength in nm.

use std::path::PathBuf;
use std::sync::Arc;

use crate::medium::{PhaseFunction, Wrap};
use crate::spectrum::Spectrum;

use super::TransformStep;

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
        /// The radiance the medium emits, W·m⁻²·sr⁻¹·nm⁻¹: its source term is σa·Le, so that a
        /// medium thick enough glows at Le (Kirchhoff). None: it does not emit.
        emission: Option<Spectrum>,
    },
    /// Extinction `scale` × `density`(p, λ) in m⁻¹ and albedo `albedo`(p, λ), inside the unit
    /// cube of the density volume's frame (Mitsuba's `heterogeneous`).
    Heterogeneous {
        density: VolumeDesc,
        albedo: VolumeDesc,
        /// m⁻¹.
        scale: f64,
        phase: PhaseFunction,
    },
}

/// A quantity in space: a spectrum, or a voxel grid over the unit cube of its frame.
#[derive(Clone, Debug)]
pub enum VolumeDesc {
    Constant {
        value: Spectrum,
        /// Places the unit cube (the extent of a medium whose density this is), in metres.
        to_world: Vec<TransformStep>,
    },
    Grid {
        /// Voxels along x, y, z; `values` holds x fastest, then y, then z, `channels` (1 or 3,
        /// an RGB colour) per voxel.
        res: [usize; 3],
        channels: usize,
        values: Arc<Vec<f32>>,
        wrap: Wrap,
        to_world: Vec<TransformStep>,
        /// The file it was read from, for messages.
        file: PathBuf,
    },
}

/// A homogeneous medium's coefficients, as the file gives them.
#[derive(Clone, Debug)]
pub enum Coefficients {
    /// Extinction σt(λ), m⁻¹, and single-scattering albedo σs/σt in [0, 1], a spectrum or a
    /// volume (Mitsuba's `sigma_t` × `scale` and `albedo`).
    Extinction {
        sigma_t: Spectrum,
        albedo: VolumeDesc,
    },
    /// Absorption σa(λ) and scattering σs(λ), m⁻¹.
    AbsorptionScattering {
        sigma_a: Spectrum,
        sigma_s: Spectrum,
    },
}
