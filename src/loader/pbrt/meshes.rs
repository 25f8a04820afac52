//! pbrt-v4's meshes written in the scene file (`src/pbrt/shapes.cpp`): `trianglemesh` and
//! `loopsubdiv` (`crate::geometry::shape::loop_subdivide`).

use glam::{DVec2, DVec3};

use super::params::{Params, R};
use crate::loader::Loc;
use crate::loader::desc::ShapeKind;

/// `P` and `indices` of a mesh: whole indices below the vertex count, `per` to a face.
fn positions_and_indices(
    p: &Params,
    loc: Loc,
    kind: &str,
    per: usize,
) -> R<(Vec<[f64; 3]>, Vec<u32>)> {
    let pts = p
        .nums("P", &["point3", "point"])?
        .ok_or_else(|| p.err(loc, format!("a {kind} needs \"point3 P\"")))?;
    if !pts.len().is_multiple_of(3) || pts.len() < 3 * per {
        return Err(p.err(
            p.loc_of("P"),
            format!("\"P\" must hold 3 numbers per vertex, {per} vertices or more"),
        ));
    }
    let n = pts.len() / 3;
    let idx: Vec<f64> = match p.nums("indices", &["integer"])? {
        Some(v) => v.to_vec(),
        // pbrt-v4: a single triangle (or patch) needs no indices
        None if n == per => (0..per).map(|i| i as f64).collect(),
        None => {
            return Err(p.err(
                loc,
                format!("a {kind} of more than {per} vertices needs \"integer indices\""),
            ));
        }
    };
    if !idx.len().is_multiple_of(per)
        || idx
            .iter()
            .any(|&i| i < 0.0 || i.fract() != 0.0 || i as usize >= n)
    {
        return Err(p.err(
            p.loc_of("indices"),
            format!("\"indices\" must be whole numbers below {n}, {per} per face"),
        ));
    }
    Ok((
        pts.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
        idx.iter().map(|&i| i as u32).collect(),
    ))
}

/// A mesh's per-vertex `point2 uv` and `normal N` (N negated under `ReverseOrientation`), each
/// one per each of the `n` vertices; the parameters `unread` of a `kind` refused.
#[allow(clippy::type_complexity)]
fn vertex_data(
    p: &Params,
    kind: &str,
    n: usize,
    reverse: bool,
    unread: &[&str],
) -> R<(Option<Vec<[f64; 2]>>, Option<Vec<[f64; 3]>>)> {
    for &name in unread {
        if p.get(name).is_some() {
            return Err(p.err(
                p.loc_of(name),
                format!("a {kind}'s \"{name}\" is not read yet"),
            ));
        }
    }
    let per_vertex = |name: &str, ty: &[&str], k: usize| -> R<Option<Vec<f64>>> {
        let Some(v) = p.nums(name, ty)? else {
            return Ok(None);
        };
        if v.len() != k * n {
            return Err(p.err(
                p.loc_of(name),
                format!("\"{name}\" must hold {k} numbers for each of the {n} vertices"),
            ));
        }
        Ok(Some(v.to_vec()))
    };
    let uvs =
        per_vertex("uv", &["point2"], 2)?.map(|v| v.chunks(2).map(|c| [c[0], c[1]]).collect());
    let sign = if reverse { -1.0 } else { 1.0 };
    let normals = per_vertex("N", &["normal"], 3)?.map(|v| {
        v.chunks(3)
            .map(|c| [sign * c[0], sign * c[1], sign * c[2]])
            .collect()
    });
    Ok((uvs, normals))
}

/// `trianglemesh`: `point3 P`, `integer indices` (optional for a single triangle), and
/// optional `point2 uv` and `normal N` (one per vertex). With N, each triangle is wound so
/// that its geometric normal lies on N's side, as pbrt-v4 turns it (its normals are
/// authoritative; `ReverseOrientation` negates them).
pub(super) fn triangle_mesh(p: &Params, loc: Loc, reverse: bool) -> R<ShapeKind> {
    let (vertices, idx) = positions_and_indices(p, loc, "trianglemesh", 3)?;
    let (uvs, normals) = vertex_data(
        p,
        "trianglemesh",
        vertices.len(),
        reverse,
        &["S", "faceIndices"],
    )?;
    let mut faces: Vec<[u32; 3]> = idx.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    if let Some(ns) = &normals {
        wind_to_normals(&vertices, &mut faces, ns);
    }
    Ok(ShapeKind::Inline {
        vertices,
        faces,
        normals,
        uvs,
    })
}

/// Winds each triangle so that its geometric normal lies on its vertex normals' side, as
/// pbrt-v4 turns a mesh's normal to N.
fn wind_to_normals(vertices: &[[f64; 3]], faces: &mut [[u32; 3]], normals: &[[f64; 3]]) {
    let v = |i: u32| DVec3::from(vertices[i as usize]);
    for f in faces {
        let g = (v(f[1]) - v(f[0])).cross(v(f[2]) - v(f[0]));
        let s: DVec3 = f.iter().map(|&i| DVec3::from(normals[i as usize])).sum();
        if g.dot(s) < 0.0 {
            f.swap(1, 2);
        }
    }
}

