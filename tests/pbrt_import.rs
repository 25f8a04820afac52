//! pbrt-v4 scenes (`spectrace::loader::pbrt`) against closed forms: pbrt-v4's light
//! normalisation (∫ȳ·L dλ = `scale`, its film's Y; spectrace's Y is 683 lm/W times it), a
//! diffuse sphere under a uniform sky (Y = ρ·scale), and the side of the image its camera puts
//! `up × view direction` on. Located errors are in `tests/bad_scenes/pbrt_*.pbrt`.

mod support;

use std::path::Path;

use spectrace::colour::cie::K_M;

fn render(name: &str) -> (Vec<[f32; 3]>, u32, u32) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/pbrt")
        .join(name);
    let desc = spectrace::loader::pbrt::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let (w, h) = (desc.film.width, desc.film.height);
    let scene = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
    let (img, _) = support::render::render_with(&scene, |_| {});
    (img.xyz, w, h)
}

/// Y over the pixels whose centres lie within `r0` ≤ r < `r1` pixels of the image centre.
fn ring_mean(img: &[[f32; 3]], w: u32, h: u32, r0: f64, r1: f64) -> (f64, usize) {
    let (mut sum, mut n) = (0.0, 0);
    for y in 0..h {
        for x in 0..w {
            let (dx, dy) = (
                x as f64 + 0.5 - w as f64 / 2.0,
                y as f64 + 0.5 - h as f64 / 2.0,
            );
            let r = (dx * dx + dy * dy).sqrt();
            if r >= r0 && r < r1 {
                sum += img[(y * w + x) as usize][1] as f64;
                n += 1;
            }
        }
    }
    (sum / n as f64, n)
}

/// The sky reads Y = 683 × 2 cd/m² (pbrt-v4's `scale` 2 on a blackbody normalised to ∫ȳ = 1),
/// the sphere half of it. The sphere spans 9.1 pixels of radius (its angular radius
/// asin(1/5) against the 15° half-field): its inside within 7, the sky beyond 11.
#[test]
fn sphere_under_a_uniform_sky_reflects_rho() {
    let (img, w, h) = render("furnace.pbrt");
    let sky = 2.0 * K_M;
    let (inside, n_in) = ring_mean(&img, w, h, 0.0, 7.0);
    let (outside, n_out) = ring_mean(&img, w, h, 11.5, 100.0);
    println!(
        "sphere {inside} ({n_in} px), sky {outside} ({n_out} px), want {} and {sky}",
        0.5 * sky
    );
    assert!(
        (outside / sky - 1.0).abs() < 1e-4,
        "sky {outside} against {sky}"
    );
    assert!(
        (inside / (0.5 * sky) - 1.0).abs() < 2e-3,
        "sphere {inside} against {}",
        0.5 * sky
    );
}

/// The square at world −x shows on the image's right (pbrt-v4's `up × dir`), at Y = 683 × 3.
#[test]
fn camera_puts_up_cross_dir_on_the_right() {
    let (img, w, h) = render("mirror.pbrt");
    let half = |right: bool| -> f64 {
        let mut s = 0.0;
        for y in 0..h {
            for x in 0..w {
                if (x >= w / 2) == right {
                    s += img[(y * w + x) as usize][1] as f64;
                }
            }
        }
        s
    };
    let (l, r) = (half(false), half(true));
    println!("left {l}, right {r}");
    assert!(l == 0.0 && r > 0.0, "left half {l}, right half {r}");
    // 5.5 px per unit at 5 m (10 px for tan 20°): the square spans 2.75 to 8.2 px right of the
    // centre and ±2.75 px up and down; this pixel's centre is 5.5 px right, 0.5 px down, 2.25 px
    // or more from its edges (the filter reaches 1.5)
    let x = w / 2 + 5;
    let y = h / 2;
    let v = img[(y * w + x) as usize][1] as f64;
    assert!(
        (v / (3.0 * K_M) - 1.0).abs() < 1e-3,
        "{v} against {}",
        3.0 * K_M
    );
}

#[derive(serde::Deserialize)]
struct Refs {
    case: Vec<RefCase>,
}

#[derive(serde::Deserialize)]
struct RefCase {
    name: String,
    spp: u32,
    pbrt: String,
    y: f64,
    stderr: f64,
    /// Row-major indices of the object's pixels (more than 2 % off the background).
    object: Vec<usize>,
    y_object: f64,
    stderr_object: f64,
}

