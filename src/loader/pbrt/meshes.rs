//! pbrt-v4's meshes written in the scene file (`src/pbrt/shapes.cpp`): `trianglemesh` and
//! `loopsubdiv` (`crate::geometry::shape::loop_subdivide`).

use glam::DVec3;

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

/// `trianglemesh`: `point3 P`, `integer indices` (optional for a single triangle), and
/// optional `point2 uv` and `normal N` (one per vertex). With N, each triangle is wound so
/// that its geometric normal lies on N's side, as pbrt-v4 turns it (its normals are
/// authoritative; `ReverseOrientation` negates them).
pub(super) fn triangle_mesh(p: &Params, loc: Loc, reverse: bool) -> R<ShapeKind> {
    let (vertices, idx) = positions_and_indices(p, loc, "trianglemesh", 3)?;
    let n = vertices.len();
    for unread in ["S", "faceIndices"] {
        if p.get(unread).is_some() {
            return Err(p.err(
                p.loc_of(unread),
                format!("a trianglemesh's \"{unread}\" is not read yet"),
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
    let normals: Option<Vec<[f64; 3]>> = per_vertex("N", &["normal"], 3)?.map(|v| {
        let sign = if reverse { -1.0 } else { 1.0 };
        v.chunks(3)
            .map(|c| [sign * c[0], sign * c[1], sign * c[2]])
            .collect()
    });
    let mut faces: Vec<[u32; 3]> = idx.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    if let Some(ns) = &normals {
        let v = |i: u32| DVec3::from(vertices[i as usize]);
        for f in &mut faces {
            let g = (v(f[1]) - v(f[0])).cross(v(f[2]) - v(f[0]));
            let s: DVec3 = f.iter().map(|&i| DVec3::from(ns[i as usize])).sum();
            if g.dot(s) < 0.0 {
                f.swap(1, 2);
            }
        }
    }
    Ok(ShapeKind::Inline {
        vertices,
        faces,
        normals,
        uvs,
    })
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
