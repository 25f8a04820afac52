//! The exit pupil seen from the film, bounded so camera rays are not wasted on the rear
//! element's blocked zones, and the normalisation that makes a lens camera's pixel a radiance.
//!
//! **Bounds** (after pbrt-v4 §5.3.4): the film's radius is cut into [`SEGMENTS`] rings; for
//! each, film points across the ring along +x shoot rays at a grid over a square of 1.5 times
//! the rear element's semi-aperture on the plane of its vertex, at 400, 550 and 700 nm (the
//! pupil moves with wavelength where the lens disperses). The box around the grid points whose
//! rays get through, grown by two grid cells on every side, is the ring's pupil; a film point
//! at polar angle φ uses its ring's box rotated by φ (the system is rotationally symmetric).
//! Rays sampled in the box that the lens blocks carry zero weight, so a box that is too large
//! only costs time; the two-cell margin keeps it from being too small.
//!
//! **Normalisation**: a camera ray from film point x to the point p on the rear plane carries
//! the weight cos⁴θ / (z_r² · pdf(p)) — the film irradiance estimator dE = L cos θ cos θ' dA/d²
//! with d = z_r/cos θ (pbrt-v4 eq. 5.3) — divided by G₀ = ∫ cos⁴θ / z_r² dA over the pupil of
//! the film's centre at 587.56 nm. A pixel thus reads the film irradiance over the projected
//! solid angle of the on-axis pupil: a lossless lens looking at a uniform radiance L reads L at
//! the centre of the image (as a pinhole camera does) and less toward the corners by exactly
//! the lens's relative illumination (vignetting, cos⁴ fall-off, pupil distortion).

use glam::{DVec2, DVec3};

use super::{Direction, LensError, LensRay, LensSystem};

/// Rings of film radius with their own pupil bounds.
pub const SEGMENTS: usize = 32;
/// Grid points per side on the rear plane when bounding a ring's pupil.
const GRID: usize = 48;
/// Grid points per side when integrating G₀.
const NORM_GRID: usize = 256;
/// Wavelengths at which the bounds are taken, nm.
const BOUND_WAVELENGTHS: [f64; 3] = [400.0, 550.0, 700.0];

/// Per-ring exit pupil bounds and the lens's radiance normalisation.
#[derive(Clone, Debug, PartialEq)]
pub struct ExitPupil {
    /// (min, max) corners of each ring's box on the rear plane, mm; None where no ray passes.
    boxes: Vec<Option<(DVec2, DVec2)>>,
    /// Film radius the rings span (half the diagonal), mm.
    film_radius: f64,
    /// z of the rear vertex, mm.
    rear_z: f64,
    /// G₀ = ∫ cos⁴θ / z_r² dA over the on-axis pupil at 587.56 nm, sr.
    g0: f64,
}

