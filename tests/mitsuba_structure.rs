//! Mitsuba scene structure read as Mitsuba 3.9.1 reads it: `<path>` folders join the file
//! resolver, includes resolve against the scene's folder (not the including file's), area
//! emitters and samplers declared at the top level are referred to by id, and every Mitsuba
//! sampler name is accepted with a note. Each layout below was loaded by Mitsuba 3.9.1 itself
//! (`scripts/check_mitsuba_structure.py` builds the same folders and prints what Mitsuba found).

use std::fs;
use std::path::{Path, PathBuf};

use spectrace::loader::mitsuba::load;

/// A fresh folder under the system's temporary folder.
fn fresh_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("spectrace-mi-{name}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&d);
    fs::create_dir_all(&d).unwrap();
    d
}

fn write(p: &Path, text: &str) {
    fs::create_dir_all(p.parent().unwrap()).unwrap();
    fs::write(p, text).unwrap();
}

/// One triangle in the z = 0 plane, as OBJ, with `n` extra vertices so files can be told apart.
fn obj(n: usize) -> String {
    let mut s = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for _ in 0..n {
        s.push_str("v 0 0 0\n");
    }
    s + "f 1 2 3\n"
}

const HEAD: &str = r#"<scene version="3.0.0">
  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <emitter type="constant"/>
"#;

