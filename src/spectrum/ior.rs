//! Indices of refraction as functions of wavelength: real for dielectrics, complex for
//! conductors.

use std::sync::Arc;

use super::curve::PiecewiseLinear;

/// Sellmeier dispersion (`../shared/PHYSICS.md`, "Dielectrics"), λ in µm:
/// n²(λ) = 1 + A + Σ_i B_i λ² / (λ² − C_i), with C_i in µm². Unused terms have B_i = 0.
/// The coefficients are kept in f64, as the catalogues print them, so paraxial optics
/// (`crate::optics`) reproduces a lens-design program's focal lengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sellmeier {
    pub a: f64,
    pub b: [f64; 4],
    /// µm²
    pub c: [f64; 4],
}

impl Sellmeier {
    /// Index at `lambda_nm` (nm). Near a pole or where n² < 1 it returns the nearest valid
    /// value, 1; callers check validity ranges at build time.
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        self.eval_f64(lambda_nm as f64) as f32
    }

    /// [`Self::eval`] in double precision.
    pub fn eval_f64(&self, lambda_nm: f64) -> f64 {
        let l2 = (lambda_nm * 1e-3).powi(2);
        let mut n2 = 1.0 + self.a;
        for i in 0..4 {
            if self.b[i] != 0.0 {
                n2 += self.b[i] * l2 / (l2 - self.c[i]);
            }
        }
        valid_sqrt(n2)
    }
}

/// √(n²) where n² > 1 and finite, else 1 (near a pole or outside a formula's range).
fn valid_sqrt(n2: f64) -> f64 {
    if n2 > 1.0 && n2.is_finite() {
        n2.sqrt()
    } else {
        1.0
    }
}

/// The catalogues' power series (refractiveindex.info "formula 3": HOYA, Sumita, most OHARA
/// and some CDGM glasses), λ in µm: n²(λ) = A + Σ_i c_i λ^{p_i}. Unused terms have c_i = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Polynomial {
    pub a: f64,
    pub c: [f64; 6],
    /// The exponents p_i (even integers in the catalogues, any real here).
    pub p: [f64; 6],
}

impl Polynomial {
    /// Index at `lambda_nm` (nm); 1 where the series gives n² ≤ 1.
    #[inline]
    pub fn eval(&self, lambda_nm: f32) -> f32 {
        self.eval_f64(lambda_nm as f64) as f32
    }

    /// [`Self::eval`] in double precision.
    pub fn eval_f64(&self, lambda_nm: f64) -> f64 {
        let l = lambda_nm * 1e-3;
        let mut n2 = self.a;
        for i in 0..6 {
            if self.c[i] != 0.0 {
                n2 += self.c[i] * l.powf(self.p[i]);
            }
        }
        valid_sqrt(n2)
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
    Polynomial(Polynomial),
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
            Ior::Polynomial(p) => p.eval(lambda_nm),
            Ior::Cauchy(c) => c.eval(lambda_nm),
            Ior::Table(t) => {
                let (lo, hi) = t.domain();
                t.eval(lambda_nm.clamp(lo, hi))
            }
        }
    }

    /// [`Self::eval`] in double precision (the formulas are evaluated in f64 throughout; a
    /// table and a Cauchy model are f32 data).
    pub fn eval_f64(&self, lambda_nm: f64) -> f64 {
        match self {
            Ior::Sellmeier(s) => s.eval_f64(lambda_nm),
            Ior::Polynomial(p) => p.eval_f64(lambda_nm),
            Ior::Constant(_) | Ior::Cauchy(_) | Ior::Table(_) => self.eval(lambda_nm as f32) as f64,
        }
    }

    /// A model glass from its catalogue n_d and Abbe number V_d, for glasses no catalogue here
    /// holds: the two-term Cauchy law n = A + B/λ² through n_d at the d line with
    /// n_F − n_C = (n_d − 1)/V_d (exact at d, and in n_F − n_C). None unless n_d ≥ 1 and V_d > 0.
    pub fn model(nd: f64, vd: f64) -> Option<Ior> {
        if !(nd >= 1.0 && vd > 0.0 && nd.is_finite() && vd.is_finite()) {
            return None;
        }
        let inv2 = |l_nm: f32| 1.0 / (l_nm as f64 * 1e-3).powi(2);
        let b = (nd - 1.0) / vd / (inv2(FRAUNHOFER_F_NM) - inv2(FRAUNHOFER_C_NM));
        let a = nd - b * inv2(FRAUNHOFER_D_NM);
        Some(Ior::Cauchy(Cauchy {
            a: a as f32,
            b: b as f32,
            c: 0.0,
        }))
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

    #[test]
    fn a_model_glass_has_its_nd_and_abbe_number() {
        let g = Ior::model(1.5168, 64.17).unwrap();
        assert!((g.eval(FRAUNHOFER_D_NM) - 1.5168).abs() < 2e-6);
        assert!(
            (g.abbe_number() - 64.17).abs() < 0.02,
            "{}",
            g.abbe_number()
        );
        assert!(Ior::model(0.9, 50.0).is_none() && Ior::model(1.5, 0.0).is_none());
    }

    #[test]
    fn the_power_series_is_the_catalogue_formula() {
        // HOYA BSC7's printed coefficients; its catalogue n_d is 1.51680
        let p = Polynomial {
            a: 2.2702566,
            c: [
                -0.0091988101,
                0.011609706,
                -7.6123911e-05,
                2.8558727e-05,
                -1.2566486e-06,
                0.0,
            ],
            p: [2.0, -2.0, -4.0, -6.0, -8.0, 0.0],
        };
        assert!((p.eval_f64(587.5618) - 1.5168).abs() < 1e-5);
    }
}
