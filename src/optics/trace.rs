//! Exact ray tracing through a lens system: each surface intersected as the sphere (or plane) it
//! is, clipped to its clear aperture, and refracted by Snell's law in vector form with the
//! indices at the ray's wavelength (pbrt-v4 §5.3.2 traces the same way, with one index per
//! element; here every element disperses).

use glam::DVec3;

use super::LensSystem;

/// A ray in lens space (mm; see the module docs of [`crate::optics`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LensRay {
    /// Origin, mm.
    pub o: DVec3,
    /// Unit direction.
    pub d: DVec3,
}

/// Which way a ray crosses the system.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// From the film (z = 0) toward the object: the last surface first (camera rays).
    FromFilm,
    /// From the object toward the film: the first surface first (spot diagrams).
    FromObject,
}

impl LensSystem {
    /// Traces `ray` through every surface at `lambda_nm`; returns the ray leaving the last
    /// surface crossed (its origin on that surface), or None if it misses a surface, falls
    /// outside a clear aperture or the stop, or is totally internally reflected.
    pub fn trace(&self, mut ray: LensRay, lambda_nm: f64, dir: Direction) -> Option<LensRay> {
        let n = self.surfaces().len();
        for k in 0..n {
            let i = match dir {
                Direction::FromFilm => n - 1 - k,
                Direction::FromObject => k,
            };
            let (n1, n2) = match dir {
                Direction::FromFilm => (
                    self.index_after(i, lambda_nm),
                    self.index_before(i, lambda_nm),
                ),
                Direction::FromObject => (
                    self.index_before(i, lambda_nm),
                    self.index_after(i, lambda_nm),
                ),
            };
            ray = self.cross(i, ray, n1, n2)?;
        }
        Some(ray)
    }

    /// Crosses surface `i` from index `n1` into `n2`.
    fn cross(&self, i: usize, ray: LensRay, n1: f64, n2: f64) -> Option<LensRay> {
        let s = &self.surfaces()[i];
        let z = self.vertex_z(i);
        let c = s.curvature();
        let (p, normal) = if c == 0.0 {
            let t = (z - ray.o.z) / ray.d.z;
            if !(t > 0.0 && t.is_finite()) {
                return None;
            }
            (ray.o + t * ray.d, DVec3::Z)
        } else {
            let centre = DVec3::new(0.0, 0.0, z - s.radius);
            let p = sphere_hit(ray, centre, s.radius)?;
            (p, (p - centre) / s.radius.abs())
        };
        if p.x * p.x + p.y * p.y > s.semi_aperture * s.semi_aperture {
            return None;
        }
        if s.is_stop() {
            return Some(LensRay { o: p, d: ray.d });
        }
        let nf = if normal.dot(ray.d) > 0.0 {
            -normal
        } else {
            normal
        };
        let d = refract(ray.d, nf, n1 / n2)?;
        Some(LensRay { o: p, d })
    }
}

/// The intersection of `ray` with the sphere of `radius` (signed) about `centre` on the cap
/// that holds the vertex (where (p − centre)·ẑ has the sign of the radius), nearest first.
fn sphere_hit(ray: LensRay, centre: DVec3, radius: f64) -> Option<DVec3> {
    let oc = ray.o - centre;
    let b = oc.dot(ray.d);
    let cc = oc.length_squared() - radius * radius;
    let disc = b * b - cc;
    if !(disc >= 0.0) {
        return None;
    }
    let sq = disc.sqrt();
    // roots −b ∓ √disc, the nearer first; a ray starting on the previous surface needs t > 0
    for t in [-b - sq, -b + sq] {
        if t > 1e-9 {
            let p = ray.o + t * ray.d;
            if (p.z - centre.z) * radius > 0.0 {
                return Some(p);
            }
        }
    }
    None
}

/// Snell's law in vector form: the refraction of unit `d` at unit normal `n` facing against it,
/// with `eta` = n₁/n₂; None on total internal reflection.
fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -n.dot(d);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}
