//! Disks (ellipses under non-uniform scaling), kept in world space.

use super::{Intersection, PrimHit, SurfaceSample};
use crate::geometry::error::{GeometryError, check_finite3, check_positive};
use crate::geometry::float::gamma;
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use crate::sampling::concentric_disk;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The object-space disk x² + y² ≤ radius² in the plane z = 0 with normal +z, transformed to
/// world space. Under a non-uniform scale it is an ellipse: the points `centre + a·u + b·v` with
/// a² + b² ≤ 1, where `u` and `v` are the images of radius·x̂ and radius·ŷ.
///
/// uv = (ρ, φ/2π) with ρ = √(a² + b²) ∈ [0, 1] and φ = atan2(b, a) ∈ [0, 2π).
#[derive(Clone, Debug, PartialEq)]
pub struct Disk {
    center: Vec3,
    u: Vec3,
    v: Vec3,
    /// Unit normal: the transformed object +z (inverse transpose), so mirroring keeps it
    /// consistent with the transform.
    n: Vec3,
    /// Dual basis: `(p − centre)·u_dual = a`, `(p − centre)·v_dual = b` for p in the plane.
    u_dual: Vec3,
    v_dual: Vec3,
    /// How far `centre + a·u + b·v` (|a|,|b| ≤ 1) may lie off the plane (centre, n) because `n`
    /// is rounded, m.
    plane_slack: f32,
    area: f32,
    /// pbrt-v4's disk (`innerradius`, `phimax`): the part kept, on (a, b), and pbrt-v4's uv
    /// (u = φ/φ_max, v = (1 − ρ)/(1 − ρ_inner)); None: the whole disk with Mitsuba's uv. Area
    /// and sampling stay the whole disk's (a cut disk cannot emit).
    clip: Option<super::Clip>,
}

impl Disk {
    /// A disk of `radius` (m, > 0) in the object xy plane, normal +z, transformed by
    /// `transform`. Errors for a non-positive or non-finite radius, or if the transformed disk
    /// is not finite or has zero area.
    pub fn new(transform: &Transform, radius: f32) -> Result<Disk, GeometryError> {
        check_positive("disk radius", radius)?;
        let center = check_finite3("disk centre", transform.point(Vec3::ZERO))?;
        let u = check_finite3("disk axis", transform.vector(Vec3::X * radius))?;
        let v = check_finite3("disk axis", transform.vector(Vec3::Y * radius))?;
        let n = transform.normal(Vec3::Z).normalize_or_zero();
        let uxv = u.cross(v);
        let det = uxv.dot(n);
        let area = PI * uxv.length();
        if !(det.abs() > 0.0) || !area.is_finite() || n == Vec3::ZERO {
            return Err(GeometryError::NotPositive {
                what: "transformed disk area",
                value: area,
            });
        }
        let u_dual = v.cross(n) / det;
        let v_dual = n.cross(u) / det;
        let plane_slack =
            n.dot(u).abs() + n.dot(v).abs() + gamma(4) * (u.abs() + v.abs()).max_element();
        Ok(Disk {
            center,
            u,
            v,
            n,
            u_dual,
            v_dual,
            plane_slack,
            area,
            clip: None,
        })
    }

    /// pbrt-v4's disk cut to `clip` (its `innerradius`, `phimax`, on the unit disk), with
    /// pbrt-v4's uv.
    pub fn clipped(self, clip: super::Clip) -> Disk {
        Disk {
            clip: Some(clip),
            ..self
        }
    }

    /// Centre, m.
    pub fn center(&self) -> Vec3 {
        self.center
    }

    /// Unit normal (front face).
    pub fn normal(&self) -> Vec3 {
        self.n
    }

    /// Area π|u × v|, m².
    pub fn area(&self) -> f32 {
        self.area
    }

    pub(crate) fn aabb(&self) -> (Vec3, Vec3) {
        // Extent of centre + a u + b v over the unit disk: √(u_i² + v_i²) per axis.
        let e = Vec3::from(
            (self.u * self.u + self.v * self.v)
                .to_array()
                .map(f32::sqrt),
        );
        (self.center - e, self.center + e)
    }

    /// Local coordinates (a, b) of a point, projected along the normal.
    #[inline]
    pub(crate) fn local_coords(&self, p: Vec3) -> (f32, f32) {
        let w = p - self.center;
        (w.dot(self.u_dual), w.dot(self.v_dual))
    }

    /// Hit in (0, t_max). Robustness: the signed height of the origin above the plane is
    /// compared with its rounding error bound; an origin on the plane (a ray spawned from the
    /// disk, or any ray starting in its plane) cannot hit it.
    #[inline]
    pub(crate) fn intersect(&self, ray: &Ray) -> Option<(f32, PrimHit)> {
        let oc = ray.o - self.center;
        let height = oc.dot(self.n);
        let height_err = gamma(5) * oc.abs().dot(self.n.abs());
        if !(height.abs() > height_err) {
            return None;
        }
        let dn = ray.d.dot(self.n);
        // t > 0 needs the ray to move toward the plane.
        if !(height * dn < 0.0) {
            return None;
        }
        let t = -height / dn;
        if !(t < ray.t_max) {
            return None;
        }
        let (a, b) = self.local_coords(ray.at(t));
        let kept = self.clip.is_none_or(|c| c.keeps(a, b, 0.0));
        (a * a + b * b <= 1.0 && kept).then_some((t, PrimHit::Disk { a, b }))
    }

