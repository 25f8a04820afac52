//! The example scenes load and build, and what they state arrives in the scene.

use std::path::{Path, PathBuf};

use spectrace::build::build;
use spectrace::light::Light;

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

/// The TOML forms of Mitsuba's `direct` and `moment` integrators and its `null`,
/// `thindielectric` and `mask` materials arrive in the description as their Mitsuba forms do.
#[test]
fn direct_moment_null_thin_dielectric_and_mask_in_toml() {
    use spectrace::loader::desc::{IntegratorKind, MaterialKind};
    let text = r#"
[camera]
eye = [0, 1, 4]
target = [0, 1, 0]
fov = "40 deg"

[film]
width = 8
height = 8

[integrator]
type = "direct"
emitter_samples = 2
bsdf_samples = 3
second_moment = true

[materials.pane]
type = "thin_dielectric"
ior = 1.5

[materials.nothing]
type = "null"

[materials.leaf]
type = "diffuse"
reflectance = 0.4

[materials.leaf_cutout]
type = "mask"
opacity = 0.25
material = "leaf"

[[shapes]]
type = "rectangle"
material = "pane"

[[shapes]]
type = "sphere"
radius = 0.5
material = "nothing"

[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.toml");
    let d = spectrace::loader::load_str(text, &path).unwrap();
    assert_eq!(
        d.integrator.kind,
        IntegratorKind::Direct {
            emitter_samples: 2,
            bsdf_samples: 3
        }
    );
    assert!(d.integrator.moment);
    let kinds: Vec<&MaterialKind> = d.materials.iter().map(|m| &m.kind).collect();
    assert!(kinds.iter().any(|k| matches!(
        k,
        MaterialKind::ThinDielectric { int_ior, exterior_ior } if *int_ior == 1.5 && *exterior_ior == 1.0
    )));
    assert!(kinds.iter().any(|k| matches!(k, MaterialKind::Null)));
    assert!(kinds.iter().any(|k| matches!(
        k,
        MaterialKind::Mask { inner, .. } if matches!(**inner, MaterialKind::Diffuse { .. })
    )));
    spectrace::build::build(&d).unwrap();
    // a mask of a material that does not exist, or of another mask, is a located error
    let bad = text.replace("material = \"leaf\"", "material = \"lead\"");
    let e = spectrace::loader::load_str(&bad, &path)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("materials.leaf_cutout.material") && e.contains("\"lead\""),
        "{e}"
    );
    let bad = text.replace("material = \"leaf\"", "material = \"leaf_cutout\"");
    let e = spectrace::loader::load_str(&bad, &path)
        .unwrap_err()
        .to_string();
    assert!(e.contains("cannot hold another mask or blend"), "{e}");
    // samples for another integrator are a located error
    let bad = text.replace("type = \"direct\"", "type = \"path\"");
    let e = spectrace::loader::load_str(&bad, &path)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("integrator.emitter_samples") && e.contains("direct"),
        "{e}"
    );
}

/// TOML `roughness = [α_u, α_v]` gives an anisotropic lobe (α_u along ∂p/∂u); a list of
/// another length, or a list for a plastic (isotropic, as Mitsuba's), is a located error.
#[test]
fn anisotropic_roughness_in_toml() {
    use spectrace::loader::desc::MaterialKind;
    let text = r#"
[camera]
eye = [0, 1, 4]
target = [0, 1, 0]
fov = "40 deg"

[film]
width = 8
height = 8

[materials.brushed]
type = "conductor"
metal = "Al"
roughness = [0.05, 0.3]

[materials.frosted]
type = "dielectric"
ior = 1.5
roughness = 0.2

[[shapes]]
type = "sphere"
radius = 0.5
material = "brushed"

[[shapes]]
type = "rectangle"
material = "frosted"

[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.toml");
    let d = spectrace::loader::load_str(text, &path).unwrap();
    let rough: Vec<Option<[f64; 2]>> = d
        .materials
        .iter()
        .filter_map(|m| match &m.kind {
            MaterialKind::Conductor { roughness, .. }
            | MaterialKind::Dielectric { roughness, .. } => Some(*roughness),
            _ => None,
        })
        .collect();
    assert!(rough.contains(&Some([0.05, 0.3])), "{rough:?}");
    assert!(rough.contains(&Some([0.2, 0.2])), "{rough:?}");
    spectrace::build::build(&d).unwrap();
    for (bad, want) in [
        ("roughness = [0.05, 0.3]", "roughness = [0.05]"),
        ("roughness = [0.05, 0.3]", "roughness = [0.05, 1.5]"),
        (
            "type = \"dielectric\"\nior = 1.5",
            "type = \"plastic\"\nior = 1.5",
        ),
    ] {
        let mut t = text.replace(bad, want);
        if want.contains("plastic") {
            t = t.replace(
                "roughness = 0.2",
                "roughness = [0.1, 0.2]\nreflectance = 0.5",
            );
        }
        let e = spectrace::loader::load_str(&t, &path)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("inline.toml:") && e.contains(".roughness"),
            "{e}"
        );
        println!("{want}: {e}");
    }
}