/// The mean Y of a pbrt-v4 scene rendered by spectrace, on pbrt-v4's scale (Y / 683), with its
/// standard error from two seeds: over the pixels `subset`, or all when None.
fn mean_y(text: &str, spp: u32, subsets: [Option<&[usize]>; 2]) -> [(f64, f64); 2] {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pbrt/inline.pbrt");
    let desc = spectrace::loader::pbrt::load_str(text, &path).unwrap_or_else(|e| panic!("{e}"));
    let scene = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
    let ys: Vec<Vec<f64>> = [1u32, 2]
        .iter()
        .map(|&seed| {
            let (img, _) = support::render::render_with(&scene, |o| {
                o.spp = spp;
                o.seed = seed;
            });
            img.xyz.iter().map(|p| p[1] as f64 / K_M).collect()
        })
        .collect();
    subsets.map(|subset| {
        let all: Vec<usize> = (0..ys[0].len()).collect();
        let idx = subset.unwrap_or(&all);
        let n = idx.len() as f64;
        let d: Vec<f64> = idx.iter().map(|&i| ys[0][i] - ys[1][i]).collect();
        let dm = d.iter().sum::<f64>() / n;
        let var = d.iter().map(|x| (x - dm).powi(2)).sum::<f64>() / n;
        let mean = idx.iter().map(|&i| ys[0][i] + ys[1][i]).sum::<f64>() / (2.0 * n);
        (mean, var.sqrt() / 2.0 / n.sqrt())
    })
}

