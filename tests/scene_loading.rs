//! The example scenes load and build, and what they state arrives in the scene.

use std::path::{Path, PathBuf};

use spectrace::light::Light;
use spectrace::scene::build;

fn scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("scenes/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    v.sort();
    v
}

#[test]
fn example_scenes_load_and_build() {
    let all = scenes();
    assert!(all.len() >= 4);
    for p in all {
        let desc = spectrace::loader::load(&p).unwrap_or_else(|e| panic!("{e}"));
        let scene = build(&desc).unwrap_or_else(|e| panic!("{e}"));
        assert!(!scene.lights.is_empty(), "{}", p.display());
        assert_eq!(scene.surfaces.len(), scene.shapes.len());
        assert!(
            scene.light_power.iter().all(|w| w.is_finite() && *w > 0.0),
            "{}: {:?}",
            p.display(),
            scene.light_power
        );
    }
}

#[test]
fn cornell_box_is_in_millimetres() {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.toml");
    let scene = build(&spectrace::loader::load(&p).unwrap()).unwrap();
    // the classic box is 556 mm wide, 548.8 mm high, 559.2 mm deep
    let (lo, hi) = scene.bounds;
    let size = hi - lo;
    assert!(
        (size.x - 0.556).abs() < 1e-4
            && (size.y - 0.5488).abs() < 1e-4
            && (size.z - 0.5592).abs() < 1e-4,
        "{size}"
    );
    // the ceiling light: 130 mm × 105 mm, 60 W
    let light = scene
        .lights
        .iter()
        .position(|l| matches!(l, Light::Area(_)))
        .expect("area light");
    let Light::Area(a) = &scene.lights[light] else {
        unreachable!()
    };
    let area = scene.shapes[a.shape as usize].area();
    assert!((area - 0.130 * 0.105).abs() < 1e-6, "{area}");
    assert!(
        (scene.light_power[light] - 60.0).abs() < 0.06,
        "{}",
        scene.light_power[light]
    );
}
