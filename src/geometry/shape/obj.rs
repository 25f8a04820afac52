//! Loading Wavefront OBJ files into a [`Mesh`] (with `tobj`).

use super::Mesh;
use crate::geometry::error::GeometryError;
use crate::geometry::transform::Transform;
use glam::{Vec2, Vec3};
use std::io::BufReader;
use std::path::Path;

impl Mesh {
    /// Loads an OBJ file as one mesh: faces are triangulated (as fans), vertices get a single
    /// index, all objects and groups are merged, and the result is transformed by `transform`.
    /// Materials (`mtllib`, `usemtl`) are ignored; no other file is read.
    ///
    /// Vertex normals and uvs are kept if any object has them; objects without them get zero
    /// normals (the shading normal falls back to the geometric one) and zero uvs. Coordinates are
    /// taken as metres. A `vt u v` (v up, the OBJ convention) becomes uv = (u, 1 − v), so that v
    /// runs down an image from its first stored row, as textures look it up (and as Mitsuba
    /// reads OBJ files).
    ///
    /// Errors name the path: `cannot open mesh <path>: <io error>` if the file cannot be opened
    /// or read, `malformed mesh file <path>: <tobj's message>` if it cannot be parsed (e.g. a bad
    /// number or a face index out of range), and `malformed mesh file <path>: mesh ...` if the data is
    /// invalid for [`Mesh::new`] (no faces, non-finite values, zero area). Unknown statements are
    /// ignored, as tobj does.
    pub fn load_obj(path: &Path, transform: &Transform) -> Result<Mesh, GeometryError> {
        let open_error = |source| GeometryError::MeshOpen {
            path: path.to_path_buf(),
            source,
        };
        if path.is_dir() {
            return Err(open_error(std::io::Error::other("is a directory")));
        }
        let (file, _) =
            crate::files::open_regular(path, crate::files::MAX_MESH_BYTES).map_err(open_error)?;
        Self::parse_obj(&mut BufReader::new(file), path, transform)
    }

    /// Parses OBJ text from `reader` as [`Mesh::load_obj`] does a file; `path` names it in
    /// errors.
    pub fn parse_obj(
        reader: &mut impl std::io::BufRead,
        path: &Path,
        transform: &Transform,
    ) -> Result<Mesh, GeometryError> {
        let open_error = |source| GeometryError::MeshOpen {
            path: path.to_path_buf(),
            source,
        };
        let parse_error = |message: String| GeometryError::MeshParse {
            path: path.to_path_buf(),
            message,
        };
        #[allow(clippy::needless_update)]
        let options = tobj::LoadOptions {
            single_index: true,
            triangulate: true,
            ignore_points: true,
            ignore_lines: true,
            // Other fields exist only with optional tobj features.
            ..Default::default()
        };
        // face indices are checked on their way to tobj, which would overflow on some
        // (`obj_check.rs`)
        let mut checked = super::obj_check::IndexCheck::new(reader);
        let loaded = tobj::load_obj_buf(&mut checked, &options, |_| {
            Err(tobj::LoadError::GenericFailure)
        });
        if let Some(e) = checked.error {
            return Err(parse_error(e));
        }
        let models = match loaded {
            Ok((models, _materials)) => models,
            Err(tobj::LoadError::ReadError) => {
                return Err(open_error(std::io::Error::other("read error")));
            }
            Err(e) => return Err(parse_error(e.to_string())),
        };

        let any_normals = models.iter().any(|m| !m.mesh.normals.is_empty());
        let any_uvs = models.iter().any(|m| !m.mesh.texcoords.is_empty());
        let mut positions = Vec::new();
        let mut normals = Vec::new();
        let mut uvs = Vec::new();
        let mut indices = Vec::new();
        for model in &models {
            let mesh = &model.mesh;
            let base = positions.len();
            let count = mesh.positions.len() / 3;
            positions.extend(mesh.positions.chunks_exact(3).map(Vec3::from_slice));
            if any_normals {
                if mesh.normals.len() == 3 * count {
                    normals.extend(mesh.normals.chunks_exact(3).map(Vec3::from_slice));
                } else {
                    normals.resize(base + count, Vec3::ZERO);
                }
            }
            if any_uvs {
                if mesh.texcoords.len() == 2 * count {
                    uvs.extend(
                        mesh.texcoords
                            .chunks_exact(2)
                            .map(|t| Vec2::new(t[0], 1.0 - t[1])),
                    );
                } else {
                    uvs.resize(base + count, Vec2::ZERO);
                }
            }
            for tri in mesh.indices.chunks_exact(3) {
                let offset = |i: u32| u32::try_from(base + i as usize).unwrap_or(u32::MAX);
                indices.push([offset(tri[0]), offset(tri[1]), offset(tri[2])]);
            }
        }
        let normals = any_normals.then_some(normals);
        let uvs = any_uvs.then_some(uvs);
        Mesh::new(positions, normals, uvs, indices, transform)
            .map_err(|e| parse_error(e.to_string()))
    }
}
