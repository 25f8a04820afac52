//! A pbrt-v4 shape's geometry placed in the scene: under the current transformation, with its
//! material, area light (one shape per triangle or patch when the light's `power` is shared
//! so, as pbrt-v4 makes a light of each), orientation and alpha.

use std::f64::consts::PI;
use std::path::Path;

use glam::{DMat4, DVec3};

use super::params::{Params, R};
use super::quadrics::cut;
use super::{Reader, meshes};
use crate::loader::Loc;
use crate::loader::desc::*;
use crate::spectrum::Spectrum;

/// A 4×4 matrix as the row-major transform step spectrace's build applies.
pub(super) fn matrix_step(m: &DMat4) -> TransformStep {
    let c = m.to_cols_array_2d();
    let mut r = [0.0; 16];
    for (row, out) in r.chunks_mut(4).enumerate() {
        for (col, o) in out.iter_mut().enumerate() {
            *o = c[col][row];
        }
    }
    TransformStep::Matrix(r)
}

/// The shape under `m` with its emission: one shape, or, when an area light's `power` is
/// shared per triangle (pbrt-v4 makes a light of each), one per triangle.
pub(super) fn place(
    geometry: ShapeKind,
    m: DMat4,
    area: Option<f64>,
    p: &Params,
    loc: Loc,
    r: &mut Reader,
) -> R<Vec<ShapeDesc>> {
    let power = r.state.area_light.as_ref().and_then(|a| a.power);
    match geometry {
        ShapeKind::Inline {
            vertices,
            faces,
            normals,
            uvs,
        } if power.is_some() => {
            // pbrt-v4 gives each triangle the whole `power`: one shape per triangle
            let world = |i: u32| m.transform_point3(DVec3::from(vertices[i as usize]));
            let pick = |f: &[u32; 3]| f.map(|i| i as usize);
            faces
                .iter()
                .map(|f| {
                    let a = 0.5
                        * (world(f[1]) - world(f[0]))
                            .cross(world(f[2]) - world(f[0]))
                            .length();
                    let [i, j, k] = pick(f);
                    let tri = ShapeKind::Inline {
                        vertices: vec![vertices[i], vertices[j], vertices[k]],
                        faces: vec![[0, 1, 2]],
                        normals: normals.as_ref().map(|n| vec![n[i], n[j], n[k]]),
                        uvs: uvs.as_ref().map(|t| vec![t[i], t[j], t[k]]),
                    };
                    finish_shape(tri, m, Some(a), p, loc, r)
                })
                .collect()
        }
        ShapeKind::Ply { path, .. } if power.is_some() => ply_lights(&path, m, p, loc, r),
        g => finish_shape(g, m, area, p, loc, r).map(|s| vec![s]),
    }
}

/// A `plymesh` under an area light's `power`, which pbrt-v4 gives each of its triangles and
/// quads (bilinear patches, corners (q₀, q₁, q₃, q₂)) whole: the file read here, a shape per
/// triangle and per quad (each emitting over its own area), as a `trianglemesh`'s and a
/// `bilinearmesh`'s. Faces of other sizes are refused, as pbrt-v4 skips them.
fn ply_lights(path: &Path, m: DMat4, p: &Params, loc: Loc, r: &mut Reader) -> R<Vec<ShapeDesc>> {
    let ply =
        crate::geometry::shape::read_ply_polygons(path).map_err(|e| p.err(loc, e.to_string()))?;
    let sign: f64 = if r.state.reverse_orientation {
        -1.0
    } else {
        1.0
    };
    let vertices: Vec<[f64; 3]> = ply
        .positions
        .iter()
        .map(|v| v.as_dvec3().to_array())
        .collect();
    let normals: Option<Vec<[f64; 3]>> = ply
        .normals
        .as_ref()
        .map(|n| n.iter().map(|v| (sign * v.as_dvec3()).to_array()).collect());
    let uvs: Option<Vec<[f64; 2]>> = ply
        .uvs
        .as_ref()
        .map(|t| t.iter().map(|v| v.as_dvec2().to_array()).collect());
    let (mut triangles, mut quads) = (Vec::new(), Vec::new());
    for (i, f) in ply.faces.iter().enumerate() {
        if let Some(k) = f.iter().find(|&&k| k as usize >= vertices.len()) {
            return Err(p.err(
                loc,
                format!(
                    "{}: face {i} names vertex {k}, the file has {}",
                    path.display(),
                    vertices.len()
                ),
            ));
        }
        match f.as_slice() {
            &[a, b, c] => triangles.push([a, b, c]),
            &[a, b, c, d] => quads.push([a, b, d, c]),
            other => {
                return Err(p.err(
                    loc,
                    format!(
                        "{}: face {i}, of {} vertices, under an area light's \"power\" (pbrt-v4 reads triangles and quads)",
                        path.display(),
                        if other.is_empty() {
                            "fewer than three".to_string()
                        } else {
                            other.len().to_string()
                        }
                    ),
                ));
            }
        }
    }
    let mut shapes = Vec::new();
    if !triangles.is_empty() {
        let tris = ShapeKind::Inline {
            vertices: vertices.clone(),
            faces: triangles,
            normals: normals.clone(),
            uvs: uvs.clone(),
        };
        shapes.extend(place(tris, m, None, p, loc, r)?);
    }
    let patches = meshes::Bilinear::new(vertices, quads, uvs, normals);
    for i in 0..patches.len() {
        let area = patches.area(i, &m);
        shapes.push(finish_shape(
            patches.triangles(std::iter::once(i)),
            m,
            Some(area),
            p,
            loc,
            r,
        )?);
    }
    Ok(shapes)
}

