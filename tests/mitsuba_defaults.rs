//! Mitsuba 3 defaults and conventions read as Mitsuba 3.9.1 reads them, against numbers Mitsuba
//! itself produced (`tests/data/mitsuba_defaults.toml`, written by
//! `scripts/gen_mitsuba_defaults.py`): the sensor's field of view without `fov`, the D65 shape
//! and scale of an emitter's absent, bare-float, `d65` and `rgb` spectrum, `max_depth` as path
//! length, a point light placed by `to_world`; and, from Mitsuba's documented defaults, the
//! perfect-mirror conductor, Beckmann as the rough BSDFs' default distribution, and the refusal
//! of what spectrace cannot render (anisotropic roughness).

mod support;

use std::path::Path;

use serde::Deserialize;
use spectrace::loader::SceneDesc;
use spectrace::loader::desc::LightSelection;
use spectrace::loader::mitsuba::load_str;

#[derive(Deserialize)]
struct Data {
    fov: Vec<Fov>,
    emitter: Vec<Emitter>,
    max_depth: Vec<MaxDepth>,
    point: Vec<PointCase>,
}

#[derive(Deserialize)]
struct Fov {
    width: u32,
    height: u32,
    xml: String,
    x_fov: f64,
}

#[derive(Deserialize)]
struct Emitter {
    xml: String,
    spp: u32,
    xyz: [f64; 3],
    stderr: [f64; 3],
}

#[derive(Deserialize)]
struct MaxDepth {
    max_depth: i32,
    y_centre: f64,
    y_corner: f64,
}

#[derive(Deserialize)]
struct PointCase {
    transform: String,
    position: [f64; 3],
}

fn data() -> Data {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mitsuba_defaults.toml");
    toml::from_str(&std::fs::read_to_string(&p).expect("tests/data/mitsuba_defaults.toml"))
        .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn load(xml: &str) -> SceneDesc {
    load_str(xml, Path::new("defaults.xml"), &[]).unwrap_or_else(|e| panic!("{e}\n{xml}"))
}

fn err(xml: &str) -> String {
    match load_str(xml, Path::new("t.xml"), &[]) {
        Ok(d) => match spectrace::build::build(&d) {
            Ok(_) => panic!("no error for:\n{xml}"),
            Err(e) => e.to_string(),
        },
        Err(e) => e.to_string(),
    }
}

/// Mitsuba 3.9.1's XYZ film multiplies by `MI_CIE_Y_NORMALIZATION` = 1/106.7502594.
const MITSUBA_Y_NORM: f64 = 106.7502594;

/// The same scene as the generator's `ENV`: a constant environment seen by a 16 × 16 camera.
fn env_scene(depth: i32, radiance: &str, shapes: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="{depth}"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, -3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="64"/></sampler>
    <film type="hdrfilm">
      <integer name="width" value="16"/><integer name="height" value="16"/>
      <rfilter type="box"/><string name="pixel_format" value="xyz"/>
    </film>
  </sensor>
  <emitter type="constant">{radiance}</emitter>{shapes}
</scene>"#
    )
}

