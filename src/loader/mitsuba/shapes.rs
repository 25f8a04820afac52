//! Mitsuba shapes and emitters.

use std::collections::HashMap;

use super::bsdf::bsdf;
use super::convert::{Cx, R};
use super::sensor::camera_frame;
use super::xml::Element;
use crate::loader::desc::*;
use crate::spectrum::Spectrum;
use crate::units::{Angle, Length, angle, length};

pub(super) fn shape(
    cx: &Cx<'_>,
    s: &Element,
    materials: &mut Vec<MaterialDesc>,
    ids: &HashMap<String, (usize, bool)>,
) -> R<ShapeDesc> {
    let t = s.attr("type").unwrap_or("");
    let mut transform = match s.children.iter().find(|c| c.tag == "transform") {
        Some(tr) => cx.transform(tr)?,
        None => Vec::new(),
    };
    let kind = match t {
        "obj" => {
            let f = cx
                .string(s, "filename")
                .ok_or_else(|| cx.err(s, "missing filename"))?;
            ShapeKind::Obj {
                path: cx.dir(s).join(f),
                normals: mesh_normals(cx, s)?,
            }
        }
        "rectangle" => ShapeKind::Rectangle,
        "cube" => ShapeKind::Box,
        "disk" => ShapeKind::Disk,
        "sphere" => {
            let c = match cx.child(s, "center") {
                Some(c) => cx.vec3(c)?,
                None => [0.0; 3],
            };
            let r = cx.opt_float(s, "radius")?.unwrap_or(1.0);
            if r <= 0.0 {
                return Err(cx.err(s, "radius must be positive"));
            }
            let l = |x: f64| Length::new::<length::meter>(x);
            ShapeKind::Sphere {
                center: c.map(l),
                radius: l(r),
            }
        }
        "ply" => {
            let f = cx
                .string(s, "filename")
                .ok_or_else(|| cx.err(s, "missing filename"))?;
            ShapeKind::Ply {
                path: cx.dir(s).join(f),
                normals: mesh_normals(cx, s)?,
            }
        }
        other => return Err(cx.unsupported(s, "shape", other)),
    };
    if cx.child(s, "flip_normals").and_then(|f| f.attr("value")) == Some("true") {
        // a mirror through the object's z = 0 plane reverses the winding and the normal
        transform.insert(0, TransformStep::Scale([1.0, 1.0, -1.0]));
    }
    let mut material = None;
    let mut two_sided = false;
    let mut emission = None;
    for c in &s.children {
        match c.tag.as_str() {
            "bsdf" => {
                let (m, two) = bsdf(cx, c, &format!("shape@{}", cx.loc(s).line))?;
                material = Some(materials.len());
                two_sided = two;
                materials.push(m);
            }
            "ref" => {
                let id = c.attr("id").unwrap_or("");
                let &(m, two) = ids.get(id).ok_or_else(|| {
                    cx.err(c, format!("refers to bsdf \"{id}\", which is not defined"))
                })?;
                material = Some(m);
                two_sided = two;
            }
            "emitter" => {
                if c.attr("type") != Some("area") {
                    return Err(cx.unsupported(c, "shape emitter", c.attr("type").unwrap_or("")));
                }
                emission = Some(EmissionDesc {
                    spectrum: cx.spectrum_prop(c, "radiance", 1.0, true)?,
                    amount: EmitAmount::Scale(1.0),
                    two_sided: false,
                    sampling_weight: sampling_weight(cx, c)?,
                    loc: cx.loc(c),
                });
            }
            _ => {}
        }
    }
    if material.is_none() {
        // Mitsuba's default BSDF is diffuse with reflectance 0.5
        material = Some(materials.len());
        materials.push(MaterialDesc {
            name: format!("default@{}", cx.loc(s).line),
            kind: MaterialKind::Diffuse {
                reflectance: Spectrum::Constant(0.5),
            },
            loc: cx.loc(s),
        });
    }
    Ok(ShapeDesc {
        kind,
        transform,
        material,
        two_sided,
        emission,
        unit_m: 1.0,
        loc: cx.loc(s),
    })
}

/// Mitsuba's meshes: the file's vertex normals, or smooth ones computed from the faces when it
/// has none; `face_normals = true` shades with face normals only (src/render/mesh.cpp).
fn mesh_normals(cx: &Cx<'_>, s: &Element) -> R<MeshNormals> {
    match cx.child(s, "face_normals") {
        None => Ok(MeshNormals::FromFileOrSmooth),
        Some(c) => match c.attr("value") {
            Some("true") => Ok(MeshNormals::Flat),
            Some("false") => Ok(MeshNormals::FromFileOrSmooth),
            v => Err(cx.err(
                c,
                format!("expected true or false, found {}", v.unwrap_or("nothing")),
            )),
        },
    }
}

