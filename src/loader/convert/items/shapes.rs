//! `[[shapes]]`: geometry, transforms and emission.

use super::*;

pub(super) fn transform(cx: &Cx<'_>, t: &S<Vec<S<Value>>>, field: &str) -> R<Vec<TransformStep>> {
    let mut out = Vec::new();
    for (i, step) in t.get_ref().iter().enumerate() {
        let f = format!("{field}[{i}]");
        let Value::Table(tab) = step.get_ref() else {
            return Err(cx.err(
                &step.span(),
                &f,
                "expected a table like { translate = [x, y, z] }",
            ));
        };
        if tab.len() != 1 {
            return Err(cx.err(
                &step.span(),
                &f,
                "each transform step has exactly one of translate, rotate, scale, matrix, look_at",
            ));
        }
        let (key, val) = tab
            .iter()
            .next()
            .map(|(k, v)| (k.as_str(), v.clone()))
            .unwrap_or(("", Value::Boolean(false)));
        let v = S::new(step.span(), val);
        let f = format!("{f}.{key}");
        out.push(match key {
            "translate" => TransformStep::Translate(cx.point(&v, &f)?),
            "scale" => {
                let s = match v.get_ref() {
                    Value::Array(_) => cx.vec3(&v, &f)?,
                    _ => [cx.number(&v, &f)?; 3],
                };
                if s.contains(&0.0) {
                    return Err(cx.err(&step.span(), &f, "a scale factor of 0 flattens the shape"));
                }
                TransformStep::Scale(s)
            }
            "rotate" => {
                let Value::Table(r) = v.get_ref() else {
                    return Err(cx.err(&step.span(), &f, "expected { axis = [x, y, z], angle = \"30 deg\" }"));
                };
                let get = |k: &str| r.get(k).cloned().map(|x| S::new(step.span(), x));
                if let Some(k) = r.keys().find(|k| *k != "axis" && *k != "angle") {
                    return Err(cx.err(&step.span(), format!("{f}.{k}"), "unknown key; expected axis and angle"));
                }
                let axis = cx.vec3(&get("axis").ok_or_else(|| cx.err(&step.span(), &f, "missing axis"))?, &format!("{f}.axis"))?;
                if axis == [0.0; 3] {
                    return Err(cx.err(&step.span(), format!("{f}.axis"), "the rotation axis is zero"));
                }
                let angle: Angle = cx.quantity(&get("angle").ok_or_else(|| cx.err(&step.span(), &f, "missing angle"))?, &format!("{f}.angle"))?;
                TransformStep::Rotate { axis, angle }
            }
            "matrix" => {
                let Value::Array(a) = v.get_ref() else {
                    return Err(cx.err(&step.span(), &f, "expected 16 numbers, row-major"));
                };
                if a.len() != 16 {
                    return Err(cx.err(&step.span(), &f, format!("expected 16 numbers, row-major; found {}", a.len())));
                }
                let mut m = [0.0; 16];
                for (k, x) in a.iter().enumerate() {
                    m[k] = cx.number(&S::new(step.span(), x.clone()), &format!("{f}[{k}]"))?;
                }
                TransformStep::Matrix(m)
            }
            "look_at" => {
                let Value::Table(r) = v.get_ref() else {
                    return Err(cx.err(&step.span(), &f, "expected { eye = [..], target = [..], up = [..] }"));
                };
                let get = |k: &str| {
                    r.get(k).cloned().map(|x| S::new(step.span(), x)).ok_or_else(|| cx.err(&step.span(), format!("{f}.{k}"), "missing"))
                };
                TransformStep::LookAt {
                    eye: cx.point(&get("eye")?, &format!("{f}.eye"))?,
                    target: cx.point(&get("target")?, &format!("{f}.target"))?,
                    up: cx.vec3(&get("up")?, &format!("{f}.up"))?,
                }
            }
            o => {
                return Err(cx.err(&step.span(), &f, format!("unknown transform `{o}`; expected translate, rotate, scale, matrix or look_at")));
            }
        });
    }
    Ok(out)
}