/// `<path>` folders are searched before the scene's folder, the latest first; a name found in
/// none of them is read from the scene's folder.
#[test]
fn path_folders_are_searched_latest_first() {
    let d = fresh_dir("path");
    write(&d.join("a/tri.obj"), &obj(1));
    write(&d.join("b/tri.obj"), &obj(2));
    write(&d.join("tri.obj"), &obj(3));
    write(&d.join("only_here.obj"), &obj(4));
    let scene = format!(
        r#"{HEAD}  <path value="a"/>
  <path value="b"/>
  <shape type="obj"><string name="filename" value="tri.obj"/></shape>
  <shape type="obj"><string name="filename" value="only_here.obj"/></shape>
</scene>"#
    );
    write(&d.join("scene.xml"), &scene);
    let desc = load(&d.join("scene.xml"), &[]).unwrap();
    let paths: Vec<PathBuf> = desc
        .shapes
        .iter()
        .map(|s| match &s.kind {
            spectrace::loader::desc::ShapeKind::Obj { path, .. } => path.clone(),
            other => panic!("not an obj: {other:?}"),
        })
        .collect();
    assert_eq!(paths[0], d.join("b/tri.obj"), "the latest <path> wins");
    assert_eq!(paths[1], d.join("only_here.obj"));

    // a folder that does not exist is a located error
    write(
        &d.join("bad.xml"),
        &format!("{HEAD}  <path value=\"nowhere\"/>\n</scene>"),
    );
    let e = load(&d.join("bad.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("bad.xml:7") && e.contains("nowhere"), "{e}");
}

/// An include is looked for next to the file that includes it, then by the scene's resolver;
/// every other file an included file names (here a mesh) is resolved by the scene's resolver,
/// not against the included file's folder; a `<path>` in an included file has no effect.
#[test]
fn includes_resolve_as_mitsuba() {
    let d = fresh_dir("include");
    write(
        &d.join("parts/shapes.xml"),
        r#"<scene version="3.0.0">
  <path value="meshes"/>
  <include filename="light.xml"/>
  <include filename="parts/light2.xml"/>
  <shape type="obj"><string name="filename" value="tri.obj"/></shape></scene>"#,
    );
    write(
        &d.join("parts/light.xml"),
        r#"<scene version="3.0.0"><emitter type="point"><point name="position" value="0, 3, 0"/></emitter></scene>"#,
    );
    write(
        &d.join("parts/light2.xml"),
        r#"<scene version="3.0.0"><emitter type="point"><point name="position" value="0, 4, 0"/></emitter></scene>"#,
    );
    write(&d.join("parts/tri.obj"), &obj(1));
    write(&d.join("parts/meshes/tri.obj"), &obj(2));
    write(&d.join("tri.obj"), &obj(3));
    write(
        &d.join("scene.xml"),
        &format!("{HEAD}  <include filename=\"parts/shapes.xml\"/>\n</scene>"),
    );
    let desc = load(&d.join("scene.xml"), &[]).unwrap();
    assert_eq!(
        desc.lights.len(),
        3,
        "the constant and both included point lights"
    );
    match &desc.shapes[0].kind {
        spectrace::loader::desc::ShapeKind::Obj { path, .. } => {
            assert_eq!(path, &d.join("tri.obj"))
        }
        other => panic!("not an obj: {other:?}"),
    }
    assert!(
        desc.notes
            .iter()
            .any(|n| n.contains("<path> inside an included file")),
        "{:?}",
        desc.notes
    );
}

/// An area emitter declared at the top level with an id is a declaration: the shapes that
/// refer to it emit, and it is not a light of its own. A sampler declared at the top level is
/// referred to from the sensor; its `sample_count` is read.
#[test]
fn top_level_emitters_and_samplers_are_referred_to() {
    let d = fresh_dir("refs");
    write(
        &d.join("scene.xml"),
        r#"<scene version="3.0.0">
  <sampler type="ldsampler" id="s"><integer name="sample_count" value="64"/></sampler>
  <emitter type="area" id="lamp"><rgb name="radiance" value="3, 3, 3"/></emitter>
  <sensor type="perspective">
    <ref id="s"/>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <shape type="sphere"><ref id="lamp"/></shape>
  <shape type="disk"/>
</scene>"#,
    );
    let desc = load(&d.join("scene.xml"), &[]).unwrap();
    assert_eq!(desc.film.spp, 64);
    assert!(desc.lights.is_empty());
    assert!(desc.shapes[0].emission.is_some() && desc.shapes[1].emission.is_none());
    assert!(
        desc.notes.len() == 1 && desc.notes[0].contains("ldsampler"),
        "{:?}",
        desc.notes
    );
    spectrace::build::build(&desc).expect("builds");

    // an area emitter at the top level without an id belongs in a shape
    write(
        &d.join("bad.xml"),
        &format!("{HEAD}  <emitter type=\"area\"/>\n</scene>"),
    );
    let e = load(&d.join("bad.xml"), &[]).unwrap_err().to_string();
    assert!(
        e.contains("bad.xml:7") && e.contains("inside a <shape>"),
        "{e}"
    );
}

/// Every sampler Mitsuba 3.9.1 names is accepted, and spectrace renders as many samples as it
/// would (sample_count 10: Mitsuba's `sampler.sample_count()` reports 10, 16, 12, 25, 16);
/// another name is refused with the list.
#[test]
fn every_mitsuba_sampler_is_accepted() {
    let d = fresh_dir("samplers");
    for (name, spp) in [
        ("independent", 10),
        ("stratified", 16),
        ("multijitter", 12),
        ("orthogonal", 25),
        ("ldsampler", 16),
    ] {
        let f = d.join(format!("{name}.xml"));
        write(
            &f,
            &(HEAD.replace(
                "<film",
                &format!(
                    "<sampler type=\"{name}\"><integer name=\"sample_count\" value=\"10\"/></sampler><film"
                ),
            ) + "</scene>"),
        );
        let desc = load(&f, &[]).unwrap();
        assert_eq!(desc.film.spp, spp, "{name}");
    }
    let f = d.join("bad.xml");
    write(
        &f,
        &(HEAD.replace("<film", "<sampler type=\"sobol\"/><film") + "</scene>"),
    );
    let e = load(&f, &[]).unwrap_err().to_string();
    assert!(e.contains("\"sobol\"") && e.contains("ldsampler"), "{e}");
}

/// Band radiance per pixel of an emitter of 2 W/m²/sr/nm seen head-on, behind a rectangle of
/// BSDF `sheet` (none if empty), at Mitsuba path length `depth`, with `spp` samples.
fn sheet_render(depth: i32, sheet: &str, spp: u32) -> Vec<f32> {
    let blocker = if sheet.is_empty() {
        String::new()
    } else {
        format!(
            r#"<shape type="rectangle">
    <transform name="to_world"><scale value="10"/><translate z="1"/></transform>
    <bsdf type="{sheet}"/>
  </shape>"#
        )
    };
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="{depth}"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="20"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  {blocker}
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/><translate z="-1"/></transform>
    <emitter type="area"><spectrum name="radiance" value="2"/></emitter>
  </shape>
</scene>"#
    );
    let desc =
        spectrace::loader::mitsuba::load_str(&xml, std::path::Path::new("sheet.xml"), &[]).unwrap();
    let s = spectrace::build::build(&desc).unwrap();
    let mut o = spectrace::render::RenderOptions::from_scene(&s);
    o.threads = Some(1);
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let (film, _) = spectrace::render::render(&s, &o, &cancel, &|_, _| {}).unwrap();
    film.image().band
}

/// Mitsuba's `null` BSDF: light passes straight through, but the crossing counts toward
/// `max_depth` (Mitsuba 3.9.1 renders an emitter behind a null rectangle black at max_depth 1
/// and at its full radiance from max_depth 2). With the same seed the wavelengths are the same,
/// so the emitter seen through the null surface gives exactly the image of the emitter alone.
#[test]
fn null_bsdf_passes_light_and_counts_a_bounce() {
    let alone = sheet_render(1, "", 4);
    assert!(alone.iter().all(|&l| l > 100.0));
    assert!(
        sheet_render(1, "null", 4).iter().all(|&l| l == 0.0),
        "the null crossing uses the only bounce"
    );
    for depth in [2, 3] {
        let through = sheet_render(depth, "null", 4);
        for (a, b) in alone.iter().zip(&through) {
            assert!(
                (a - b).abs() <= 1e-5 * a,
                "max_depth {depth}: {b} through null, {a} alone"
            );
        }
    }
}

/// Mitsuba's `thindielectric` (index 1.5046 in air): a sheet in front of an emitter passes
/// 1 − R of it, R = 2F/(1 + F) with the Fresnel reflectance F (0.0401 at normal incidence; the
/// camera's rays are within 10° of it, where F changes by < 0.1 %): 0.9221 of the emitter alone
/// with the same seed, over 16 384 samples (binomial noise 0.23 %).
#[test]
fn thin_dielectric_passes_one_minus_its_reflectance() {
    let sum = |v: Vec<f32>| v.iter().map(|&l| l as f64).sum::<f64>();
    let alone = sum(sheet_render(2, "", 256));
    let through = sum(sheet_render(2, "thindielectric", 256));
    let eta = 1.5046f64 / 1.000277;
    let f = ((eta - 1.0) / (eta + 1.0)).powi(2);
    let want = 1.0 - 2.0 * f / (1.0 + f);
    println!("transmitted {:.5}, closed form {want:.5}", through / alone);
    assert!(
        (through / alone / want - 1.0).abs() < 0.01,
        "{} vs {want}",
        through / alone
    );
}

/// `direct` reads its sample counts as Mitsuba (`shading_samples` sets both, each count
/// overrides it); `volpath` without media is `path` with the same depth; `moment` wraps one.
#[test]
fn integrators_read_as_mitsuba() {
    use spectrace::loader::desc::IntegratorKind;
    let load = |integrator: &str| {
        let xml = HEAD.replacen(
            "<scene version=\"3.0.0\">",
            &format!("<scene version=\"3.0.0\">{integrator}"),
            1,
        ) + "</scene>";
        spectrace::loader::mitsuba::load_str(&xml, std::path::Path::new("i.xml"), &[])
            .unwrap()
            .integrator
    };
    let d = load(
        r#"<integrator type="direct"><integer name="shading_samples" value="3"/><integer name="bsdf_samples" value="2"/></integrator>"#,
    );
    assert_eq!(
        d.kind,
        IntegratorKind::Direct {
            emitter_samples: 3,
            bsdf_samples: 2
        }
    );
    let v =
        load(r#"<integrator type="volpath"><integer name="max_depth" value="5"/></integrator>"#);
    assert_eq!(
        (v.kind, v.max_depth, v.moment),
        (IntegratorKind::Path, 4, false)
    );
    let m = load(r#"<integrator type="moment"><integrator type="direct"/></integrator>"#);
    assert!(m.moment);
    assert_eq!(
        m.kind,
        IntegratorKind::Direct {
            emitter_samples: 1,
            bsdf_samples: 1
        }
    );
}

/// `$name` is substituted once, left to right, as Mitsuba does: a default that names itself
/// leaves its text in place (then a located number error), instead of growing for ever.
#[test]
fn self_referring_defaults_do_not_loop() {
    let xml = HEAD.replacen(
        "<scene version=\"3.0.0\">",
        "<scene version=\"3.0.0\"><default name=\"spp\" value=\"1$spp\"/>",
        1,
    )
    .replace(
        "<film",
        "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler><film",
    ) + "</scene>";
    let e = spectrace::loader::mitsuba::load_str(&xml, std::path::Path::new("d.xml"), &[])
        .unwrap_err()
        .to_string();
    assert!(e.contains("\"1$spp\" is not a number"), "{e}");
}

/// Two `<default>`s of one name: the first wins, as in Mitsuba 3.9.1 (measured:
/// `mi.load_string` with `max_depth` defaulted to 3, then to 7, gives a path integrator of
/// max_depth 3). Mitsuba's documentation scenes rely on it: they default `integrator` to
/// `volpath` before including a file that defaults it to `path`.
#[test]
fn the_first_default_wins() {
    let xml = HEAD.replacen(
        "<scene version=\"3.0.0\">",
        "<scene version=\"3.0.0\"><default name=\"d\" value=\"3\"/><default name=\"d\" value=\"7\"/><integrator type=\"path\"><integer name=\"max_depth\" value=\"$d\"/></integrator>",
        1,
    ) + "</scene>";
    let desc = spectrace::loader::mitsuba::load_str(&xml, std::path::Path::new("d.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    // Mitsuba's path length 3 is 2 bounces
    assert_eq!(desc.integrator.max_depth, 2);
}
