//! spectrace: a spectral path tracer whose numbers mean something.
//!
//! See `ARCHITECTURE.md` for the module map.

// uom's `quantity!`/`system!` macros need their helper macros in scope at the crate root.
// Only `units` uses them.
#[macro_use]
extern crate uom;

pub mod cli;
pub mod colour;
pub mod film;
pub mod geometry;
pub mod image_io;
pub mod integrator;
pub mod light;
pub mod loader;
pub mod material;
pub mod output;
pub mod render;
pub mod sampler;
pub mod sampling;
pub mod scene;
pub mod spectrum;
pub mod units;
