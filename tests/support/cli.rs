//! Running the `spectrace` binary from integration tests.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh, empty folder under the system's temporary folder, named for the test and process.
pub fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("spectrace-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Runs `spectrace ARGS` in `dir`; returns whether it succeeded and its standard error.
pub fn spectrace(dir: &Path, args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}
