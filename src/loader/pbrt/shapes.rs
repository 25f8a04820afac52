//! pbrt-v4's shapes (`src/pbrt/shapes.cpp`): each reads its own parameters into a shape of the
//! scene description, under the current transformation, material and area light; and pbrt's
//! `LookAt`.

use std::path::Path;

use glam::{DMat4, DVec3};

use super::Reader;
use super::params::{Params, R};
use crate::loader::Loc;
use crate::loader::desc::*;
use crate::spectrum::Spectrum;
use crate::units::{Length, length::meter};

/// pbrt's `LookAt`: camera-from-world for an eye, a point looked at and an up vector
/// (`Transform LookAt`, `transform.cpp`): the camera's +z towards the point, +y up, +x =
/// up × dir.
pub(super) fn look_at(v: &[f64]) -> Result<DMat4, String> {
    let (eye, at, up) = (
        DVec3::new(v[0], v[1], v[2]),
        DVec3::new(v[3], v[4], v[5]),
        DVec3::new(v[6], v[7], v[8]),
    );
    let dir = (at - eye)
        .try_normalize()
        .ok_or("LookAt: the eye and the point looked at coincide")?;
    let right = up
        .try_normalize()
        .map(|u| u.cross(dir))
        .filter(|r| r.length() > 1e-9)
        .ok_or("LookAt: the up vector is zero or along the view direction")?
        .normalize();
    let new_up = dir.cross(right);
    let world_from_camera = DMat4::from_cols(
        right.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        eye.extend(1.0),
    );
    Ok(world_from_camera.inverse())
}

pub(super) fn len(x: f64) -> Length {
    Length::new::<meter>(x)
}

/// A 4×4 matrix as the row-major transform step spectrace's build applies.
fn matrix_step(m: &DMat4) -> TransformStep {
    let c = m.to_cols_array_2d();
    let mut r = [0.0; 16];
    for (row, out) in r.chunks_mut(4).enumerate() {
        for (col, o) in out.iter_mut().enumerate() {
            *o = c[col][row];
        }
    }
    TransformStep::Matrix(r)
}

/// A `Shape`: its geometry, the current transformation, material, orientation and area light.
pub(super) fn shape(kind: &str, p: &Params, loc: Loc, r: &mut Reader, file: &Path) -> R<ShapeDesc> {
    let geometry = match kind {
        "sphere" => {
            let radius = p.float("radius", 1.0)?;
            if !(radius > 0.0) {
                return Err(p.err(p.loc_of("radius"), "a sphere's radius must be positive"));
            }
            for partial in ["zmin", "zmax", "phimax"] {
                if p.get(partial).is_some() {
                    return Err(p.err(
                        p.loc_of(partial),
                        format!("a partial sphere (\"{partial}\") is not read yet"),
                    ));
                }
            }
            ShapeKind::Sphere {
                center: [len(0.0), len(0.0), len(0.0)],
                radius: len(radius),
            }
        }
        // pbrt-v4's cylinder: around z from zmin to zmax, open at both ends, normals outwards
        "cylinder" => {
            let radius = p.float("radius", 1.0)?;
            let (z0, z1) = (p.float("zmin", -1.0)?, p.float("zmax", 1.0)?);
            if p.get("phimax").is_some() {
                return Err(p.err(
                    p.loc_of("phimax"),
                    "a partial cylinder (\"phimax\") is not read yet",
                ));
            }
            if !(radius > 0.0) || z0 == z1 {
                return Err(p.err(loc, "a cylinder needs a positive radius and zmin ≠ zmax"));
            }
            ShapeKind::Cylinder {
                p0: [len(0.0), len(0.0), len(z0.min(z1))],
                p1: [len(0.0), len(0.0), len(z0.max(z1))],
                radius: len(radius),
                flipped: false,
            }
        }
        "trianglemesh" => triangle_mesh(p, loc)?,
        "plymesh" => {
            let name = p
                .string("filename")?
                .ok_or_else(|| p.err(loc, "a plymesh needs a \"string filename\""))?;
            if p.get("displacement").is_some() {
                return Err(p.err(
                    p.loc_of("displacement"),
                    "a plymesh's displacement is not read yet",
                ));
            }
            ShapeKind::Ply {
                path: r.resolve(file, &name),
                normals: MeshNormals::FromFile,
            }
        }
        "disk" => {
            let radius = p.float("radius", 1.0)?;
            let height = p.float("height", 0.0)?;
            if p.get("innerradius").is_some() || p.get("phimax").is_some() {
                return Err(p.err(loc, "a partial disk (innerradius, phimax) is not read yet"));
            }
            // the unit disk in z = 0, scaled to `radius` and raised to `height`, before the CTM
            let m = r.state.ctm
                * DMat4::from_translation(DVec3::new(0.0, 0.0, height))
                * DMat4::from_scale(DVec3::splat(radius));
            return finish_shape(ShapeKind::Disk, m, p, loc, r);
        }
        other => {
            return Err(p.err(
                loc,
                format!("the shape \"{other}\" is not read yet (spectrace reads sphere, cylinder, disk, trianglemesh and plymesh)"),
            ));
        }
    };
    let m = r.state.ctm;
    finish_shape(geometry, m, p, loc, r)
}

