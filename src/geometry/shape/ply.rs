//! Loading Stanford PLY files (ASCII, binary little- and big-endian) into a [`Mesh`]: vertex
//! `x y z` with optional `nx ny nz` and `u v` (or `s t`), faces as `vertex_indices` (or
//! `vertex_index`) lists, triangulated as fans. Other vertex and face properties are kept as
//! Mitsuba's mesh attributes ([`super::ply_attributes`]); other elements are skipped.

use glam::{Vec2, Vec3};

use super::Mesh;
use super::ply_attributes::{Columns, MeshAttribute};
use super::ply_header::{Format, Ty, parse_header, split_header};
use crate::geometry::error::GeometryError;
use crate::geometry::transform::Transform;
use std::path::Path;

/// Reads values one at a time from the body in the file's format.
struct Body<'a> {
    data: &'a [u8],
    pos: usize,
    format: Format,
    tokens: std::str::SplitAsciiWhitespace<'a>,
}

impl Body<'_> {
    fn read(&mut self, ty: Ty) -> Option<f64> {
        if self.format == Format::Ascii {
            return self.tokens.next()?.parse().ok();
        }
        let n = ty.size();
        let b = self.data.get(self.pos..self.pos + n)?;
        self.pos += n;
        let mut a = [0u8; 8];
        a[..n].copy_from_slice(b);
        if self.format == Format::Be {
            a[..n].reverse();
        }
        Some(match ty {
            Ty::I8 => a[0] as i8 as f64,
            Ty::U8 => a[0] as f64,
            Ty::I16 => i16::from_le_bytes([a[0], a[1]]) as f64,
            Ty::U16 => u16::from_le_bytes([a[0], a[1]]) as f64,
            Ty::I32 => i32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
            Ty::U32 => u32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
            Ty::F32 => f32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
            Ty::F64 => f64::from_le_bytes(a),
        })
    }
}

impl Mesh {
    /// Loads a PLY file as one mesh, transformed by `transform`. Errors name the path, like
    /// [`Mesh::load_obj`].
    pub fn load_ply(path: &Path, transform: &Transform) -> Result<Mesh, GeometryError> {
        Ok(Self::load_ply_attributes(path, transform)?.0)
    }

    /// [`Mesh::load_ply`] with the file's other vertex and face properties as Mitsuba's mesh
    /// attributes (`vertex_…`, `face_…`; face values given per triangle of the fans).
    pub fn load_ply_attributes(
        path: &Path,
        transform: &Transform,
    ) -> Result<(Mesh, Vec<MeshAttribute>), GeometryError> {
        let bytes =
            crate::files::read_bytes_gz(path, crate::files::MAX_MESH_BYTES).map_err(|source| {
                GeometryError::MeshOpen {
                    path: path.to_path_buf(),
                    source,
                }
            })?;
        Self::parse_ply(&bytes, path, transform)
    }

