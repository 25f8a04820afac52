//! Mitsuba's `TensorFile` format (`src/core/tensor.cpp` in Mitsuba 3, written by its
//! `tensor_io.write`), which its `measured_polarized` BSDF reads (`.pbsdf` files), and the
//! pBSDF table read from one (`read_pbsdf`).
//!
//! Layout, little-endian: the magic `tensor_file\0` (12 bytes), a version (two bytes, 1 and 0),
//! a u32 field count; per field a u16 name length and the name, a u16 rank, a u8 type code
//! (3: u16, 10: f32, the two a pBSDF uses), a u64 offset of its data from the start of the
//! file and rank × u64 extents; the data in C order.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use crate::loader::desc::PbsdfTable;

/// One field: its type code (1 u8, 3 u16, 10 f32, …), extents and raw bytes.
pub(super) struct Field<'a> {
    pub(super) dtype: u8,
    pub(super) shape: Vec<u64>,
    data: &'a [u8],
}

/// A cursor over the header, with errors naming the byte offset.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let Some(end) = end else {
            return Err(format!(
                "the header ends early, at byte {}",
                self.bytes.len()
            ));
        };
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }
    fn u8(&mut self) -> Result<u8, String> {
        Ok(self.take(1)?[0])
    }
    fn u16(&mut self) -> Result<u16, String> {
        Ok(u16::from_le_bytes(
            self.take(2)?.try_into().expect("2 bytes"),
        ))
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(
            self.take(4)?.try_into().expect("4 bytes"),
        ))
    }
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }
}

/// The fields of a tensor file's bytes, by name.
pub(super) fn fields(bytes: &[u8]) -> Result<HashMap<String, Field<'_>>, String> {
    let mut r = Reader { bytes, at: 0 };
    if r.take(12).ok() != Some(b"tensor_file\0".as_slice()) {
        return Err("not a Mitsuba tensor file (no `tensor_file` magic)".into());
    }
    let (major, minor) = (r.u8()?, r.u8()?);
    if (major, minor) != (1, 0) {
        return Err(format!("tensor file version {major}.{minor}, expected 1.0"));
    }
    let n = r.u32()?;
    let mut out = HashMap::new();
    for _ in 0..n {
        let len = r.u16()? as usize;
        let name = String::from_utf8_lossy(r.take(len)?).into_owned();
        let rank = r.u16()? as usize;
        let dtype = r.u8()?;
        let offset = r.u64()?;
        let shape = (0..rank).map(|_| r.u64()).collect::<Result<Vec<_>, _>>()?;
        let size = match dtype {
            1 | 2 => 1,
            3 | 4 | 9 => 2,
            5 | 6 | 10 => 4,
            7 | 8 | 11 => 8,
            t => return Err(format!("field `{name}` has unknown type code {t}")),
        };
        let count = shape.iter().try_fold(1u64, |a, &d| a.checked_mul(d));
        let len = count.and_then(|c| c.checked_mul(size));
        let range = len
            .and_then(|l| offset.checked_add(l).map(|e| (offset, e)))
            .filter(|&(_, e)| e <= bytes.len() as u64);
        let Some((a, b)) = range else {
            return Err(format!(
                "field `{name}` ({shape:?} of type {dtype}) at byte {offset} runs past the \
                 file's end ({} bytes)",
                bytes.len()
            ));
        };
        let data = &bytes[a as usize..b as usize];
        out.insert(name, Field { dtype, shape, data });
    }
    Ok(out)
}

/// The values of field `name`, which must be f32 (type 10), u16 (type 3) or u8 (type 1), as
/// f32.
pub(super) fn values(
    f: &HashMap<String, Field<'_>>,
    name: &str,
) -> Result<(Vec<f32>, Vec<u64>), String> {
    let field = f.get(name).ok_or_else(|| {
        format!("no field `{name}` (a pBSDF has phi_d, theta_d, theta_h, wvls, M)")
    })?;
    let v = match field.dtype {
        10 => field
            .data
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
            .collect(),
        3 => field
            .data
            .chunks_exact(2)
            .map(|c| u16::from_le_bytes(c.try_into().expect("2 bytes")) as f32)
            .collect(),
        1 => field.data.iter().map(|&b| b as f32).collect(),
        t => {
            return Err(format!(
                "field `{name}` has type code {t}, expected f32 (10), u16 (3) or u8 (1)"
            ));
        }
    };
    Ok((v, field.shape.clone()))
}

/// A grid field: its values, strictly increasing and finite, at least one.
fn grid(f: &HashMap<String, Field<'_>>, name: &str, unit: &str) -> Result<Vec<f32>, String> {
    let (v, shape) = values(f, name)?;
    if v.is_empty() {
        return Err(format!(
            "field `{name}` (shape {shape:?}) holds no values: the grid's coordinates ({unit}) \
             must be stored (Mitsuba would read whatever bytes follow in their place)"
        ));
    }
    if v.iter().any(|x| !x.is_finite()) || v.windows(2).any(|p| !(p[1] > p[0])) {
        return Err(format!(
            "field `{name}` must be finite and strictly increasing ({unit})"
        ));
    }
    Ok(v)
}

