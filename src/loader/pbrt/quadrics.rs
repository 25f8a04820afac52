//! pbrt-v4's quadrics' parameters: angles in degrees, and whether a sphere, disk or cylinder
//! is cut (`zmin`, `zmax`, `phimax`, `innerradius`).

use crate::loader::desc::ShapeKind;
use crate::units::length::meter;

/// An angle of `x` degrees.
pub(super) fn degrees(x: f64) -> crate::units::Angle {
    crate::units::Angle::new::<crate::units::angle::degree>(x)
}

/// Whether a pbrt-v4 quadric is cut (`zmin`, `zmax`, `phimax`, `innerradius`): then it cannot
/// emit, whose sampling would need the part kept.
pub(super) fn cut(kind: &ShapeKind) -> bool {
    let m = |l: &crate::units::Length| l.get::<meter>();
    let whole = |a: &crate::units::Angle| a.get::<crate::units::angle::degree>() >= 360.0;
    match kind {
        ShapeKind::PbrtSphere { radius, z, phi_max } => {
            let r = m(radius);
            z[0].min(z[1]).get::<meter>() > -r || m(&z[0]).max(m(&z[1])) < r || !whole(phi_max)
        }
        ShapeKind::PbrtDisk { inner, phi_max } => *inner > 0.0 || !whole(phi_max),
        ShapeKind::PbrtCylinder { phi_max, .. } => !whole(phi_max),
        _ => false,
    }
}
