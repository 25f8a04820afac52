//! Running OpenImageIO's `idiff` and `oiiotool` from tests.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Thresholds for one comparison (see `idiff --help`); a pixel fails when its absolute
/// difference exceeds `fail` and its relative difference exceeds `failrelative`.
#[derive(Clone, Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Thresholds {
    pub spp: u32,
    pub fail: f64,
    pub failrelative: f64,
    pub failpercent: f64,
    pub warn: f64,
    pub why: String,
}

fn tool(name: &str) -> PathBuf {
    let ok = Command::new(name)
        .arg("--help")
        .output()
        .is_ok_and(|o| o.status.success() || !o.stdout.is_empty());
    assert!(
        ok,
        "`{name}` not found: install OpenImageIO's tools (`pip install OpenImageIO` or `apt-get install openimageio-tools`); .ci/run does this"
    );
    PathBuf::from(name)
}

/// Keeps only `channels` of `src` in `dst` (oiiotool --ch).
pub fn extract(src: &Path, channels: &str, dst: &Path) {
    let out = Command::new(tool("oiiotool"))
        .arg(src)
        .args(["--ch", channels, "-o"])
        .arg(dst)
        .output()
        .expect("oiiotool runs");
    assert!(
        out.status.success(),
        "oiiotool failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Compares `ours` with `reference`. On failure, writes `idiff -o diff.exr -abs -scale 10` next
/// to `ours` and returns Err with the idiff report and the diff path.
pub fn idiff(reference: &Path, ours: &Path, t: &Thresholds) -> Result<String, String> {
    let args = |cmd: &mut Command| {
        cmd.args([
            "-fail",
            &t.fail.to_string(),
            "-failrelative",
            &t.failrelative.to_string(),
        ])
        .args([
            "-failpercent",
            &t.failpercent.to_string(),
            "-warn",
            &t.warn.to_string(),
        ]);
    };
    let mut cmd = Command::new(tool("idiff"));
    args(&mut cmd);
    let out = cmd.arg(reference).arg(ours).output().expect("idiff runs");
    let report = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    // idiff exits 0 (pass), 1 (warning), 2 (failure), 3+ (size mismatch, unreadable)
    match out.status.code() {
        Some(0) | Some(1) => Ok(report),
        _ => {
            let diff = ours.with_file_name("diff.exr");
            let mut cmd = Command::new(tool("idiff"));
            args(&mut cmd);
            let _ = cmd
                .arg("-o")
                .arg(&diff)
                .args(["-abs", "-scale", "10"])
                .arg(reference)
                .arg(ours)
                .output();
            Err(format!(
                "{report}\ndifference image (×10): {}",
                diff.display()
            ))
        }
    }
}
