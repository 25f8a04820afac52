//! Spectra: sampled wavelengths ([`sampled`], [`sampling`]), curves ([`curve`], [`blackbody`],
//! [`ior`], [`rgb2spec`]), and data loading ([`data`], [`named`]). Colour lives in
//! [`crate::colour`].

pub mod blackbody;
pub mod curve;
pub mod data;
pub mod ior;
pub mod named;
pub mod photometry;
pub mod rgb2spec;
pub mod sampled;
pub mod sampling;

pub use curve::{PiecewiseLinear, Spectrum};
pub use sampled::{N_WAVELENGTHS, SampledSpectrum, SampledWavelengths};
pub use sampling::{WavelengthRange, WavelengthSampler};