/// Small scenes against pbrt-v4's own renders (`tests/data/pbrt_refs.toml`, written by
/// `scripts/gen_pbrt_refs.py` with a pbrt-v4 build): named metals smooth and rough, a BK7
/// sphere before a lit wall, a box lit by a disk and a point light, photometric amounts,
/// layered materials, Loop subdivision surfaces, bilinear patches (a light with `power`, a
/// twisted patch) and a diffuse transmitter. The mean Y of the whole image and of the
/// object's pixels each within 5 standard errors of the two renderers' difference.
#[test]
fn scenes_match_pbrt_v4() {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pbrt_refs.toml");
    let refs: Refs = toml::from_str(&std::fs::read_to_string(&p).expect("pbrt_refs.toml")).unwrap();
    let mut failures = Vec::new();
    for c in refs.case {
        let [(y, se), (yo, seo)] = mean_y(&c.pbrt, c.spp, [None, Some(&c.object)]);
        for (what, y, se, ry, rse) in [
            ("image", y, se, c.y, c.stderr),
            ("object", yo, seo, c.y_object, c.stderr_object),
        ] {
            let tol = 5.0 * (se * se + rse * rse).sqrt();
            let line = format!(
                "{} ({what}): spectrace {y:.5} ± {se:.5}, pbrt-v4 {ry:.5} ± {rse:.5} ({:+.2} %, z {:+.1})",
                c.name,
                (y / ry - 1.0) * 100.0,
                (y - ry) / (se * se + rse * rse).sqrt()
            );
            println!("{line}");
            if (y - ry).abs() > tol {
                failures.push(line);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// An equal-area map's `illuminance` as pbrt-v4 documents it: a white map asked for ∫ȳ·E dλ = 2
/// on an upward plane lights a floor of reflectance 1 to Y = 2/π (×683 in cd/m²), seen by an
/// orthographic camera (pbrt-v4 itself renders 2 × 2/π: it measures the map with half each
/// pixel's solid angle, README).
#[test]
fn equal_area_map_gives_the_illuminance_asked_for() {
    let text = r#"LookAt 0 5 0  0 0 0  0 0 1
Camera "orthographic"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
Sampler "zsobol" "integer pixelsamples" 64
Integrator "path" "integer maxdepth" 1
WorldBegin
AttributeBegin
Rotate -90 1 0 0
LightSource "infinite" "string filename" "white.exr" "float illuminance" 2
AttributeEnd
Material "diffuse" "spectrum reflectance" [300 1 900 1]
Shape "trianglemesh" "point3 P" [-50 0 -50  50 0 -50  50 0 50  -50 0 50] "integer indices" [0 2 1 0 3 2]
"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pbrt/inline.pbrt");
    let desc = spectrace::loader::pbrt::load_str(text, &path).unwrap_or_else(|e| panic!("{e}"));
    let scene = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
    let ys: Vec<f64> = [1u32, 2]
        .iter()
        .map(|&seed| {
            let (img, _) = support::render::render_with(&scene, |o| o.seed = seed);
            img.xyz.iter().map(|p| p[1] as f64 / K_M).sum::<f64>() / img.xyz.len() as f64
        })
        .collect();
    let (y, se) = ((ys[0] + ys[1]) / 2.0, (ys[0] - ys[1]).abs() / 2.0);
    let truth = 2.0 / std::f64::consts::PI;
    println!("Y {y:.5} ± {se:.5} against 2/π = {truth:.5}");
    assert!(
        (y / truth - 1.0).abs() < 2e-3 + 5.0 * se / truth,
        "{y} against {truth}"
    );
}

/// `diffusetransmission` (R/π on the lit side, T/π through), as pbrt-v4 defines it with its
/// `scale`: a sheet of R = 0.3 and T = 0.5 scaled by 0.8, under a distant light of
/// illuminance 2 at normal incidence, seen by an orthographic camera from the lit side
/// (Y = 0.24 · 2/π) and from the other (Y = 0.4 · 2/π). The light is sampled exactly.
#[test]
fn diffuse_transmission_reflects_r_and_passes_t() {
    for (from, want) in [("0 5 0", 0.24), ("0 -5 0", 0.4)] {
        let text = format!(
            r#"LookAt 0 5 0  0 0 0  0 0 1
Camera "orthographic"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
Sampler "zsobol" "integer pixelsamples" 16
Integrator "path" "integer maxdepth" 1
WorldBegin
LightSource "distant" "point3 from" [{from}] "point3 to" [0 0 0] "float illuminance" 2
Material "diffusetransmission" "spectrum reflectance" [300 0.3 900 0.3]
  "spectrum transmittance" [300 0.5 900 0.5] "float scale" 0.8
Shape "trianglemesh" "point3 P" [-50 0 -50  50 0 -50  50 0 50  -50 0 50] "integer indices" [0 2 1 0 3 2]
"#
        );
        let [(y, se), _] = mean_y(&text, 16, [None, None]);
        let truth = want * 2.0 / std::f64::consts::PI;
        println!("light from {from}: Y {y:.5} ± {se:.5} against {truth:.5}");
        assert!((y / truth - 1.0).abs() < 1e-3, "{y} against {truth}");
    }
}

/// `Attribute "shape"` sets a default a `Shape` may override, the latest `Attribute` first,
/// and `AttributeEnd` forgets it (pbrt-v4's `shapeAttributes`); an attribute a shape does not
/// read is not an error.
#[test]
fn attributes_are_defaults_within_their_block() {
    use spectrace::loader::desc::ShapeKind;
    let text = r#"LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [30]
WorldBegin
AttributeBegin
Attribute "shape" "float radius" 0.25 "float unknownthing" 3
Attribute "shape" "float radius" 0.5
Shape "sphere"
Shape "sphere" "float radius" 2
AttributeEnd
Shape "sphere"
"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pbrt/inline.pbrt");
    let desc = spectrace::loader::pbrt::load_str(text, &path).unwrap_or_else(|e| panic!("{e}"));
    let radii: Vec<f64> = desc
        .shapes
        .iter()
        .map(|s| match &s.kind {
            ShapeKind::PbrtSphere { radius, .. } => radius.get::<spectrace::units::length::meter>(),
            k => panic!("{k:?}"),
        })
        .collect();
    assert_eq!(radii, [0.5, 2.0, 1.0]);
}

/// `ActiveTransform`: transformations apply to the active CTMs only; a shape under two equal
/// CTMs is placed by them (here, after StartTime and EndTime each moved by 1 along x, at
/// x = 1), `CoordSysTransform` sets both, and a shape under two different CTMs (motion blur)
/// is an error naming the directive.
#[test]
fn active_transforms_apply_to_their_ctm() {
    use spectrace::loader::desc::{ShapeKind, TransformStep};
    let head = r#"LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [30]
WorldBegin
TransformTimes 0 1
ActiveTransform StartTime
Translate 1 0 0
ActiveTransform EndTime
Translate 1 0 0
ActiveTransform All
"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pbrt/inline.pbrt");
    let desc = spectrace::loader::pbrt::load_str(&format!("{head}Shape \"sphere\"\n"), &path)
        .unwrap_or_else(|e| panic!("{e}"));
    let s = &desc.shapes[0];
    assert!(matches!(s.kind, ShapeKind::PbrtSphere { .. }));
    match s.transform.as_slice() {
        [TransformStep::Matrix(m)] => assert_eq!((m[3], m[7], m[11]), (1.0, 0.0, 0.0)),
        t => panic!("{t:?}"),
    }
    let moving = format!("{head}ActiveTransform EndTime\nTranslate 0 1 0\nShape \"sphere\"\n");
    let e = spectrace::loader::pbrt::load_str(&moving, &path).expect_err("motion blur");
    assert!(
        e.to_string()
            .contains("Shape under an animated transformation"),
        "{e}"
    );
    let back = format!(
        "{head}CoordinateSystem \"here\"\nActiveTransform EndTime\nTranslate 0 1 0\nCoordSysTransform \"here\"\nShape \"sphere\"\n"
    );
    spectrace::loader::pbrt::load_str(&back, &path).unwrap_or_else(|e| panic!("{e}"));
}

/// gzip-compressed scene and mesh files, as pbrt-v4 reads them (`.pbrt.gz`, `.ply.gz`): a
/// compressed scene includes a compressed PLY square (ρ = 0.5) under a uniform sky of Y = 2,
/// which an orthographic camera sees filling the frame at Y = ρ · 2 (683 cd/m² per unit).
#[test]
fn gzip_compressed_scenes_and_meshes_are_read() {
    use std::io::Write;
    let gz = |path: &Path, data: &[u8]| {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        e.write_all(data).unwrap();
        std::fs::write(path, e.finish().unwrap()).unwrap();
    };
    let dir = std::env::temp_dir().join(format!("spectrace-pbrt-gz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n-5 -5 0\n5 -5 0\n5 5 0\n-5 5 0\n4 0 1 2 3\n";
    gz(&dir.join("square.ply.gz"), ply.as_bytes());
    let scene = r#"LookAt 0 0 5  0 0 0  0 1 0
Camera "orthographic"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
Sampler "zsobol" "integer pixelsamples" 64
Integrator "path" "integer maxdepth" 2
WorldBegin
LightSource "infinite" "blackbody L" 5000 "float scale" 2
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "plymesh" "string filename" "square.ply.gz"
"#;
    gz(&dir.join("scene.pbrt.gz"), scene.as_bytes());
    let desc =
        spectrace::loader::pbrt::load(&dir.join("scene.pbrt.gz")).unwrap_or_else(|e| panic!("{e}"));
    let built = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
    let (img, _) = support::render::render_with(&built, |_| {});
    let y = img.xyz.iter().map(|p| p[1] as f64 / K_M).sum::<f64>() / img.xyz.len() as f64;
    std::fs::remove_dir_all(&dir).ok();
    println!("Y {y:.5} against 1");
    assert!((y - 1.0).abs() < 2e-3, "{y}");
}

/// pbrt-v4's `spectral` film becomes spectrace's spectral EXR bins (its `nbuckets` over
/// 360–830 nm); a `gbuffer` film's image is the rgb film's, with a note that its extra
/// channels are not written.
#[test]
fn spectral_and_gbuffer_films_are_read() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pbrt/inline.pbrt");
    let scene = |film: &str| {
        format!(
            "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\n{film}\nWorldBegin\nShape \"sphere\"\n"
        )
    };
    let desc = spectrace::loader::pbrt::load_str(
        &scene(r#"Film "spectral" "integer nbuckets" 8 "integer xresolution" 4 "integer yresolution" 4"#),
        &path,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(desc.film.spectral_bins, 8);
    let desc = spectrace::loader::pbrt::load_str(&scene(r#"Film "gbuffer""#), &path)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(desc.film.spectral_bins, 0);
    assert!(
        desc.notes.iter().any(|n| n.contains("gbuffer")),
        "{:?}",
        desc.notes
    );
    let e = spectrace::loader::pbrt::load_str(
        &scene(r#"Film "spectral" "float lambdamin" 400"#),
        &path,
    )
    .unwrap_err();
    assert!(e.to_string().contains("360–830"), "{e}");
}

/// Light tracing and BDPT refuse pbrt-v4's spherical camera (its importance is not modelled,
/// nor is it in pbrt-v4): an error naming the camera, not an image.
#[test]
fn light_tracing_and_bdpt_refuse_a_spherical_camera() {
    let text = r#"Camera "spherical"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pbrt/inline.pbrt");
    let desc = spectrace::loader::pbrt::load_str(text, &path).unwrap_or_else(|e| panic!("{e}"));
    let scene = spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"));
    support::render::assert_light_and_bdpt_refuse(&scene, "spherical camera");
}

/// A cropped render is written as pbrt-v4 writes it: the window as the EXR's data window in
/// a display window of the full image. pbrt-v4's own render of the `crop` reference scene
/// (`cropwindow` [0.2, 0.7] × [0.45, 0.95] of 64 × 48) has its pixel data at (13, 22), 32 × 24
/// pixels, in a 64 × 48 display window (`oiiotool --info -v` on its output).
#[test]
fn a_cropped_render_is_written_as_a_data_window() {
    let dir = support::cli::tmpdir("pbrt-crop-window");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/pbrt/crop/scene.pbrt");
    let exr = dir.join("crop.exr");
    let (ok, err) = support::cli::spectrace(
        &dir,
        &[
            "render",
            scene.to_str().unwrap(),
            "--spp",
            "1",
            "--quiet",
            "-o",
            exr.to_str().unwrap(),
        ],
    );
    assert!(ok, "{err}");
    let img = spectrace::image_io::read_exr(&exr).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((img.width, img.height), (32, 24));
    let want = spectrace::image_io::DataWindow {
        at: [13, 22],
        full: [64, 48],
    };
    assert_eq!(img.window, Some(want));
}
