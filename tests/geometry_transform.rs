//! Transforms: rotations, composition order, normals under non-uniform scale, look_at and
//! input validation.

use glam::{Mat4, Vec3, Vec4};
use spectrace::geometry::{GeometryError, Transform};
use std::f32::consts::FRAC_PI_2;

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).length() <= tol
}

#[test]
fn rotate_90_about_z_maps_x_to_y() {
    let r = Transform::rotate(Vec3::Z, FRAC_PI_2).unwrap();
    assert!(
        close(r.vector(Vec3::X), Vec3::Y, 1e-6),
        "{}",
        r.vector(Vec3::X)
    );
    assert!(close(r.vector(Vec3::Y), -Vec3::X, 1e-6));
    assert!(close(
        r.point(Vec3::new(1.0, 0.0, 5.0)),
        Vec3::new(0.0, 1.0, 5.0),
        1e-6
    ));
    // Axis length does not matter; about x, y maps to z.
    let rx = Transform::rotate(Vec3::X * 7.0, FRAC_PI_2).unwrap();
    assert!(close(rx.vector(Vec3::Y), Vec3::Z, 1e-6));
}

#[test]
fn then_applies_self_first() {
    let s = Transform::scale(Vec3::splat(2.0)).unwrap();
    let t = Transform::translate(Vec3::new(1.0, 0.0, 0.0)).unwrap();
    // Scale then translate: (1,0,0) → (2,0,0) → (3,0,0).
    assert!(close(
        s.then(&t).point(Vec3::X),
        Vec3::new(3.0, 0.0, 0.0),
        1e-6
    ));
    // Translate then scale: (1,0,0) → (2,0,0) → (4,0,0).
    assert!(close(
        t.then(&s).point(Vec3::X),
        Vec3::new(4.0, 0.0, 0.0),
        1e-6
    ));
    let m = s.then(&t);
    assert!(close(
        m.inverse().point(m.point(Vec3::new(0.3, 4.0, -2.0))),
        Vec3::new(0.3, 4.0, -2.0),
        1e-6
    ));
    assert!(m.matrix().abs_diff_eq(
        Mat4::from_translation(Vec3::X) * Mat4::from_scale(Vec3::splat(2.0)),
        1e-6
    ));
    // Vectors ignore translation.
    assert!(close(m.vector(Vec3::X), Vec3::new(2.0, 0.0, 0.0), 1e-6));
}

#[test]
fn normals_stay_perpendicular_under_non_uniform_scale() {
    let t = Transform::scale(Vec3::new(1.0, 5.0, 0.2))
        .unwrap()
        .then(&Transform::rotate(Vec3::new(1.0, 1.0, 0.0), 0.6).unwrap())
        .then(&Transform::translate(Vec3::new(3.0, -2.0, 1.0)).unwrap());
    // A tilted plane with normal n and two tangents.
    let n = Vec3::new(1.0, 1.0, 1.0).normalize();
    let (t1, t2) = (Vec3::new(1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, -2.0));
    assert!(n.dot(t1).abs() < 1e-6 && n.dot(t2).abs() < 1e-6);
    let nw = t.normal(n).normalize();
    for tan in [t1, t2] {
        let tw = t.vector(tan).normalize();
        assert!(nw.dot(tw).abs() < 1e-5, "normal·tangent = {}", nw.dot(tw));
    }
    // Transforming the normal like a vector would be wrong here.
    assert!(t.vector(n).normalize().dot(t.vector(t1).normalize()).abs() > 0.1);
}

#[test]
fn look_at_points_forward_at_the_target() {
    let (eye, target) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(-4.0, 0.5, 10.0));
    let c = Transform::look_at(eye, target, Vec3::Y).unwrap();
    let forward = c.vector(Vec3::Z);
    assert!(close(forward, (target - eye).normalize(), 1e-6));
    assert!(close(c.point(Vec3::ZERO), eye, 1e-6));
    let up = c.vector(Vec3::Y);
    assert!(
        up.dot(forward).abs() < 1e-6 && up.y > 0.0,
        "camera +y is up"
    );
    // Camera +x is the camera's left: looking down -z with +y up, left is -x.
    let c = Transform::look_at(Vec3::ZERO, -Vec3::Z, Vec3::Y).unwrap();
    assert!(close(c.vector(Vec3::X), -Vec3::X, 1e-6));
    assert!(!c.swaps_handedness(), "rigid, right-handed");
}

#[test]
fn invalid_input_is_an_error() {
    let la = |e, t, u| Transform::look_at(e, t, u).unwrap_err().to_string();
    assert!(la(Vec3::ONE, Vec3::ONE, Vec3::Y).contains("coincide"));
    assert!(la(Vec3::ZERO, Vec3::Y * 3.0, Vec3::Y).contains("parallel"));
    assert!(la(Vec3::ZERO, Vec3::Z, Vec3::ZERO).contains("zero"));
    assert!(Transform::look_at(Vec3::NAN, Vec3::Z, Vec3::Y).is_err());

    let singular = Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0));
    assert!(matches!(
        Transform::from_matrix(singular),
        Err(GeometryError::SingularMatrix { .. })
    ));
    let mut inf = Mat4::IDENTITY;
    inf.x_axis.x = f32::INFINITY;
    assert!(
        Transform::from_matrix(inf)
            .unwrap_err()
            .to_string()
            .contains("not finite")
    );
    let mut proj = Mat4::IDENTITY;
    proj.x_axis.w = 0.5;
    assert!(matches!(
        Transform::from_matrix(proj),
        Err(GeometryError::NotAffine { .. })
    ));
    // Numerically singular: two columns parallel up to rounding.
    let nearly = Mat4::from_cols(
        Vec4::new(1.0, 2.0, 3.0, 0.0),
        Vec4::new(2.0, 4.0, 6.000001, 0.0),
        Vec4::new(0.0, 1.0, 1.0, 0.0),
        Vec4::W,
    );
    assert!(Transform::from_matrix(nearly).is_err());
    // Badly scaled but exactly invertible is fine.
    assert!(Transform::from_matrix(Mat4::from_scale(Vec3::new(1e5, 1e-4, 1.0))).is_ok());

    assert!(Transform::scale(Vec3::new(2.0, 0.0, 1.0)).is_err());
    assert!(Transform::scale(Vec3::new(2.0, f32::NAN, 1.0)).is_err());
    assert!(Transform::translate(Vec3::new(f32::INFINITY, 0.0, 0.0)).is_err());
    assert!(
        Transform::rotate(Vec3::ZERO, 1.0)
            .unwrap_err()
            .to_string()
            .contains("non-zero")
    );
    assert!(Transform::rotate(Vec3::Z, f32::NAN).is_err());

    // A valid general affine matrix round-trips.
    let m = Mat4::from_cols(
        Vec4::new(1.0, 0.2, 0.0, 0.0),
        Vec4::new(0.0, 2.0, 0.3, 0.0),
        Vec4::new(0.1, 0.0, 0.5, 0.0),
        Vec4::new(4.0, 5.0, 6.0, 1.0),
    );
    let t = Transform::from_matrix(m).unwrap();
    assert!((t.matrix() * t.inverse_matrix()).abs_diff_eq(Mat4::IDENTITY, 1e-6));
}
