//! pbrt-v4's shapes (`src/pbrt/shapes.cpp`): each reads its own parameters into a shape of the
//! scene description, under the current transformation, material and area light; and pbrt's
//! `LookAt`.

use std::f64::consts::PI;
use std::path::Path;

use glam::{DMat4, DVec3};

use super::params::{Params, R};
use super::placed::{finish_shape, place};
use super::quadrics::degrees;
use super::{Reader, meshes};
use crate::loader::Loc;
use crate::loader::desc::*;
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

/// A `Shape`: its geometry, the current transformation, material, orientation and area light;
/// several when an area light's `power` is shared per triangle (pbrt-v4 makes a light of each).
pub(super) fn shape(
    kind: &str,
    p: &Params,
    loc: Loc,
    r: &mut Reader,
    file: &Path,
) -> R<Vec<ShapeDesc>> {
    // the object-space area pbrt-v4's `Shape::Area` gives a quadric (its transform not applied)
    let quadric_area = |kind: &str| -> R<f64> {
        let radius = p.float("radius", 1.0)?;
        Ok(match kind {
            "sphere" => 4.0 * PI * radius * radius,
            "cylinder" => {
                2.0 * PI * radius * (p.float("zmax", 1.0)? - p.float("zmin", -1.0)?).abs()
            }
            _ => PI * radius * radius,
        })
    };
    let area = match kind {
        "sphere" | "cylinder" | "disk" => Some(quadric_area(kind)?),
        _ => None,
    };
    let geometry = match kind {
        "sphere" => {
            let radius = p.float("radius", 1.0)?;
            if !(radius > 0.0) {
                return Err(p.err(p.loc_of("radius"), "a sphere's radius must be positive"));
            }
            // pbrt-v4's defaults: the whole sphere
            ShapeKind::PbrtSphere {
                radius: len(radius),
                z: [
                    len(p.float("zmin", -radius)?),
                    len(p.float("zmax", radius)?),
                ],
                phi_max: degrees(p.float("phimax", 360.0)?),
            }
        }
        // pbrt-v4's cylinder: around z from zmin to zmax, open at both ends, normals outwards
        "cylinder" => {
            let radius = p.float("radius", 1.0)?;
            let (z0, z1) = (p.float("zmin", -1.0)?, p.float("zmax", 1.0)?);
            if !(radius > 0.0) || z0 == z1 {
                return Err(p.err(loc, "a cylinder needs a positive radius and zmin ≠ zmax"));
            }
            ShapeKind::PbrtCylinder {
                radius: len(radius),
                z: [len(z0.min(z1)), len(z0.max(z1))],
                phi_max: degrees(p.float("phimax", 360.0)?),
            }
        }
        "trianglemesh" => meshes::triangle_mesh(p, loc, r.state.reverse_orientation)?,
        "curve" => super::curves::curve(p, loc, &r.state.ctm)?,
        "loopsubdiv" => meshes::loop_subdiv(p, loc)?,
        // pbrt-v4 makes a light of each patch, `power` spread over its own area
        "bilinearmesh" => {
            let mesh = meshes::bilinear_mesh(p, loc, r.state.reverse_orientation)?;
            let m = r.state.ctm;
            if r.state
                .area_light
                .as_ref()
                .is_some_and(|a| a.power.is_some())
            {
                return (0..mesh.len())
                    .map(|i| {
                        let area = mesh.area(i, &m);
                        finish_shape(mesh.triangles(std::iter::once(i)), m, Some(area), p, loc, r)
                    })
                    .collect();
            }
            return finish_shape(mesh.triangles(0..mesh.len()), m, None, p, loc, r)
                .map(|s| vec![s]);
        }
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
            let kind = ShapeKind::PbrtDisk {
                inner: p.float("innerradius", 0.0)? / radius,
                phi_max: degrees(p.float("phimax", 360.0)?),
            };
            // the unit disk in z = 0, scaled to `radius` and raised to `height`, before the CTM
            let m = r.state.ctm
                * DMat4::from_translation(DVec3::new(0.0, 0.0, height))
                * DMat4::from_scale(DVec3::splat(radius));
            return finish_shape(kind, m, area, p, loc, r).map(|s| vec![s]);
        }
        other => {
            return Err(p.err(
                loc,
                format!("the shape \"{other}\" is not read yet (spectrace reads sphere, cylinder, disk, trianglemesh, bilinearmesh, plymesh, loopsubdiv and curve)"),
            ));
        }
    };
    let m = r.state.ctm;
    place(geometry, m, area, p, loc, r)
}