/// The shape `s`, named `f` in messages (`shapes[3]`, `groups.tree.shapes[0]`).
pub(super) fn shape(
    cx: &Cx<'_>,
    f: String,
    s: &S<RawShape>,
    material_names: &[&str],
) -> R<ShapeDesc> {
    let sp = s.span();
    let s = s.get_ref();
    let all = present!(s; kind, material, file, center, radius, transform, two_sided, emission, vertices, faces, interior, exterior);
    let names: Vec<&str> = SHAPES.iter().map(|k| k.name).collect();
    let field = format!("{f}.type");
    let ty = cx.required(&s.kind, &sp, &field, &names.join(", "))?;
    let k = &SHAPES[cx.kind_index(ty.get_ref(), &ty.span(), &field, "shape", &names)?];
    let allowed: Vec<&str> = [
        "kind",
        "material",
        "transform",
        "two_sided",
        "emission",
        "interior",
        "exterior",
    ]
    .iter()
    .chain(k.keys)
    .copied()
    .collect();
    cx.only(k.what, &f, &all, &allowed)?;
    let kind = (k.read)(cx, s, &sp, &f)?;
    let transform = match &s.transform {
        Some(t) => transform(cx, t, &format!("{f}.transform"))?,
        None => Vec::new(),
    };
    let material = material_index(cx, s, &f, material_names)?;
    let emission = match &s.emission {
        Some(e) => Some(emission(cx, e, &format!("{f}.emission"))?),
        None => None,
    };
    if material.is_none() && emission.is_none() {
        return Err(cx.err(
            &sp,
            &f,
            "a shape needs a `material`, an `emission`, or both",
        ));
    }
    Ok(ShapeDesc {
        kind,
        transform,
        material,
        two_sided: s.two_sided.as_ref().is_some_and(|b| *b.get_ref()),
        emission,
        interior: None,
        exterior: None,
        unit_m: cx.unit_m,
        alpha: None,
        loc: cx.src.span(&sp),
    })
}

/// A shape kind's TOML reader: its `type` name, "a sphere" for messages, the keys it takes
/// besides every shape's (`material`, `transform`, `two_sided`, `emission`) and its reader.
struct ShapeReader {
    name: &'static str,
    what: &'static str,
    keys: &'static [&'static str],
    read: fn(&Cx<'_>, &RawShape, &Range<usize>, &str) -> R<ShapeKind>,
}

/// Every shape kind of the TOML format, one line each, in the order "expected …" lists them.
const SHAPES: &[ShapeReader] = &[
    ShapeReader {
        name: "sphere",
        what: "a sphere",
        keys: &["center", "radius"],
        read: sphere,
    },
    ShapeReader {
        name: "rectangle",
        what: "a rectangle",
        keys: &[],
        read: |_, _, _, _| Ok(ShapeKind::Rectangle),
    },
    ShapeReader {
        name: "box",
        what: "a box",
        keys: &[],
        read: |_, _, _, _| Ok(ShapeKind::Box),
    },
    ShapeReader {
        name: "disk",
        what: "a disk",
        keys: &[],
        read: |_, _, _, _| Ok(ShapeKind::Disk),
    },
    ShapeReader {
        name: "obj",
        what: "an obj mesh",
        keys: &["file"],
        read: obj,
    },
    ShapeReader {
        name: "mesh",
        what: "an inline mesh",
        keys: &["vertices", "faces"],
        read: inline_mesh,
    },
];

/// A sphere: `center` (default the origin) and a positive `radius`.
fn sphere(cx: &Cx<'_>, s: &RawShape, sp: &Range<usize>, f: &str) -> R<ShapeKind> {
    let center = match &s.center {
        Some(c) => cx.point(c, &format!("{f}.center"))?,
        None => [Length::new::<length::meter>(0.0); 3],
    };
    let r = cx.required(&s.radius, sp, &format!("{f}.radius"), "a positive length")?;
    let radius = cx.length(r, &format!("{f}.radius"))?;
    if !(radius.get::<length::meter>() > 0.0) {
        return Err(cx.err(
            &r.span(),
            format!("{f}.radius"),
            format!(
                "expected a positive radius, found {}",
                radius.get::<length::meter>() / cx.unit_m
            ),
        ));
    }
    Ok(ShapeKind::Sphere { center, radius })
}

/// An OBJ file's mesh; without normals it stays flat-shaded (the Mitsuba importer smooths it).
fn obj(cx: &Cx<'_>, s: &RawShape, sp: &Range<usize>, f: &str) -> R<ShapeKind> {
    let p = cx.required(&s.file, sp, &format!("{f}.file"), "a path to a .obj file")?;
    Ok(ShapeKind::Obj {
        path: cx.path(p.get_ref()),
        normals: MeshNormals::FromFile,
    })
}

/// An inline mesh: `vertices` [x, y, z] and `faces` [i, j, k] (0-based, in range).
fn inline_mesh(cx: &Cx<'_>, s: &RawShape, sp: &Range<usize>, f: &str) -> R<ShapeKind> {
    let v = cx.required(
        &s.vertices,
        sp,
        &format!("{f}.vertices"),
        "a list of [x, y, z]",
    )?;
    let fs = cx.required(
        &s.faces,
        sp,
        &format!("{f}.faces"),
        "a list of [i, j, k] (0-based)",
    )?;
    let vertices = v
        .get_ref()
        .iter()
        .enumerate()
        .map(|(i, p)| cx.vec3(p, &format!("{f}.vertices[{i}]")))
        .collect::<R<Vec<_>>>()?;
    let mut faces = Vec::new();
    for (i, t) in fs.get_ref().iter().enumerate() {
        let idx = cx.vec3(t, &format!("{f}.faces[{i}]"))?;
        if idx
            .iter()
            .any(|&k| k < 0.0 || k.fract() != 0.0 || k as usize >= vertices.len())
        {
            return Err(cx.err(
                &t.span(),
                format!("{f}.faces[{i}]"),
                format!(
                    "expected 3 vertex indices from 0 to {}",
                    vertices.len().saturating_sub(1)
                ),
            ));
        }
        faces.push(idx.map(|k| k as u32));
    }
    Ok(ShapeKind::Inline {
        vertices,
        faces,
        normals: None,
        uvs: None,
    })
}

