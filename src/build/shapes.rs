//! Shapes: transforms in metres, then world-space geometry.

use glam::{Mat4, Vec3};
use std::sync::Arc;

use super::v3;
use crate::geometry::shape::{Clip, Cylinder, Disk, Mesh, PbrtCurve, Shape, Sphere};
use crate::geometry::transform::Transform;
use crate::loader::desc::{MeshNormals, ShapeDesc, ShapeKind, TransformStep};
use crate::units::plain;

/// The object-to-world transform: the scene unit's scale, then the steps in order.
fn transform(s: &ShapeDesc, unit_scale: bool) -> Result<Transform, String> {
    steps(&s.transform, s.unit_m, unit_scale)
}

/// A curve shape: Mitsuba's linear or B-spline curve files, or B-spline curves written in the
/// scene (pbrt-v4's, hit and shaded as its ribbons); never an emitter.
fn curve(s: &ShapeDesc) -> Result<Shape, String> {
    use crate::geometry::shape::{BSplineCurve, LinearCurve};
    if s.emission.is_some() {
        return Err("a curve cannot be an area emitter".into());
    }
    let e = |e: crate::geometry::GeometryError| e.to_string();
    Ok(match &s.kind {
        ShapeKind::LinearCurve { path } => {
            Shape::Curve(LinearCurve::load(path, &transform(s, true)?).map_err(e)?)
        }
        ShapeKind::BSplineCurve { path } => {
            Shape::BSpline(BSplineCurve::load(path, &transform(s, true)?).map_err(e)?)
        }
        ShapeKind::BSplinePoints {
            curves,
            pbrt,
            ribbon_normals,
        } => {
            let t = transform(s, true)?;
            let curves: Vec<Vec<(Vec3, f32)>> = curves
                .iter()
                .map(|c| {
                    c.iter()
                        .map(|(p, r)| (t.point(Vec3::from(p.map(|x| x as f32))), *r as f32))
                        .collect()
                })
                .collect();
            let c = BSplineCurve::new(&curves).map_err(e)?;
            Shape::BSpline(match pbrt {
                Some(PbrtCurve::Ribbon) => {
                    let n = |v: &[f64; 3]| t.normal(Vec3::from(v.map(|x| x as f32)));
                    let normals = ribbon_normals.iter().map(|[a, b]| [n(a), n(b)]).collect();
                    c.with_ribbon_normals(normals).map_err(e)?
                }
                Some(kind) => c.with_pbrt_shading(*kind),
                None => c,
            })
        }
        _ => return Err("not a curve".into()),
    })
}

/// Transform steps composed in order, after the scale `unit_m` when `unit_scale`; a matrix's
/// translation column is in units of `unit_m` metres.
pub(super) fn steps(
    list: &[TransformStep],
    unit_m: f64,
    unit_scale: bool,
) -> Result<Transform, String> {
    let e = |r: Result<Transform, crate::geometry::GeometryError>| r.map_err(|e| e.to_string());
    let u = unit_m as f32;
    let mut t = if unit_scale {
        e(Transform::scale(Vec3::splat(u)))?
    } else {
        Transform::identity()
    };
    for step in list {
        let next = match step {
            TransformStep::Translate(p) => e(Transform::translate(v3(p)))?,
            TransformStep::Rotate { axis, angle } => e(Transform::rotate(
                Vec3::new(axis[0] as f32, axis[1] as f32, axis[2] as f32),
                plain::radians(*angle),
            ))?,
            TransformStep::Scale(k) => e(Transform::scale(Vec3::new(
                k[0] as f32,
                k[1] as f32,
                k[2] as f32,
            )))?,
            TransformStep::Matrix(m) => {
                let mut cols = [0.0f32; 16];
                for r in 0..4 {
                    for c in 0..4 {
                        // row-major input; the translation column is in scene units
                        let v = m[r * 4 + c] * if c == 3 && r < 3 { unit_m } else { 1.0 };
                        cols[c * 4 + r] = v as f32;
                    }
                }
                e(Transform::from_matrix(Mat4::from_cols_array(&cols)))?
            }
            TransformStep::LookAt { eye, target, up } => e(Transform::look_at(
                v3(eye),
                v3(target),
                Vec3::new(up[0] as f32, up[1] as f32, up[2] as f32),
            ))?,
        };
        t = t.then(&next);
    }
    Ok(t)
}

