//! Open cylinders (no caps), kept as a world-space base point, a unit axis, a length and a
//! radius: Mitsuba's `cylinder` (the tube of `radius` around the segment `p0`–`p1`).

use super::{Intersection, SurfaceSample};
use crate::geometry::error::{GeometryError, check_finite3, check_positive};
use crate::geometry::float::gamma;
use crate::geometry::ray::Ray;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;

/// A cylinder in world space: the points at distance `radius` from the segment of `length` from
/// `base` along `frame.z_axis`. Its normal points away from the axis (toward it when
/// `flipped`). uv = (φ/2π, h/length): φ around the axis from `frame.x_axis` toward
/// `frame.y_axis`, h the height above `base` (Mitsuba's parameterisation).
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    base: Vec3,
    /// Orthonormal columns: x, y across the axis, z along it.
    frame: Mat3,
    length: f32,
    radius: f32,
    flipped: bool,
    /// pbrt-v4's cylinder (`phimax`): the azimuths kept, from `frame.x_axis` toward
    /// `frame.y_axis`, and pbrt-v4's uv (u = φ/φ_max, v = h/ℓ); None: the whole tube with
    /// Mitsuba's uv. Area and sampling stay the whole tube's (a cut cylinder cannot emit).
    clip: Option<super::Clip>,
}

impl Cylinder {
    /// The tube of `radius` (m, > 0) around the segment from `p0` to `p1` (m, distinct points).
    pub fn new(p0: Vec3, p1: Vec3, radius: f32, flipped: bool) -> Result<Cylinder, GeometryError> {
        check_finite3("cylinder p0", p0)?;
        check_finite3("cylinder p1", p1)?;
        check_positive("cylinder radius", radius)?;
        let axis = p1 - p0;
        let length = check_positive("cylinder length |p1 − p0|", axis.length())?;
        let z = axis / length;
        let x = z.any_orthonormal_vector();
        Ok(Cylinder {
            base: p0,
            frame: Mat3::from_cols(x, z.cross(x), z),
            length,
            radius,
            flipped,
            clip: None,
        })
    }

    /// pbrt-v4's tube, cut to the azimuths of `clip`, measured from `x` toward `y` (its object
    /// x and y, carried to world space: made orthonormal to the axis, `y` only giving the
    /// sense of rotation, so a mirroring transform turns the azimuths the other way).
    pub fn clipped(self, clip: super::Clip, x: Vec3, y: Vec3) -> Cylinder {
        let z = self.frame.z_axis;
        let x = (x - z * x.dot(z))
            .try_normalize()
            .unwrap_or(self.frame.x_axis);
        let y = z.cross(x) * if z.cross(x).dot(y) < 0.0 { -1.0 } else { 1.0 };
        Cylinder {
            frame: Mat3::from_cols(x, y, z),
            clip: Some(clip),
            ..self
        }
    }

    /// The azimuth u = 1 stands for: 2π, or pbrt-v4's φ_max.
    #[inline]
    fn phi_max(&self) -> f32 {
        self.clip.map_or(2.0 * PI, |c| c.phi_max)
    }

    /// Lateral area 2πrℓ, m².
    pub fn area(&self) -> f32 {
        2.0 * PI * self.radius * self.length
    }

    pub(crate) fn aabb(&self) -> (Vec3, Vec3) {
        let z = self.frame.z_axis;
        // the end circles' extent along each world axis: r·√(1 − zᵢ²)
        let e = Vec3::new(
            (1.0 - z.x * z.x).max(0.0).sqrt(),
            (1.0 - z.y * z.y).max(0.0).sqrt(),
            (1.0 - z.z * z.z).max(0.0).sqrt(),
        ) * self.radius;
        let p1 = self.base + z * self.length;
        // padded by the rounding of the frame
        let pad = Vec3::splat(gamma(4) * (self.radius + self.length)) + gamma(2) * self.base.abs();
        (self.base.min(p1) - e - pad, self.base.max(p1) + e + pad)
    }

