//! The immutable render-ready scene, and `build`, which makes it from a description.