/// `loopsubdiv`: `levels` (3) rounds of Loop subdivision of `P` and `indices`, with the limit
/// surface's positions and normals (`crate::geometry::shape::loop_subdivide`).
pub(super) fn loop_subdiv(p: &Params, loc: Loc) -> R<ShapeKind> {
    let (vertices, idx) = positions_and_indices(p, loc, "loopsubdiv", 3)?;
    let levels = p.int("levels", 3)?;
    if !(0..=8).contains(&levels) {
        return Err(p.err(p.loc_of("levels"), "\"levels\" must be from 0 to 8"));
    }
    let pos: Vec<DVec3> = vertices.iter().map(|&v| DVec3::from(v)).collect();
    let faces: Vec<[u32; 3]> = idx.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let s = crate::geometry::shape::loop_subdivide(&pos, &faces, levels as u32)
        .map_err(|e| p.err(loc, format!("loopsubdiv: {e}")))?;
    Ok(ShapeKind::Inline {
        vertices: s.positions.iter().map(|v| v.to_array()).collect(),
        faces: s.triangles,
        normals: Some(s.normals.iter().map(|v| v.to_array()).collect()),
        uvs: None,
    })
}

/// A `bilinearmesh`: patches of four vertices p₀₀, p₁₀, p₀₁, p₁₁ (in `indices` order), each
/// p(u, v) = lerp(v, lerp(u, p₀₀, p₁₀), lerp(u, p₀₁, p₁₁)), with `uv` (per vertex; by default
/// (u, v) itself) and `N` (per vertex) interpolated the same way.
pub(super) struct Bilinear {
    vertices: Vec<[f64; 3]>,
    patches: Vec<[u32; 4]>,
    uvs: Option<Vec<[f64; 2]>>,
    normals: Option<Vec<[f64; 3]>>,
}

/// Grid cells per side into which a patch that is not a parallelogram (or whose uv is not) is
/// cut: its surface and uv are then off by at most 1/(8·16²) of its twist |p₀₀ + p₁₁ − p₁₀ − p₀₁|.
const GRID: usize = 16;

/// `bilinearmesh`: `point3 P`, `integer indices` (optional for a single patch), optional
/// `point2 uv` and `normal N`; `ReverseOrientation` negates N as for a `trianglemesh`.
pub(super) fn bilinear_mesh(p: &Params, loc: Loc, reverse: bool) -> R<Bilinear> {
    let (vertices, idx) = positions_and_indices(p, loc, "bilinearmesh", 4)?;
    let (uvs, normals) = vertex_data(
        p,
        "bilinearmesh",
        vertices.len(),
        reverse,
        &["faceIndices", "emissionfilename"],
    )?;
    Ok(Bilinear {
        vertices,
        patches: idx.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect(),
        uvs,
        normals,
    })
}

impl Bilinear {
    /// Patches of `vertices` (corners p₀₀, p₁₀, p₀₁, p₁₁ as `bilinearmesh` orders them), with
    /// per-vertex `uvs` and `normals` if given.
    pub(super) fn new(
        vertices: Vec<[f64; 3]>,
        patches: Vec<[u32; 4]>,
        uvs: Option<Vec<[f64; 2]>>,
        normals: Option<Vec<[f64; 3]>>,
    ) -> Bilinear {
        Bilinear {
            vertices,
            patches,
            uvs,
            normals,
        }
    }

    pub(super) fn len(&self) -> usize {
        self.patches.len()
    }

