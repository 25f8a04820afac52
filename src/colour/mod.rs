//! Colour science: CIE colour matching and photometric calibration ([`cie`]), RGB spaces and
//! chromatic adaptation ([`spaces`]), CIELAB and CIEDE2000 ([`lab`]), and the PNG's display
//! transforms ([`view`]).

pub mod cie;
pub mod lab;
pub mod spaces;
pub mod view;