    /// The surface point at local coordinates (a, b), reprojected onto the disk.
    fn surface_point(&self, a: f32, b: f32) -> (Vec3, Vec3) {
        let (au, bv) = (self.u * a, self.v * b);
        let p = self.center + au + bv;
        let p_error =
            gamma(4) * (self.center.abs() + au.abs() + bv.abs()) + Vec3::splat(self.plane_slack);
        (p, p_error)
    }

    /// The uv at radius `rho` (unit disk) and azimuth `phi`: Mitsuba's (ρ, φ/2π), or
    /// pbrt-v4's with a clip.
    #[inline]
    fn uv(&self, rho: f32, phi: f32) -> Vec2 {
        match &self.clip {
            None => Vec2::new(rho, phi / (2.0 * PI)),
            Some(c) => Vec2::new(phi / c.phi_max, (1.0 - rho) / (1.0 - c.rho_min)),
        }
    }

    pub(crate) fn interaction(&self, a: f32, b: f32) -> Intersection {
        let (p, p_error) = self.surface_point(a, b);
        let mut phi = b.atan2(a);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        let rho = (a * a + b * b).sqrt();
        let radial = self.u * a + self.v * b;
        let around = self.v * a - self.u * b;
        let (dpdu, dpdv) = match &self.clip {
            // ∂p/∂ρ radial (as Mitsuba's disk, zero at the centre); ∂p/∂v = 2π·(−b, a)
            None => (radial.normalize_or_zero(), around * (2.0 * PI)),
            // pbrt-v4's: ∂p/∂u = φ_max·(−b, a), ∂p/∂v = (ρ_inner − 1)·(a, b)/ρ (in the disk's
            // axes, each the radius long; along the u axis at the centre)
            Some(c) => {
                let unit = if rho > 0.0 { radial / rho } else { self.u };
                (around * c.phi_max, unit * (c.rho_min - 1.0))
            }
        };
        Intersection {
            t: 0.0,
            p,
            p_error,
            n_geom: self.n,
            n_shading: self.n,
            uv: self.uv(rho, phi),
            dpdu,
            dpdv,
            shape: 0,
            prim: 0,
        }
    }

    pub(crate) fn sample_area(&self, u: Vec2) -> SurfaceSample {
        let d = concentric_disk(u);
        let (p, p_error) = self.surface_point(d.x, d.y);
        let phi = d.y.atan2(d.x);
        let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
        SurfaceSample {
            p,
            p_error,
            n: self.n,
            pdf_area: 1.0 / self.area,
            uv: self.uv(d.length(), phi),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ellipse_area_and_hit() {
        let t = Transform::scale(Vec3::new(2.0, 3.0, 1.0)).unwrap();
        let d = Disk::new(&t, 0.5).unwrap();
        assert!((d.area() - PI * 1.0 * 1.5).abs() < 1e-5);
        let hit = d.intersect(&Ray::new(Vec3::new(0.9, 0.0, 1.0), -Vec3::Z));
        assert!(hit.is_some_and(|(t, _)| (t - 1.0).abs() < 1e-6));
        assert!(
            d.intersect(&Ray::new(Vec3::new(1.1, 0.0, 1.0), -Vec3::Z))
                .is_none()
        );
        assert!(
            d.intersect(&Ray::new(Vec3::new(0.0, 1.4, -1.0), Vec3::Z))
                .is_some()
        );
    }

    /// pbrt-v4's disk: at radius ρ, u = φ/φ_max and v = (r − ρ)/(r − r_inner), so ∂p/∂v points
    /// to the centre with length r − r_inner and ∂p/∂u along the circle with length φ_max·ρ.
    #[test]
    fn pbrt_disk_derivatives_follow_its_uv() {
        let d = Disk::new(&Transform::identity(), 2.0)
            .unwrap()
            .clipped(super::super::Clip::disk(1.0, 0.25, 180.0));
        let it = d.interaction(0.5, 0.0);
        assert!((it.p - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-6);
        assert!(
            (it.uv - Vec2::new(0.0, 0.5 / 0.75)).length() < 1e-6,
            "{}",
            it.uv
        );
        assert!(
            (it.dpdv - Vec3::new(-1.5, 0.0, 0.0)).length() < 1e-5,
            "{}",
            it.dpdv
        );
        assert!(
            (it.dpdu - Vec3::new(0.0, PI, 0.0)).length() < 1e-5,
            "{}",
            it.dpdu
        );
    }

    #[test]
    fn mirrored_normal_follows_transform() {
        let t = Transform::scale(Vec3::new(1.0, 1.0, -1.0)).unwrap();
        assert!((Disk::new(&t, 1.0).unwrap().normal() + Vec3::Z).length() < 1e-6);
        assert!(Disk::new(&Transform::identity(), -1.0).is_err());
    }
}
