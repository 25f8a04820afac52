//! Real-ray spot diagrams: a bundle parallel to the axis (an object at infinity, on axis) traced
//! exactly through the lens and met on a plane behind it.

use glam::{DVec2, DVec3};

use super::{Direction, LensRay, LensSystem};

/// A spot on an image plane: its rays' RMS radius about their centroid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    /// RMS distance of the ray hits from their centroid, mm.
    pub rms_radius: f64,
    /// Rays of the bundle that got through the lens.
    pub rays: usize,
}

impl LensSystem {
    /// The spot of an axial bundle at `lambda_nm` on the plane `behind` mm behind the last
    /// vertex: `grid` × `grid` rays parallel to the axis, spread evenly over the first
    /// surface's clear aperture (those the lens vignettes or the stop blocks drop out). None
    /// if no ray gets through.
    pub fn axial_spot(&self, lambda_nm: f64, behind: f64, grid: usize) -> Option<Spot> {
        let front = &self.surfaces()[0];
        let z0 = self.total_length() + 1.0;
        let plane = self.film_distance() - behind;
        let mut hits = Vec::with_capacity(grid * grid);
        for i in 0..grid * grid {
            let u = DVec2::new(
                ((i % grid) as f64 + 0.5) / grid as f64,
                ((i / grid) as f64 + 0.5) / grid as f64,
            ) * 2.0
                - DVec2::ONE;
            if u.length_squared() > 1.0 {
                continue;
            }
            let o = (u * front.semi_aperture).extend(z0);
            let Some(r) = self.trace(
                LensRay { o, d: DVec3::NEG_Z },
                lambda_nm,
                Direction::FromObject,
            ) else {
                continue;
            };
            if r.d.z >= 0.0 {
                continue;
            }
            let t = (plane - r.o.z) / r.d.z;
            hits.push((r.o + t * r.d).truncate());
        }
        if hits.is_empty() {
            return None;
        }
        let n = hits.len() as f64;
        let c = hits.iter().copied().sum::<DVec2>() / n;
        let ms = hits.iter().map(|h| (*h - c).length_squared()).sum::<f64>() / n;
        Some(Spot {
            rms_radius: ms.sqrt(),
            rays: hits.len(),
        })
    }
}
