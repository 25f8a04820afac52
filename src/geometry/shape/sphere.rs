//! Spheres, kept as a world-space centre and radius.

use super::{Intersection, SurfaceSample};
use crate::geometry::error::{GeometryError, check_finite3, check_positive};
use crate::geometry::float::gamma;
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use crate::sampling::uniform_sphere;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;

/// A sphere in world space. Its normal points outward. Its uv is (φ/2π, θ/π) in the spherical
/// coordinates of its object frame (θ from object +z, φ from object +x toward +y).
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    center: Vec3,
    radius: f32,
    /// Object-to-world rotation (orthonormal columns), used for uv and the clip.
    frame: Mat3,
    /// pbrt-v4's sphere: the part kept, and pbrt-v4's uv (u = φ/φ_max, v = (θ − θ_zmin) /
    /// (θ_zmax − θ_zmin)); None: the whole sphere with Mitsuba's uv. Area, bounds and sampling
    /// stay the whole sphere's (a cut sphere cannot emit).
    clip: Option<super::Clip>,
}

impl Sphere {
    /// A sphere of `radius` (m, > 0) at `center` (m). Errors for non-finite input or a radius
    /// ≤ 0.
    pub fn new(center: Vec3, radius: f32) -> Result<Sphere, GeometryError> {
        check_finite3("sphere centre", center)?;
        check_positive("sphere radius", radius)?;
        Ok(Sphere {
            center,
            radius,
            frame: Mat3::IDENTITY,
            clip: None,
        })
    }

    /// The object-space sphere of `radius` at the origin, transformed. Only similarity
    /// transforms (rotation, translation, uniform scale, mirroring) are supported: non-uniform
    /// scaling or shear would make an ellipsoid and gives [`GeometryError::NonUniformScale`].
    pub fn with_transform(transform: &Transform, radius: f32) -> Result<Sphere, GeometryError> {
        check_positive("sphere radius", radius)?;
        let lin = Mat3::from_mat4(transform.matrix());
        let cols = [lin.x_axis, lin.y_axis, lin.z_axis];
        let scales = cols.map(Vec3::length);
        let s = (scales[0] + scales[1] + scales[2]) / 3.0;
        let tol = 1e-4 * s;
        let similar = scales.iter().all(|l| (l - s).abs() <= tol)
            && cols[0].dot(cols[1]).abs() <= tol * s
            && cols[1].dot(cols[2]).abs() <= tol * s
            && cols[0].dot(cols[2]).abs() <= tol * s;
        if !similar {
            return Err(GeometryError::NonUniformScale { scales });
        }
        let center = check_finite3("sphere centre", transform.point(Vec3::ZERO))?;
        let radius = check_positive("transformed sphere radius", radius * s)?;
        Ok(Sphere {
            center,
            radius,
            frame: lin * (1.0 / s),
            clip: None,
        })
    }

    /// pbrt-v4's sphere cut to `clip` (its `zmin`, `zmax`, `phimax`, in its object frame), with
    /// pbrt-v4's uv.
    pub fn clipped(self, clip: super::Clip) -> Sphere {
        Sphere {
            clip: Some(clip),
            ..self
        }
    }

    /// Whether the hit at `t` along `ray` is on the kept part.
    #[inline]
    fn kept(&self, ray: &Ray, t: f32) -> bool {
        // a whole pbrt-v4 sphere (every pbrt-v4 sphere has a clip, for its uv) skips the test
        self.clip.is_none_or(|c| {
            c.is_whole() || {
                let l = self.frame.transpose() * ((ray.at(t) - self.center) / self.radius);
                c.keeps(l.x, l.y, l.z)
            }
        })
    }

    /// Centre, m.
    pub fn center(&self) -> Vec3 {
        self.center
    }

    /// Radius, m.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// Surface area 4πr², m².
    pub fn area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    pub(crate) fn aabb(&self) -> (Vec3, Vec3) {
        let r = Vec3::splat(self.radius);
        (self.center - r, self.center + r)
    }

