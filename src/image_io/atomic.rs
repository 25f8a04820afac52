//! Atomic file replacement: write a temporary file beside the target, fsync it, rename it.

use std::ffi::OsString;
use std::fs::{File, OpenOptions};
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use super::{ImageError, invalid};

/// Writes `path` atomically: `f` writes into `<path>.tmp-<pid>-<n>` in the same folder, which is then
/// flushed, fsynced and renamed over `path`. Readers see either the old file or the complete new
/// one, never a partial one.
///
/// On any error (including an error returned by `f`, or a panic inside it) the temporary file
/// is removed and an existing file at `path` is left untouched. The temporary file is created
/// with `create_new`, so two writers of the same path in one process fail instead of mixing
/// their bytes. After the rename the folder is fsynced too (best effort: the new file is
/// already in place, so a failure there is not reported).
pub fn write_atomically(
    path: &Path,
    f: impl FnOnce(&mut BufWriter<File>) -> Result<(), ImageError>,
) -> Result<(), ImageError> {
    let tmp = temp_path(path)?;
    let io_err = |action: String| {
        move |source| ImageError::Io {
            path: path.to_path_buf(),
            action,
            source,
        }
    };
    let file = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .map_err(io_err(format!(
            "cannot create temporary file {}",
            tmp.display()
        )))?;
    // From here on the guard removes the temporary file unless the rename succeeded.
    let mut guard = TempGuard {
        path: Some(tmp.clone()),
    };

    let mut writer = BufWriter::new(file);
    f(&mut writer)?;
    let file = writer
        .into_inner()
        .map_err(|e| e.into_error())
        .map_err(io_err(format!(
            "cannot write temporary file {}",
            tmp.display()
        )))?;
    file.sync_all().map_err(io_err(format!(
        "cannot fsync temporary file {}",
        tmp.display()
    )))?;
    drop(file);
    std::fs::rename(&tmp, path)
        .map_err(io_err(format!("cannot rename {} over it", tmp.display())))?;
    guard.path = None;

    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
        && let Ok(d) = File::open(dir)
    {
        let _ = d.sync_all();
    }
    Ok(())
}

/// `<path>.tmp-<pid>-<n>`, in the same folder as `path`.
fn temp_path(path: &Path) -> Result<PathBuf, ImageError> {
    let Some(name) = path.file_name() else {
        return Err(invalid(path, "the output path does not name a file"));
    };
    // process id and a counter: threads of one process (a checkpoint beside the image) never
    // share a temporary file
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let mut tmp_name = OsString::from(name);
    tmp_name.push(format!(".tmp-{}-{k}", std::process::id()));
    Ok(path.with_file_name(tmp_name))
}

/// Removes the temporary file when dropped, unless disarmed by taking `path`.
struct TempGuard {
    path: Option<PathBuf>,
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if let Some(p) = self.path.take() {
            let _ = std::fs::remove_file(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temp_name_sits_beside_the_target() {
        let pid = std::process::id();
        let t = temp_path(Path::new("/a/b/out.exr")).unwrap();
        assert_eq!(t.parent(), Some(Path::new("/a/b")));
        let name = t.file_name().unwrap().to_string_lossy().into_owned();
        assert!(name.starts_with(&format!("out.exr.tmp-{pid}-")), "{name}");
        // two temporary files of one process differ (threads writing at once)
        let (a, b) = (
            temp_path(Path::new("out.png")),
            temp_path(Path::new("out.png")),
        );
        assert_ne!(a.unwrap(), b.unwrap());
        assert!(temp_path(Path::new("/")).is_err());
    }
}
