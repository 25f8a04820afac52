//! Mitsuba 3 XML import: a scene renders to the closed form on Mitsuba's scale, parameters and
//! references resolve, and unsupported input gives located errors naming an alternative.

mod support;

use std::f64::consts::PI;
use std::path::Path;

use spectrace::loader::mitsuba::load_str;

const PLANE: &str = r#"<scene version="3.0.0">
  <default name="spp" value="256"/>
  <default name="albedo" value="0.5"/>
  <integrator type="path"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="60"/>
    <transform name="to_world"><lookat origin="0, 5, 0" target="0, 0, 0" up="0, 0, -1"/></transform>
    <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
    <film type="hdrfilm">
      <integer name="width" value="32"/><integer name="height" value="32"/>
      <rfilter type="box"/>
    </film>
  </sensor>
  <bsdf type="diffuse" id="grey"><float name="reflectance" value="$albedo"/></bsdf>
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/></transform>
    <ref id="grey"/>
  </shape>
  <emitter type="point">
    <point name="position" x="0" y="2" z="0"/>
    <spectrum name="intensity" value="10"/>
  </emitter>
</scene>"#;

fn err(xml: &str) -> String {
    match load_str(xml, Path::new("t.xml"), &[]) {
        Ok(d) => match spectrace::build::build(&d) {
            Ok(_) => panic!("no error for:\n{xml}"),
            Err(e) => e.to_string(),
        },
        Err(e) => e.to_string(),
    }
}

