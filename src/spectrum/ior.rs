//! Indices of refraction as functions of wavelength: real for dielectrics, complex for
//! conductors.

use std::sync::Arc;

use super::curve::PiecewiseLinear;

/// Sellmeier dispersion (`../shared/PHYSICS.md`, "Dielectrics"), λ in µm:
/// n²(λ) = 1 + A + Σ_i B_i λ² / (λ² − C_i), with C_i in µm². Unused terms have B_i = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sellmeier {
    pub a: f32,
    pub b: [f32; 4],
    pub c: [f32; 4],
}

impl Sellmeier {
    /// Index at `lambda_nm` (nm). Near a pole or where n² < 1 it returns the nearest valid
    /// value, 1; callers check validity ranges at build time.
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        let l2 = (lambda_nm as f64 * 1e-3).powi(2);
        let mut n2 = 1.0 + self.a as f64;
        for i in 0..4 {
            if self.b[i] != 0.0 {
                n2 += self.b[i] as f64 * l2 / (l2 - self.c[i] as f64);
            }
        }
        if n2 > 1.0 && n2.is_finite() {
            n2.sqrt() as f32
        } else {
            1.0
        }
    }
}

/// Cauchy dispersion, λ in µm: n(λ) = A + B/λ² + C/λ⁴.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cauchy {
    pub a: f32,
    /// µm²
    pub b: f32,
    /// µm⁴
    pub c: f32,
}

impl Cauchy {
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        let l2 = (lambda_nm * 1e-3) * (lambda_nm * 1e-3);
        self.a + self.b / l2 + self.c / (l2 * l2)
    }
}

/// The real index of refraction of a dielectric (dimensionless), as a function of λ in nm.
#[derive(Clone, Debug, PartialEq)]
pub enum Ior {
    /// Non-dispersive.
    Constant(f32),
    Sellmeier(Sellmeier),
    Cauchy(Cauchy),
    /// Tabulated n(λ); the table is clamped to its end values outside its domain.
    Table(Arc<PiecewiseLinear>),
}

impl Ior {
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        match self {
            Ior::Constant(n) => *n,
            Ior::Sellmeier(s) => s.eval(lambda_nm),
            Ior::Cauchy(c) => c.eval(lambda_nm),
            Ior::Table(t) => {
                let (lo, hi) = t.domain();
                t.eval(lambda_nm.clamp(lo, hi))
            }
        }
    }

    /// Whether n depends on wavelength, so refraction must terminate secondary wavelengths.
    pub fn is_dispersive(&self) -> bool {
        !matches!(self, Ior::Constant(_))
    }

    /// Abbe number V_d = (n_d − 1)/(n_F − n_C) at the Fraunhofer d, F and C lines.
    pub fn abbe_number(&self) -> f64 {
        let n = |l: f32| self.eval(l) as f64;
        (n(FRAUNHOFER_D_NM) - 1.0) / (n(FRAUNHOFER_F_NM) - n(FRAUNHOFER_C_NM))
    }
}

/// Fraunhofer F line (hydrogen), nm.
pub const FRAUNHOFER_F_NM: f32 = 486.13;
/// Fraunhofer d line (helium), nm.
pub const FRAUNHOFER_D_NM: f32 = 587.56;
/// Fraunhofer C line (hydrogen), nm.
pub const FRAUNHOFER_C_NM: f32 = 656.27;

/// The complex index n + ik of a conductor, tabulated against λ in nm and clamped to the table's
/// end values outside its domain.
#[derive(Clone, Debug, PartialEq)]
pub struct ComplexIor {
    pub n: Arc<PiecewiseLinear>,
    pub k: Arc<PiecewiseLinear>,
}

impl ComplexIor {
    /// (n, k) at `lambda_nm`.
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> (f32, f32) {
        let (lo, hi) = self.n.domain();
        let l = lambda_nm.clamp(lo, hi);
        (self.n.eval(l), self.k.eval(l))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cauchy_and_constant() {
        let c = Cauchy {
            a: 1.5,
            b: 0.01,
            c: 0.0,
        };
        assert!((c.eval(500.0) - 1.54).abs() < 1e-6);
        assert!(!Ior::Constant(1.5).is_dispersive());
        assert!(Ior::Cauchy(c).is_dispersive());
    }
}