    /// Nearest root in (0, t_max) of |(o + t d − base)⊥|² = r² with the height in [0, ℓ], ⊥
    /// across the axis. As for spheres: if the origin's squared distance to the axis is within
    /// its rounding bound of r², the origin is *on* the tube and only a ray going inward can hit
    /// it, at the far root, so a ray leaving the surface never re-hits it; the discriminant uses
    /// the line's closest approach to the axis, avoiding cancellation.
    #[inline]
    pub(crate) fn intersect(&self, ray: &Ray) -> Option<f32> {
        let r = self.radius;
        let ft = self.frame.transpose();
        let o = ft * (ray.o - self.base);
        let d = ft * ray.d;
        let (o2, d2) = (Vec2::new(o.x, o.y), Vec2::new(d.x, d.y));
        let a = d2.length_squared();
        if !(a > 0.0) {
            return None; // parallel to the axis
        }
        let b = o2.dot(d2);
        let f = o2 - d2 * (b / a);
        let f_len = f.length();
        let disc = a * ((r - f_len) * (r + f_len));
        if !(disc >= 0.0) {
            return None;
        }
        let o_len = o2.length();
        let c = (o_len - r) * (o_len + r);
        let c_err = gamma(10) * (o.length() + r) * (o.length() + r);
        let sq = disc.sqrt();
        let q = if b > 0.0 { -(b + sq) } else { sq - b };
        let height_ok = |t: f32| {
            let h = o.z + t * d.z;
            let kept = self.clip.is_none_or(|c| {
                let (x, y) = (o.x + t * d.x, o.y + t * d.y);
                c.keeps(x / r, y / r, 0.0)
            });
            (0.0..=self.length).contains(&h) && kept
        };
        let accept = |t: f32| (t > 0.0 && t < ray.t_max && height_ok(t)).then_some(t);
        if c.abs() <= c_err {
            // origin on the tube: only an inward ray hits, at the far root q / a
            let b_err = gamma(6) * o_len * a.sqrt();
            if b >= -b_err {
                return None;
            }
            return accept(q / a);
        }
        if q == 0.0 {
            return None;
        }
        let (t0, t1) = (q / a, c / q);
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        accept(near).or_else(|| accept(far))
    }

    /// The surface point at angle `phi` and height `h`, its error bound and its normal.
    fn surface_point(&self, phi: f32, h: f32) -> (Vec3, Vec3, Vec3) {
        let (s, c) = phi.sin_cos();
        let radial = self.frame * Vec3::new(c, s, 0.0);
        let along = self.frame.z_axis * h;
        let p = self.base + radial * self.radius + along;
        let p_error = gamma(6) * (radial.abs() * self.radius + along.abs()) + gamma(2) * p.abs();
        let n = if self.flipped { -radial } else { radial };
        (p, p_error, n.normalize())
    }