impl ExitPupil {
    /// Bounds the pupil for a film of half-diagonal `film_radius` mm. Errors if no ray from the
    /// film centre gets through ([`LensError::Opaque`]).
    pub fn new(sys: &LensSystem, film_radius: f64) -> Result<ExitPupil, LensError> {
        let last = sys.surfaces().len() - 1;
        let rear_z = sys.vertex_z(last);
        let half = 1.5 * sys.surfaces()[last].semi_aperture;
        let cell = 2.0 * half / GRID as f64;
        let boxes = (0..SEGMENTS)
            .map(|k| {
                let r0 = film_radius * k as f64 / SEGMENTS as f64;
                let r1 = film_radius * (k + 1) as f64 / SEGMENTS as f64;
                let mut bb: Option<(DVec2, DVec2)> = None;
                for j in 0..3 {
                    let x = r0 + (r1 - r0) * j as f64 / 2.0;
                    for (gx, gy) in grid(GRID) {
                        let p = DVec2::new(-half + gx * 2.0 * half, -half + gy * 2.0 * half);
                        let through = BOUND_WAVELENGTHS
                            .iter()
                            .any(|&l| trace_to(sys, DVec2::new(x, 0.0), p, rear_z, l).is_some());
                        if through {
                            bb = Some(bb.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))));
                        }
                    }
                }
                bb.map(|(lo, hi)| (lo - DVec2::splat(2.0 * cell), hi + DVec2::splat(2.0 * cell)))
            })
            .collect::<Vec<_>>();
        let mut pupil = ExitPupil {
            boxes,
            film_radius,
            rear_z,
            g0: 0.0,
        };
        pupil.g0 = pupil.normalisation(sys);
        if !(pupil.g0 > 0.0) {
            return Err(LensError::Opaque {
                lambda_nm: crate::spectrum::ior::FRAUNHOFER_D_NM as f64,
            });
        }
        Ok(pupil)
    }

    /// G₀ by the midpoint rule over the central ring's box.
    fn normalisation(&self, sys: &LensSystem) -> f64 {
        let Some((lo, hi)) = self.boxes[0] else {
            return 0.0;
        };
        let cell = (hi - lo) / NORM_GRID as f64;
        let lambda = crate::spectrum::ior::FRAUNHOFER_D_NM as f64;
        let z2 = self.rear_z * self.rear_z;
        let mut sum = 0.0;
        for (gx, gy) in grid(NORM_GRID) {
            let p = lo + DVec2::new(gx, gy) * (hi - lo);
            if trace_to(sys, DVec2::ZERO, p, self.rear_z, lambda).is_some() {
                let c2 = z2 / (p.length_squared() + z2);
                sum += c2 * c2 / z2;
            }
        }
        sum * cell.x * cell.y
    }

    /// A point on the rear plane for film point `film` (mm, lens space) from `u` ∈ [0, 1)², and
    /// its density per unit area (mm⁻²); None where the ring has no pupil.
    pub fn sample(&self, film: DVec2, u: DVec2) -> Option<(DVec3, f64)> {
        let r = film.length();
        let k = ((r / self.film_radius * SEGMENTS as f64) as usize).min(SEGMENTS - 1);
        let (lo, hi) = self.boxes[k]?;
        let q = lo + u * (hi - lo);
        let (s, c) = if r > 0.0 {
            (film.y / r, film.x / r)
        } else {
            (0.0, 1.0)
        };
        let p = DVec2::new(c * q.x - s * q.y, s * q.x + c * q.y);
        let area = (hi.x - lo.x) * (hi.y - lo.y);
        Some((p.extend(self.rear_z), 1.0 / area))
    }

    /// The camera ray from film point `film` (mm) through the lens at `lambda_nm`, from `u`
    /// ∈ [0, 1)²: the ray leaving the front element (lens space, mm) and its weight
    /// cos⁴θ/(z_r²·pdf·G₀) (dimensionless; see the module docs). None if the lens blocks it.
    pub fn camera_ray(
        &self,
        sys: &LensSystem,
        film: DVec2,
        u: DVec2,
        lambda_nm: f64,
    ) -> Option<(LensRay, f64)> {
        let (p, pdf) = self.sample(film, u)?;
        let d = (p - film.extend(0.0)).normalize();
        let out = sys.trace(
            LensRay {
                o: film.extend(0.0),
                d,
            },
            lambda_nm,
            Direction::FromFilm,
        )?;
        let c2 = d.z * d.z;
        Some((out, c2 * c2 / (self.rear_z * self.rear_z * pdf * self.g0)))
    }

    /// G₀, sr (see the module docs).
    pub fn normalisation_sr(&self) -> f64 {
        self.g0
    }
}

/// Cell centres of an n × n grid over [0, 1)², as fractions.
fn grid(n: usize) -> impl Iterator<Item = (f64, f64)> {
    (0..n * n).map(move |i| {
        (
            ((i % n) as f64 + 0.5) / n as f64,
            ((i / n) as f64 + 0.5) / n as f64,
        )
    })
}

/// Traces from film point `film` toward `p` on the rear plane at `rear_z`.
fn trace_to(sys: &LensSystem, film: DVec2, p: DVec2, rear_z: f64, lambda: f64) -> Option<LensRay> {
    let o = film.extend(0.0);
    let d = (p.extend(rear_z) - o).normalize();
    sys.trace(LensRay { o, d }, lambda, Direction::FromFilm)
}
