//! Mitsuba's `.serialized` meshes (Mitsuba 0.5 and 3, `src/shapes/serialized.cpp`): a file of
//! one or more meshes, each a little-endian header (u16 0x041C, u16 version 3 or 4) followed by
//! a zlib stream holding
//!
//! ```text
//! u32 flags (0x1 normals, 0x2 uvs, 0x8 colours, 0x1000 f32, 0x2000 f64)
//! [version 4] a UTF-8 name, NUL-terminated
//! u64 vertex count, u64 triangle count
//! positions (3 per vertex), normals (3, if 0x1), uvs (2, if 0x2), colours (3, if 0x8; skipped)
//! indices: 3 u32 per triangle
//! ```
//!
//! and, at the end of the file, the offset of every mesh (u64 for version 4, u32 for version 3)
//! then their count (u32). uvs are used as stored (not flipped); Mitsuba 3 ignores the file's
//! face-normal flag (0x10), and so does this reader.

use std::io::Read;
use std::path::Path;

use glam::{Vec2, Vec3};

use super::Mesh;
use crate::geometry::GeometryError;
use crate::geometry::transform::Transform;

const MAGIC: u16 = 0x041C;

impl Mesh {
    /// Loads mesh `index` of a Mitsuba `.serialized` file, transformed by `transform`. Errors
    /// name the path (an unreadable file, a bad header or stream, an index out of range,
    /// indices out of range).
    pub fn load_serialized(
        path: &Path,
        index: usize,
        transform: &Transform,
    ) -> Result<Mesh, GeometryError> {
        let bytes =
            crate::files::read_bytes(path, crate::files::MAX_MESH_BYTES).map_err(|source| {
                GeometryError::MeshOpen {
                    path: path.to_path_buf(),
                    source,
                }
            })?;
        let bad = |m: String| GeometryError::MeshParse {
            path: path.to_path_buf(),
            message: m,
        };
        let u16_at = |o: usize| -> Option<u16> {
            Some(u16::from_le_bytes(
                bytes.get(o..o.checked_add(2)?)?.try_into().ok()?,
            ))
        };
        let (Some(MAGIC), Some(version)) = (u16_at(0), u16_at(2)) else {
            return Err(bad(
                "not a Mitsuba .serialized file (no 0x041C header)".into()
            ));
        };
        if version != 3 && version != 4 {
            return Err(bad(format!("version {version} (only 3 and 4 are read)")));
        }
        // where mesh `index` starts: 0 for the first, else from the table at the end
        let start = mesh_start(&bytes, index, version).map_err(bad)?;
        if u16_at(start) != Some(MAGIC) {
            return Err(bad(format!(
                "mesh {index} does not start with the 0x041C header"
            )));
        }
        let mut z = crate::files::zlib_reader(
            start
                .checked_add(4)
                .and_then(|s| bytes.get(s..))
                .unwrap_or(&[]),
        );
        let mut r = Reader { z: &mut z, path };
        let flags = r.u32()?;
        if version == 4 {
            // the mesh's name, NUL-terminated
            while r.bytes::<1>()?[0] != 0 {}
        }
        let double = flags & 0x2000 != 0;
        let nv = r.u64()? as usize;
        let nt = r.u64()? as usize;
        if nv == 0 || nt == 0 || nv > 1 << 31 || nt > 1 << 31 {
            return Err(bad(format!("{nv} vertices and {nt} triangles")));
        }
        let vec3s = |r: &mut Reader<'_>| -> Result<Vec<Vec3>, GeometryError> {
            (0..nv)
                .map(|_| Ok(Vec3::new(r.real(double)?, r.real(double)?, r.real(double)?)))
                .collect()
        };
        let positions = vec3s(&mut r)?;
        let normals = if flags & 0x1 != 0 {
            Some(vec3s(&mut r)?)
        } else {
            None
        };
        let uvs = if flags & 0x2 != 0 {
            Some(
                (0..nv)
                    .map(|_| Ok(Vec2::new(r.real(double)?, r.real(double)?)))
                    .collect::<Result<Vec<_>, GeometryError>>()?,
            )
        } else {
            None
        };
        if flags & 0x8 != 0 {
            vec3s(&mut r)?;
        }
        // grown as triangles arrive: a corrupt count cannot reserve memory the stream lacks
        let mut indices = Vec::with_capacity(nt.min(1 << 20));
        for _ in 0..nt {
            let t = [r.u32()?, r.u32()?, r.u32()?];
            if t.iter().any(|&i| i as usize >= nv) {
                return Err(bad(format!(
                    "a triangle {t:?} refers past the {nv} vertices"
                )));
            }
            indices.push(t);
        }
        Mesh::new(positions, normals, uvs, indices, transform)
    }
}

/// The byte offset of mesh `index` in a `.serialized` file of `version` (3 or 4): 0 for the
/// first, else from the table of offsets at the end; an error message if it has none.
fn mesh_start(bytes: &[u8], index: usize, version: u16) -> Result<usize, String> {
    Ok(if index == 0 {
        0
    } else {
        let n = bytes.len();
        let count = bytes
            .get(n.saturating_sub(4)..)
            .and_then(|b| b.try_into().ok())
            .map(u32::from_le_bytes)
            .ok_or_else(|| "no mesh table at the end".to_string())? as usize;
        if index >= count {
            return Err(format!(
                "shape_index {index} is out of range: the file holds {count} meshes"
            ));
        }
        // the table's entry for `index`, counted back from the end (numbers from the file:
        // checked arithmetic, so a corrupt table is an error, never an overflow)
        let off = if version == 4 {
            8usize
                .checked_mul(count - index)
                .and_then(|k| n.checked_sub(k.checked_add(4)?))
                .and_then(|o| bytes.get(o..o + 8))
                .and_then(|b| b.try_into().ok())
                .map(u64::from_le_bytes)
        } else {
            4usize
                .checked_mul(count - index + 1)
                .and_then(|k| n.checked_sub(k))
                .and_then(|o| bytes.get(o..o + 4))
                .and_then(|b| b.try_into().ok())
                .map(|b| u32::from_le_bytes(b) as u64)
        };
        off.and_then(|o| usize::try_from(o).ok())
            .ok_or_else(|| "the mesh table is truncated or corrupt".to_string())?
    })
}

struct Reader<'a> {
    z: &'a mut dyn Read,
    path: &'a Path,
}

impl Reader<'_> {
    fn bytes<const K: usize>(&mut self) -> Result<[u8; K], GeometryError> {
        let mut b = [0u8; K];
        self.z
            .read_exact(&mut b)
            .map_err(|e| GeometryError::MeshParse {
                path: self.path.to_path_buf(),
                message: format!("the compressed mesh data ends early or is corrupt ({e})"),
            })?;
        Ok(b)
    }
    fn u32(&mut self) -> Result<u32, GeometryError> {
        Ok(u32::from_le_bytes(self.bytes()?))
    }
    fn u64(&mut self) -> Result<u64, GeometryError> {
        Ok(u64::from_le_bytes(self.bytes()?))
    }
    fn real(&mut self, double: bool) -> Result<f32, GeometryError> {
        Ok(if double {
            f64::from_le_bytes(self.bytes()?) as f32
        } else {
            f32::from_le_bytes(self.bytes()?)
        })
    }
}
