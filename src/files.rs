//! Reading input files defensively: regular files only (never a device such as /dev/zero, a
//! FIFO that blocks, or a folder), and never more bytes than a cap, checked before reading.
//! Every loader reads scene, include, mesh, spectrum and image files through here, and
//! compressed data is inflated here (the one module that names `flate2`).

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// Scene files, Mitsuba includes and spectrum tables: 256 MiB.
pub const MAX_TEXT_BYTES: u64 = 256 << 20;
/// Mesh files (OBJ, PLY, Mitsuba .serialized): 8 GiB.
pub const MAX_MESH_BYTES: u64 = 8 << 30;
/// Image files (textures, environment maps): 2 GiB.
pub const MAX_IMAGE_BYTES: u64 = 2 << 30;

/// Opens `path` for reading if it is a regular file (symbolic links followed) of at most `cap`
/// bytes; returns the file and its size. The error explains a special file or a size over the
/// cap. The kind is checked before opening, so that a FIFO cannot block the open.
pub fn open_regular(path: &Path, cap: u64) -> io::Result<(File, u64)> {
    let kind = |m: &std::fs::Metadata| -> io::Result<u64> {
        if m.is_dir() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                "it is a folder, not a file",
            ));
        }
        if !m.is_file() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                "not a regular file (a device, FIFO or socket); only regular files are read",
            ));
        }
        if m.len() > cap {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "the file has {} bytes, more than the {} MiB this kind of file may have",
                    m.len(),
                    cap >> 20
                ),
            ));
        }
        Ok(m.len())
    };
    kind(&std::fs::metadata(path)?)?;
    let file = File::open(path)?;
    let len = kind(&file.metadata()?)?;
    Ok((file, len))
}

/// The bytes of a regular file of at most `cap` bytes ([`open_regular`]); a file that grows
/// past the cap while read is refused too.
pub fn read_bytes(path: &Path, cap: u64) -> io::Result<Vec<u8>> {
    let (file, len) = open_regular(path, cap)?;
    let mut out = Vec::with_capacity(len as usize);
    file.take(cap + 1).read_to_end(&mut out)?;
    if out.len() as u64 > cap {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("the file grew past {} MiB while read", cap >> 20),
        ));
    }
    Ok(out)
}

/// [`read_bytes`], inflated when the file is gzip-compressed (it begins with gzip's magic
/// number 1f 8b, which no PLY or text file does: pbrt-v4 reads `.ply.gz` and `.pbrt.gz`). The
/// inflated data is held to `cap` bytes too.
pub fn read_bytes_gz(path: &Path, cap: u64) -> io::Result<Vec<u8>> {
    let bytes = read_bytes(path, cap)?;
    if !bytes.starts_with(&[0x1f, 0x8b]) {
        return Ok(bytes);
    }
    let mut out = Vec::new();
    flate2::read::MultiGzDecoder::new(&bytes[..])
        .take(cap + 1)
        .read_to_end(&mut out)
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, format!("gzip data: {e}")))?;
    if out.len() as u64 > cap {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("the file inflates past {} MiB", cap >> 20),
        ));
    }
    Ok(out)
}

/// The first `n` bytes of a regular file (fewer if it is shorter), inflated first when it is
/// gzip-compressed (as [`read_bytes_gz`]): for reading a header without the whole file.
pub fn read_head_gz(path: &Path, n: usize) -> io::Result<Vec<u8>> {
    let (file, _) = open_regular(path, u64::MAX)?;
    let mut magic = Vec::new();
    (&file).take(2).read_to_end(&mut magic)?;
    let file = File::open(path)?;
    let mut out = Vec::new();
    if magic == [0x1f, 0x8b] {
        flate2::read::MultiGzDecoder::new(file)
            .take(n as u64)
            .read_to_end(&mut out)?;
    } else {
        file.take(n as u64).read_to_end(&mut out)?;
    }
    Ok(out)
}

/// A reader of the zlib stream (RFC 1950) in `bytes` (Mitsuba's `.serialized` meshes).
pub fn zlib_reader(bytes: &[u8]) -> impl Read + '_ {
    flate2::read::ZlibDecoder::new(bytes)
}

/// The UTF-8 text of a regular file of at most `cap` bytes ([`read_bytes_gz`]: inflated when
/// gzip-compressed).
pub fn read_text(path: &Path, cap: u64) -> io::Result<String> {
    String::from_utf8(read_bytes_gz(path, cap)?).map_err(|e| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_files_folders_and_big_files_are_refused() {
        let e = read_bytes(Path::new("/dev/zero"), 1 << 20).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        let e = read_bytes(Path::new("/tmp"), 1 << 20).unwrap_err();
        assert!(e.to_string().contains("folder"), "{e}");
        let dir = std::env::temp_dir().join(format!("spectrace-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("big.txt");
        std::fs::write(&f, vec![b'a'; 3 << 20]).unwrap();
        let e = read_text(&f, 2 << 20).unwrap_err();
        assert!(
            e.to_string().contains("3145728 bytes, more than the 2 MiB"),
            "{e}"
        );
        assert_eq!(read_text(&f, 4 << 20).unwrap().len(), 3 << 20);
        let e = read_text(&dir.join("missing"), 1).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::NotFound);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
