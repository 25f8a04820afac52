//! Polarisation: Stokes vectors and Mueller matrices (issue 28), the algebra a polarised
//! transport mode is built on.
//!
//! Conventions (those of Mitsuba 3's `mueller.h`, so that its polarised scenes read the same):
//! - A **Stokes vector** (S0, S1, S2, S3) describes a beam in a *reference frame*: a unit basis
//!   vector x perpendicular to the direction of travel. S0 is the beam's radiance (any unit:
//!   W·m⁻²·sr⁻¹·nm⁻¹ in transport), S1 the excess of linear polarisation along x over that
//!   perpendicular to it, S2 that of +45° over −45°, S3 that of right over left circular
//!   polarisation, all as seen by an observer looking back along the beam toward its source.
//!   Angles are counter-clockwise in that view.
//! - A **Mueller matrix** M maps the Stokes vector arriving in its input frame to the one
//!   leaving in its output frame, S_out = M·S_in; element (0, 0) is the element's
//!   transmittance or reflectance for unpolarised light (dimensionless).
//! - A frame change of a beam is the **rotator** R(θ) (θ the angle from the old basis to the new
//!   one, counter-clockwise seen against the beam): [`rotate_stokes_basis`]. An element turned by
//!   θ about the beam is R(−θ)·M·R(θ): [`rotated_element`].
//!
//! Every value is per wavelength: a path with N hero wavelengths carries N Stokes vectors and
//! meets N Mueller matrices (a dispersive interface's differ).

pub mod complex;
pub mod elements;
pub mod fresnel;

pub use complex::Complex;

use glam::Vec3;

/// A Stokes vector (S0, S1, S2, S3), S0 in the unit of the quantity carried.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stokes(pub [f32; 4]);

/// A Mueller matrix, rows then columns, dimensionless.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mueller(pub [[f32; 4]; 4]);

impl Stokes {
    /// Unpolarised light of intensity `s0`.
    pub fn unpolarised(s0: f32) -> Self {
        Stokes([s0, 0.0, 0.0, 0.0])
    }

    /// Fully linearly polarised light of intensity `s0` at `angle` radians from the basis
    /// vector (counter-clockwise seen against the beam).
    pub fn linear(s0: f32, angle: f32) -> Self {
        Stokes([s0, s0 * (2.0 * angle).cos(), s0 * (2.0 * angle).sin(), 0.0])
    }

    /// The vector times `s`.
    pub fn scale(&self, s: f32) -> Stokes {
        Stokes(self.0.map(|x| x * s))
    }

    /// The degree of polarisation √(S1² + S2² + S3²)/S0, in [0, 1] for physical light (0 when
    /// S0 is 0).
    pub fn degree(&self) -> f32 {
        let [s0, s1, s2, s3] = self.0;
        if s0 > 0.0 {
            (s1 * s1 + s2 * s2 + s3 * s3).sqrt() / s0
        } else {
            0.0
        }
    }

    /// The degree of linear polarisation √(S1² + S2²)/S0 (0 when S0 is 0).
    pub fn degree_linear(&self) -> f32 {
        let [s0, s1, s2, _] = self.0;
        if s0 > 0.0 {
            (s1 * s1 + s2 * s2).sqrt() / s0
        } else {
            0.0
        }
    }

    /// The angle of linear polarisation, ½·atan2(S2, S1), radians in (−π/2, π/2].
    pub fn angle_linear(&self) -> f32 {
        0.5 * self.0[2].atan2(self.0[1])
    }
}

impl Mueller {
    /// The identity (a non-interacting element).
    pub const IDENTITY: Mueller = Mueller([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]);

    /// The transpose.
    pub fn transpose(&self) -> Mueller {
        let m = &self.0;
        Mueller(std::array::from_fn(|i| std::array::from_fn(|j| m[j][i])))
    }

    /// Every element times `s`.
    pub fn scale(&self, s: f32) -> Mueller {
        Mueller(self.0.map(|row| row.map(|x| x * s)))
    }
}