    pub(crate) fn interaction(&self, p_approx: Vec3) -> Intersection {
        let local = self.frame.transpose() * (p_approx - self.base);
        let mut phi = local.y.atan2(local.x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        let h = local.z.clamp(0.0, self.length);
        let (p, p_error, n) = self.surface_point(phi, h);
        Intersection {
            t: 0.0,
            p,
            p_error,
            n_geom: n,
            n_shading: n,
            uv: Vec2::new(phi / self.phi_max(), h / self.length),
            // ∂p/∂u = φ_max·r·(−sin φ, cos φ, 0) in the cylinder's frame
            dpdu: self.frame
                * Vec3::new(-phi.sin(), phi.cos(), 0.0)
                * (self.phi_max() * self.radius),
            // ∂p/∂v = length·axis
            dpdv: self.frame.z_axis * self.length,
            shape: 0,
            prim: 0,
        }
    }

    /// The arc of the wall that faces `p`, as (φ of its centre, its half-width), rad: from a
    /// point at distance ρ > r from the axis the points whose outward normal faces it are
    /// those within acos(r/ρ) of its own φ, at any height (the cross-section is a circle, so
    /// the segment from `p` to such a point meets the tube only there: it is the first hit).
    /// None for a flipped cylinder or a point within the radius of the axis.
    fn facing_arc(&self, p: Vec3) -> Option<(f32, f32)> {
        if self.flipped {
            return None;
        }
        let local = self.frame.transpose() * (p - self.base);
        let rho = local.x.hypot(local.y);
        // a margin above r, so that points on the wall itself are sampled by area
        if !(rho > self.radius * (1.0 + 1e-4)) {
            return None;
        }
        let half = (self.radius / rho).acos();
        (half > 0.0).then(|| (local.y.atan2(local.x), half))
    }

    /// For a one-sided emitter seen from `p`: a point uniform by area on the arc that faces
    /// `p` ([`Cylinder::facing_arc`]), pdf 1/(2·half·r·ℓ) per m²; None where there is no such
    /// arc (sample by area instead). The rest of the wall faces away and emits nothing toward
    /// `p`.
    pub(crate) fn sample_facing(&self, p: Vec3, u: Vec2) -> Option<SurfaceSample> {
        let (centre, half) = self.facing_arc(p)?;
        let mut phi = centre + half * (2.0 * u.x - 1.0);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        if phi >= 2.0 * PI {
            phi -= 2.0 * PI;
        }
        let (q, p_error, n) = self.surface_point(phi, u.y * self.length);
        Some(SurfaceSample {
            p: q,
            p_error,
            n,
            pdf_area: 1.0 / (2.0 * half * self.radius * self.length),
            uv: Vec2::new(phi / self.phi_max(), u.y),
        })
    }

    /// The area density, m⁻², of [`Cylinder::sample_facing`] from `p` at any point of the
    /// facing arc; None where it samples by area.
    pub(crate) fn pdf_facing(&self, p: Vec3) -> Option<f32> {
        let (_, half) = self.facing_arc(p)?;
        Some(1.0 / (2.0 * half * self.radius * self.length))
    }

    /// A point uniform by area, pdf 1/area.
    pub(crate) fn sample_area(&self, u: Vec2) -> SurfaceSample {
        let (p, p_error, n) = self.surface_point(2.0 * PI * u.x, u.y * self.length);
        SurfaceSample {
            p,
            p_error,
            n,
            pdf_area: 1.0 / self.area(),
            uv: Vec2::new(2.0 * PI * u.x / self.phi_max(), u.y),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_from_outside_and_inside_and_respects_the_ends() {
        let c = Cylinder::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), 0.5, false).unwrap();
        let ray = |o: Vec3, d: Vec3| Ray::new(o, d.normalize());
        // from outside, toward the axis: the near wall at distance 1.5
        let t = c
            .intersect(&ray(Vec3::new(2.0, 0.0, 1.0), -Vec3::X))
            .unwrap();
        assert!((t - 1.5).abs() < 1e-5);
        let it = c.interaction(Vec3::new(2.0 - t, 0.0, 1.0));
        assert!((it.n_geom - Vec3::X).length() < 1e-5 && (it.uv.y - 0.5).abs() < 1e-5);
        // from the axis: the wall at distance 0.5
        let t = c
            .intersect(&ray(Vec3::new(0.0, 0.0, 1.0), Vec3::Y))
            .unwrap();
        assert!((t - 0.5).abs() < 1e-5);
        // above the top, and parallel to the axis: no hit
        assert!(
            c.intersect(&ray(Vec3::new(2.0, 0.0, 2.5), -Vec3::X))
                .is_none()
        );
        assert!(
            c.intersect(&ray(Vec3::new(0.1, 0.0, -1.0), Vec3::Z))
                .is_none()
        );
        // a ray through the open end hits the far wall from inside
        let t = c
            .intersect(&ray(Vec3::new(0.0, 0.0, 3.0), Vec3::new(0.25, 0.0, -1.0)))
            .unwrap();
        let h = 3.0 - t * (1.0 / (1.0f32 + 0.0625).sqrt());
        assert!((0.0..=2.0).contains(&h));
        // leaving the surface does not re-hit it; going across hits the opposite wall at 2r
        let s = c.sample_area(Vec2::new(0.3, 0.4));
        assert!(c.intersect(&ray(s.p, s.n)).is_none());
        let t = c.intersect(&ray(s.p, -s.n)).unwrap();
        assert!((t - 1.0).abs() < 1e-4, "{t}");
        assert!((c.area() - 2.0 * PI).abs() < 1e-5);
    }
}
