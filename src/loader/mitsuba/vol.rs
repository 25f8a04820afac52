//! Mitsuba's binary grid files (`.vol`, version 3): "VOL", the version byte 3, then
//! little-endian int32 encoding (1 = float32, the only one read here), x, y, z resolution and
//! channel count, six float32 bounds (min x, y, z, max x, y, z; unused when the grid is placed
//! by its `to_world`), then x·y·z·channels float32 values, x fastest, then y, then z.

use std::path::Path;

/// Header bytes before the values.
const HEADER: usize = 48;

/// The largest grid read, in values: 2³¹ (8 GiB of float32).
const MAX_VALUES: u64 = 1 << 31;

/// A grid file's contents.
pub struct VolFile {
    pub res: [usize; 3],
    pub channels: usize,
    /// The bounds the file declares: minimum and maximum corner.
    pub bounds: [[f32; 3]; 2],
    pub values: Vec<f32>,
}

/// Reads a `.vol` file; errors say what is wrong with it.
pub(super) fn read(path: &Path) -> Result<VolFile, String> {
    let bytes = crate::files::read_bytes(path, MAX_VALUES * 4 + HEADER as u64)
        .map_err(|e| format!("cannot read grid file {}: {e}", path.display()))?;
    parse(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses the bytes of a `.vol` file (see the module's doc); errors say what is wrong.
pub fn parse(b: &[u8]) -> Result<VolFile, String> {
    if b.len() < HEADER || &b[0..3] != b"VOL" {
        return Err("not a Mitsuba .vol grid (it does not start with \"VOL\")".into());
    }
    if b[3] != 3 {
        return Err(format!(
            "version {} of the .vol format; spectrace reads version 3",
            b[3]
        ));
    }
    let int = |i: usize| i32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    let encoding = int(4);
    if encoding != 1 {
        return Err(format!(
            "encoding {encoding}; spectrace reads float32 grids (encoding 1)"
        ));
    }
    let dims = [int(8), int(12), int(16), int(20)];
    if let Some(d) = dims.iter().find(|d| **d <= 0) {
        return Err(format!(
            "resolution {} × {} × {} with {} channels: every count must be positive, not {d}",
            dims[0], dims[1], dims[2], dims[3]
        ));
    }
    let count = dims.iter().map(|&d| d as u64).product::<u64>();
    if count > MAX_VALUES {
        return Err(format!(
            "{} × {} × {} voxels of {} channels is {count} values, more than spectrace reads ({MAX_VALUES})",
            dims[0], dims[1], dims[2], dims[3]
        ));
    }
    let want = HEADER as u64 + 4 * count;
    if b.len() as u64 != want {
        return Err(format!(
            "the header declares {} × {} × {} voxels of {} channels ({want} bytes), but the file has {} bytes",
            dims[0],
            dims[1],
            dims[2],
            dims[3],
            b.len()
        ));
    }
    let float = |i: usize| f32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    let bounds = [
        [float(24), float(28), float(32)],
        [float(36), float(40), float(44)],
    ];
    let values = b[HEADER..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    Ok(VolFile {
        res: [dims[0] as usize, dims[1] as usize, dims[2] as usize],
        channels: dims[3] as usize,
        bounds,
        values,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(dims: [i32; 4], values: &[f32]) -> Vec<u8> {
        let mut b = b"VOL\x03".to_vec();
        b.extend_from_slice(&1i32.to_le_bytes());
        for d in dims {
            b.extend_from_slice(&d.to_le_bytes());
        }
        for f in [0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0] {
            b.extend_from_slice(&f.to_le_bytes());
        }
        for v in values {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b
    }

    #[test]
    fn reads_what_it_writes() {
        let v = parse(&file([2, 1, 1, 1], &[0.25, 4.0])).expect("valid");
        assert_eq!(v.res, [2, 1, 1]);
        assert_eq!(v.channels, 1);
        assert_eq!(v.values, vec![0.25, 4.0]);
    }

    #[test]
    fn header_and_size_must_agree() {
        let e = parse(&file([2, 2, 2, 1], &[0.0; 7])).err().expect("short");
        assert!(e.contains("the file has"), "{e}");
        let e = parse(&file([10000, 10000, 10000, 1], &[]))
            .err()
            .expect("huge");
        assert!(e.contains("more than spectrace reads"), "{e}");
        let e = parse(&file([-1, 2, 2, 1], &[])).err().expect("negative");
        assert!(e.contains("must be positive"), "{e}");
        assert!(parse(b"VOX").is_err());
    }
}
