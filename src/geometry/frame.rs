//! Orthonormal frames for local shading coordinates (normal along +z).

use glam::Vec3;

/// An orthonormal basis (s, t, n). Local coordinates have n = +z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit vector `n` (Duff et al. 2017, "Building an Orthonormal Basis,
    /// Revisited").
    #[inline]
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }

    /// A frame with normal `n` and first tangent along `s` projected perpendicular to `n` (Gram–
    /// Schmidt, as Mitsuba 3 builds its shading frame from ∂p/∂u), t = n × s. Falls back to
    /// [`Frame::from_normal`] when `s` is zero, not finite, or within about 0.06° of `n`, where
    /// the projection would lose its orthogonality to rounding.
    #[inline]
    pub fn from_normal_tangent(n: Vec3, s: Vec3) -> Self {
        let perp = s - n * n.dot(s);
        let l2 = perp.length_squared();
        if l2 > 1e-6 * s.length_squared() && l2.is_finite() && l2 > 0.0 {
            let s = perp / l2.sqrt();
            Self {
                s,
                t: n.cross(s),
                n,
            }
        } else {
            Self::from_normal(n)
        }
    }

    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orthonormal_and_round_trips() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.81).normalize(),
        ] {
            let f = Frame::from_normal(n);
            assert!(
                f.s.dot(f.t).abs() < 1e-6 && f.s.dot(f.n).abs() < 1e-6 && f.t.dot(f.n).abs() < 1e-6
            );
            assert!((f.s.cross(f.t) - f.n).length() < 1e-5, "right-handed");
            let v = Vec3::new(0.2, 0.7, -0.4);
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-6);
            assert!((f.to_local(n) - Vec3::Z).length() < 1e-6);
        }
    }
}