/// TOML `type = "blend"`: two named materials and a weight; errors for a list of another
/// length, an unknown name, a blend of a blend, and a weight outside [0, 1], each located.
#[test]
fn blend_in_toml() {
    use spectrace::loader::desc::MaterialKind;
    let text = r#"
[camera]
eye = [0, 1, 4]
target = [0, 1, 0]
fov = "40 deg"

[film]
width = 8
height = 8

[materials.paint]
type = "diffuse"
reflectance = 0.4

[materials.gold]
type = "conductor"
metal = "Au"
roughness = 0.2

[materials.worn]
type = "blend"
weight = 0.3
materials = ["paint", "gold"]

[[shapes]]
type = "sphere"
radius = 0.5
material = "worn"

[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.toml");
    let d = spectrace::loader::load_str(text, &path).unwrap();
    assert!(d.materials.iter().any(|m| matches!(
        &m.kind,
        MaterialKind::Blend { a, b, .. }
            if matches!(**a, MaterialKind::Diffuse { .. }) && matches!(**b, MaterialKind::Conductor { .. })
    )));
    spectrace::build::build(&d).unwrap();
    for (from, to, want) in [
        (r#"["paint", "gold"]"#, r#"["paint"]"#, "two materials"),
        (
            r#"["paint", "gold"]"#,
            r#"["paint", "silver"]"#,
            "\"silver\"",
        ),
        (
            r#"["paint", "gold"]"#,
            r#"["paint", "worn"]"#,
            "cannot hold another mask or blend",
        ),
        ("weight = 0.3", "weight = 1.3", "weight is 1.3"),
    ] {
        let e = spectrace::loader::load_str(&text.replace(from, to), &path)
            .unwrap_err()
            .to_string();
        println!("{to}: {e}");
        assert!(
            e.contains("inline.toml:") && e.contains("materials.worn") && e.contains(want),
            "{to}: {e}"
        );
    }
}

/// A wavelength range that misses the CIE colour-matching functions (360–830 nm) loads, with a
/// note that X, Y, Z, R, G, B will be black and L holds the radiance; one that overlaps them
/// has no note.
#[test]
fn wavelength_range_outside_the_cmfs_is_noted() {
    let scene = |range: &str| {
        format!(
            "[scene]\nwavelength_range = {range}\n[camera]\neye = [0, 1, 4]\ntarget = [0, 1, 0]\nfov = \"40 deg\"\n[film]\nwidth = 8\nheight = 8\nspp = 1\n[materials.m]\ntype = \"diffuse\"\nreflectance = 0.5\n[[shapes]]\ntype = \"sphere\"\nradius = \"1 m\"\nmaterial = \"m\"\n[[lights]]\ntype = \"point\"\nposition = [0, 3, 0]\npower = \"10 W\"\n"
        )
    };
    let p = Path::new("range.toml");
    let ir = spectrace::loader::load_str(&scene("[\"900 nm\", \"1000 nm\"]"), p).unwrap();
    assert_eq!(ir.notes.len(), 1, "{:?}", ir.notes);
    assert!(
        ir.notes[0].contains("900–1000 nm lies outside the CIE colour-matching functions")
            && ir.notes[0].contains("L channel"),
        "{}",
        ir.notes[0]
    );
    let uv = spectrace::loader::load_str(&scene("[\"200 nm\", \"360 nm\"]"), p).unwrap();
    assert_eq!(uv.notes.len(), 1);
    let vis = spectrace::loader::load_str(&scene("[\"700 nm\", \"1000 nm\"]"), p).unwrap();
    assert!(vis.notes.is_empty(), "{:?}", vis.notes);
}