    /// pbrt-v4's area of patch `i` under `m` (what an area light's `power` is spread over):
    /// the patch cut into 3 × 3 quads, each measured by half its diagonals' cross product
    /// (exact for a planar patch).
    pub(super) fn area(&self, i: usize, m: &glam::DMat4) -> f64 {
        let c = self.patches[i].map(|k| m.transform_point3(DVec3::from(self.vertices[k as usize])));
        let at = |u: f64, v: f64| (c[0].lerp(c[1], u)).lerp(c[2].lerp(c[3], u), v);
        let mut area = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                let (u0, u1, v0, v1) = (
                    i as f64 / 3.0,
                    (i + 1) as f64 / 3.0,
                    j as f64 / 3.0,
                    (j + 1) as f64 / 3.0,
                );
                area += 0.5
                    * (at(u1, v1) - at(u0, v0))
                        .cross(at(u1, v0) - at(u0, v1))
                        .length();
            }
        }
        area
    }

    /// The triangles of the patches `which`: two for a parallelogram with parallelogram uv
    /// (exact: the map is then affine), else a `GRID` × `GRID` grid. Every vertex carries its
    /// uv; each triangle is wound so that its normal lies on ∂p/∂u × ∂p/∂v's side (pbrt-v4's
    /// patch normal), or on N's when N is given.
    pub(super) fn triangles(&self, which: impl Iterator<Item = usize>) -> ShapeKind {
        let (mut vertices, mut uvs, mut faces) = (Vec::new(), Vec::new(), Vec::new());
        let mut normals = Vec::new();
        for i in which {
            let k = self.patches[i].map(|k| k as usize);
            let pos = k.map(|k| DVec3::from(self.vertices[k]));
            let uv = match &self.uvs {
                Some(t) => k.map(|k| DVec2::from(t[k])),
                None => [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]].map(DVec2::from),
            };
            let twist = (pos[0] + pos[3] - pos[1] - pos[2]).length();
            let size = (pos[1] - pos[0]).length() + (pos[2] - pos[0]).length();
            let uv_twist = (uv[0] + uv[3] - uv[1] - uv[2]).length();
            let g = if twist <= 1e-9 * size && uv_twist <= 1e-9 {
                1
            } else {
                GRID
            };
            let base = vertices.len() as u32;
            for j in 0..=g {
                for i in 0..=g {
                    let (u, v) = (i as f64 / g as f64, j as f64 / g as f64);
                    let lerp4 =
                        |a: DVec3, b: DVec3, c: DVec3, d: DVec3| a.lerp(b, u).lerp(c.lerp(d, u), v);
                    vertices.push(lerp4(pos[0], pos[1], pos[2], pos[3]).to_array());
                    uvs.push(
                        uv[0]
                            .lerp(uv[1], u)
                            .lerp(uv[2].lerp(uv[3], u), v)
                            .to_array(),
                    );
                    let n = match &self.normals {
                        Some(ns) => {
                            let n = k.map(|k| DVec3::from(ns[k]));
                            lerp4(n[0], n[1], n[2], n[3])
                        }
                        // the patch's own normal ∂p/∂u × ∂p/∂v (its diagonals' at a corner
                        // where it vanishes)
                        None => {
                            let dpdu = (pos[1] - pos[0]).lerp(pos[3] - pos[2], v);
                            let dpdv = (pos[2] - pos[0]).lerp(pos[3] - pos[1], u);
                            let n = dpdu.cross(dpdv);
                            if n.length_squared() > 0.0 {
                                n
                            } else {
                                (pos[3] - pos[0]).cross(pos[2] - pos[1])
                            }
                        }
                    };
                    normals.push(n.normalize_or(DVec3::Z).to_array());
                }
            }
            let at = |i: usize, j: usize| base + (j * (g + 1) + i) as u32;
            for j in 0..g {
                for i in 0..g {
                    faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                    faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        wind_to_normals(&vertices, &mut faces, &normals);
        ShapeKind::Inline {
            vertices,
            faces,
            normals: Some(normals),
            uvs: Some(uvs),
        }
    }
}

/// A triangle mesh without uv given pbrt-v4's default ones: (0, 0), (1, 0), (1, 1) at each
/// triangle's corners (its `Triangle::GetUVs`), the vertices unshared so that each triangle
/// has its own; other shapes unchanged.
pub(super) fn per_triangle_uv(kind: ShapeKind) -> ShapeKind {
    let ShapeKind::Inline {
        vertices,
        faces,
        normals,
        uvs: None,
    } = kind
    else {
        return kind;
    };
    let corners = |f: &[u32; 3]| f.map(|i| i as usize);
    ShapeKind::Inline {
        vertices: faces
            .iter()
            .flat_map(|f| corners(f).map(|i| vertices[i]))
            .collect(),
        normals: normals.map(|n| {
            faces
                .iter()
                .flat_map(|f| corners(f).map(|i| n[i]))
                .collect()
        }),
        uvs: Some(
            faces
                .iter()
                .flat_map(|_| [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
                .collect(),
        ),
        faces: (0..faces.len() as u32)
            .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
            .collect(),
    }
}

/// Whether a PLY file's vertices carry texture coordinates (its header names one of
/// `UV_NAMES`); a file that cannot be read answers false (its own error comes when the scene
/// is built).
pub(super) fn ply_has_uv(path: &std::path::Path) -> bool {
    let Ok(head) = crate::files::read_head_gz(path, 1 << 16) else {
        return false;
    };
    let text = String::from_utf8_lossy(&head);
    let header = text.split("end_header").next().unwrap_or("");
    let mut in_vertex = false;
    for line in header.lines() {
        match line.split_whitespace().collect::<Vec<_>>().as_slice() {
            ["element", name, ..] => in_vertex = *name == "vertex",
            ["property", .., name]
                if in_vertex && crate::geometry::shape::UV_NAMES.contains(name) =>
            {
                return true;
            }
            _ => {}
        }
    }
    false
}