/// A point light of spectral intensity 10 (Mitsuba's unitless numbers, read as W·sr⁻¹·nm⁻¹)
/// 2 m over a ρ = 0.5 plane: on Mitsuba's scale Y = ρ/π · 10 · cos θ / r² · (∫ȳ / 106.7502594),
/// Mitsuba 3.9.1's film normalisation.
#[test]
fn point_light_over_plane_on_mitsuba_scale() {
    let desc = load_str(PLANE, Path::new("plane.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(desc.film.spp, 256);
    assert_eq!(
        desc.integrator.max_depth, 1,
        "Mitsuba max_depth 2 = one bounce"
    );
    let scene = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
    let (mut img, _) = support::render::render_with(&scene, |_| {});
    spectrace::output::to_mitsuba_scale(&mut img);
    for (px, py) in [(16, 16), (5, 20), (28, 3)] {
        let (r2, cos) = support::render::plane_point(&scene, px, py);
        let want = 0.5 / PI * 10.0 * cos / r2 * (106.856895 / 106.7502594);
        let got = img.xyz[py * 32 + px][1] as f64;
        assert!(
            (got / want - 1.0).abs() < 0.01,
            "pixel ({px},{py}): Y = {got}, want {want}"
        );
    }
}

#[test]
fn defines_override_defaults() {
    let d = load_str(PLANE, Path::new("plane.xml"), &[("spp".into(), "8".into())]).unwrap();
    assert_eq!(d.film.spp, 8);
    let e = err(&PLANE.replace("value=\"$albedo\"", "value=\"$nope\""));
    assert!(
        e.contains("$nope is not defined") && e.starts_with("t.xml:"),
        "{e}"
    );
}

#[test]
fn import_errors_are_located_and_suggest_alternatives() {
    let e = err(&PLANE.replace("type=\"diffuse\"", "type=\"difuse\""));
    assert!(
        e.contains("t.xml:14:") && e.contains("\"difuse\"") && e.contains("\"diffuse\""),
        "{e}"
    );
    let e = err(&PLANE.replace("type=\"rectangle\"", "type=\"ply\""));
    assert!(e.contains("missing filename"), "{e}");
    let e = err(&PLANE.replace(
        "type=\"rectangle\">",
        "type=\"ply\"><string name=\"filename\" value=\"nope.ply\"/>",
    ));
    assert!(e.contains("nope.ply"), "{e}");
    let e = err(&PLANE.replace("type=\"rectangle\"", "type=\"torus\""));
    assert!(
        e.contains("torus") && e.contains("(supported: obj, ply"),
        "{e}"
    );
    let e = err(&PLANE.replace(
        "<rotate x=\"1\" angle=\"-90\"/>",
        "<rotate x=\"1\" angle=\"right\"/>",
    ));
    assert!(
        e.contains("\"right\" is not a number") && e.contains("t.xml:16:"),
        "{e}"
    );
    let e = err(&PLANE.replace("<ref id=\"grey\"/>", "<ref id=\"gray\"/>"));
    assert!(e.contains("\"gray\"") && e.contains("not defined"), "{e}");
    let e = err(&PLANE.replace(
        "<integrator type=\"path\">",
        "<include filename=\"missing.xml\"/><integrator type=\"path\">",
    ));
    assert!(e.contains("missing.xml"), "{e}");
    let e = err(&PLANE.replace("<emitter type=\"point\">", "<emitter type=\"sunsky\">"));
    assert!(e.contains("sunsky") && e.contains("(supported: "), "{e}");
    let e = err(&PLANE.replace(
        "<bsdf type=\"diffuse\" id=\"grey\">",
        "<bsdf type=\"blendbsdf\" id=\"grey\">",
    ));
    assert!(e.contains("blendbsdf"), "{e}");
    let e = err("<scene version=\"3.0.0\"><sensor type=\"perspective\">");
    assert!(e.contains("never closed") || e.contains("t.xml:1:"), "{e}");
    let e = err(&PLANE.replace("version=\"3.0.0\"", "version=\"0.5\""));
    assert!(e.contains("version 0.5"), "{e}");
}

/// Spot, filter and mesh settings are read as Mitsuba 3 reads them (src/emitters/spot.cpp,
/// src/rfilters/gaussian.cpp, src/render/mesh.cpp); a spot texture's missing image is named
/// with its line.
#[test]
fn spot_filter_and_mesh_normals_follow_mitsuba() {
    use spectrace::loader::desc::{LightKind, MeshNormals, ShapeKind, SpotFalloff};
    let spot = PLANE.replace(
        r#"<emitter type="point">
    <point name="position" x="0" y="2" z="0"/>"#,
        r#"<emitter type="spot">
    <transform name="to_world"><lookat origin="0, 2, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
    <float name="cutoff_angle" value="30"/>"#,
    );
    let d = load_str(&spot, Path::new("t.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    match &d.lights[0].kind {
        LightKind::Spot {
            cone_angle,
            falloff_start,
            falloff,
            ..
        } => {
            use spectrace::units::angle::degree;
            assert_eq!(*falloff, SpotFalloff::LinearAngle);
            assert!((cone_angle.get::<degree>() - 30.0).abs() < 1e-9);
            // beam_width defaults to 3/4 of cutoff_angle
            assert!((falloff_start.get::<degree>() - 22.5).abs() < 1e-9);
        }
        k => panic!("{k:?}"),
    }
    let e = err(&spot.replace(
        r#"<float name="cutoff_angle" value="30"/>"#,
        r#"<float name="cutoff_angle" value="30"/>
    <texture type="bitmap" name="texture"><string name="filename" value="a.png"/></texture>"#,
    ));
    assert!(
        e.contains("t.xml:22:") && e.contains("a.png") && e.contains("does not exist"),
        "{e}"
    );

    // the default rfilter is Mitsuba's gaussian (stddev 0.5)
    let d = load_str(
        &PLANE.replace(r#"<rfilter type="box"/>"#, ""),
        Path::new("t.xml"),
        &[],
    )
    .unwrap();
    assert_eq!(
        d.film.filter,
        spectrace::film::filter::gaussian::Desc::mitsuba(0.5)
    );
    let d = load_str(
        &PLANE.replace(
            r#"<rfilter type="box"/>"#,
            r#"<rfilter type="gaussian"><float name="stddev" value="0.3"/></rfilter>"#,
        ),
        Path::new("t.xml"),
        &[],
    )
    .unwrap();
    assert_eq!(
        d.film.filter,
        spectrace::film::filter::gaussian::Desc::mitsuba(0.3)
    );

    // meshes without normals are smoothed unless face_normals is true
    let mesh = |extra: &str| {
        PLANE.replace(
            r#"<shape type="rectangle">"#,
            &format!(r#"<shape type="obj"><string name="filename" value="m.obj"/>{extra}"#),
        )
    };
    let normals = |xml: &str| {
        let d = load_str(xml, Path::new("t.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
        match &d.shapes[0].kind {
            ShapeKind::Obj { normals, .. } => *normals,
            k => panic!("{k:?}"),
        }
    };
    assert_eq!(normals(&mesh("")), MeshNormals::FromFileOrSmooth);
    assert_eq!(
        normals(&mesh(r#"<boolean name="face_normals" value="true"/>"#)),
        MeshNormals::Flat
    );
    let e = err(&mesh(r#"<boolean name="face_normals" value="yes"/>"#));
    assert!(
        e.contains("face_normals") && e.contains("true or false"),
        "{e}"
    );
}
