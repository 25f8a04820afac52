//! Planck's law (`../shared/PHYSICS.md`, "Planck and Wien"), with the 2019 SI constants.

/// Planck constant, J·s.
pub const PLANCK_H: f64 = 6.626_070_15e-34;
/// Speed of light in vacuum, m/s.
pub const LIGHT_C: f64 = 299_792_458.0;
/// Boltzmann constant, J/K.
pub const BOLTZMANN_K: f64 = 1.380_649e-23;
/// Wien's displacement constant b, m·K.
pub const WIEN_B: f64 = 2.897_771_955e-3;

/// The second radiation constant c₂ that CIE 015:2018 uses in the definition of illuminant A, m·K.
pub const CIE_A_C2_M_K: f64 = 1.435e-2;
/// The temperature in CIE 015:2018's formula for illuminant A (with [`CIE_A_C2_M_K`]), K.
pub const CIE_A_T_K: f64 = 2848.0;

/// Spectral radiance of a black body, in W·m⁻²·sr⁻¹·nm⁻¹, at `lambda_nm` (nm) and
/// `temperature_k` (K): L = 2hc²/λ⁵ / (exp(hc/(λkT)) − 1), × 1e-9 for per nm.
/// Returns 0 for non-positive temperatures or wavelengths.
pub fn planck(lambda_nm: f64, temperature_k: f64) -> f64 {
    if !(lambda_nm > 0.0 && temperature_k > 0.0) {
        return 0.0;
    }
    let l = lambda_nm * 1e-9;
    let x = PLANCK_H * LIGHT_C / (l * BOLTZMANN_K * temperature_k);
    2.0 * PLANCK_H * LIGHT_C * LIGHT_C / l.powi(5) / x.exp_m1() * 1e-9
}

/// Wavelength of peak spectral radiance (per unit wavelength), in nm: λ_max = b/T.
pub fn wien_peak_nm(temperature_k: f64) -> f64 {
    WIEN_B / temperature_k * 1e9
}

/// A black body of temperature `temperature_k` (K), scaled by `scale`.
///
/// With `scale = 1` it evaluates absolute spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹. The normalised
/// form ([`Blackbody::normalized`]) divides by the peak value, so that its maximum is 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blackbody {
    pub temperature_k: f32,
    pub scale: f32,
}

impl Blackbody {
    /// Absolute spectral radiance, W·m⁻²·sr⁻¹·nm⁻¹.
    pub fn absolute(temperature_k: f32) -> Self {
        Self {
            temperature_k,
            scale: 1.0,
        }
    }
    /// Peak-normalised shape: maximum 1 at λ = b/T (dimensionless).
    pub fn normalized(temperature_k: f32) -> Self {
        let t = temperature_k as f64;
        let peak = planck(wien_peak_nm(t), t);
        Self {
            temperature_k,
            scale: if peak > 0.0 { (1.0 / peak) as f32 } else { 0.0 },
        }
    }
    /// CIE standard illuminant A as CIE 015:2018 eq. (4.1) defines it, at every wavelength:
    /// S_A(λ) = 100 (560/λ)⁵ (exp(c₂/(2848·560)) − 1) / (exp(c₂/(2848 λ)) − 1), λ in nm, with the
    /// CIE's c₂ = 1.435e7 nm·K. That is Planck's law at the temperature T for which
    /// hc/(k T) = c₂/2848 K, i.e. T = 2848 K × (hc/k)/c₂ = 2855.54 K (the "2856 K" of ITS-90),
    /// scaled to 100 at 560 nm (relative SPD, dimensionless).
    pub fn cie_illuminant_a() -> Self {
        let t = CIE_A_T_K * (PLANCK_H * LIGHT_C / BOLTZMANN_K) / CIE_A_C2_M_K;
        let at_560 = planck(560.0, t);
        Self {
            temperature_k: t as f32,
            scale: (100.0 / at_560) as f32,
        }
    }
    /// Value at `lambda_nm`, in the unit the scale gives it.
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        (planck(lambda_nm as f64, self.temperature_k as f64) * self.scale as f64) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalized_peaks_at_one() {
        let b = Blackbody::normalized(5000.0);
        let peak = wien_peak_nm(5000.0) as f32;
        assert!((b.eval(peak) - 1.0).abs() < 1e-6);
        assert!(b.eval(peak - 20.0) < 1.0 && b.eval(peak + 20.0) < 1.0);
        assert_eq!(planck(500.0, 0.0), 0.0);
    }

    #[test]
    fn cie_a_is_the_cie_formula() {
        // CIE 015:2018 eq. (4.1), evaluated directly
        let formula = |l: f64| {
            let c = 1.435e7 / 2848.0;
            100.0 * (560.0 / l).powi(5) * (c / 560.0f64).exp_m1() / (c / l).exp_m1()
        };
        let a = Blackbody::cie_illuminant_a();
        for l in [
            300.0f32, 360.0, 450.0, 560.0, 700.0, 780.0, 805.0, 830.0, 1000.0,
        ] {
            let (got, want) = (a.eval(l) as f64, formula(l as f64));
            assert!((got / want - 1.0).abs() < 1e-6, "{l} nm: {got} vs {want}");
        }
        // the CIE 15:2004 table (colour-science SDS_ILLUMINANTS["A"]): S_A(780 nm) = 241.675
        assert!((a.eval(780.0) - 241.675).abs() < 1e-3, "{}", a.eval(780.0));
    }
}
