//! Mitsuba shapes and emitters.

use std::collections::HashMap;

use super::bsdf::bsdf;
use super::cx::{Cx, R};
use super::emitters::sampling_weight;
use super::xml::Element;
use crate::loader::desc::*;
use crate::spectrum::Spectrum;
use crate::units::{Length, length};

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
    let kind = shape_kind(cx, s, t)?;
    if cx.child(s, "flip_normals").and_then(|f| f.attr("value")) == Some("true")
        && !matches!(kind, ShapeKind::Cylinder { .. })
    {
        // a mirror through the object's z = 0 plane reverses the winding and the normal
        transform.insert(0, TransformStep::Scale([1.0, 1.0, -1.0]));
    }
    let mut material = None;
    let mut two_sided = false;
    let mut emission = None;
    let (mut interior, mut exterior) = (None, None);
    for c in &s.children {
        match c.tag.as_str() {
            "bsdf" => {
                let (m, two) = bsdf(cx, c, &format!("shape@{}", cx.loc(s).line))?;
                material = Some(materials.len());
                two_sided = two;
                materials.push(m);
            }
            "ref" | "medium" if matches!(c.attr("name"), Some("interior") | Some("exterior")) => {
                let side = c.attr("name").unwrap_or_default();
                let m = super::media::medium_index(cx, c, &format!("{side}@{}", cx.loc(s).line))?;
                if side == "interior" {
                    interior = Some(m);
                } else {
                    exterior = Some(m);
                }
            }
            // a reference to a BSDF, or to an area emitter declared at the top level
            "ref" if cx.resolve(c)?.tag == "emitter" => {
                emission = Some(area_emitter(cx, cx.resolve(c)?)?);
            }
            "ref" => {
                let id = c.attr("id").unwrap_or("");
                let &(m, two) = ids.get(id).ok_or_else(|| {
                    cx.err(
                        c,
                        format!("refers to \"{id}\", which is not a <bsdf> or area <emitter> declared before it"),
                    )
                })?;
                material = Some(m);
                two_sided = two;
            }
            "emitter" => emission = Some(area_emitter(cx, c)?),
            "medium" => {
                return Err(cx.err(
                    c,
                    "a shape's <medium> needs name=\"interior\" or name=\"exterior\"",
                ));
            }
            _ => {}
        }
    }
    if material.is_none() && emission.is_none() {
        // Mitsuba's default BSDF is diffuse with reflectance 0.5; an emitting shape without a
        // BSDF gets a black one instead (measured in Mitsuba 3.9.1: `shape.bsdf()` is
        // SmoothDiffuse with reflectance 0), which is spectrace's pure emitter (no material)
        material = Some(materials.len());
        materials.push(MaterialDesc {
            name: format!("default@{}", cx.loc(s).line),
            kind: MaterialKind::Diffuse {
                reflectance: Spectrum::Constant(0.5).into(),
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
        interior,
        exterior,
        unit_m: 1.0,
        alpha: None,
        loc: cx.loc(s),
    })
}

/// The geometry of a Mitsuba shape of type `t` (its material, emitter and transform are
/// read by [`shape`]).
fn shape_kind(cx: &Cx<'_>, s: &Element, t: &str) -> R<ShapeKind> {
    match SHAPES.iter().find(|(n, _)| *n == t) {
        Some((_, read)) => read(cx, s),
        None => Err(cx.unsupported(s, "shape", t)),
    }
}

/// A shape plugin's reader of its geometry.
type Reader = fn(&Cx<'_>, &Element) -> R<ShapeKind>;

/// The shape plugins the importer reads (besides `shapegroup` and `instance`, read by the
/// scene), one line each: the registry that dispatch and the importer's supported list come
/// from.
pub(super) const SHAPES: &[(&str, Reader)] = &[
    ("obj", obj_shape),
    ("ply", ply_shape),
    ("serialized", serialized_shape),
    ("rectangle", |_, _| Ok(ShapeKind::Rectangle)),
    ("cube", |_, _| Ok(ShapeKind::Box)),
    ("sphere", sphere_shape),
    ("disk", |_, _| Ok(ShapeKind::Disk)),
    ("cylinder", cylinder_shape),
    ("sdfgrid", sdfgrid_shape),
    ("linearcurve", |cx, s| {
        Ok(ShapeKind::LinearCurve {
            path: filename(cx, s)?,
        })
    }),
    ("bsplinecurve", |cx, s| {
        Ok(ShapeKind::BSplineCurve {
            path: filename(cx, s)?,
        })
    }),
];

/// A mesh plugin's `filename`, resolved as Mitsuba resolves it.
fn filename(cx: &Cx<'_>, s: &Element) -> R<std::path::PathBuf> {
    let f = cx
        .string(s, "filename")
        .ok_or_else(|| cx.err(s, "missing filename"))?;
    Ok(cx.resolve_file(&f))
}

/// Mitsuba's `obj`.
fn obj_shape(cx: &Cx<'_>, s: &Element) -> R<ShapeKind> {
    Ok(ShapeKind::Obj {
        path: filename(cx, s)?,
        normals: mesh_normals(cx, s)?,
    })
}

/// Mitsuba's `cylinder`.
fn cylinder_shape(cx: &Cx<'_>, s: &Element) -> R<ShapeKind> {
    let l = |x: f64| Length::new::<length::meter>(x);
    let point = |key: &str, default: [f64; 3]| -> R<[f64; 3]> {
        match cx.child(s, key) {
            Some(c) => cx.vec3(c),
            None => Ok(default),
        }
    };
    let (p0, p1) = (point("p0", [0.0; 3])?, point("p1", [0.0, 0.0, 1.0])?);
    let r = cx.opt_float(s, "radius")?.unwrap_or(1.0);
    if r <= 0.0 || p0 == p1 {
        return Err(cx.err(s, "a cylinder needs a positive radius and p0 ≠ p1"));
    }
    Ok(ShapeKind::Cylinder {
        p0: p0.map(l),
        p1: p1.map(l),
        radius: l(r),
        flipped: cx.child(s, "flip_normals").and_then(|f| f.attr("value")) == Some("true"),
    })
}

/// Mitsuba's `sphere`.
fn sphere_shape(cx: &Cx<'_>, s: &Element) -> R<ShapeKind> {
    let c = match cx.child(s, "center") {
        Some(c) => cx.vec3(c)?,
        None => [0.0; 3],
    };
    let r = cx.opt_float(s, "radius")?.unwrap_or(1.0);
    if r <= 0.0 {
        return Err(cx.err(s, "radius must be positive"));
    }
    let l = |x: f64| Length::new::<length::meter>(x);
    Ok(ShapeKind::Sphere {
        center: c.map(l),
        radius: l(r),
    })
}

/// Mitsuba's `ply`.
fn ply_shape(cx: &Cx<'_>, s: &Element) -> R<ShapeKind> {
    Ok(ShapeKind::Ply {
        path: filename(cx, s)?,
        normals: mesh_normals(cx, s)?,
    })
}

/// Mitsuba's `serialized`.
fn serialized_shape(cx: &Cx<'_>, s: &Element) -> R<ShapeKind> {
    let path = filename(cx, s)?;
    let shape_index = match cx.opt_float(s, "shape_index")? {
        None => 0,
        Some(i) if i >= 0.0 && i.fract() == 0.0 => i as usize,
        Some(i) => {
            return Err(cx.err(s, format!("shape_index must be an integer ≥ 0, not {i}")));
        }
    };
    Ok(ShapeKind::Serialized {
        path,
        shape_index,
        normals: mesh_normals(cx, s)?,
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

/// A shape's area emitter: `radiance` (Mitsuba's D65-shaped spectrum), `sampling_weight`.
fn area_emitter(cx: &Cx<'_>, c: &Element) -> R<EmissionDesc> {
    if c.attr("type") != Some("area") {
        return Err(cx.unsupported(c, "shape emitter", c.attr("type").unwrap_or("")));
    }
    // a textured radiance (a bitmap) is read as Mitsuba reads it: texel values as radiance,
    // without its D65 shaping (measured: a grey texel v emits the constant v)
    let texture = match cx.child(c, "radiance") {
        Some(r) if cx.resolve(r)?.tag == "texture" => {
            if cx.resolve(r)?.attr("type") != Some("bitmap") {
                return Err(cx.err(r, "an emitter's radiance texture must be a bitmap here"));
            }
            Some(cx.texture_of(r)?)
        }
        _ => None,
    };
    Ok(EmissionDesc {
        spectrum: if texture.is_some() {
            Spectrum::Constant(0.0)
        } else {
            cx.spectrum_prop(c, "radiance", 1.0, true)?
        },
        texture,
        amount: EmitAmount::Scale(1.0),
        two_sided: false,
        sampling_weight: sampling_weight(cx, c)?,
        loc: cx.loc(c),
    })
}

/// Mitsuba's `shapegroup` (declared at the top level with an `id`): its nested shapes, in their
/// own object space. Emitters, nested groups and instances inside are refused.
pub(super) fn shapegroup(
    cx: &Cx<'_>,
    g: &Element,
    materials: &mut Vec<MaterialDesc>,
    ids: &HashMap<String, (usize, bool)>,
) -> R<GroupDesc> {
    let id = g
        .attr("id")
        .ok_or_else(|| cx.err(g, "a shapegroup needs an id for its instances to refer to"))?;
    let mut shapes = Vec::new();
    for c in &g.children {
        match c.tag.as_str() {
            "shape" if matches!(c.attr("type"), Some("shapegroup" | "instance")) => {
                return Err(cx.err(
                    c,
                    "a shapegroup cannot hold another shapegroup or an instance",
                ));
            }
            "shape" => {
                let s = shape(cx, c, materials, ids)?;
                if s.emission.is_some() {
                    return Err(cx.err(
                        c,
                        "a shape inside a shapegroup cannot emit (Mitsuba refuses it too); place the emitter outside the group",
                    ));
                }
                if s.interior.is_some() || s.exterior.is_some() {
                    return Err(cx.err(
                        c,
                        "a shape inside a shapegroup cannot bound a medium yet; place the shape outside the group",
                    ));
                }
                shapes.push(s);
            }
            other => {
                return Err(cx.err(
                    c,
                    format!("<{other}> is not allowed in a shapegroup, only <shape>"),
                ));
            }
        }
    }
    if shapes.is_empty() {
        return Err(cx.err(g, "a shapegroup needs at least one shape"));
    }
    Ok(GroupDesc {
        id: id.to_string(),
        shapes,
        loc: cx.loc(g),
    })
}

/// Mitsuba's `instance`: a `<ref>` to a shapegroup declared before it, and `to_world`.
pub(super) fn instance(cx: &Cx<'_>, s: &Element, groups: &[GroupDesc]) -> R<InstanceDesc> {
    let r = s
        .children
        .iter()
        .find(|c| c.tag == "ref")
        .ok_or_else(|| cx.err(s, "an instance needs a <ref id=\"…\"/> to a shapegroup"))?;
    let id = r.attr("id").unwrap_or("");
    let group = groups.iter().position(|g| g.id == id).ok_or_else(|| {
        cx.err(
            r,
            format!("refers to \"{id}\", which is not a shapegroup declared before it"),
        )
    })?;
    let transform = match s.children.iter().find(|c| c.tag == "transform") {
        Some(tr) => cx.transform(tr)?,
        None => Vec::new(),
    };
    if let Some(c) = s
        .children
        .iter()
        .find(|c| matches!(c.tag.as_str(), "bsdf" | "emitter"))
    {
        return Err(cx.err(c, "an instance takes its shapes' materials from the group; a <bsdf> or <emitter> here has no effect in Mitsuba and is refused"));
    }
    Ok(InstanceDesc {
        group,
        transform,
        unit_m: 1.0,
        loc: cx.loc(s),
    })
}

/// Mitsuba's `sdfgrid`: `filename` (a one-channel `.vol` grid over the object's unit cube),
/// `normals` (`smooth`, the default, or `analytic`).
fn sdfgrid_shape(cx: &Cx<'_>, s: &Element) -> R<ShapeKind> {
    let at = |k: &str| cx.child(s, k).unwrap_or(s);
    let path = filename(cx, s)?;
    if !path.is_file() {
        return Err(cx.err(
            at("filename"),
            format!("grid file {} does not exist", path.display()),
        ));
    }
    let vol = super::vol::read(&path).map_err(|m| cx.err(at("filename"), m))?;
    if vol.channels != 1 {
        return Err(cx.err(
            at("filename"),
            format!("an SDF grid has one channel, this file {}", vol.channels),
        ));
    }
    let smooth = match cx.string(s, "normals").as_deref() {
        None | Some("smooth") => true,
        Some("analytic") => false,
        Some(o) => {
            return Err(cx.err(
                at("normals"),
                format!("normals \"{o}\" is not one of \"analytic\", \"smooth\""),
            ));
        }
    };
    Ok(ShapeKind::SdfGrid {
        res: vol.res,
        values: std::sync::Arc::new(vol.values),
        smooth,
    })
}
