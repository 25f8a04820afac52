//! First-order (paraxial) optics of a lens system: the y–nu ray trace (Smith, *Modern Optical
//! Engineering*, 4th ed., §2.6; Kingslake & Johnson, *Lens Design Fundamentals*, §3.4).
//!
//! A paraxial ray at height y (mm) with reduced angle nu crosses surface i as
//! n'u' = n·u − y·φ_i with the surface power φ_i = (n' − n)·c_i (c_i = 1/R_i, mm⁻¹), then
//! travels y ← y + t_i·u' to the next surface. Everything is linear in (y, u), so the heights
//! and angles used here are exact first-order quantities, not small-angle approximations of a
//! real ray.

use super::{LensError, LensSystem};

/// First-order properties of a lens system at one wavelength, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paraxial {
    /// Wavelength in vacuum, nm.
    pub lambda_nm: f64,
    /// Effective focal length 1/Φ (Φ the system's power, image space in air), mm; infinite
    /// for an afocal system, negative for a diverging one.
    pub efl: f64,
    /// Back focal length: from the last vertex to the paraxial focus of a ray parallel to the
    /// axis, mm (negative when the focus is virtual, in front of the last vertex).
    pub bfl: f64,
}

impl LensSystem {
    /// Traces a paraxial ray entering surface 0 at height `y` (mm) and angle `u` (rad, in air)
    /// through every surface; returns (height at the last surface, angle behind it).
    fn ynu(&self, lambda_nm: f64, mut y: f64, mut u: f64) -> (f64, f64) {
        let s = self.surfaces();
        for i in 0..s.len() {
            let (n, n2) = (
                self.index_before(i, lambda_nm),
                self.index_after(i, lambda_nm),
            );
            let phi = (n2 - n) * s[i].curvature();
            u = (n * u - y * phi) / n2;
            if i + 1 < s.len() {
                y += s[i].thickness * u;
            }
        }
        (y, u)
    }

    /// The effective and back focal lengths at `lambda_nm` (nm in vacuum).
    pub fn paraxial(&self, lambda_nm: f64) -> Paraxial {
        let (y, u) = self.ynu(lambda_nm, 1.0, 0.0);
        let n_image = self.index_after(self.surfaces().len() - 1, lambda_nm);
        Paraxial {
            lambda_nm,
            efl: -1.0 / (n_image * u),
            bfl: -y / u,
        }
    }

    /// Distance behind the last vertex (mm) at which a point `object` mm in front of the first
    /// vertex is imaged paraxially at `lambda_nm`; None for a virtual image or an afocal system.
    pub fn image_distance(&self, object: f64, lambda_nm: f64) -> Option<f64> {
        // the ray from the axial object point at unit slope reaches the first vertex at height
        // `object`
        let (y, u) = self.ynu(lambda_nm, object, 1.0);
        let d = -y / u;
        (d.is_finite() && d > 0.0).then_some(d)
    }

    /// The film distance (from the last vertex, mm) that brings a point `focus` mm in front of
    /// the **film** into paraxial focus at `lambda_nm`, as pbrt-v4 measures its
    /// `focusdistance`. Solved by fixed-point iteration on the film position (the lens's own
    /// length, the other surfaces' thicknesses, is fixed). Errors when no real image exists.
    pub fn focus_film_distance(&self, focus: f64, lambda_nm: f64) -> Result<f64, LensError> {
        let body = self.total_length() - self.film_distance();
        let mut d = self.paraxial(lambda_nm).bfl;
        for _ in 0..100 {
            let object = focus - body - d;
            let next = (object > 0.0)
                .then(|| self.image_distance(object, lambda_nm))
                .flatten()
                .ok_or(LensError::NoImage { focus })?;
            if (next - d).abs() < 1e-12 * d.abs().max(1.0) {
                return Ok(next);
            }
            d = next;
        }
        Ok(d)
    }
}