/// The shape's transform, material, emission and orientation.
fn finish_shape(kind: ShapeKind, m: DMat4, p: &Params, loc: Loc, r: &mut Reader) -> R<ShapeDesc> {
    // pbrt-v4's materials reflect on both sides, so orientation matters only for a one-sided
    // area light: which side emits after `ReverseOrientation` and mirroring transforms
    // (pbrt-v4 flips quadrics and meshes differently) is not read yet
    let mirrored = m.determinant() < 0.0;
    if let Some(a) = &r.state.area_light
        && !a.two_sided
        && (r.state.reverse_orientation || mirrored)
    {
        return Err(p.err(
            loc,
            "a one-sided area light under ReverseOrientation or a mirroring transform is not read yet (make it \"bool twosided\" true)",
        ));
    }
    let transform = vec![matrix_step(&m)];
    let material = Some(match r.state.material {
        Some(m) => m,
        None => *r.default_material.get_or_insert_with(|| {
            r.materials.push(MaterialDesc {
                name: "pbrt-v4 default diffuse".into(),
                kind: MaterialKind::Diffuse {
                    reflectance: Spectrum::Constant(0.5).into(),
                },
                loc,
            });
            r.materials.len() - 1
        }),
    });
    let emission = r.state.area_light.as_ref().map(|a| EmissionDesc {
        spectrum: a.spectrum.clone(),
        texture: None,
        amount: EmitAmount::Scale(a.scale),
        two_sided: a.two_sided,
        sampling_weight: 1.0,
        loc: a.loc,
    });
    Ok(ShapeDesc {
        kind,
        transform,
        material,
        // pbrt-v4's materials reflect on both sides
        two_sided: true,
        emission,
        interior: None,
        exterior: None,
        unit_m: 1.0,
        loc,
    })
}

/// `trianglemesh`: `point3 P` and `integer indices` (optional for a single triangle).
fn triangle_mesh(p: &Params, loc: Loc) -> R<ShapeKind> {
    let pts = p
        .nums("P", &["point3", "point"])?
        .ok_or_else(|| p.err(loc, "a trianglemesh needs \"point3 P\""))?;
    if !pts.len().is_multiple_of(3) || pts.len() < 9 {
        return Err(p.err(
            p.loc_of("P"),
            "\"P\" must hold 3 numbers per vertex, 3 vertices or more",
        ));
    }
    let n = pts.len() / 3;
    let idx: Vec<f64> = match p.nums("indices", &["integer"])? {
        Some(v) => v.to_vec(),
        None if n == 3 => vec![0.0, 1.0, 2.0],
        None => {
            return Err(p.err(
                loc,
                "a trianglemesh of more than 3 vertices needs \"integer indices\"",
            ));
        }
    };
    if !idx.len().is_multiple_of(3)
        || idx
            .iter()
            .any(|&i| i < 0.0 || i.fract() != 0.0 || i as usize >= n)
    {
        return Err(p.err(
            p.loc_of("indices"),
            format!("\"indices\" must be whole numbers below {n}, 3 per triangle"),
        ));
    }
    for unread in ["N", "uv", "S", "faceIndices"] {
        if p.get(unread).is_some() {
            return Err(p.err(
                p.loc_of(unread),
                format!("a trianglemesh's \"{unread}\" is not read yet"),
            ));
        }
    }
    Ok(ShapeKind::Inline {
        vertices: pts.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
        faces: idx
            .chunks(3)
            .map(|c| [c[0] as u32, c[1] as u32, c[2] as u32])
            .collect(),
    })
}
