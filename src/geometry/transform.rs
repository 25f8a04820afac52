//! Affine transforms with their inverses.
//!
//! A [`Transform`] maps object space to world space (or camera space to world space). Lengths
//! are in metres, angles in radians, rotations are right-handed (counter-clockwise looking down
//! the axis toward the origin). Every constructor validates its input, so a `Transform` always
//! holds a finite, invertible, affine matrix and its finite inverse.

use super::error::{GeometryError, check_finite, check_finite3};
use glam::{Mat3, Mat4, Vec3, Vec4};

/// An invertible affine transform (object → world) and its inverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    m: Mat4,
    inv: Mat4,
}

impl Default for Transform {
    fn default() -> Self {
        Self::identity()
    }
}

impl Transform {
    /// The identity.
    pub const fn identity() -> Transform {
        Transform {
            m: Mat4::IDENTITY,
            inv: Mat4::IDENTITY,
        }
    }

    /// Translation by `v` (m). Errors if `v` is not finite.
    pub fn translate(v: Vec3) -> Result<Transform, GeometryError> {
        check_finite3("translation", v)?;
        Ok(Transform {
            m: Mat4::from_translation(v),
            inv: Mat4::from_translation(-v),
        })
    }

    /// Right-handed rotation by `angle_rad` about `axis` (any non-zero length). Errors for a zero
    /// or non-finite axis or a non-finite angle.
    pub fn rotate(axis: Vec3, angle_rad: f32) -> Result<Transform, GeometryError> {
        check_finite3("rotation axis", axis)?;
        check_finite("rotation angle", angle_rad)?;
        let axis = axis
            .try_normalize()
            .ok_or(GeometryError::ZeroAxis(axis.to_array()))?;
        let m = Mat4::from_axis_angle(axis, angle_rad);
        Ok(Transform {
            m,
            inv: m.transpose(),
        })
    }

    /// Scaling by `s` along the axes. Errors if any factor is zero or not finite (negative
    /// factors mirror and are allowed).
    pub fn scale(s: Vec3) -> Result<Transform, GeometryError> {
        check_finite3("scale", s)?;
        let inv = s.recip();
        if s.x == 0.0 || s.y == 0.0 || s.z == 0.0 || !inv.is_finite() {
            return Err(GeometryError::SingularMatrix {
                determinant: s.element_product(),
            });
        }
        Ok(Transform {
            m: Mat4::from_scale(s),
            inv: Mat4::from_scale(inv),
        })
    }

