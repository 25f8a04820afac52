//! The render command's files: EXR channels and header, the spectral EXR read back, the PNG,
//! the built-in default scene, errors, and a render stopped with Ctrl-C.

mod support;

use std::path::Path;
use std::process::Command;

use spectrace::image_io::{AttrValue, read_exr, spectral_channels};
use support::cli::{spectrace, tmpdir};
use support::render::scene_from;

fn scene_path(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn spectral_exr_reads_back_with_the_same_bins_and_values() {
    let scene = scene_from(
        &std::fs::read_to_string(scene_path("radiometry.toml"))
            .unwrap()
            .replace("width = 256\nheight = 256", "width = 24\nheight = 16"),
    );
    let (img, stats) = support::render::render_with(&scene, |o| {
        o.spp = 4;
        o.spectral_bins = 16;
    });
    let dir = tmpdir("spectral");
    let path = dir.join("s.exr");
    let info = spectrace::output::RenderInfo {
        sensor: None,
        scene_file: "radiometry.toml",
        integrator: "path",
        spp: 4,
        seed: 0,
        seconds: stats.elapsed.as_secs_f64(),
        partial: false,
        nan_samples: 0,
        inf_samples: 0,
        range: scene.wavelengths,
        mitsuba_units: false,
        moment: false,
        stop: "complete",
        rel_error: stats.rel_error,
        aovs: &[],
        window: None,
    };
    spectrace::output::write_exr(&path, &img, &info).unwrap();
    let back = read_exr(&path).unwrap();
    let bins = spectral_channels(&back);
    assert_eq!(bins.len(), 16);
    let b = img.bins.as_ref().unwrap();
    for (k, (lambda, ch)) in bins.iter().enumerate() {
        assert!(
            (lambda - b.centre(k)).abs() < 1e-3,
            "bin {k}: {lambda} nm vs {}",
            b.centre(k)
        );
        assert_eq!(back.channels[*ch].1, img.spectral[k], "bin {k} values");
    }
    assert_eq!(
        back.channel("Y").unwrap(),
        img.xyz.iter().map(|p| p[1]).collect::<Vec<_>>()
    );
    assert_eq!(back.channel("L").unwrap(), img.band.as_slice());
    assert_eq!(
        back.attribute("spectralLayoutVersion"),
        Some(&AttrValue::Text("1.0".into()))
    );
    assert_eq!(
        back.attribute("emissiveUnits"),
        Some(&AttrValue::Text("W.m^-2.sr^-1".into()))
    );
    // the bins integrate to the band radiance: Σ bins · Δλ = L
    let dl = b.width();
    for i in 0..img.band.len() {
        let sum: f32 = img.spectral.iter().map(|s| s[i] * dl).sum();
        assert!(
            (sum - img.band[i]).abs() <= 1e-4 * img.band[i].abs().max(1e-6),
            "pixel {i}: {sum} vs {}",
            img.band[i]
        );
    }
}

#[test]
fn render_command_writes_exr_and_png_with_documented_header() {
    let dir = tmpdir("cli");
    let (ok, err) = spectrace(
        &dir,
        &[
            "render",
            &scene_path("furnace.toml"),
            "--spp",
            "2",
            "-o",
            "f.exr",
            "--quiet",
        ],
    );
    assert!(ok, "{err}");
    let exr = read_exr(&dir.join("f.exr")).unwrap();
    for c in ["X", "Y", "Z", "R", "G", "B", "L"] {
        assert!(exr.channel(c).is_some(), "channel {c}");
    }
    assert!(
        exr.channels
            .iter()
            .all(|(_, v)| v.iter().all(|x| x.is_finite()))
    );
    assert_eq!(
        exr.attribute("spectrace:samplesPerPixel"),
        Some(&AttrValue::Int(2))
    );
    assert_eq!(
        exr.attribute("spectrace:integrator"),
        Some(&AttrValue::Text("path".into()))
    );
    assert_eq!(exr.attribute("spectrace:partial"), Some(&AttrValue::Int(0)));
    assert!(
        matches!(exr.attribute("spectrace:units"), Some(AttrValue::Text(t)) if t.contains("cd/m^2"))
    );
    assert!(dir.join("f.png").is_file());
    // a bad scene is an error naming the file and line, and writes nothing
    std::fs::write(dir.join("bad.toml"), "[camera]\neye = [0, 0, 0\n").unwrap();
    let (ok, err) = spectrace(&dir, &["render", "bad.toml", "-o", "bad.exr"]);
    assert!(
        !ok && err.contains("bad.toml:") && !dir.join("bad.exr").exists(),
        "{err}"
    );
    let (ok, err) = spectrace(
        &dir,
        &[
            "render",
            &scene_path("furnace.toml"),
            "-o",
            "no/such/dir/x.exr",
        ],
    );
    assert!(!ok && err.contains("does not exist"), "{err}");
}

#[test]
fn no_arguments_render_the_default_scene() {
    let dir = tmpdir("default");
    let (ok, err) = spectrace(&dir, &[]);
    assert!(ok, "{err}");
    assert!(
        err.contains("spectrace.exr") && err.contains("spectrace.png"),
        "says where: {err}"
    );
    let exr = read_exr(&dir.join("spectrace.exr")).unwrap();
    let y = exr.channel("Y").unwrap();
    assert!(y.iter().any(|v| *v > 0.0) && y.iter().all(|v| v.is_finite()));
    assert!(dir.join("spectrace.png").is_file());
}

#[test]
fn ctrl_c_writes_a_partial_image() {
    let dir = tmpdir("ctrlc");
    let child = Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .current_dir(&dir)
        .args([
            "render",
            &scene_path("cornell.toml"),
            "--spp",
            "100000",
            "-o",
            "c.exr",
            "--quiet",
        ])
        .spawn()
        .expect("starts");
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success());
    let out = child.wait_with_output().expect("exits");
    assert!(out.status.success(), "exit status {:?}", out.status);
    let exr = read_exr(&dir.join("c.exr")).unwrap();
    assert_eq!(exr.attribute("spectrace:partial"), Some(&AttrValue::Int(1)));
    let y = exr.channel("Y").unwrap();
    assert!(y.iter().all(|v| v.is_finite()) && y.iter().any(|v| *v > 0.0));
}