/// The pBSDF table of the `.pbsdf` file `path` (Mitsuba's `measured_polarized`): grids φ_d,
/// θ_d, θ_h (radians), wavelengths (nm) and M (φ_d × θ_d × θ_h × λ × 4 × 4). Errors name the
/// file and the field.
pub(crate) fn read_pbsdf(path: &Path) -> Result<PbsdfTable, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let at = |e: String| format!("{}: {e}", path.display());
    let f = fields(&bytes).map_err(at)?;
    let phi_d = grid(&f, "phi_d", "radians").map_err(at)?;
    let theta_d = grid(&f, "theta_d", "radians").map_err(at)?;
    let theta_h = grid(&f, "theta_h", "radians").map_err(at)?;
    let wavelengths = grid(&f, "wvls", "nm").map_err(at)?;
    let (m, shape) = values(&f, "M").map_err(at)?;
    let want = [
        phi_d.len(),
        theta_d.len(),
        theta_h.len(),
        wavelengths.len(),
        4,
        4,
    ]
    .map(|d| d as u64);
    if shape != want {
        return Err(at(format!(
            "field `M` has shape {shape:?}; the grids and wavelengths make it {want:?}"
        )));
    }
    Ok(PbsdfTable {
        phi_d,
        theta_d,
        theta_h,
        wavelengths,
        m: Arc::new(m),
    })
}

/// The bytes of a tensor file holding `fields` (name, type code 1, 3 or 10, shape, values), as
/// Mitsuba's `tensor_io.write` lays them out (data aligned to 8 bytes): for tests and tools
/// that make pBSDF files.
pub fn write_tensor_file(fields: &[(&str, u8, Vec<u64>, Vec<f32>)]) -> Vec<u8> {
    let mut head = b"tensor_file\0".to_vec();
    head.extend([1u8, 0]);
    head.extend((fields.len() as u32).to_le_bytes());
    let header_len: usize = head.len()
        + fields
            .iter()
            .map(|(n, _, s, _)| 2 + n.len() + 2 + 1 + 8 + 8 * s.len())
            .sum::<usize>();
    let mut data = Vec::new();
    let mut offset = header_len.div_ceil(8) * 8;
    for (name, dtype, shape, v) in fields {
        head.extend((name.len() as u16).to_le_bytes());
        head.extend(name.as_bytes());
        head.extend((shape.len() as u16).to_le_bytes());
        head.push(*dtype);
        head.extend((offset as u64).to_le_bytes());
        for d in shape {
            head.extend(d.to_le_bytes());
        }
        let mut bytes = Vec::new();
        for &x in v {
            match dtype {
                1 => bytes.push(x as u8),
                3 => bytes.extend((x as u16).to_le_bytes()),
                _ => bytes.extend(x.to_le_bytes()),
            }
        }
        let padded = bytes.len().div_ceil(8) * 8;
        bytes.resize(padded, 0);
        offset += padded;
        data.push(bytes);
    }
    head.resize(header_len.div_ceil(8) * 8, 0);
    for d in data {
        head.extend(d);
    }
    head
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file written by [`write_tensor_file`] reads back, and damaged ones are refused with
    /// the reason.
    #[test]
    fn round_trip_and_refusals() {
        let m: Vec<f32> = (0..2 * 3 * 2 * 16).map(|i| i as f32).collect();
        let file = |phi: Vec<f32>| {
            write_tensor_file(&[
                ("phi_d", 10, vec![1, phi.len() as u64], phi),
                ("theta_d", 10, vec![1, 3], vec![0.0, 0.5, 1.5]),
                ("theta_h", 10, vec![1, 1], vec![0.0]),
                ("wvls", 3, vec![2], vec![450.0, 650.0]),
                ("M", 10, vec![2, 3, 1, 2, 4, 4], m.clone()),
            ])
        };
        let dir = std::env::temp_dir().join(format!("spectrace-tensor-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let p = dir.join("t.pbsdf");
        std::fs::write(&p, file(vec![-3.0, 3.0])).expect("written");
        let t = read_pbsdf(&p).expect("reads");
        assert_eq!(t.phi_d, vec![-3.0, 3.0]);
        assert_eq!(t.wavelengths, vec![450.0, 650.0]);
        assert_eq!(*t.m, m);
        // the grids must be stored and increasing; M must match them
        std::fs::write(&p, file(vec![])).expect("written");
        let e = read_pbsdf(&p).expect_err("an empty grid");
        assert!(e.contains("`phi_d`") && e.contains("no values"), "{e}");
        std::fs::write(&p, file(vec![1.0, 0.0])).expect("written");
        let e = read_pbsdf(&p).expect_err("a decreasing grid");
        assert!(e.contains("strictly increasing"), "{e}");
        std::fs::write(&p, file(vec![0.0, 1.0, 2.0])).expect("written");
        let e = read_pbsdf(&p).expect_err("M too small");
        assert!(e.contains("field `M` has shape"), "{e}");
        let mut bytes = file(vec![-3.0, 3.0]);
        bytes.truncate(bytes.len() - 9);
        std::fs::write(&p, bytes).expect("written");
        let e = read_pbsdf(&p).expect_err("truncated");
        assert!(e.contains("runs past the file's end"), "{e}");
        std::fs::write(&p, b"not a tensor").expect("written");
        assert!(read_pbsdf(&p).expect_err("no magic").contains("magic"));
        std::fs::remove_dir_all(&dir).ok();
    }
}
