//! Lens systems: a sequence of spherical interfaces between glasses, traced exactly (Snell's law
//! at every surface, per wavelength) and paraxially (first-order optics).
//!
//! ## Conventions
//! - Lengths are **millimetres** (`f64`), the unit of lens prescriptions; the camera converts to
//!   metres at its boundary.
//! - Surfaces are listed **object side first**, as in pbrt-v4's lens files and lens-design
//!   programs. Surface i has a radius of curvature R_i (positive when its centre lies on the
//!   film side, the usual optics sign; 0 for the flat aperture stop), the axial thickness t_i to
//!   the next surface (for the last surface: to the film), the medium behind it (on its film
//!   side) and a clear semi-aperture.
//! - **Lens space**: the optical axis is +z, pointing from the film toward the object; the film
//!   is the plane z = 0 and surface i's vertex is at z_i = Σ_{j ≥ i} t_j. Camera space (which
//!   looks along +z) is lens space scaled to metres, so the camera sits at the centre of the film.
//! - Every index is evaluated at the wavelength in vacuum, nm, through [`Ior::eval_f64`]; air is
//!   index 1 (as pbrt-v4 and lens-design programs in "air-relative" mode take it).

use crate::spectrum::ior::Ior;

mod paraxial;
mod pupil;
mod spot;
pub mod thin_film;
mod trace;

pub use paraxial::Paraxial;
pub use pupil::ExitPupil;
pub use spot::Spot;
pub use trace::{Direction, LensRay};

/// One interface of a lens system.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// Radius of curvature, mm: positive when the centre lies on the film side; `f64::INFINITY`
    /// for a flat refracting surface; 0 only for the aperture stop.
    pub radius: f64,
    /// Axial distance to the next surface, or to the film for the last one, mm.
    pub thickness: f64,
    /// The medium behind the surface (film side); `Ior::Constant(1.0)` for air.
    pub medium: Ior,
    /// Clear semi-aperture (radius of the usable zone), mm.
    pub semi_aperture: f64,
}

impl Surface {
    /// Whether this is the aperture stop (radius 0: a flat, non-refracting opening).
    pub fn is_stop(&self) -> bool {
        self.radius == 0.0
    }

    /// Curvature 1/R, mm⁻¹ (0 for a plane or the stop).
    pub fn curvature(&self) -> f64 {
        if self.radius == 0.0 || self.radius.is_infinite() {
            0.0
        } else {
            1.0 / self.radius
        }
    }

    /// Sag of the surface at height h (mm), measured from the vertex toward the film side
    /// positive: R − sign(R)·√(R² − h²); None beyond the sphere (|h| > |R|).
    pub fn sag(&self, h: f64) -> Option<f64> {
        let c = self.curvature();
        if c == 0.0 {
            return Some(0.0);
        }
        let r = self.radius;
        let d = r * r - h * h;
        (d >= 0.0).then(|| r - r.signum() * d.sqrt())
    }
}

/// Why a lens system cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LensError {
    #[error("a lens system needs at least one refracting surface")]
    Empty,
    #[error("surface {surface}: no aperture stop (a surface of radius 0) is given")]
    NoStop { surface: usize },
    #[error("surfaces {first} and {second} are both aperture stops (radius 0); a lens has one")]
    TwoStops { first: usize, second: usize },
    #[error(
        "surface {surface}: its semi-aperture {semi_aperture} mm is larger than its radius of \
         curvature {radius} mm (the clear zone would leave the sphere)"
    )]
    ApertureBeyondSphere {
        surface: usize,
        semi_aperture: f64,
        radius: f64,
    },
    #[error("surface {surface}: {what} must be finite and {bound}, found {value}")]
    Value {
        surface: usize,
        what: &'static str,
        bound: &'static str,
        value: f64,
    },
    #[error(
        "surfaces {surface} and {next} cross: at height {height} mm the first lies {overlap} mm \
         behind the second"
    )]
    Crossing {
        surface: usize,
        next: usize,
        height: f64,
        overlap: f64,
    },
    #[error(
        "the film is not behind the lens: the last surface's distance to the film is {value} mm"
    )]
    FilmBehindNothing { value: f64 },
    #[error(
        "no real image forms of a point {focus} mm in front of the film: it lies within the \
         lens's front focal distance"
    )]
    NoImage { focus: f64 },
    #[error(
        "no ray from the centre of the film gets through this lens at {lambda_nm:.2} nm (its stop \
         or clear apertures are too small, or light cannot cross it)"
    )]
    Opaque { lambda_nm: f64 },
}

/// A lens system: its surfaces, object side first (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct LensSystem {
    surfaces: Vec<Surface>,
    stop: usize,
}

