//! spectrace: a spectral path tracer whose numbers mean something.
//!
//! See `ARCHITECTURE.md` for the module map.

// `!(x > 0.0)` is the NaN-safe form of "not positive": it is true for NaN, which is what every
// such check here wants (a NaN distance, pdf or radius must be rejected). clippy's suggested
// `x <= 0.0` is false for NaN and would let NaN through, so the lint is wrong for this code.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

// uom's `quantity!`/`system!` macros need their helper macros in scope at the crate root.
// Only `units` uses them.
#[macro_use]
extern crate uom;

pub mod api;
pub mod build;
pub mod cli;
pub mod colour;
pub mod data;
pub mod daylight;
pub mod falsecolour;
pub mod files;
pub mod film;
pub mod geometry;
pub mod image_io;
pub mod integrator;
pub mod light;
pub mod loader;
pub mod material;
pub mod medium;
pub mod optics;
pub mod output;
pub mod params;
pub mod plot;
pub mod polarisation;
pub mod render;
pub mod sampler;
pub mod sampling;
pub mod scene;
pub mod sensor;
pub mod spectrum;
pub mod texture;
pub mod units;

/// The library API at the crate root: `spectrace::Scene`, `spectrace::render`,
/// `spectrace::Error`, … (see [`api`]).
pub use api::*;