    /// Nearest root in (0, t_max) of |o + t d − c|² = r².
    ///
    /// Robustness: `c_ = |o − c|² − r²` decides whether the origin is outside (> 0) or inside;
    /// if |c_| is within its rounding error bound the origin is *on* the sphere, and then only a
    /// ray going inward (b = (o − c)·d clearly < 0) can hit it, at the far root. A ray spawned
    /// from the surface and leaving it therefore never re-hits. The discriminant uses the
    /// perpendicular distance of the line from the centre (Haines et al., Ray Tracing Gems ch. 7)
    /// to avoid cancellation.
    #[inline]
    pub(crate) fn intersect(&self, ray: &Ray) -> Option<f32> {
        let r = self.radius;
        let oc = ray.o - self.center;
        let a = ray.d.length_squared();
        let b = oc.dot(ray.d);
        let f = oc - ray.d * (b / a);
        let f_len = f.length();
        let disc = a * ((r - f_len) * (r + f_len));
        if !(disc >= 0.0) {
            return None;
        }
        let oc_len = oc.length();
        let c = (oc_len - r) * (oc_len + r);
        let c_err = gamma(8) * oc_len * (oc_len + r);
        let sq = disc.sqrt();
        let q = if b > 0.0 { -(b + sq) } else { sq - b };
        if c.abs() <= c_err {
            // Origin on the surface: only an inward ray hits, at the far root q / a.
            let b_err = gamma(4) * oc_len * a.sqrt();
            if b >= -b_err {
                return None;
            }
            let t = q / a;
            return (t > 0.0 && t < ray.t_max && self.kept(ray, t)).then_some(t);
        }
        if q == 0.0 {
            return None;
        }
        let (t0, t1) = (q / a, c / q);
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        // the near root, else (behind the origin, or cut away) the far one
        let accept = |t: f32| (t > 0.0 && t < ray.t_max && self.kept(ray, t)).then_some(t);
        accept(near).or_else(|| accept(far))
    }

    /// The surface point in direction `p_obj` from the centre (any non-zero length), its error
    /// bound and the outward normal.
    fn surface_point(&self, p_obj: Vec3) -> (Vec3, Vec3, Vec3) {
        let len = p_obj.length();
        let dir = if len > 0.0 && len.is_finite() {
            p_obj / len
        } else {
            self.frame.z_axis.normalize_or(Vec3::Z)
        };
        let p_obj = dir * self.radius;
        let p = self.center + p_obj;
        let p_error = gamma(6) * p_obj.abs() + gamma(1) * p.abs();
        (p, p_error, dir)
    }