    /// Camera-to-world transform of a camera at `eye` looking at `target`.
    ///
    /// Camera space (Mitsuba's convention, right-handed): **+z looks forward** (toward the
    /// target), **+y is up** (`up` projected perpendicular to the view direction) and **+x points
    /// to the camera's left**. Errors if `eye == target`, if `up` is zero or parallel to the view
    /// direction, or if any input is not finite.
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3) -> Result<Transform, GeometryError> {
        check_finite3("look_at eye", eye)?;
        check_finite3("look_at target", target)?;
        check_finite3("look_at up", up)?;
        let dir = (target - eye)
            .try_normalize()
            .ok_or(GeometryError::LookAt("eye and target coincide"))?;
        let up_n = up
            .try_normalize()
            .ok_or(GeometryError::LookAt("up vector is zero"))?;
        let left = up_n.cross(dir);
        if left.length() < 1e-6 {
            return Err(GeometryError::LookAt(
                "up vector is parallel to the view direction",
            ));
        }
        let left = left.normalize();
        let new_up = dir.cross(left);
        let m = Mat4::from_cols(
            left.extend(0.0),
            new_up.extend(0.0),
            dir.extend(0.0),
            eye.extend(1.0),
        );
        Transform::from_matrix(m)
    }

    /// A transform from a column-major matrix (glam convention: `m * p` with column vectors).
    ///
    /// Errors if an entry is not finite, if the bottom row is not (0, 0, 0, 1) within 1e-6 (only
    /// affine transforms are supported), or if the matrix is numerically singular: determinant
    /// zero, linear part's |det| ≤ f32::EPSILON × the product of its column lengths (columns
    /// dependent to within rounding), or an inverse with `m · m⁻¹` off the identity by > 1e-3.
    pub fn from_matrix(m: Mat4) -> Result<Transform, GeometryError> {
        if !m.is_finite() {
            return Err(GeometryError::NotFinite {
                what: "transform matrix",
                value: format!("{m}"),
            });
        }
        let row = m.row(3);
        if !row.abs_diff_eq(Vec4::W, 1e-6) {
            return Err(GeometryError::NotAffine {
                row: row.to_array(),
            });
        }
        let mut m = m;
        // Make the bottom row exact.
        m.x_axis.w = 0.0;
        m.y_axis.w = 0.0;
        m.z_axis.w = 0.0;
        m.w_axis.w = 1.0;
        let determinant = m.determinant();
        let inv = m.inverse();
        // Relative volume of the column parallelepiped: below f32 precision, a rounding-sized
        // change of the entries could make the matrix singular.
        let lin = Mat3::from_mat4(m);
        let col_norms = lin.x_axis.length() * lin.y_axis.length() * lin.z_axis.length();
        let singular = determinant == 0.0
            || lin.determinant().abs() <= f32::EPSILON * col_norms
            || !inv.is_finite()
            || !(m * inv).abs_diff_eq(Mat4::IDENTITY, 1e-3)
            || !(inv * m).abs_diff_eq(Mat4::IDENTITY, 1e-3);
        if singular {
            return Err(GeometryError::SingularMatrix { determinant });
        }
        Ok(Transform { m, inv })
    }

    /// `self` followed by `next`: `a.then(&b).point(p) == b.point(a.point(p))`.
    pub fn then(&self, next: &Transform) -> Transform {
        Transform {
            m: next.m * self.m,
            inv: self.inv * next.inv,
        }
    }

    /// Transforms a point.
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        self.m.transform_point3(p)
    }

    /// Transforms a direction or offset (ignores the translation).
    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.m.transform_vector3(v)
    }

    /// Transforms a surface normal with the inverse transpose, so that it stays perpendicular to
    /// transformed tangents. The result is **not** normalised.
    #[inline]
    pub fn normal(&self, n: Vec3) -> Vec3 {
        Mat3::from_mat4(self.inv).transpose() * n
    }

    /// The bounds (min, max) of the box `lo`–`hi` transformed: its eight corners' (without
    /// padding for their rounding).
    pub fn box_bounds(&self, lo: Vec3, hi: Vec3) -> (Vec3, Vec3) {
        let mut b = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for k in 0..8 {
            let c = Vec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            );
            let w = self.point(c);
            b = (b.0.min(w), b.1.max(w));
        }
        b
    }

    /// The inverse transform (world → object).
    pub fn inverse(&self) -> Transform {
        Transform {
            m: self.inv,
            inv: self.m,
        }
    }

    /// The object-to-world matrix.
    pub fn matrix(&self) -> Mat4 {
        self.m
    }

    /// The world-to-object matrix.
    pub fn inverse_matrix(&self) -> Mat4 {
        self.inv
    }

    /// True if the transform mirrors (negative determinant of the linear part), which flips the
    /// winding of triangles.
    pub fn swaps_handedness(&self) -> bool {
        Mat3::from_mat4(self.m).determinant() < 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_round_trips() {
        let t = Transform::rotate(Vec3::new(1.0, 2.0, 3.0), 0.7)
            .unwrap()
            .then(&Transform::scale(Vec3::new(2.0, -3.0, 0.5)).unwrap())
            .then(&Transform::translate(Vec3::new(4.0, 5.0, 6.0)).unwrap());
        let p = Vec3::new(0.3, -1.2, 2.5);
        assert!((t.inverse().point(t.point(p)) - p).length() < 1e-5);
        assert!(t.swaps_handedness());
    }

    #[test]
    fn rejects_bad_matrices() {
        assert!(Transform::from_matrix(Mat4::ZERO).is_err());
        assert!(Transform::from_matrix(Mat4::from_cols_array(&[f32::NAN; 16])).is_err());
        let mut proj = Mat4::IDENTITY;
        proj.z_axis.w = 1.0;
        assert!(Transform::from_matrix(proj).is_err());
        assert!(Transform::scale(Vec3::new(1.0, 0.0, 1.0)).is_err());
        assert!(Transform::rotate(Vec3::ZERO, 1.0).is_err());
    }
}