/// The tube of `radius` around the object-space segment `ends` under the shape's transform,
/// and the transform. The cross-section must stay a circle perpendicular to the axis: the
/// transform may stretch along the axis (as Mitsuba's scenes do) but not across it.
fn cylinder(
    s: &ShapeDesc,
    (p0, p1): (Vec3, Vec3),
    radius: crate::units::Length,
    flipped: bool,
) -> Result<(Cylinder, Transform), String> {
    let t = transform(s, false)?;
    let axis = (p1 - p0).normalize_or_zero();
    let e1 = axis.any_orthonormal_vector();
    let (w1, w2, wa) = (t.vector(e1), t.vector(axis.cross(e1)), t.vector(axis));
    let scale = w1.length();
    let tol = 1e-5 * scale * scale;
    if (w1.length() - w2.length()).abs() > 1e-5 * scale
        || w1.dot(w2).abs() > tol
        || w1.dot(wa).abs() > tol * wa.length() / scale.max(f32::MIN_POSITIVE)
        || w2.dot(wa).abs() > tol * wa.length() / scale.max(f32::MIN_POSITIVE)
    {
        return Err("a cylinder's transform must scale its cross-section uniformly and keep it perpendicular to the axis (else the tube would be elliptic or oblique)".into());
    }
    let c = Cylinder::new(
        t.point(p0),
        t.point(p1),
        plain::metres(radius) * scale,
        flipped,
    )
    .map_err(|e| e.to_string())?;
    Ok((c, t))
}

/// Builds one shape in world space.
pub(super) fn shape(s: &ShapeDesc) -> Result<Shape, String> {
    let shape = match &s.kind {
        ShapeKind::Sphere { center, radius } => {
            // the object sphere at its centre, then the transform, whose rotation orients
            // the uv (Mitsuba: to_world · translate(center) · scale(radius))
            let t = Transform::translate(v3(center))
                .map_err(|e| e.to_string())?
                .then(&transform(s, false)?);
            Shape::Sphere(
                Sphere::with_transform(&t, plain::metres(*radius)).map_err(|e| match e {
                    crate::geometry::GeometryError::NonUniformScale { .. } => "a sphere's transform must scale uniformly (non-uniform scale would make an ellipsoid)".to_string(),
                    e => e.to_string(),
                })?,
            )
        }
        ShapeKind::Rectangle => Shape::Mesh(Mesh::rectangle(&transform(s, true)?)),
        ShapeKind::Box => Shape::Mesh(Mesh::cuboid(&transform(s, true)?)),
        ShapeKind::Cylinder {
            p0,
            p1,
            radius,
            flipped,
        } => Shape::Cylinder(cylinder(s, (v3(p0), v3(p1)), *radius, *flipped)?.0),
        ShapeKind::PbrtCylinder { radius, z, phi_max } => {
            let (z0, z1) = (plain::metres(z[0]), plain::metres(z[1]));
            let ends = (Vec3::new(0.0, 0.0, z0), Vec3::new(0.0, 0.0, z1));
            let (c, t) = cylinder(s, ends, *radius, false)?;
            let degrees = super::materials::radians(phi_max).to_degrees();
            let (x, y) = (t.vector(Vec3::X), t.vector(Vec3::Y));
            Shape::Cylinder(c.clipped(Clip::disk(1.0, 0.0, degrees), x, y))
        }
        ShapeKind::Disk => {
            Shape::Disk(Disk::new(&transform(s, true)?, 1.0).map_err(|e| e.to_string())?)
        }
        ShapeKind::PbrtDisk { inner, phi_max } => {
            let disk = Disk::new(&transform(s, true)?, 1.0).map_err(|e| e.to_string())?;
            let degrees = super::materials::radians(phi_max).to_degrees();
            Shape::Disk(disk.clipped(Clip::disk(1.0, *inner as f32, degrees)))
        }
        ShapeKind::PbrtSphere { radius, z, phi_max } => {
            let r = plain::metres(*radius);
            let sphere = Sphere::with_transform(&transform(s, false)?, r).map_err(|_| {
                "a sphere's transform must scale uniformly (non-uniform scale would make an ellipsoid)".to_string()
            })?;
            let degrees = super::materials::radians(phi_max).to_degrees();
            let (z0, z1) = (plain::metres(z[0]), plain::metres(z[1]));
            Shape::Sphere(sphere.clipped(Clip::sphere(r, z0, z1, degrees)))
        }
        ShapeKind::Obj { path, normals } => {
            let mesh = Mesh::load_obj(path, &transform(s, true)?).map_err(|e| e.to_string())?;
            Shape::Mesh(with_normals(mesh, *normals))
        }
        ShapeKind::Serialized {
            path,
            shape_index,
            normals,
        } => {
            let mesh = Mesh::load_serialized(path, *shape_index, &transform(s, true)?)
                .map_err(|e| e.to_string())?;
            Shape::Mesh(with_normals(mesh, *normals))
        }
        ShapeKind::Ply { path, normals } => {
            let mesh = Mesh::load_ply(path, &transform(s, true)?).map_err(|e| e.to_string())?;
            Shape::Mesh(with_normals(mesh, *normals))
        }
        ShapeKind::LinearCurve { .. }
        | ShapeKind::BSplineCurve { .. }
        | ShapeKind::BSplinePoints { .. } => curve(s)?,
        ShapeKind::SdfGrid {
            res,
            values,
            smooth,
        } => {
            if s.emission.is_some() {
                return Err("an SDF grid cannot be an area emitter".into());
            }
            let g = crate::geometry::shape::SdfGrid::new(
                *res,
                values.as_ref().clone(),
                transform(s, true)?,
                *smooth,
            )?;
            Shape::SdfGrid(Box::new(g))
        }
        ShapeKind::Inline { .. } => Shape::Mesh(inline_mesh(&s.kind, &transform(s, true)?)?),
    };
    // an SDF grid or a B-spline curve has no area to sample and never emits
    if !(shape.area() > 0.0 || matches!(shape, Shape::SdfGrid(_) | Shape::BSpline(_))) {
        return Err("the shape has zero area".into());
    }
    Ok(shape)
}