/// Whether a texture looks an image (or checks) up by uv.
fn image(t: &TextureDesc) -> bool {
    match t {
        TextureDesc::Bitmap { .. } | TextureDesc::PbrtImage(_) => true,
        TextureDesc::Checkerboard { .. } => true,
        TextureDesc::Scaled(t) => t.iter().any(image),
        TextureDesc::Mix(t) => t.iter().any(image),
        _ => false,
    }
}

/// Whether a material looks an image up by uv.
fn image_textured(k: &MaterialKind) -> bool {
    match k {
        MaterialKind::Diffuse { reflectance } => image(reflectance),
        MaterialKind::Layered(l) => image(&l.reflectance) || image(&l.albedo),
        MaterialKind::DiffuseTransmission {
            reflectance,
            transmittance,
        } => image(reflectance) || image(transmittance),
        MaterialKind::Blend { a, b, weight } => {
            image_textured(a) || image_textured(b) || image(weight)
        }
        MaterialKind::BumpMap { height, inner, .. } => image(height) || image_textured(inner),
        _ => false,
    }
}

/// The shape's transform, material, emission and orientation; `area` (m²) is what an area
/// light's `power` is spread over: L = power / (sides · area · π) per unit of ∫ȳ·S dλ.
pub(super) fn finish_shape(
    kind: ShapeKind,
    m: DMat4,
    area: Option<f64>,
    p: &Params,
    loc: Loc,
    r: &mut Reader,
) -> R<ShapeDesc> {
    let textured = r
        .state
        .material
        .is_some_and(|i| image_textured(&r.materials[i].kind))
        || r.state
            .area_light
            .as_ref()
            .is_some_and(|a| a.image.is_some());
    let kind = match kind {
        // pbrt-v4's triangles without uv: (0, 0), (1, 0), (1, 1) at each one's corners
        ShapeKind::Inline { uvs: None, .. } if textured => meshes::per_triangle_uv(kind),
        ShapeKind::Ply { ref path, .. } if textured && !meshes::ply_has_uv(path) => {
            return Err(p.err(
                loc,
                format!("an image texture on a PLY mesh without uv ({}) is not read yet (pbrt-v4 gives each triangle its own default uv)", path.display()),
            ));
        }
        ShapeKind::BSplinePoints { .. } if textured => {
            return Err(p.err(
                loc,
                "an image or checkerboard texture on a curve is not read yet (pbrt-v4's uv of curves differ from spectrace's)",
            ));
        }
        k => k,
    };
    // pbrt-v4's materials reflect on both sides, so orientation matters only for a one-sided
    // area light: which side emits after `ReverseOrientation` and mirroring transforms
    // (pbrt-v4 flips quadrics and meshes differently) is not read yet
    let mirrored = m.determinant() < 0.0;
    if r.state.area_light.is_some() && cut(&kind) {
        return Err(p.err(
            loc,
            "an area light on a partial sphere, disk or cylinder is not read yet (zmin, zmax, phimax, innerradius)",
        ));
    }
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
    // an area light of alpha 0 is pbrt-v4's invisible light: never met, lighting by light
    // sampling alone
    let alpha = alpha(p, r)?;
    let emission = r.state.area_light.as_ref().map(|a| {
        let k = match (a.power, area) {
            (Some(power), Some(area)) if area > 0.0 => {
                let sides = if a.two_sided { 2.0 } else { 1.0 };
                a.scale * power / (sides * area * PI)
            }
            _ => a.scale,
        };
        super::area_light::emission(a, k)
    });
    Ok(ShapeDesc {
        kind,
        transform,
        material,
        // pbrt-v4's materials reflect on both sides
        two_sided: true,
        emission,
        // a shape between two different media changes a ray's medium; one inside the same
        // medium on both sides does not
        interior: (r.state.media.0 != r.state.media.1)
            .then_some(r.state.media.0)
            .flatten(),
        exterior: (r.state.media.0 != r.state.media.1)
            .then_some(r.state.media.1)
            .flatten(),
        unit_m: 1.0,
        alpha,
        loc,
    })
}

/// A shape's `alpha` (pbrt-v4's alpha test): a float texture or a number in [0, 1]; None
/// when 1 (opaque) or absent. Refused on an area light unless 0 (pbrt-v4 masks its emission
/// point by point; at 0 it makes the light invisible, `crate::light::AreaLight::invisible`)
/// and inside an object (instanced shapes are opaque here).
fn alpha(p: &Params, r: &Reader) -> R<Option<TextureDesc>> {
    let alpha = match p.get("alpha") {
        None => return Ok(None),
        Some(q) if q.ty == "texture" => {
            let name = q.strs.first().cloned().unwrap_or_default();
            r.float_textures.get(&name).cloned().ok_or_else(|| {
                p.err(
                    q.loc,
                    format!("\"alpha\": no float texture named \"{name}\""),
                )
            })?
        }
        Some(_) => match p.float("alpha", 1.0)? {
            a if a >= 1.0 => return Ok(None),
            a => Spectrum::Constant(a.max(0.0) as f32).into(),
        },
    };
    if r.defining.is_some() {
        return Err(p.err(
            p.loc_of("alpha"),
            "an alpha test inside ObjectBegin is not read yet",
        ));
    }
    if alpha.reads_position() {
        return Err(p.err(
            p.loc_of("alpha"),
            "an alpha texture of a spherical, cylindrical or planar mapping is not read yet (spectrace reads uv there)",
        ));
    }
    let zero = matches!(alpha, TextureDesc::Uniform(Spectrum::Constant(a)) if a <= 0.0);
    if r.state.area_light.is_some() && !zero {
        return Err(p.err(
            p.loc_of("alpha"),
            "an area light's alpha other than 0 is not read yet (pbrt-v4 masks its emission point by point)",
        ));
    }
    Ok(Some(alpha))
}