    /// uv = (φ/2π, θ/π) of the outward unit normal `n`, and its object-frame image, φ and θ.
    #[inline]
    fn angles(&self, n: Vec3) -> (Vec3, f32, f32) {
        let local = self.frame.transpose() * n;
        let mut phi = local.y.atan2(local.x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        (local, phi, local.z.clamp(-1.0, 1.0).acos())
    }

    /// The uv at (φ, θ) and the rates (dφ/du, dθ/dv): Mitsuba's (φ/2π, θ/π), or pbrt-v4's
    /// with a clip.
    #[inline]
    fn uv(&self, phi: f32, theta: f32) -> (Vec2, f32, f32) {
        match &self.clip {
            None => (Vec2::new(phi / (2.0 * PI), theta / PI), 2.0 * PI, PI),
            Some(c) => {
                let (t0, t1) = c.theta_range();
                let v = (theta - t0) / (t1 - t0);
                (Vec2::new(phi / c.phi_max, v), c.phi_max, t1 - t0)
            }
        }
    }

    pub(crate) fn interaction(&self, p_approx: Vec3) -> Intersection {
        let (p, p_error, n) = self.surface_point(p_approx - self.center);
        let (local, phi, theta) = self.angles(n);
        let (uv, du, dv) = self.uv(phi, theta);
        Intersection {
            t: 0.0,
            p,
            p_error,
            n_geom: n,
            n_shading: n,
            uv,
            // ∂p/∂u = dφ/du·(−y, x, 0) in the object frame, scaled by the radius
            dpdu: self.frame * Vec3::new(-local.y, local.x, 0.0) * (du * self.radius),
            // ∂p/∂v = dθ/dv·r·(cos θ cos φ, cos θ sin φ, −sin θ) in the object frame
            dpdv: self.frame
                * Vec3::new(local.z * phi.cos(), local.z * phi.sin(), -theta.sin())
                * (dv * self.radius),
            shape: 0,
            prim: 0,
        }
    }

    pub(crate) fn sample_area(&self, u: Vec2) -> SurfaceSample {
        let (p, p_error, n) = self.surface_point(uniform_sphere(u));
        let (_, phi, theta) = self.angles(n);
        SurfaceSample {
            p,
            p_error,
            n,
            pdf_area: 1.0 / self.area(),
            uv: self.uv(phi, theta).0,
        }
    }

    /// The squared distance from `p` to the centre, m², and sin²θ_max and 1 − cos θ_max of the
    /// cone of directions the sphere subtends seen from `p`; None when `p` is inside or on the
    /// sphere, where the caller samples by area.
    ///
    /// "On" is within 4·10⁻⁶ of the largest coordinate magnitude (about 64 f32 ulps): a point
    /// computed on the sphere's inside (a closed emitting sphere lighting itself) may round to
    /// just outside, and must not sample the outer cap. pbrt-v4 makes the same decision with
    /// the shading point's error bounds and normal, which this interface does not carry.
    ///
    /// For small cones 1 − cos θ_max would cancel in f32 (pbrt-v4 §6.2.4 switches to a series
    /// below sin²θ_max ≈ 6.9·10⁻⁴), so it is computed as sin²θ_max / (1 + cos θ_max) everywhere.
    #[inline]
    fn cone(&self, p: Vec3) -> Option<(f32, f32, f32)> {
        let d2 = (p - self.center).length_squared();
        let r2 = self.radius * self.radius;
        let slack =
            4e-6 * (p.abs().max_element().max(self.center.abs().max_element()) + self.radius);
        if !(d2 > (self.radius + slack) * (self.radius + slack)) {
            return None;
        }
        let sin2_max = r2 / d2;
        let cos_max = (1.0 - sin2_max).max(0.0).sqrt();
        Some((d2, sin2_max, sin2_max / (1.0 + cos_max)))
    }

    /// A point on the part of the sphere visible from `p`, its direction uniform in the cone the
    /// sphere subtends (pbrt-v4 §6.2.4, `Sphere::Sample(ctx, u)`; Mitsuba 3 `Sphere::sample_direction`),
    /// and its density with respect to solid angle at `p`, 1 / (2π(1 − cos θ_max)) sr⁻¹. None
    /// when `p` is inside or on the sphere ([`Sphere::cone`]): sample by area then.
    ///
    /// Steps: 1 − cos θ = u.x·(1 − cos θ_max) about the axis from `p` to the centre, azimuth
    /// 2π·u.y; the distance to the near intersection in the cancellation-free form
    /// t = (d² − r²) / (d·(cos θ + √(sin²θ_max − sin²θ))) (the product of the two roots is
    /// d² − r²); the point p + t·ω projected onto the sphere. pbrt-v4 instead finds the angle at
    /// the centre from the law of sines, whose cosine rounds to 1 when `p` is within ~10⁻⁴·r of
    /// the surface; this form stays accurate there.
    #[inline(never)]
    pub(crate) fn sample_cone(&self, p: Vec3, u: Vec2) -> Option<(SurfaceSample, f32)> {
        let (d2, sin2_max, one_minus_cos_max) = self.cone(p)?;
        let to_c = self.center - p;
        let d = d2.sqrt();
        let omc = u.x * one_minus_cos_max;
        let sin2_t = (omc * (2.0 - omc)).max(0.0);
        let cos_t = 1.0 - omc;
        let phi = 2.0 * PI * u.y;
        let sin_t = sin2_t.sqrt();
        let wi = crate::geometry::Frame::from_normal(to_c / d).to_world(Vec3::new(
            sin_t * phi.cos(),
            sin_t * phi.sin(),
            cos_t,
        ));
        let r = self.radius;
        let t = (d - r) * (d + r) / (d * (cos_t + (sin2_max - sin2_t).max(0.0).sqrt()));
        let (p_s, p_error, n) = self.surface_point(p + wi * t - self.center);
        let (_, phi_s, theta_s) = self.angles(n);
        let pdf = 1.0 / (2.0 * PI * one_minus_cos_max);
        let s = SurfaceSample {
            p: p_s,
            p_error,
            n,
            pdf_area: 1.0 / self.area(),
            uv: self.uv(phi_s, theta_s).0,
        };
        (pdf.is_finite() && t.is_finite()).then_some((s, pdf))
    }

    /// The density of [`Sphere::sample_cone`] from `p` with respect to solid angle, sr⁻¹, or
    /// None when `p` is inside or on the sphere (area sampling applies there).
    pub(crate) fn pdf_cone(&self, p: Vec3) -> Option<f32> {
        let (_, _, one_minus_cos_max) = self.cone(p)?;
        Some(1.0 / (2.0 * PI * one_minus_cos_max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_from_outside_and_inside() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, 5.0), 1.0).unwrap();
        let t = s.intersect(&Ray::new(Vec3::ZERO, Vec3::Z)).unwrap();
        assert!((t - 4.0).abs() < 1e-5);
        let t = s
            .intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::Z))
            .unwrap();
        assert!((t - 1.0).abs() < 1e-5);
        assert!(s.intersect(&Ray::new(Vec3::ZERO, -Vec3::Z)).is_none());
        assert!(
            s.intersect(&Ray::new(Vec3::new(2.0, 0.0, 0.0), Vec3::Z))
                .is_none()
        );
    }

    #[test]
    fn rejects_ellipsoids_and_bad_radii() {
        let t = Transform::scale(Vec3::new(1.0, 2.0, 1.0)).unwrap();
        assert!(matches!(
            Sphere::with_transform(&t, 1.0),
            Err(GeometryError::NonUniformScale { .. })
        ));
        assert!(Sphere::new(Vec3::ZERO, 0.0).is_err());
        assert!(Sphere::new(Vec3::ZERO, f32::NAN).is_err());
        assert!(Sphere::new(Vec3::new(f32::INFINITY, 0.0, 0.0), 1.0).is_err());
    }
}
