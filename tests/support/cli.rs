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

/// The Y channel of an EXR as (width, height, values).
pub fn y_channel(path: &Path) -> (usize, usize, Vec<f64>) {
    let img = spectrace::image_io::read_exr(path).unwrap_or_else(|e| panic!("{e}"));
    let y = img
        .channel("Y")
        .unwrap_or_else(|| panic!("{}: no Y", path.display()))
        .iter()
        .map(|&v| v as f64)
        .collect();
    (img.width, img.height, y)
}

/// Renders `scene` to `exr` at 256 spp with `seed` on Mitsuba's scale (`--mitsuba-units`),
/// as the Mitsuba reference comparisons do; panics with spectrace's error output if it fails.
pub fn render_mitsuba_units(scene: &Path, exr: &Path, seed: &str) {
    let o = Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .arg("render")
        .arg(scene)
        .arg("-o")
        .arg(exr)
        .args(["--quiet", "--mitsuba-units", "--spp", "256", "--seed", seed])
        .output()
        .expect("spectrace runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
