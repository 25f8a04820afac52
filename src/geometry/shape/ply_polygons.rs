//! A PLY file's polygons as stored (not as the fans of triangles a [`super::Mesh`] holds),
//! for readers that treat triangles and quads apart.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::ply::parse_raw;
use crate::geometry::error::GeometryError;

/// A PLY file's polygons as stored, untransformed (object space, the file's length unit):
/// for readers that treat triangles and quads apart (pbrt-v4 makes bilinear patches of quads).
#[derive(Clone, Debug)]
pub struct PlyPolygons {
    pub positions: Vec<Vec3>,
    pub normals: Option<Vec<Vec3>>,
    pub uvs: Option<Vec<Vec2>>,
    /// Each face's vertex indices, in the file's order (empty for a face of fewer than three,
    /// which has no triangles).
    pub faces: Vec<Vec<u32>>,
}

/// Reads a PLY file (gzip-compressed or not) as its polygons. Errors name the path, as
/// [`super::Mesh::load_ply`]'s.
pub fn read_ply_polygons(path: &Path) -> Result<PlyPolygons, GeometryError> {
    let bytes =
        crate::files::read_bytes_gz(path, crate::files::MAX_MESH_BYTES).map_err(|source| {
            GeometryError::MeshOpen {
                path: path.to_path_buf(),
                source,
            }
        })?;
    let (raw, _) = parse_raw(&bytes, path)?;
    // a face of n vertices is the fan of n − 2 triangles [f₀, f_k, f_k+1], consecutive
    let mut faces = Vec::with_capacity(raw.sizes.len());
    let mut next = 0;
    for &n in &raw.sizes {
        let fan = &raw.triangles[next..next + n.saturating_sub(2)];
        next += fan.len();
        let mut face = Vec::with_capacity(n);
        if let Some(first) = fan.first() {
            face.extend_from_slice(&first[..2]);
            face.extend(fan.iter().map(|t| t[2]));
        }
        faces.push(face);
    }
    Ok(PlyPolygons {
        positions: raw.positions,
        normals: raw.normals,
        uvs: raw.uvs,
        faces,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polygons come back as stored: a triangle, a quad and a pentagon, each with its
    /// vertices in the file's order (not as the fan of triangles the mesh holds).
    #[test]
    fn polygons_keep_the_file_s_faces() {
        let dir = std::env::temp_dir().join(format!("spectrace-plyfaces-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut text = String::from(
            "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n",
        );
        for i in 0..7 {
            text.push_str(&format!("{i} {} 0 0.{i} 0.5\n", i * i));
        }
        text.push_str("3 0 1 2\n4 3 4 5 6\n5 6 5 4 3 0\n");
        let p = dir.join("faces.ply");
        std::fs::write(&p, text).unwrap();
        let ply = read_ply_polygons(&p).unwrap();
        assert_eq!(
            ply.faces,
            vec![vec![0, 1, 2], vec![3, 4, 5, 6], vec![6, 5, 4, 3, 0]]
        );
        assert_eq!(ply.positions[3], Vec3::new(3.0, 9.0, 0.0));
        assert_eq!(ply.uvs.as_ref().unwrap()[2], Vec2::new(0.2, 0.5));
        assert!(ply.normals.is_none());
    }
}
