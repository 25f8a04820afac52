//! Every lens file in `tests/bad_lenses/` fails, through a realistic camera in a TOML scene,
//! with the error its header promises, at the line its `# <-- error` marks (as
//! `tests/bad_scenes.rs` checks scenes); and the shipped lens files read and build.

mod support;

use std::path::{Path, PathBuf};

fn scene_with(lens: &Path) -> String {
    format!(
        "[camera]\ntype = \"realistic\"\neye = [0, 0, 0]\ntarget = [0, 0, 1]\nlens_file = \"{}\"\n\
         [film]\nwidth = 8\nheight = 8\n\
         [[shapes]]\ntype = \"sphere\"\ncenter = [0, 0, 5]\nradius = 1\nemission = {{ radiance = \"1 W/m^2/sr\" }}\n",
        lens.display().to_string().replace('\\', "/")
    )
}

fn load_and_build(lens: &Path) -> Result<(), String> {
    let toml = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_lenses/scene.toml");
    let desc = spectrace::loader::load_str(&scene_with(lens), &toml).map_err(|e| e.to_string())?;
    spectrace::build::build(&desc)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

fn corpus() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_lenses");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("corpus folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "lens"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_bad_lens_file_errors_at_its_line() {
    let files = corpus();
    assert!(files.len() >= 12, "{} files", files.len());
    let mut failures = Vec::new();
    for path in &files {
        match support::corpus::check(path, || load_and_build(path)) {
            Ok(msg) => println!("{msg}"),
            Err(f) => failures.extend(f),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_shipped_lens_files_build_and_focus() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lenses");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|e| e == "lens") {
            n += 1;
            load_and_build(&path).unwrap_or_else(|e| panic!("{e}"));
        }
    }
    assert!(n >= 1);
}