/// Horizontal field of view of the built camera, degrees: the angle between the rays through
/// the left and right edges of the film's middle row.
fn built_x_fov(desc: &SceneDesc) -> f64 {
    let scene = spectrace::build::build(desc).unwrap_or_else(|e| panic!("{e}"));
    let (w, h) = (desc.film.width as f32, desc.film.height as f32);
    let ray = |x: f32| {
        scene
            .camera
            .generate_ray(glam::Vec2::new(x, h / 2.0), glam::Vec2::splat(0.5))
            .d
            .normalize()
    };
    (ray(0.0).dot(ray(w)) as f64)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// Without `fov` Mitsuba takes a 50 mm lens on a 36 × 24 mm frame, matched along the
/// diagonal (34.02° across a square film); `focal_length`, `fov_axis` y / smaller / larger /
/// diagonal on square and non-square films give Mitsuba's `x_fov` to 1e-4 relative (f32
/// arithmetic in the camera: measured agreement 2e-6).
#[test]
fn field_of_view_matches_mitsuba() {
    let mut failures = Vec::new();
    for c in data().fov {
        let xml = format!(
            r#"<scene version="3.0.0">
  <sensor type="perspective">{}
    <film type="hdrfilm"><integer name="width" value="{}"/><integer name="height" value="{}"/></film>
  </sensor>
  <emitter type="constant"/>
</scene>"#,
            c.xml, c.width, c.height
        );
        let got = match load_str(&xml, Path::new("fov.xml"), &[]) {
            Ok(d) => built_x_fov(&d),
            Err(e) => {
                failures.push(format!("{}×{} {}: {e}", c.width, c.height, c.xml));
                continue;
            }
        };
        println!(
            "{}×{} {:60} spectrace {got:.4}°, Mitsuba {:.4}°",
            c.width, c.height, c.xml, c.x_fov
        );
        if (got / c.x_fov - 1.0).abs() > 1e-4 {
            failures.push(format!(
                "{}×{} {}: x fov {got:.4}°, Mitsuba {:.4}°",
                c.width, c.height, c.xml, c.x_fov
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let e = err(&env_scene(2, "", "").replace(
        "<float name=\"fov\" value=\"40\"/>",
        "<float name=\"fov\" value=\"40\"/><string name=\"focal_length\" value=\"50mm\"/>",
    ));
    assert!(e.contains("either focal_length or fov"), "{e}");
    let e = err(&env_scene(2, "", "").replace(
        "<float name=\"fov\" value=\"40\"/>",
        "<string name=\"focal_length\" value=\"fifty\"/>",
    ));
    assert!(e.contains("t.xml:4:") && e.contains("\"fifty\""), "{e}");
}

/// An emitter's spectrum as Mitsuba reads it: absent = its D65 (CIE D65 / 98.997), a bare
/// float v = v × that D65, `<spectrum type="d65">` with `scale`, `<rgb>` = the sigmoid
/// spectrum × 2·max(rgb) × that D65, `<spectrum value>` flat. The imported spectrum's XYZ on
/// Mitsuba's film scale (∫S x̄ dλ / 106.7502594) against Mitsuba's render of a constant
/// environment with it. Tolerance: 5 standard errors of Mitsuba's mean plus 0.1 % for the two
/// renderers' CIE tables (1 nm in spectrace, 5 nm in Mitsuba; measured ≤ 0.05 % on the flat and
/// D65 cases), and 0.5 % for a coloured `rgb`, whose sigmoid coefficients come from different
/// fits in the two renderers (measured up to 0.18 %, in Z).
#[test]
fn emitter_spectra_match_mitsuba() {
    let mut failures = Vec::new();
    for c in data().emitter {
        let desc = load(&env_scene(-1, &c.xml, ""));
        let s = &desc.lights[0].spectrum;
        let xyz =
            spectrace::colour::cie::integrate_xyz(|l| s.eval(l) as f64).map(|v| v / MITSUBA_Y_NORM);
        let coloured = c.xml.contains("<rgb") && !c.xml.contains("1, 1, 1");
        for i in 0..3 {
            let rel = xyz[i] / c.xyz[i] - 1.0;
            let tol = 5.0 * c.stderr[i] / c.xyz[i] + if coloured { 0.005 } else { 0.001 };
            println!(
                "{:75} {}: spectrace {:.5}, Mitsuba {:.5} ({} spp), {:+.3} %",
                c.xml,
                ["X", "Y", "Z"][i],
                xyz[i],
                c.xyz[i],
                c.spp,
                rel * 100.0
            );
            if rel.abs() > tol {
                failures.push(format!(
                    "{} {}: {:.5} vs Mitsuba {:.5} ({:+.3} %, tolerance {:.3} %)",
                    c.xml,
                    ["X", "Y", "Z"][i],
                    xyz[i],
                    c.xyz[i],
                    rel * 100.0,
                    tol * 100.0
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `max_depth` is Mitsuba's path length: 1 shows emitters only (the ρ = 0.5 rectangle in front
/// of a uniform environment is black), 2 adds one bounce (ρ·L = 0.5). Mean Y of the central
/// 4 × 4 pixels (all on the rectangle) and of two 2 × 2 corners (all environment), against
/// Mitsuba's render, within 5 standard errors of spectrace's 64-spp mean (measured σ of one
/// pixel at 64 spp: 0.0 on the environment, 0.02 on the lit rectangle, so 5σ/√16 = 0.025)
/// plus Mitsuba's film normalisation offset (0.1 %).
#[test]
fn max_depth_is_path_length() {
    let rect = r#"
  <shape type="rectangle">
    <transform name="to_world"><scale value="0.5"/><rotate y="1" angle="180"/></transform>
    <bsdf type="diffuse"><spectrum name="reflectance" value="0.5"/></bsdf>
  </shape>"#;
    let radiance = r#"<spectrum name="radiance" value="1"/>"#;
    let mut failures = Vec::new();
    for c in data().max_depth {
        let desc = load(&env_scene(c.max_depth, radiance, rect));
        let scene = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
        let (mut img, _) = support::render::render_with(&scene, |_| {});
        spectrace::output::to_mitsuba_scale(&mut img);
        let y = |x: usize, yy: usize| img.xyz[yy * 16 + x][1] as f64;
        let centre: f64 = (6..10)
            .flat_map(|j| (6..10).map(move |i| (i, j)))
            .map(|(i, j)| y(i, j))
            .sum::<f64>()
            / 16.0;
        let corner = [
            (0, 0),
            (1, 0),
            (0, 1),
            (1, 1),
            (14, 14),
            (15, 14),
            (14, 15),
            (15, 15),
        ]
        .iter()
        .map(|&(i, j)| y(i, j))
        .sum::<f64>()
            / 8.0;
        println!(
            "max_depth {}: centre Y spectrace {centre:.4}, Mitsuba {:.4}; corner {corner:.4}, Mitsuba {:.4}",
            c.max_depth, c.y_centre, c.y_corner
        );
        let tol = 0.025 + 0.001 * c.y_centre;
        if (centre - c.y_centre).abs() > tol || (corner / c.y_corner - 1.0).abs() > 0.002 {
            failures.push(format!(
                "max_depth {}: centre {centre:.4} vs Mitsuba {:.4}, corner {corner:.4} vs {:.4}",
                c.max_depth, c.y_centre, c.y_corner
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(
        load(&env_scene(-1, radiance, rect)).integrator.max_depth,
        1024
    );
    let e = err(&env_scene(0, radiance, rect));
    assert!(e.contains("t.xml:2:") && e.contains("black"), "{e}");
    let e = err(&env_scene(-2, radiance, rect));
    assert!(e.contains("max_depth"), "{e}");
    // rr_depth: where Russian roulette starts, Mitsuba's default 5 (its path integrator's
    // documentation); it changes only the noise (roulette is unbiased)
    assert_eq!(load(&env_scene(3, radiance, rect)).integrator.rr_depth, 5);
    let rr = |v: &str| {
        env_scene(3, radiance, rect).replace(
            "</integrator>",
            &format!("<integer name=\"rr_depth\" value=\"{v}\"/></integrator>"),
        )
    };
    assert_eq!(load(&rr("5")).integrator.max_depth, 2);
    assert_eq!(load(&rr("2")).integrator.rr_depth, 2);
    // emitters: the light tree unless one sets sampling_weight (Mitsuba's Emitter, default
    // 1), which keeps Mitsuba's rule, selection in proportion to it
    let desc = load(&env_scene(3, radiance, rect));
    assert_eq!(desc.integrator.light_selection, LightSelection::Tree);
    assert!(desc.lights.iter().all(|l| l.sampling_weight == 1.0));
    let weighted = env_scene(3, radiance, rect).replacen(
        "</emitter>",
        "<float name=\"sampling_weight\" value=\"2.5\"/></emitter>",
        1,
    );
    assert_eq!(load(&weighted).lights[0].sampling_weight, 2.5);
    assert_eq!(
        load(&weighted).integrator.light_selection,
        LightSelection::Uniform
    );
    let negative = weighted.replace("2.5", "-1");
    assert!(
        err(&negative).contains("sampling_weight"),
        "{}",
        err(&negative)
    );
    assert!(err(&rr("0")).contains("rr_depth"));
    let e = err(&env_scene(3, radiance, rect).replace(
        "</integrator>",
        "<boolean name=\"hide_emitters\" value=\"true\"/></integrator>",
    ));
    assert!(e.contains("hide_emitters"), "{e}");
}

/// A point light placed by `to_world` sits at the image of the origin (Mitsuba's position).
#[test]
fn point_light_to_world_matches_mitsuba() {
    for c in data().point {
        let xml = format!(
            r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/></sensor>
  <emitter type="point"><transform name="to_world">{}</transform></emitter>
</scene>"#,
            c.transform
        );
        let desc = load(&xml);
        let spectrace::loader::desc::LightKind::Point { position, .. } = &desc.lights[0].kind
        else {
            panic!("not a point light");
        };
        let got = position.map(|p| p.value);
        println!(
            "{}: spectrace {got:?}, Mitsuba {:?}",
            c.transform, c.position
        );
        for i in 0..3 {
            assert!(
                (got[i] - c.position[i]).abs() < 1e-4,
                "{}: position {got:?}, Mitsuba {:?}",
                c.transform,
                c.position
            );
        }
    }
    let e = err(r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/></sensor>
  <emitter type="point"><point name="position" value="1, 2, 3"/>
    <transform name="to_world"><translate x="1"/></transform></emitter>
</scene>"#);
    assert!(
        e.contains("t.xml:4:") && e.contains("position or to_world"),
        "{e}"
    );
}

/// A directional emitter without `direction` shines along the image of +z under `to_world`
/// (Mitsuba 3.9.1: rotating x by 90° then y by 30° sends light along (0, −1, 0); its
/// `sample_direction` returns (0, 1, 0), toward the light).
#[test]
fn directional_to_world_matches_mitsuba() {
    let xml = r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/></sensor>
  <emitter type="directional"><transform name="to_world">
    <rotate x="1" angle="90"/><rotate y="1" angle="30"/></transform></emitter>
</scene>"#;
    let desc = load(xml);
    let spectrace::loader::desc::LightKind::Directional { direction, .. } = &desc.lights[0].kind
    else {
        panic!("not a directional light");
    };
    println!("direction {direction:?}, Mitsuba (0, -1, 0)");
    let want = [0.0, -1.0, 0.0];
    for i in 0..3 {
        assert!((direction[i] - want[i]).abs() < 1e-9, "{direction:?}");
    }
    let e = err(&xml.replace(
        "<emitter type=\"directional\">",
        "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, -1, 0\"/>",
    ));
    assert!(e.contains("direction or to_world"), "{e}");
}

fn bsdf_scene(bsdf: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/></sensor>
  <emitter type="constant"/>
  {bsdf}
  <shape type="sphere"><ref id="m"/></shape>
</scene>"#
    )
}

fn conductor(desc: &SceneDesc) -> (f32, f32, f64, Option<[f64; 2]>) {
    match &desc.materials[0].kind {
        spectrace::loader::desc::MaterialKind::Conductor {
            ior,
            exterior_ior,
            roughness,
            ..
        } => (
            ior.n.eval(550.0),
            ior.k.eval(550.0),
            *exterior_ior,
            *roughness,
        ),
        other => panic!("not a conductor: {other:?}"),
    }
}

/// Mitsuba's `conductor` without `material` is material "none": eta = 0, k = 1, a perfect mirror
/// (Mitsuba 3.9.1's sampled weight is 1 at every wavelength); eta and k are relative to vacuum
/// (exterior index 1, and `ext_ior` is an unreferenced property, an error, in Mitsuba).
#[test]
fn conductor_defaults_match_mitsuba() {
    for b in [
        r#"<bsdf type="conductor" id="m"/>"#,
        r#"<bsdf type="conductor" id="m"><string name="material" value="none"/></bsdf>"#,
    ] {
        let desc = load(&bsdf_scene(b));
        let (n, k, ext, _) = conductor(&desc);
        let r: Vec<f32> = [1.0f32, 0.7, 0.3, 0.05]
            .iter()
            .map(|&c| {
                spectrace::material::fresnel::fresnel_conductor(c, n / ext as f32, k / ext as f32)
            })
            .collect();
        println!("{b}: eta {n}, k {k}, exterior {ext}, R(cos θ = 1, 0.7, 0.3, 0.05) = {r:?}");
        assert_eq!((n, k, ext), (0.0, 1.0, 1.0), "{b}");
        assert!(r.iter().all(|&r| (r - 1.0).abs() < 1e-6), "{b}: R = {r:?}");
    }
    // eta given alone (or with material "none") keeps Mitsuba's k = 1
    let (n, k, ext, _) = conductor(&load(&bsdf_scene(
        r#"<bsdf type="conductor" id="m"><string name="material" value="none"/><float name="eta" value="0.2"/></bsdf>"#,
    )));
    assert_eq!((n, k, ext), (0.2, 1.0, 1.0));
    let (n, k, ext, _) = conductor(&load(&bsdf_scene(
        r#"<bsdf type="conductor" id="m"><float name="eta" value="0.2"/></bsdf>"#,
    )));
    assert_eq!((n, k, ext), (0.2, 1.0, 1.0));
    // a named metal is relative to vacuum as well
    let (_, _, ext, _) = conductor(&load(&bsdf_scene(
        r#"<bsdf type="conductor" id="m"><string name="material" value="Au"/></bsdf>"#,
    )));
    assert_eq!(ext, 1.0);
    let e = err(&bsdf_scene(
        r#"<bsdf type="conductor" id="m"><float name="ext_ior" value="1.5"/></bsdf>"#,
    ));
    assert!(e.contains("t.xml:4:") && e.contains("ext_ior"), "{e}");
    let e = err(&bsdf_scene(
        r#"<bsdf type="conductor" id="m"><string name="material" value="Au"/><float name="eta" value="0.2"/></bsdf>"#,
    ));
    assert!(e.contains("material or eta and k"), "{e}");
}

/// Mitsuba's rough BSDFs default to Beckmann (and take "beckmann" or "ggx"); `alpha` defaults
/// to 0.1; `alpha_u` and `alpha_v` are the roughness along ∂p/∂u and across it; one alone is
/// an error.
#[test]
fn rough_bsdf_defaults_match_mitsuba() {
    use spectrace::loader::desc::{Distribution, MaterialKind};
    let dist = |d: &SceneDesc| match &d.materials[0].kind {
        MaterialKind::Conductor { distribution, .. }
        | MaterialKind::Dielectric { distribution, .. } => *distribution,
        other => panic!("{other:?}"),
    };
    for t in ["roughconductor", "roughdielectric"] {
        let d = load(&bsdf_scene(&format!(r#"<bsdf type="{t}" id="m"/>"#)));
        println!("{t} without distribution: {:?}", dist(&d));
        assert_eq!(dist(&d), Distribution::Beckmann, "{t}: Mitsuba's default");
        for (v, want) in [
            ("beckmann", Distribution::Beckmann),
            ("ggx", Distribution::Ggx),
        ] {
            let d = load(&bsdf_scene(&format!(
                r#"<bsdf type="{t}" id="m"><string name="distribution" value="{v}"/></bsdf>"#
            )));
            assert_eq!(dist(&d), want, "{t} {v}");
        }
        let e = err(&bsdf_scene(&format!(
            r#"<bsdf type="{t}" id="m"><string name="distribution" value="phong"/></bsdf>"#
        )));
        assert!(e.contains("t.xml:4:") && e.contains("\"phong\""), "{e}");
        let d = load(&bsdf_scene(&format!(
            r#"<bsdf type="{t}" id="m"><string name="distribution" value="ggx"/>
  <float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/></bsdf>"#
        )));
        let r = match &d.materials[0].kind {
            MaterialKind::Conductor { roughness, .. }
            | MaterialKind::Dielectric { roughness, .. } => *roughness,
            other => panic!("{other:?}"),
        };
        assert_eq!(r, Some([0.1, 0.3]), "{t}: alpha_u, alpha_v");
        let e = err(&bsdf_scene(&format!(
            r#"<bsdf type="{t}" id="m"><float name="alpha_v" value="0.3"/></bsdf>"#
        )));
        assert!(
            e.contains("t.xml:4:") && e.contains("both alpha_u and alpha_v"),
            "{e}"
        );
    }
    let desc = load(&bsdf_scene(
        r#"<bsdf type="roughconductor" id="m"><string name="distribution" value="ggx"/>
  <float name="alpha_u" value="0.3"/><float name="alpha_v" value="0.3"/></bsdf>"#,
    ));
    assert_eq!(conductor(&desc).3, Some([0.3, 0.3]));
    let desc = load(&bsdf_scene(
        r#"<bsdf type="roughconductor" id="m"><string name="distribution" value="ggx"/></bsdf>"#,
    ));
    assert_eq!(
        conductor(&desc).3,
        Some([0.1, 0.1]),
        "Mitsuba's default alpha"
    );
}

/// A shape without a `<bsdf>` is diffuse with reflectance 0.5 in Mitsuba 3.9.1, except an
/// emitting one, which gets reflectance 0 (measured: `shape.bsdf()` of an area-emitting
/// rectangle is SmoothDiffuse[reflectance = 0]); spectrace reads the emitter as a pure emitter
/// with no material, the plain shape as the 0.5 diffuse.
#[test]
fn emitting_shape_without_bsdf_is_black_as_in_mitsuba() {
    let d = load(
        r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/></sensor>
  <shape type="rectangle"><emitter type="area"/></shape>
  <shape type="sphere"/>
</scene>"#,
    );
    assert_eq!(d.shapes[0].material, None, "the emitter reflects nothing");
    let m = d.shapes[1]
        .material
        .expect("the plain sphere has Mitsuba's default BSDF");
    match &d.materials[m].kind {
        spectrace::loader::desc::MaterialKind::Diffuse { reflectance } => {
            assert!(
                matches!(reflectance, spectrace::loader::desc::TextureDesc::Uniform(s) if s.eval(550.0) == 0.5)
            );
        }
        other => panic!("{other:?}"),
    }
}