impl std::ops::Mul for Mueller {
    type Output = Mueller;
    fn mul(self, o: Mueller) -> Mueller {
        let (a, b) = (&self.0, &o.0);
        Mueller(std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum())
        }))
    }
}

impl std::ops::Mul<Stokes> for Mueller {
    type Output = Stokes;
    fn mul(self, s: Stokes) -> Stokes {
        let m = &self.0;
        Stokes(std::array::from_fn(|i| {
            (0..4).map(|k| m[i][k] * s.0[k]).sum()
        }))
    }
}

/// The rotator R(θ): re-expresses a Stokes vector in a basis turned by `theta` radians
/// (counter-clockwise seen against the beam). Horizontal light (1, 1, 0, 0) reads
/// (1, 0, −1, 0), −45°, in a basis turned by +45°.
pub fn rotator(theta: f32) -> Mueller {
    let (s, c) = (2.0 * theta).sin_cos();
    Mueller([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, c, s, 0.0],
        [0.0, -s, c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// The element `m` turned by `theta` radians about the beam (counter-clockwise seen against
/// it): R(−θ)·M·R(θ).
pub fn rotated_element(theta: f32, m: &Mueller) -> Mueller {
    let r = rotator(theta);
    r.transpose() * *m * r
}

/// The implicit Stokes basis of a beam travelling along `forward` (unit): a unit vector
/// perpendicular to it, a fixed function of the direction (the first tangent of
/// [`Frame::from_normal`](crate::geometry::Frame::from_normal)), as Mitsuba's `stokes_basis`.
/// Polarised transport expresses every beam's Stokes vector in this basis, so Mueller matrices
/// along a path chain by plain products.
#[inline]
pub fn stokes_basis(forward: Vec3) -> Vec3 {
    crate::geometry::Frame::from_normal(forward).s
}

/// The rotator that re-expresses a Stokes vector travelling along `forward` (unit) in the
/// basis `current` as one in the basis `target` (both unit and perpendicular to `forward`).
pub fn rotate_stokes_basis(forward: Vec3, current: Vec3, target: Vec3) -> Mueller {
    let cos = current.dot(target).clamp(-1.0, 1.0);
    let mut theta = cos.acos();
    if forward.dot(current.cross(target)) < 0.0 {
        theta = -theta;
    }
    rotator(theta)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Stokes, b: Stokes) -> bool {
        a.0.iter().zip(b.0).all(|(x, y)| (x - y).abs() < 1e-6)
    }

    #[test]
    fn rotating_the_basis_by_45_degrees_reads_horizontal_light_as_minus_45() {
        let h = Stokes([1.0, 1.0, 0.0, 0.0]);
        let r = rotator(std::f32::consts::FRAC_PI_4) * h;
        assert!(close(r, Stokes([1.0, 0.0, -1.0, 0.0])), "{r:?}");
        // the same from the bases themselves: x turned toward y, seen against a beam along +z
        let b = rotate_stokes_basis(Vec3::Z, Vec3::X, Vec3::new(1.0, 1.0, 0.0).normalize()) * h;
        assert!(close(b, r), "{b:?}");
    }

    #[test]
    fn a_rotated_element_turns_its_axis() {
        // a horizontal polariser turned by 30° passes light at 30° unchanged
        let p = rotated_element(std::f32::consts::FRAC_PI_6, &elements::linear_polariser());
        let s = Stokes::linear(1.0, std::f32::consts::FRAC_PI_6);
        assert!(close(p * s, s), "{:?}", p * s);
    }

    #[test]
    fn degree_and_angle_of_linear_light() {
        let s = Stokes::linear(2.0, 0.3);
        assert!((s.degree() - 1.0).abs() < 1e-6);
        assert!((s.degree_linear() - 1.0).abs() < 1e-6);
        assert!((s.angle_linear() - 0.3).abs() < 1e-6);
        assert_eq!(Stokes::unpolarised(1.0).degree(), 0.0);
    }
}