    /// Parses PLY data (ASCII or binary) as [`Mesh::load_ply_attributes`] does a file; `path`
    /// names it in errors.
    pub fn parse_ply(
        bytes: &[u8],
        path: &Path,
        transform: &Transform,
    ) -> Result<(Mesh, Vec<MeshAttribute>), GeometryError> {
        let (raw, attributes) = parse_raw(bytes, path)?;
        let mesh = Mesh::new(
            raw.positions,
            raw.normals,
            raw.uvs,
            raw.triangles,
            transform,
        )
        .map_err(|e| GeometryError::MeshParse {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        Ok((mesh, attributes))
    }
}

/// A PLY file's vertex data, its faces as fans of triangles and each face's vertex count.
pub(super) struct Raw {
    pub(super) positions: Vec<Vec3>,
    pub(super) normals: Option<Vec<Vec3>>,
    pub(super) uvs: Option<Vec<Vec2>>,
    pub(super) triangles: Vec<[u32; 3]>,
    pub(super) sizes: Vec<usize>,
}

/// Parses PLY data as stored; `path` names it in errors.
pub(super) fn parse_raw(
    bytes: &[u8],
    path: &Path,
) -> Result<(Raw, Vec<MeshAttribute>), GeometryError> {
    let bad = |m: &str| GeometryError::MeshParse {
        path: path.to_path_buf(),
        message: m.to_string(),
    };
    let (header, body_start) = split_header(bytes, &bad)?;
    let (format, elems) = parse_header(header, &bad)?;
    let text = if format == Format::Ascii {
        std::str::from_utf8(&bytes[body_start..]).map_err(|_| bad("ASCII body is not text"))?
    } else {
        ""
    };
    let mut body = Body {
        data: &bytes[body_start..],
        pos: 0,
        format,
        tokens: text.split_ascii_whitespace(),
    };
    let (mut positions, mut normals, mut uvs, mut indices) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut sizes = Vec::new();
    let truncated = || bad("the file ends early or has a bad value");
    let mut vertex_extra = Columns::new("vertex_", &elems, "vertex");
    let mut face_extra = Columns::new("face_", &elems, "face");
    let body_len = bytes.len() - body_start;
    for e in &elems {
        if e.props.is_empty() {
            // nothing to read; a vertex needs a position
            if e.name == "vertex" && e.count > 0 {
                return Err(bad("element vertex has no properties (x, y, z)"));
            }
            continue;
        }
        // every entry reads at least one byte per property (a token and its separator in
        // ASCII): a declared count the data cannot hold is refused before looping
        if e.count.saturating_mul(e.props.len()) > body_len {
            return Err(bad(&format!(
                "element {} declares {} entries, more than the {body_len} bytes after the header can hold",
                e.name, e.count
            )));
        }
        for _ in 0..e.count {
            let mut v = [0.0f64; 8]; // x y z nx ny nz u v
            let mut face: Vec<u32> = Vec::new();
            let mut face_values = Vec::new();
            for (pi, p) in e.props.iter().enumerate() {
                match p.list {
                    Some(ct) => {
                        let n = body.read(ct).ok_or_else(truncated)? as usize;
                        for _ in 0..n {
                            let x = body.read(p.ty).ok_or_else(truncated)?;
                            if e.name == "face"
                                && (p.name == "vertex_indices" || p.name == "vertex_index")
                            {
                                if !(x >= 0.0 && x <= u32::MAX as f64 && x.fract() == 0.0) {
                                    return Err(bad(&format!(
                                        "face {}: vertex index {x} is not a vertex",
                                        indices.len()
                                    )));
                                }
                                face.push(x as u32);
                            }
                        }
                    }
                    None => {
                        let x = body.read(p.ty).ok_or_else(truncated)?;
                        match (slot(&p.name), e.name.as_str()) {
                            (Some(k), _) => v[k] = x,
                            (None, "vertex") => vertex_extra.push(pi, x),
                            (None, "face") => face_values.push((pi, x)),
                            (None, _) => {}
                        }
                    }
                }
            }
            if e.name == "vertex" {
                positions.push(Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32));
                normals.push(Vec3::new(v[3] as f32, v[4] as f32, v[5] as f32));
                uvs.push(Vec2::new(v[6] as f32, v[7] as f32));
            } else if e.name == "face" {
                sizes.push(face.len());
                for k in 1..face.len().saturating_sub(1) {
                    indices.push([face[0], face[k], face[k + 1]]);
                    for &(pi, x) in &face_values {
                        face_extra.push(pi, x);
                    }
                }
            }
        }
    }
    let has = |name: &str| {
        elems
            .iter()
            .any(|e| e.name == "vertex" && e.props.iter().any(|p| p.name == name))
    };
    let normals = has("nx").then_some(normals);
    let uvs = UV_NAMES.iter().any(|n| has(n)).then_some(uvs);
    let mut attributes = vertex_extra.attributes(false);
    attributes.extend(face_extra.attributes(true));
    let raw = Raw {
        positions,
        normals,
        uvs,
        triangles: indices,
        sizes,
    };
    Ok((raw, attributes))
}

/// The names a vertex's first texture coordinate goes by (pbrt-v4's and Mitsuba's readers
/// take each).
pub const UV_NAMES: [&str; 4] = ["u", "s", "texture_u", "texture_s"];

/// The slot of a vertex property in `x y z nx ny nz u v`; None for other properties.
fn slot(name: &str) -> Option<usize> {
    Some(match name {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        "nx" => 3,
        "ny" => 4,
        "nz" => 5,
        "u" | "s" | "texture_u" | "texture_s" => 6,
        "v" | "t" | "texture_v" | "texture_t" => 7,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_and_binary_quads() {
        let dir = std::env::temp_dir().join(format!("spectrace-ply-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let ascii = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n2 0 0\n2 3 0\n0 3 0\n4 0 1 2 3\n";
        let p = dir.join("a.ply");
        std::fs::write(&p, ascii).unwrap();
        let m = Mesh::load_ply(&p, &Transform::identity()).unwrap();
        assert!((m.area() - 6.0).abs() < 1e-5);
        let mut bin = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
        for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for c in v {
                bin.extend_from_slice(&c.to_le_bytes());
            }
        }
        bin.push(3);
        for i in [0i32, 1, 2] {
            bin.extend_from_slice(&i.to_le_bytes());
        }
        let p = dir.join("b.ply");
        std::fs::write(&p, &bin).unwrap();
        assert!((Mesh::load_ply(&p, &Transform::identity()).unwrap().area() - 0.5).abs() < 1e-6);
        std::fs::write(&p, &bin[..bin.len() - 3]).unwrap();
        assert!(Mesh::load_ply(&p, &Transform::identity()).is_err());
        assert!(Mesh::load_ply(&dir.join("missing.ply"), &Transform::identity()).is_err());
    }
}