impl LensSystem {
    /// Checks and builds a system. Errors (numbered from 1, as a lens file's lines are): no
    /// surface; no stop or two; a thickness that is negative or not finite (the last, the film
    /// distance, must be positive); a semi-aperture that is not positive or exceeds its sphere;
    /// adjacent surfaces that cross inside their common clear zone.
    pub fn new(surfaces: Vec<Surface>) -> Result<LensSystem, LensError> {
        if surfaces.iter().all(Surface::is_stop) {
            return Err(LensError::Empty);
        }
        let mut stop = None;
        for (i, s) in surfaces.iter().enumerate() {
            let n = i + 1;
            let bad = |what, bound, value| LensError::Value {
                surface: n,
                what,
                bound,
                value,
            };
            if s.radius.is_nan() {
                return Err(bad("the radius", "a number (0 for the stop)", s.radius));
            }
            if !(s.thickness.is_finite() && s.thickness >= 0.0) {
                return Err(bad("the thickness", "≥ 0 mm", s.thickness));
            }
            if !(s.semi_aperture.is_finite() && s.semi_aperture > 0.0) {
                return Err(bad("the aperture", "> 0 mm", 2.0 * s.semi_aperture));
            }
            if s.is_stop() {
                if let Some(first) = stop {
                    return Err(LensError::TwoStops {
                        first: first + 1,
                        second: n,
                    });
                }
                stop = Some(i);
            } else if s.radius.is_finite() && s.semi_aperture > s.radius.abs() {
                return Err(LensError::ApertureBeyondSphere {
                    surface: n,
                    semi_aperture: s.semi_aperture,
                    radius: s.radius,
                });
            }
        }
        let Some(stop) = stop else {
            return Err(LensError::NoStop {
                surface: surfaces.len(),
            });
        };
        let last = surfaces[surfaces.len() - 1].thickness;
        if !(last > 0.0) {
            return Err(LensError::FilmBehindNothing { value: last });
        }
        let sys = LensSystem { surfaces, stop };
        sys.check_crossings()?;
        Ok(sys)
    }

    /// Adjacent surfaces must not cross inside their common clear zone: at every height up to
    /// the smaller semi-aperture, the next surface lies behind this one (checked at 64 heights).
    fn check_crossings(&self) -> Result<(), LensError> {
        for i in 0..self.surfaces.len() - 1 {
            let (a, b) = (&self.surfaces[i], &self.surfaces[i + 1]);
            let h_max = a.semi_aperture.min(b.semi_aperture);
            for k in 0..=64 {
                let h = h_max * k as f64 / 64.0;
                let (Some(sa), Some(sb)) = (a.sag(h), b.sag(h)) else {
                    continue;
                };
                // positions along the film-ward direction: vertex i at 0, vertex i+1 at t_i
                let overlap = sa - (a.thickness + sb);
                if overlap > 1e-9 {
                    return Err(LensError::Crossing {
                        surface: i + 1,
                        next: i + 2,
                        height: h,
                        overlap,
                    });
                }
            }
        }
        Ok(())
    }

    /// The surfaces, object side first.
    pub fn surfaces(&self) -> &[Surface] {
        &self.surfaces
    }

    /// Index of the aperture stop in [`Self::surfaces`].
    pub fn stop(&self) -> usize {
        self.stop
    }

    /// Distance from the last surface's vertex to the film, mm.
    pub fn film_distance(&self) -> f64 {
        self.surfaces[self.surfaces.len() - 1].thickness
    }

    /// Moves the film to `d` mm behind the last vertex (focusing by moving the film). `d` must
    /// be positive and finite.
    pub fn with_film_distance(mut self, d: f64) -> Result<LensSystem, LensError> {
        if !(d.is_finite() && d > 0.0) {
            return Err(LensError::FilmBehindNothing { value: d });
        }
        let n = self.surfaces.len();
        self.surfaces[n - 1].thickness = d;
        Ok(self)
    }

    /// Sets the stop's diameter (mm), as pbrt-v4's `aperturediameter` does: it must be
    /// positive and at most the stop's own diameter in the prescription (a larger one would
    /// not be the stop any more).
    pub fn with_stop_diameter(mut self, d: f64) -> Result<LensSystem, LensError> {
        let s = &mut self.surfaces[self.stop];
        if !(d.is_finite() && d > 0.0 && d <= 2.0 * s.semi_aperture * (1.0 + 1e-12)) {
            return Err(LensError::Value {
                surface: self.stop + 1,
                what: "the stop diameter",
                bound: "positive and at most the prescription's",
                value: d,
            });
        }
        s.semi_aperture = d / 2.0;
        Ok(self)
    }

    /// z of surface i's vertex in lens space (mm from the film toward the object).
    pub fn vertex_z(&self, i: usize) -> f64 {
        self.surfaces[i..].iter().map(|s| s.thickness).sum()
    }

    /// Index of refraction in front of surface i (object side) at `lambda_nm`: air for the
    /// first surface.
    pub fn index_before(&self, i: usize, lambda_nm: f64) -> f64 {
        if i == 0 {
            1.0
        } else {
            medium_index(&self.surfaces[i - 1].medium, lambda_nm)
        }
    }

    /// Index behind surface i (film side) at `lambda_nm`.
    pub fn index_after(&self, i: usize, lambda_nm: f64) -> f64 {
        medium_index(&self.surfaces[i].medium, lambda_nm)
    }

    /// Whether any element's index depends on wavelength (then a camera ray serves one
    /// wavelength only).
    pub fn is_dispersive(&self) -> bool {
        self.surfaces.iter().any(|s| s.medium.is_dispersive())
    }

    /// Total axial length from the front vertex to the film, mm.
    pub fn total_length(&self) -> f64 {
        self.vertex_z(0)
    }
}

/// A medium's index; the stop's "medium" (pbrt-v4 writes 0 there) and any index below 1 read as
/// air.
fn medium_index(m: &Ior, lambda_nm: f64) -> f64 {
    let n = m.eval_f64(lambda_nm);
    if n >= 1.0 { n } else { 1.0 }
}

#[cfg(test)]
mod tests;
