//! Participating media (issue 27, under way): so far the phase functions, with exact sampling
//! and tests against their closed forms. Media, their boundaries and the estimators that
//! cross them are still to come; scenes with media are refused by both loaders.

pub mod homogeneous;
pub mod phase;

pub use homogeneous::{Flight, Homogeneous};
pub use phase::{PhaseFunction, PhaseSample};
