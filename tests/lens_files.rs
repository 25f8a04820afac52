//! Every lens file in `tests/bad_lenses/` fails, through a realistic camera in a TOML scene,
//! with the error its header promises, at the line its `# <-- error` marks (as
//! `tests/bad_scenes.rs` checks scenes); and the shipped lens files read and build.

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
        let text = std::fs::read_to_string(path).unwrap();
        let expects: Vec<&str> = text
            .lines()
            .filter_map(|l| l.strip_prefix("# expect: "))
            .collect();
        assert!(
            !expects.is_empty(),
            "{}: no `# expect:` line",
            path.display()
        );
        let marker = text
            .lines()
            .position(|l| l.contains("# <-- error"))
            .map(|i| i + 1);
        let msg = match std::panic::catch_unwind(|| load_and_build(path)) {
            Err(_) => {
                failures.push(format!("{}: PANICKED", path.display()));
                continue;
            }
            Ok(Ok(())) => {
                failures.push(format!("{}: built without error", path.display()));
                continue;
            }
            Ok(Err(m)) => m,
        };
        let prefix = format!("{}:", path.display());
        if !msg.starts_with(&prefix) {
            failures.push(format!(
                "{}: not located in the lens file: {msg}",
                path.display()
            ));
        }
        for e in &expects {
            if !msg.contains(e) {
                failures.push(format!("{}: lacks \"{e}\": {msg}", path.display()));
            }
        }
        if let Some(line) = marker
            && !msg.starts_with(&format!("{prefix}{line}:"))
        {
            failures.push(format!("{}: expected line {line}: {msg}", path.display()));
        }
        println!("{msg}");
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
