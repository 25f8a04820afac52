//! Sky luminance distributions relative to the zenith luminance L_z.
//!
//! - **CIE standard general sky** (CIE S 011/E:2003 = ISO 15469:2004), 15 types:
//!   L(Z, χ)/L_z = f(χ)·φ(Z) / (f(Z_s)·φ(0)), with the gradation φ(Z) = 1 + a·exp(b / cos Z)
//!   (φ = 1 at the horizon) and the indicatrix f(χ) = 1 + c·(exp(d·χ) − exp(d·π/2)) + e·cos² χ;
//!   Z is the element's zenith angle, Z_s the sun's, χ the angle between element and sun.
//!   Parameters as tabulated by Darula & Kittler (eSim 2002) for the standard; type 1 is the
//!   standard's overcast sky with steep gradation, type 12 the CIE standard clear sky.
//! - **CIE standard overcast sky** (Moon & Spencer 1942, CIE S 003): L/L_z = (1 + 2 cos Z)/3.
//!   Close to type 1 but not equal (type 1 is 20 % darker near Z = 80°; their horizontal
//!   illuminances differ by 0.25 %), and the one with the closed form E_h = (7π/9)·L_z.

/// A sky model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkyModel {
    /// Moon–Spencer: (1 + 2 cos Z)/3, no sun dependence.
    Overcast,
    /// CIE general sky type 1–15.
    General(u8),
}

/// (a, b, c, d, e) of the 15 CIE general sky types.
const PARAMS: [[f64; 5]; 15] = [
    [4.0, -0.70, 0.0, -1.0, 0.00],
    [4.0, -0.70, 2.0, -1.5, 0.15],
    [1.1, -0.8, 0.0, -1.0, 0.00],
    [1.1, -0.8, 2.0, -1.5, 0.15],
    [0.0, -1.0, 0.0, -1.0, 0.00],
    [0.0, -1.0, 2.0, -1.5, 0.15],
    [0.0, -1.0, 5.0, -2.5, 0.30],
    [0.0, -1.0, 10.0, -3.0, 0.45],
    [-1.0, -0.55, 2.0, -1.5, 0.15],
    [-1.0, -0.55, 5.0, -2.5, 0.30],
    [-1.0, -0.55, 10.0, -3.0, 0.45],
    [-1.0, -0.32, 10.0, -3.0, 0.45],
    [-1.0, -0.32, 16.0, -3.0, 0.30],
    [-1.0, -0.15, 16.0, -3.0, 0.30],
    [-1.0, -0.15, 24.0, -2.8, 0.15],
];

impl SkyModel {
    /// L/L_z for an element at zenith angle `z` (rad), `chi` (rad) from the sun whose zenith
    /// angle is `zs` (rad); 0 below the horizon.
    pub fn relative_luminance(self, z: f64, chi: f64, zs: f64) -> f64 {
        let cos_z = z.cos();
        if cos_z < 0.0 {
            return 0.0;
        }
        match self {
            SkyModel::Overcast => (1.0 + 2.0 * cos_z) / 3.0,
            SkyModel::General(t) => {
                let [a, b, c, d, e] = PARAMS[(t.clamp(1, 15) - 1) as usize];
                let grad = |cz: f64| {
                    if cz <= 0.0 {
                        1.0
                    } else {
                        1.0 + a * (b / cz).exp()
                    }
                };
                let ind = |x: f64| {
                    1.0 + c * ((d * x).exp() - (d * std::f64::consts::FRAC_PI_2).exp())
                        + e * x.cos().powi(2)
                };
                ind(chi) * grad(cos_z) / (ind(zs) * grad(1.0))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Point values from an independent script (`scripts/gen_cie_sky_vectors.py`, the CIE
    /// formula in Python; `tests/data/cie_sky_vectors.csv`).
    #[test]
    fn point_values() {
        let r = f64::to_radians;
        let t12 = SkyModel::General(12);
        // sun at elevation 30° (Z_s = 60°), element Z = 45° in the sun's azimuth: χ = 15°
        let v = t12.relative_luminance(r(45.0), r(15.0), r(60.0));
        assert!((v - 5.3808011629).abs() < 1e-8, "{v}");
        // opposite azimuth: χ = 105°
        let v = t12.relative_luminance(r(45.0), r(105.0), r(60.0));
        assert!((v - 0.8965281806).abs() < 1e-8, "{v}");
        assert_eq!(
            SkyModel::General(5).relative_luminance(r(70.0), 1.0, 0.3),
            1.0
        );
        assert_eq!(SkyModel::Overcast.relative_luminance(0.0, 0.0, 0.0), 1.0);
        assert_eq!(
            SkyModel::Overcast.relative_luminance(r(91.0), 0.0, 0.0),
            0.0
        );
        // type 1 at the horizon: 1/φ(0) = 1/(1 + 4 e^−0.7) = 0.33486
        let v = SkyModel::General(1).relative_luminance(r(90.0), 1.0, 0.5);
        assert!((v - 0.334858).abs() < 1e-5, "{v}");
    }
}