/// A loaded mesh's vertex normals as the description asks (normals are computed in world
/// space, as Mitsuba computes them after applying `to_world`).
fn with_normals(mut mesh: Mesh, normals: MeshNormals) -> Mesh {
    match normals {
        MeshNormals::FromFile => {}
        MeshNormals::FromFileOrSmooth => mesh.smooth_if_no_normals(),
        MeshNormals::Flat => mesh.drop_normals(),
    }
    mesh
}

/// A mesh written in the scene file (`ShapeKind::Inline`), with its optional vertex normals
/// and uv.
fn inline_mesh(
    kind: &ShapeKind,
    t: &crate::geometry::transform::Transform,
) -> Result<Mesh, String> {
    let ShapeKind::Inline {
        vertices,
        faces,
        normals,
        uvs,
    } = kind
    else {
        return Err("not a mesh written in the scene file".into());
    };
    let v3 = |v: &[f64; 3]| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
    let positions = vertices.iter().map(v3).collect();
    let normals = normals.as_ref().map(|n| n.iter().map(v3).collect());
    let uvs = uvs.as_ref().map(|t| {
        t.iter()
            .map(|t| glam::Vec2::new(t[0] as f32, t[1] as f32))
            .collect()
    });
    Mesh::new(positions, normals, uvs, faces.to_vec(), t).map_err(|e| e.to_string())
}

/// The shapes' alpha tests (pbrt-v4's `alpha`), by shape index: grey textures.
pub(super) fn alpha_tests(
    desc: &crate::loader::desc::SceneDesc,
) -> Result<Vec<Option<crate::geometry::accel::AlphaFn>>, crate::loader::LoadError> {
    let err = |loc: crate::loader::Loc, field: String, msg: String| {
        crate::loader::LoadError::new(&desc.path, loc, field, msg)
    };
    let mut alpha = Vec::with_capacity(desc.shapes.len());
    for (i, s) in desc.shapes.iter().enumerate() {
        let t = match &s.alpha {
            Some(t) => {
                let t = super::textures::texture(t)
                    .map_err(|e| err(s.loc, format!("shapes[{i}].alpha"), e))?;
                if !super::textures::is_grey(&t) {
                    return Err(err(
                        s.loc,
                        format!("shapes[{i}].alpha"),
                        "an alpha must be a grey texture".into(),
                    ));
                }
                let w = crate::spectrum::SampledWavelengths::<1> {
                    lambda: [550.0],
                    pdf: [1.0],
                };
                let f: crate::geometry::accel::AlphaFn = Arc::new(move |uv| t.sample(uv, &w).0[0]);
                Some(f)
            }
            None => None,
        };
        alpha.push(t);
    }
    Ok(alpha)
}
