//! RGB colour spaces derived from their primaries and white points, and Bradford chromatic
//! adaptation. Matrices are computed in f64 from the chromaticities (SMPTE RP 177), so each space
//! is defined by the numbers its standard publishes.

use glam::{DMat3, DVec3};

/// An RGB colour space: primaries and white point as CIE 1931 xy chromaticities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RgbSpace {
    pub name: &'static str,
    /// xy of the R, G and B primaries.
    pub primaries: [[f64; 2]; 3],
    /// XYZ of the white point, Y = 1.
    pub white: [f64; 3],
}

/// CIE D65 white chromaticity, xy (CIE 015, 4 decimals).
pub const D65_XY: [f64; 2] = [0.3127, 0.3290];
/// CIE D65 white as XYZ with Y = 1, from the 1 nm tables (ASTM E308). `../shared/PHYSICS.md`'s
/// XYZ → sRGB matrix is derived from this white, so the sRGB and Rec. 2020 spaces use it.
pub const D65_WHITE: [f64; 3] = [0.95047, 1.0, 1.08883];
/// ACES white point (≈ D60), xy (SMPTE ST 2065-1).
pub const ACES_WHITE_XY: [f64; 2] = [0.32168, 0.33767];
/// ACES white as XYZ with Y = 1.
pub const ACES_WHITE: [f64; 3] = white_from_xy(ACES_WHITE_XY);

/// XYZ with Y = 1 of chromaticity xy, usable in constants.
pub const fn white_from_xy(xy: [f64; 2]) -> [f64; 3] {
    [xy[0] / xy[1], 1.0, (1.0 - xy[0] - xy[1]) / xy[1]]
}

/// sRGB / Rec. 709 (IEC 61966-2-1), D65.
pub const SRGB: RgbSpace = RgbSpace {
    name: "sRGB",
    primaries: [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],
    white: D65_WHITE,
};
/// Rec. 2020 (ITU-R BT.2020), D65 given as the chromaticity (0.3127, 0.3290) as the standard
/// does.
pub const REC2020: RgbSpace = RgbSpace {
    name: "Rec.2020",
    primaries: [[0.708, 0.292], [0.170, 0.797], [0.131, 0.046]],
    white: white_from_xy(D65_XY),
};
/// ACES2065-1 (AP0 primaries, SMPTE ST 2065-1), ACES white.
pub const ACES2065_1: RgbSpace = RgbSpace {
    name: "ACES2065-1",
    primaries: [[0.7347, 0.2653], [0.0, 1.0], [0.0001, -0.0770]],
    white: ACES_WHITE,
};

/// XYZ with Y = 1 of chromaticity xy.
pub fn xy_to_xyz(xy: [f64; 2]) -> DVec3 {
    DVec3::from(white_from_xy(xy))
}

impl RgbSpace {
    /// The matrix taking linear RGB to XYZ (white RGB = (1,1,1) maps to the white with Y = 1).
    pub fn rgb_to_xyz(&self) -> DMat3 {
        let p = DMat3::from_cols(
            xy_to_xyz(self.primaries[0]),
            xy_to_xyz(self.primaries[1]),
            xy_to_xyz(self.primaries[2]),
        );
        let s = p.inverse() * DVec3::from(self.white);
        DMat3::from_cols(p.x_axis * s.x, p.y_axis * s.y, p.z_axis * s.z)
    }
    /// The matrix taking XYZ to linear RGB.
    pub fn xyz_to_rgb(&self) -> DMat3 {
        self.rgb_to_xyz().inverse()
    }
}

/// The Bradford cone-response matrix (Lam 1985).
const BRADFORD: DMat3 = DMat3::from_cols_array(&[
    0.8951, -0.7502, 0.0389, // column 0
    0.2664, 1.7135, -0.0685, // column 1
    -0.1614, 0.0367, 1.0296, // column 2
]);

/// Bradford chromatic adaptation from white `src` to white `dst` (XYZ, Y = 1), as an XYZ → XYZ
/// matrix. Use [`xy_to_xyz`] for whites given as chromaticities.
pub fn bradford(src: [f64; 3], dst: [f64; 3]) -> DMat3 {
    let s = BRADFORD * DVec3::from(src);
    let d = BRADFORD * DVec3::from(dst);
    BRADFORD.inverse() * DMat3::from_diagonal(d / s) * BRADFORD
}

/// XYZ (D65-referred, as the film produces) to linear sRGB.
pub fn xyz_to_srgb(xyz: [f64; 3]) -> [f64; 3] {
    (SRGB.xyz_to_rgb() * DVec3::from(xyz)).to_array()
}
/// Linear sRGB to XYZ.
pub fn srgb_to_xyz(rgb: [f64; 3]) -> [f64; 3] {
    (SRGB.rgb_to_xyz() * DVec3::from(rgb)).to_array()
}
/// XYZ (D65-referred) to linear Rec. 2020.
pub fn xyz_to_rec2020(xyz: [f64; 3]) -> [f64; 3] {
    (REC2020.xyz_to_rgb() * DVec3::from(xyz)).to_array()
}
/// XYZ (D65-referred) to ACES2065-1, adapting D65 to the ACES white with Bradford.
pub fn xyz_to_aces2065_1(xyz: [f64; 3]) -> [f64; 3] {
    (ACES2065_1.xyz_to_rgb() * bradford(D65_WHITE, ACES_WHITE) * DVec3::from(xyz)).to_array()
}
/// ACES2065-1 to D65-referred XYZ (the inverse of [`xyz_to_aces2065_1`]).
pub fn aces2065_1_to_xyz(rgb: [f64; 3]) -> [f64; 3] {
    (bradford(ACES_WHITE, D65_WHITE) * ACES2065_1.rgb_to_xyz() * DVec3::from(rgb)).to_array()
}

/// The sRGB transfer function (IEC 61966-2-1): linear → encoded, for values in [0, 1].
pub fn srgb_encode(v: f64) -> f64 {
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}
/// The inverse sRGB transfer function: encoded → linear.
pub fn srgb_decode(v: f64) -> f64 {
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transfer_round_trip() {
        for i in 0..=100 {
            let v = i as f64 / 100.0;
            assert!((srgb_decode(srgb_encode(v)) - v).abs() < 1e-12);
        }
    }

    #[test]
    fn bradford_identity_and_white_mapping() {
        let m = bradford(D65_WHITE, D65_WHITE);
        assert!(m.abs_diff_eq(DMat3::IDENTITY, 1e-12));
        let w = bradford(D65_WHITE, ACES_WHITE) * DVec3::from(D65_WHITE);
        assert!(w.abs_diff_eq(DVec3::from(ACES_WHITE), 1e-12));
        assert!(xy_to_xyz(ACES_WHITE_XY).abs_diff_eq(DVec3::from(ACES_WHITE), 1e-12));
    }
}