/// The index of the shape's `material` among the file's materials, an error naming them if
/// it is not one.
fn material_index(cx: &Cx<'_>, s: &RawShape, f: &str, material_names: &[&str]) -> R<Option<usize>> {
    Ok(match &s.material {
        Some(m) => Some(
            material_names
                .iter()
                .position(|n| *n == m.get_ref())
                .ok_or_else(|| {
                    cx.err(
                        &m.span(),
                        format!("{f}.material"),
                        format!(
                            "refers to material \"{}\", which is not defined; defined: {}",
                            m.get_ref(),
                            if material_names.is_empty() {
                                "none".to_string()
                            } else {
                                material_names.join(", ")
                            }
                        ),
                    )
                })?,
        ),
        None => None,
    })
}

/// An error at `v` (the field `field`) if its amount `x` is negative: light cannot be.
pub(super) fn non_negative(cx: &Cx<'_>, v: &S<Value>, field: &str, x: f64) -> R<()> {
    if x >= 0.0 {
        return Ok(());
    }
    Err(cx.err(
        &v.span(),
        field,
        format!("light cannot be negative, found {x}"),
    ))
}

/// Exactly one of the listed amount keys.
pub(super) fn one_amount<'v>(
    cx: &Cx<'_>,
    span: &Range<usize>,
    field: &str,
    opts: &[(&'static str, &'v Option<S<Value>>)],
) -> R<(&'static str, &'v S<Value>)> {
    let given: Vec<_> = opts
        .iter()
        .filter_map(|(n, v)| v.as_ref().map(|v| (*n, v)))
        .collect();
    let names = opts.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ");
    match given.as_slice() {
        [one] => Ok(*one),
        [] => Err(cx.err(span, field, format!("missing; give exactly one of {names}"))),
        [_, second, ..] => Err(cx.err(
            &second.1.span(),
            format!("{field}.{}", second.0),
            format!("give exactly one of {names}"),
        )),
    }
}

pub(super) fn emission(cx: &Cx<'_>, e: &S<RawEmission>, f: &str) -> R<EmissionDesc> {
    let sp = e.span();
    let e = e.get_ref();
    let spectrum = match &e.spectrum {
        Some(s) => cx.spectrum(s, &format!("{f}.spectrum"), SpectrumUse::Emission)?,
        None => Spectrum::Constant(1.0),
    };
    let amount = emit_amount(cx, &sp, f, &e.radiance, &e.luminance, &e.power, &e.scale)?;
    Ok(EmissionDesc {
        texture: None,
        spectrum,
        amount,
        two_sided: e.two_sided.as_ref().is_some_and(|b| *b.get_ref()),
        sampling_weight: 1.0,
        loc: cx.src.span(&sp),
    })
}

pub(super) fn emit_amount(
    cx: &Cx<'_>,
    sp: &Range<usize>,
    f: &str,
    radiance: &Option<S<Value>>,
    luminance: &Option<S<Value>>,
    power: &Option<S<Value>>,
    scale: &Option<S<Value>>,
) -> R<EmitAmount> {
    let (which, v) = one_amount(
        cx,
        sp,
        f,
        &[
            ("radiance", radiance),
            ("luminance", luminance),
            ("power", power),
            ("scale", scale),
        ],
    )?;
    let field = format!("{f}.{which}");
    let amount = match which {
        "radiance" => EmitAmount::Radiance(cx.quantity::<Radiance>(v, &field)?),
        "luminance" => EmitAmount::Luminance(cx.quantity::<Luminance>(v, &field)?),
        "power" => match cx.quantity_of(v, &field, &[D::Power, D::LuminousFlux])? {
            (D::Power, w) => EmitAmount::Power(Power::new::<power::watt>(w)),
            (_, lm) => EmitAmount::LuminousFlux(LuminousFlux::new::<luminous_flux::lumen>(lm)),
        },
        _ => EmitAmount::Scale(cx.number(v, &field)?),
    };
    let si = match &amount {
        EmitAmount::Radiance(r) => r.get::<radiance::watt_per_square_meter_steradian>(),
        EmitAmount::Luminance(l) => l.get::<luminance::candela_per_square_meter>(),
        EmitAmount::Power(p) => p.get::<power::watt>(),
        EmitAmount::LuminousFlux(p) => p.get::<luminous_flux::lumen>(),
        EmitAmount::Scale(s) => *s,
    };
    non_negative(cx, v, &field, si)?;
    Ok(amount)
}
