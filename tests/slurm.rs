//! The Slurm recipe of `docs/render-farm.md`, end to end: `scripts/slurm_test.sh` starts a
//! one-node Slurm cluster (Debian's slurm-wlm, installed if missing; needs root), submits an
//! array of 4 `render --part` jobs and a merge job that depends on it, and checks that the
//! merged image is bit-identical to one render (OpenImageIO's idiff with zero tolerance).
//!
//! Ignored by default (it installs packages and starts daemons); `.ci/run` runs it as root:
//! `cargo test --test slurm -- --ignored`.

use std::path::Path;
use std::process::Command;

#[test]
#[ignore = "installs slurm-wlm and starts a local cluster; run with --ignored as root"]
fn slurm_array_parts_merge_bit_identical() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let status = Command::new("bash")
        .arg(root.join("scripts/slurm_test.sh"))
        .arg(env!("CARGO_BIN_EXE_spectrace"))
        .arg(root.join("tests/reference/cornell/scene.xml"))
        .args(["64", "4"])
        .current_dir(root)
        .status()
        .expect("runs scripts/slurm_test.sh");
    assert!(status.success(), "scripts/slurm_test.sh failed: {status:?}");
}
