//! pbrt-v4's quadrics: the part of a sphere (`zmin`, `zmax`, `phimax`), a disk (`innerradius`,
//! `phimax`) or a cylinder (`phimax`) that is kept, tested on a hit's object-frame coordinates
//! in units of the radius (pbrt-v4's `Sphere::BasicIntersect`, `Disk::BasicIntersect`,
//! `Cylinder::BasicIntersect`), and the ranges pbrt-v4's uv span (u = φ/φ_max; v over θ, the
//! radius or the height). A quadric with a `Clip` has pbrt-v4's uv and ∂p/∂u, ∂p/∂v.

use std::f32::consts::PI;

/// The kept part of a quadric, in its object frame scaled to unit radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clip {
    /// Heights kept, [z_lo, z_hi] (−∞ and +∞ where the quadric is not cut).
    pub z: [f32; 2],
    /// Azimuths kept, φ ∈ [0, phi_max] from object +x toward +y, radians.
    pub phi_max: f32,
    /// Distances from the axis below this are cut away (a disk's inner radius), ≥ 0.
    pub rho_min: f32,
}

impl Clip {
    /// A sphere of `radius` cut to heights [z0, z1] (either order, clamped to the sphere) and
    /// azimuths [0, phi_max] (degrees, clamped to [0, 360]), as pbrt-v4 reads them.
    pub fn sphere(radius: f32, z0: f32, z1: f32, phi_max_deg: f32) -> Clip {
        let (lo, hi) = (z0.min(z1) / radius, z0.max(z1) / radius);
        Clip {
            z: [
                if lo > -1.0 { lo } else { f32::NEG_INFINITY },
                if hi < 1.0 { hi } else { f32::INFINITY },
            ],
            phi_max: phi_max_deg.clamp(0.0, 360.0).to_radians(),
            rho_min: 0.0,
        }
    }

    /// A disk of `radius` with a hole of `inner` (m) and azimuths [0, phi_max] (degrees).
    pub fn disk(radius: f32, inner: f32, phi_max_deg: f32) -> Clip {
        Clip {
            z: [f32::NEG_INFINITY, f32::INFINITY],
            phi_max: phi_max_deg.clamp(0.0, 360.0).to_radians(),
            rho_min: (inner / radius).max(0.0),
        }
    }

    /// The whole quadric read as pbrt-v4's (its uv), nothing cut away.
    pub fn whole() -> Clip {
        Clip {
            z: [f32::NEG_INFINITY, f32::INFINITY],
            phi_max: 2.0 * PI,
            rho_min: 0.0,
        }
    }

    /// The polar angles θ (radians, from object +z) at the sphere's lower and upper cut (π and
    /// 0 uncut): pbrt-v4's `thetaZMin`, `thetaZMax`, between which its v runs from 0 to 1.
    pub fn theta_range(&self) -> (f32, f32) {
        (
            self.z[0].clamp(-1.0, 1.0).acos(),
            self.z[1].clamp(-1.0, 1.0).acos(),
        )
    }

    /// Whether nothing is cut away (every point is kept).
    #[inline]
    pub fn is_whole(&self) -> bool {
        self.z == [f32::NEG_INFINITY, f32::INFINITY]
            && self.phi_max >= 2.0 * PI
            && self.rho_min <= 0.0
    }

    /// Whether the point (x, y, z) (object frame, unit radius) is on the kept part.
    #[inline]
    pub fn keeps(&self, x: f32, y: f32, z: f32) -> bool {
        if z < self.z[0] || z > self.z[1] || x * x + y * y < self.rho_min * self.rho_min {
            return false;
        }
        if self.phi_max >= 2.0 * PI {
            return true;
        }
        let mut phi = y.atan2(x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        phi <= self.phi_max
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// pbrt-v4's rules: heights clamped and ordered, azimuth from +x toward +y, the hole.
    #[test]
    fn clips_as_pbrt_reads_its_parameters() {
        let c = Clip::sphere(2.0, 1.0, -3.0, 90.0);
        assert_eq!(c.z, [f32::NEG_INFINITY, 0.5]);
        assert!(c.keeps(0.5, 0.5, 0.3) && !c.keeps(0.5, 0.5, 0.6));
        assert!(!c.keeps(-0.5, 0.5, 0.0) && !c.keeps(0.5, -0.1, 0.0));
        let d = Clip::disk(1.0, 0.25, 360.0);
        assert!(!d.keeps(0.2, 0.1, 0.0) && d.keeps(-0.3, -0.1, 0.0));
    }
}