/// `--bdpt-strategy` takes S,T of a strategy bdpt has, and only with bdpt.
#[test]
fn bdpt_strategy_flag_is_checked() {
    let dir = tmpdir("bdpt-strategy");
    let furnace = scene_path("furnace.toml");
    for (args, says) in [
        (
            vec!["--integrator", "bdpt", "--bdpt-strategy", "1,1"],
            "no such strategy",
        ),
        (
            vec!["--integrator", "bdpt", "--bdpt-strategy", "2"],
            "expected S,T",
        ),
        (
            vec![
                "--integrator",
                "bdpt",
                "--bdpt-strategy",
                "4294967295,4294967295",
            ],
            "max_depth",
        ),
        (vec!["--bdpt-strategy", "0,2"], "needs the bdpt integrator"),
    ] {
        let mut all = vec![
            "render",
            furnace.as_str(),
            "-o",
            "x.exr",
            "--quiet",
            "--spp",
            "1",
        ];
        all.extend(args.iter().copied());
        let (ok, err) = spectrace(&dir, &all);
        assert!(!ok && err.contains(says), "{args:?}: {err}");
    }
}

/// Light tracing connects particles to the lens, which an orthographic camera does not have: a
/// clear error, no image. (`bdpt` renders it without those strategies.)
#[test]
fn light_tracing_refuses_an_orthographic_camera() {
    let dir = tmpdir("ortho-light");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reference/orthographic/scene.xml")
        .display()
        .to_string();
    let base = one_sample(&scene);
    let (ok, err) = spectrace(&dir, &[&base[..], &["--integrator", "light"]].concat());
    assert!(!ok && err.contains("orthographic camera"), "{err}");
    assert!(!dir.join("o.exr").exists(), "no image after an error");
    let (ok, err) = spectrace(&dir, &[&base[..], &["--integrator", "bdpt"]].concat());
    assert!(ok, "{err}");
}

/// An integrator that does not render media, chosen on the command line for a scene with media:
/// a clear error, no image (it would render the scene as if the media were not there).
#[test]
fn an_integrator_without_media_refuses_a_scene_with_media() {
    let dir = tmpdir("media-whitted");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/media.toml")
        .display()
        .to_string();
    let base = one_sample(&scene);
    for integrator in ["whitted", "direct"] {
        let (ok, err) = spectrace(&dir, &[&base[..], &["--integrator", integrator]].concat());
        assert!(
            !ok && err.contains("participating media") && err.contains(integrator),
            "{integrator}: {err}"
        );
        assert!(!dir.join("o.exr").exists(), "no image after an error");
    }
}

/// A polarised scene (it holds polarisers) under an integrator that carries no Stokes vectors
/// is refused with the reason, not rendered as if the polarisers were grey filters; under
/// `path`, `light` and `bdpt` it writes the Stokes channels.
#[test]
fn a_polarised_scene_renders_under_path_light_and_bdpt_only() {
    let dir = tmpdir("polarised");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/polarisation.toml")
        .display()
        .to_string();
    let base = one_sample(&scene);
    for integrator in ["whitted", "direct"] {
        let (ok, err) = spectrace(&dir, &[&base[..], &["--integrator", integrator]].concat());
        assert!(
            !ok && err.contains("renders polarised") && err.contains(integrator),
            "{integrator}: {err}"
        );
        assert!(!dir.join("o.exr").exists(), "no image after an error");
    }
    for integrator in ["path", "light", "bdpt"] {
        let (ok, err) = spectrace(&dir, &[&base[..], &["--integrator", integrator]].concat());
        assert!(ok, "{integrator}: {err}");
        let img = spectrace::image_io::read_exr(&dir.join("o.exr")).expect("the image");
        for c in [
            "S1.Y", "S2.Y", "S3.Y", "DoLP", "AoLP", "pol0.Y", "pol45.Y", "pol90.Y", "pol135.Y",
        ] {
            assert!(
                img.channels.iter().any(|(n, _)| n == c),
                "{integrator}: no {c}"
            );
        }
        std::fs::remove_file(dir.join("o.exr")).expect("removed");
    }
}

/// The arguments that render `scene` at 1 spp into `o.exr`, quietly.
fn one_sample(scene: &str) -> [&str; 7] {
    ["render", scene, "-o", "o.exr", "--quiet", "--spp", "1"]
}