pub(super) fn emitter(cx: &Cx<'_>, e: &Element) -> R<LightDesc> {
    let t = e.attr("type").unwrap_or("");
    let l = |x: f64| Length::new::<length::meter>(x);
    let to_world = e.children.iter().find(|c| c.tag == "transform");
    // Mitsuba places a point light by `position` or by `to_world` (its image of the origin),
    // never both
    let position = || -> R<Point> {
        match (cx.child(e, "position"), to_world) {
            (Some(_), Some(tr)) => Err(cx.err(
                tr,
                "give either position or to_world, not both (as Mitsuba requires)",
            )),
            (Some(p), None) => Ok(cx.vec3(p)?.map(l)),
            (None, Some(tr)) => Ok(camera_frame(cx, e, &cx.transform(tr)?)?.0),
            (None, None) => Ok([l(0.0), l(0.0), l(0.0)]),
        }
    };
    let (kind, spectrum) = match t {
        "point" => (
            LightKind::Point {
                position: position()?,
                amount: PointAmount::Scale(1.0),
            },
            cx.spectrum_prop(e, "intensity", 1.0, true)?,
        ),
        "constant" => (
            LightKind::Environment {
                amount: EmitAmount::Scale(1.0),
            },
            cx.spectrum_prop(e, "radiance", 1.0, true)?,
        ),
        "directional" => {
            // Mitsuba: `direction`, or the image of +z under `to_world`, never both
            let d = match (cx.child(e, "direction"), to_world) {
                (Some(_), Some(tr)) => {
                    return Err(cx.err(
                        tr,
                        "give either direction or to_world, not both (as Mitsuba requires)",
                    ));
                }
                (Some(d), None) => cx.vec3(d)?,
                (None, Some(tr)) => {
                    let (eye, target, _) = camera_frame(cx, e, &cx.transform(tr)?)?;
                    [0, 1, 2].map(|i| target[i].value - eye[i].value)
                }
                (None, None) => [0.0, 0.0, 1.0],
            };
            (
                LightKind::Directional {
                    direction: d,
                    angular_diameter: Angle::new::<angle::radian>(0.0),
                    amount: DirectionalAmount::Scale(1.0),
                },
                cx.spectrum_prop(e, "irradiance", 1.0, true)?,
            )
        }
        "spot" => {
            let cutoff = cx.opt_float(e, "cutoff_angle")?.unwrap_or(20.0);
            let width = cx.opt_float(e, "beam_width")?.unwrap_or(cutoff * 0.75);
            let steps = match e.children.iter().find(|c| c.tag == "transform") {
                Some(tr) => cx.transform(tr)?,
                None => return Err(cx.err(e, "a spot needs a to_world with lookat")),
            };
            if let Some(t) = cx.child(e, "texture") {
                return Err(cx.err(
                    t,
                    "a spot's projected texture is not supported (spectrace has no textures yet); remove it",
                ));
            }
            let (eye, target, _) = camera_frame(cx, e, &steps)?;
            (
                LightKind::Spot {
                    position: eye,
                    target,
                    cone_angle: Angle::new::<angle::degree>(cutoff),
                    // Mitsuba's falloff is linear in the angle from beam_width to cutoff_angle
                    // (src/emitters/spot.cpp, falloff_curve)
                    falloff_start: Angle::new::<angle::degree>(width.min(cutoff)),
                    falloff: SpotFalloff::LinearAngle,
                    amount: PointAmount::Scale(1.0),
                },
                cx.spectrum_prop(e, "intensity", 1.0, true)?,
            )
        }
        other => return Err(cx.unsupported(e, "emitter", other)),
    };
    Ok(LightDesc {
        kind,
        spectrum,
        sampling_weight: sampling_weight(cx, e)?,
        loc: cx.loc(e),
    })
}

/// An emitter's `sampling_weight`: its relative probability of being chosen for emitter
/// sampling (Mitsuba 3, `Emitter`), finite and ≥ 0, 1 by default.
fn sampling_weight(cx: &Cx<'_>, e: &Element) -> R<f64> {
    let Some(c) = cx.child(e, "sampling_weight") else {
        return Ok(1.0);
    };
    let w = cx.float(c)?;
    if !(w.is_finite() && w >= 0.0) {
        return Err(cx.err(
            c,
            format!("sampling_weight must be a finite number ≥ 0, not {w}"),
        ));
    }
    Ok(w)
}
