//! Lights in physical units.
