//! Every file in `tests/bad_scenes/` (spectrace TOML, Mitsuba XML or pbrt-v4 read by the importers)
//! fails to load with the error its header promises.
//!
//! Header lines `# expect: TEXT` list substrings the message must contain, `# not: TEXT`
//! substrings it must not (in an XML file, inside a `<!-- … -->` comment). A line marked
//! `# <-- error` is where the error must point (line and column are always reported);
//! `support::corpus::check` reads them.

mod support;

use std::path::{Path, PathBuf};

fn corpus() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenes");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("corpus folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| {
            p.extension()
                .is_some_and(|e| e == "toml" || e == "xml" || e == "pbrt")
        })
        .collect();
    v.sort();
    v
}

fn load_and_build(path: &Path) -> Result<(), String> {
    let desc = if path.extension().is_some_and(|e| e == "xml") {
        spectrace::loader::mitsuba::load(path, &[])
    } else if path.extension().is_some_and(|e| e == "pbrt") {
        spectrace::loader::pbrt::load(path)
    } else {
        spectrace::loader::load(path)
    }
    .map_err(|e| {
        assert!(
            e.loc.line >= 1 && e.loc.col >= 1,
            "{}: error without a position: {e}",
            path.display()
        );
        e.to_string()
    })?;
    spectrace::build::build(&desc)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

#[test]
fn every_bad_scene_errors_cleanly() {
    let files = corpus();
    assert!(files.len() >= 25, "the corpus has {} scenes", files.len());
    let mut failures = Vec::new();
    for path in &files {
        match support::corpus::check(path, || load_and_build(path)) {
            Ok(msg) => println!("{msg}"),
            Err(f) => failures.extend(f),
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A FIFO named as the scene, an include or a mesh is refused at once (opening it would block
/// until a writer comes, reading it could go on for ever).
#[test]
fn fifos_are_refused_without_blocking() {
    let dir = std::env::temp_dir().join(format!("spectrace-fifo-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("pipe");
    let ok = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(ok.success());
    let (tx, rx) = std::sync::mpsc::channel();
    let d = dir.clone();
    std::thread::spawn(move || {
        let sensor = r#"<sensor type="perspective"><float name="fov" value="40"/></sensor>"#;
        let scene = |body: &str| format!(r#"<scene version="3.0.0">{sensor}{body}</scene>"#);
        let mut msgs = Vec::new();
        msgs.push(
            spectrace::loader::mitsuba::load(&d.join("pipe"), &[])
                .err()
                .map(|e| e.to_string()),
        );
        msgs.push(
            spectrace::loader::load(&d.join("pipe"))
                .err()
                .map(|e| e.to_string()),
        );
        for body in [
            r#"<include filename="pipe"/>"#,
            r#"<shape type="obj"><string name="filename" value="pipe"/></shape>"#,
        ] {
            let p = d.join("s.xml");
            std::fs::write(&p, scene(body)).unwrap();
            let r = spectrace::loader::mitsuba::load(&p, &[]).map_err(|e| e.to_string());
            msgs.push(match r {
                Ok(desc) => spectrace::build::build(&desc).err().map(|e| e.to_string()),
                Err(e) => Some(e),
            });
        }
        tx.send(msgs).unwrap();
    });
    let msgs = rx
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("loading FIFOs blocked");
    for m in msgs {
        let m = m.expect("a FIFO was accepted");
        assert!(
            m.contains("not a regular file") && m.contains("pipe"),
            "{m}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
