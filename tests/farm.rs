//! Long renders and render farms, through the `spectrace` binary: parts merged bit for bit,
//! checkpoints resumed bit for bit after SIGKILL and Ctrl-C, the time and error budgets, and
//! the errors of `merge` and `--resume`.
//!
//! Truth: the image of one uninterrupted render with the same seed and samples (the claim is
//! bit-identity, so any difference fails), and for the error estimate the Mitsuba 3 reference
//! of the scene.

mod support;

use std::path::Path;
use std::process::{Child, Command};
use std::time::Duration;

use spectrace::image_io::{AttrValue, ExrImage, read_exr};
use support::cli::{spectrace, tmpdir};

/// The 96×96 Cornell box of the Mitsuba references (about 1 s at 64 spp).
fn cornell() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reference/cornell/scene.xml")
        .display()
        .to_string()
}

fn spawn(dir: &Path, args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .current_dir(dir)
        .args(args)
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("starts")
}

/// Whether every float channel of `a` equals `b`'s bit for bit (and they have the same ones).
fn same_pixels(a: &ExrImage, b: &ExrImage) -> Result<(), String> {
    let names = |i: &ExrImage| {
        i.channels
            .iter()
            .map(|(n, _)| n.clone())
            .collect::<Vec<_>>()
    };
    if names(a) != names(b) {
        return Err(format!("channels {:?} vs {:?}", names(a), names(b)));
    }
    for ((name, x), (_, y)) in a.channels.iter().zip(&b.channels) {
        if let Some(i) = x
            .iter()
            .zip(y)
            .position(|(p, q)| p.to_bits() != q.to_bits())
        {
            return Err(format!("channel {name} pixel {i}: {} vs {}", x[i], y[i]));
        }
    }
    Ok(())
}

fn text(img: &ExrImage, name: &str) -> String {
    match img.attribute(name) {
        Some(AttrValue::Text(t)) => t.clone(),
        Some(AttrValue::Int(i)) => i.to_string(),
        Some(AttrValue::Double(d)) => d.to_string(),
        other => panic!("{name}: {other:?}"),
    }
}

/// Renders `scene` in `n` parts and merges them; the merged pixels equal one render's, and a
/// part alone does not (the comparison can fail).
fn check_parts(tag: &str, extra: &[&str], spp: u32, ns: &[u32]) {
    let dir = tmpdir(tag);
    let scene = cornell();
    let spp_s = spp.to_string();
    let mut base = vec![
        "render",
        scene.as_str(),
        "--spp",
        &spp_s,
        "--seed",
        "11",
        "-q",
    ];
    base.extend_from_slice(extra);
    let mut single = base.clone();
    single.extend(["-o", "single.exr"]);
    let (ok, err) = spectrace(&dir, &single);
    assert!(ok, "{err}");
    let one = read_exr(&dir.join("single.exr")).unwrap();
    for &n in ns {
        let mut parts = Vec::new();
        for i in 0..n {
            let (part, out) = (format!("{i}/{n}"), format!("part{n}_{i}.exr"));
            let mut args = base.clone();
            args.extend(["--part", &part, "-o", &out]);
            let (ok, err) = spectrace(&dir, &args);
            assert!(ok, "{tag} part {part}: {err}");
            parts.push(out);
        }
        let merged = format!("merged{n}.exr");
        let mut args = vec!["merge", "-q", "-o", &merged];
        args.extend(parts.iter().rev().map(String::as_str));
        let (ok, err) = spectrace(&dir, &args);
        assert!(ok, "{tag} merge of {n}: {err}");
        let m = read_exr(&dir.join(&merged)).unwrap();
        if let Err(e) = same_pixels(&one, &m) {
            panic!("{tag}: the merge of {n} parts differs from one render: {e}");
        }
        assert_eq!(text(&m, "spectrace:samplesPerPixel"), spp.to_string());
        assert!(m.words.is_empty(), "the merged image carries no state");
        if n > 1 {
            let p0 = read_exr(&dir.join(&parts[0])).unwrap();
            assert!(
                same_pixels(&one, &p0).is_err(),
                "{tag}: a part alone is not the render"
            );
            assert!(!p0.words.is_empty(), "a part carries its sums");
        }
    }
}

#[test]
fn parts_merge_to_one_render_bit_for_bit() {
    check_parts("parts-path", &["--spectral-bins", "5"], 8, &[1, 3, 8]);
    check_parts("parts-bdpt", &["--integrator", "bdpt"], 4, &[3]);
    check_parts("parts-light", &["--integrator", "light"], 4, &[4]);
}

/// Starts a checkpointed render, kills it with SIGKILL at random moments (and once with
/// Ctrl-C), resumes it until it finishes, and compares with an uninterrupted render.
fn check_resume(tag: &str, integrator: &str, spp: &str, seed: u64) {
    let dir = tmpdir(tag);
    let scene = cornell();
    let common = [
        "--spp",
        spp,
        "--seed",
        "5",
        "--integrator",
        integrator,
        "-q",
    ];
    let mut args = vec!["render", scene.as_str(), "-o", "ref.exr"];
    args.extend(common);
    let (ok, err) = spectrace(&dir, &args);
    assert!(ok, "{err}");
    let mut args = vec!["render", scene.as_str(), "-o", "out.exr"];
    args.extend(common);
    args.extend(["--checkpoint", "ck", "--checkpoint-every", "0.03s"]);
    let mut rng = support::Rng::new(seed);
    let mut child = spawn(&dir, &args);
    let (mut kills, mut interrupts) = (0, 0);
    for session in 0..400 {
        let ms = 120 + (rng.uniform() * 400.0) as u64;
        std::thread::sleep(Duration::from_millis(ms));
        if child.try_wait().expect("waits").is_some() {
            break;
        }
        if session == 2 {
            // Ctrl-C: the render writes its partial image and a last checkpoint
            let pid = child.id().to_string();
            let _ = Command::new("kill").args(["-INT", &pid]).status();
            interrupts += 1;
        } else {
            let _ = child.kill(); // SIGKILL
            kills += 1;
        }
        let status = child.wait().expect("exits");
        if status.success() && dir.join("out.exr").exists() && session != 2 {
            break;
        }
        child = spawn(&dir, &["render", "--resume", "ck", "-q"]);
    }
    let status = child.wait().expect("exits");
    assert!(
        status.success(),
        "{tag}: the last session failed: {status:?}"
    );
    assert!(
        kills >= 2,
        "{tag}: only {kills} kills; the render was too quick to test"
    );
    assert_eq!(interrupts, 1);
    let (a, b) = (
        read_exr(&dir.join("ref.exr")).unwrap(),
        read_exr(&dir.join("out.exr")).unwrap(),
    );
    if let Err(e) = same_pixels(&a, &b) {
        panic!("{tag}: resumed after {kills} kills differs from one render: {e}");
    }
    assert_eq!(text(&b, "spectrace:stopReason"), "complete");
    let left: Vec<_> = std::fs::read_dir(dir.join("ck"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-"))
        .collect();
    assert!(left.len() <= 1, "temporary files left: {left:?}");
}

#[test]
fn checkpoints_resume_bit_for_bit_after_sigkill_and_ctrl_c() {
    check_resume("resume-path", "path", "192", 1);
    check_resume("resume-bdpt", "bdpt", "64", 2);
    check_resume("resume-light", "light", "128", 3);
}

#[test]
fn resume_refuses_a_changed_scene_and_new_settings() {
    let dir = tmpdir("resume-errors");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, support::render::furnace_toml("path", 0.5, 2)).unwrap();
    let s = scene.display().to_string();
    let (ok, err) = spectrace(
        &dir,
        &[
            "render",
            &s,
            "--spp",
            "2",
            "-q",
            "--checkpoint",
            "ck",
            "-o",
            "a.exr",
        ],
    );
    assert!(ok, "{err}");
    let (ok, err) = spectrace(&dir, &["render", "--resume", "ck", "--spp", "9"]);
    assert!(!ok && err.contains("--spp cannot be given again"), "{err}");
    let (ok, err) = spectrace(&dir, &["render", &s, "--spp", "2", "--checkpoint", "ck"]);
    assert!(!ok && err.contains("already holds a checkpoint"), "{err}");
    let text = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(&scene, format!("{text}\n# edited\n")).unwrap();
    let (ok, err) = spectrace(&dir, &["render", "--resume", "ck", "-q"]);
    assert!(!ok && err.contains("changed since the checkpoint"), "{err}");
    let (ok, err) = spectrace(&dir, &["render", "--resume", "nowhere", "-q"]);
    assert!(
        !ok && err.contains("cannot read") && err.contains("args.toml"),
        "{err}"
    );
    // a render that cannot start leaves no checkpoint folder and no image
    let ortho =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/orthographic/scene.xml");
    let o = ortho.display().to_string();
    let args = [
        "render",
        &o,
        "--integrator",
        "light",
        "--checkpoint",
        "ck2",
        "-o",
        "o.exr",
    ];
    let (ok, err) = spectrace(&dir, &args);
    assert!(!ok && err.contains("orthographic"), "{err}");
    assert!(!dir.join("ck2").exists() && !dir.join("o.exr").exists());
}

#[test]
fn merge_refuses_missing_duplicate_and_foreign_parts() {
    let dir = tmpdir("merge-errors");
    let scene = cornell();
    let part = |i: u32, seed: &str, out: &str| {
        let p = format!("{i}/3");
        let args = [
            "render", &scene, "--spp", "3", "--seed", seed, "-q", "--part", &p, "-o", out,
        ];
        let (ok, err) = spectrace(&dir, &args);
        assert!(ok, "{err}");
    };
    part(0, "1", "a0.exr");
    part(1, "1", "a1.exr");
    part(2, "1", "a2.exr");
    part(2, "2", "b2.exr");
    let merge = |files: &[&str]| {
        let mut args = vec!["merge", "-o", "m.exr"];
        args.extend_from_slice(files);
        spectrace(&dir, &args)
    };
    let (ok, err) = merge(&["a0.exr", "a1.exr"]);
    assert!(!ok && err.contains("parts missing: 2/3"), "{err}");
    let (ok, err) = merge(&["a0.exr", "a1.exr", "a1.exr"]);
    assert!(!ok && err.contains("both part 1/3"), "{err}");
    let (ok, err) = merge(&["a0.exr", "a1.exr", "b2.exr"]);
    assert!(!ok && err.contains("seed 2 against 1"), "{err}");
    let (ok, err) = spectrace(
        &dir,
        &["render", &scene, "--spp", "1", "-q", "-o", "plain.exr"],
    );
    assert!(ok, "{err}");
    let (ok, err) = merge(&["a0.exr", "plain.exr"]);
    assert!(
        !ok && err.contains("not a spectrace checkpoint or render part"),
        "{err}"
    );
    assert!(
        !dir.join("m.exr").exists(),
        "no file is written after an error"
    );
    let (ok, err) = spectrace(&dir, &["render", &scene, "--spp", "2", "--part", "0/3"]);
    assert!(!ok && err.contains("too few for 3 parts"), "{err}");
    let (ok, err) = spectrace(&dir, &["render", &scene, "--part", "3/3"]);
    assert!(!ok && err.contains("0 to 2 of 3"), "{err}");
}

/// `--time` without `--spp` renders passes until the next would overrun, and says so.
#[test]
fn time_budget_stops_at_a_pass_boundary() {
    let dir = tmpdir("time");
    let (ok, err) = spectrace(
        &dir,
        &["render", &cornell(), "--time", "1.5s", "-q", "-o", "t.exr"],
    );
    assert!(ok, "{err}");
    let img = read_exr(&dir.join("t.exr")).unwrap();
    assert_eq!(text(&img, "spectrace:stopReason"), "time limit");
    assert_eq!(text(&img, "spectrace:partial"), "0");
    let spp: u32 = text(&img, "spectrace:samplesPerPixel").parse().unwrap();
    // pass boundaries: 1, 2, 4, …, 64, then every 64
    assert!(
        spp > 0 && (spp.is_power_of_two() || spp.is_multiple_of(64)),
        "{spp} spp"
    );
    let (ok, err) = spectrace(&dir, &["render", &cornell(), "--time", "10 parsecs"]);
    assert!(!ok && err.contains("unknown unit"), "{err}");
}

/// `--target-error` stops when the estimated relative RMS error of Y is below the target, and
/// the estimate is honest: it matches the measured error against Mitsuba 3's reference (whose
/// own noise, known from its two seeds, is taken out).
#[test]
fn target_error_estimate_matches_the_error_against_mitsuba() {
    let dir = tmpdir("target");
    let args = [
        "render",
        &cornell(),
        "--target-error",
        "0.05",
        "--mitsuba-units",
        "-q",
    ];
    let mut args = args.to_vec();
    args.extend(["-o", "e.exr"]);
    let (ok, err) = spectrace(&dir, &args);
    assert!(ok, "{err}");
    let img = read_exr(&dir.join("e.exr")).unwrap();
    assert_eq!(text(&img, "spectrace:stopReason"), "target error");
    let est: f64 = text(&img, "spectrace:estimatedRelativeErrorY")
        .parse()
        .unwrap();
    assert!(est <= 0.05, "estimate {est}");
    let refdir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/cornell");
    let ra = read_exr(&refdir.join("ref_a.exr")).unwrap();
    let rb = read_exr(&refdir.join("ref_b.exr")).unwrap();
    let (ya, yb, ours) = (
        ra.channel("Y").unwrap(),
        rb.channel("Y").unwrap(),
        img.channel("Y").unwrap(),
    );
    let n = ya.len() as f64;
    let ms = |a: &[f32], b: &[f32]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (*x as f64 - *y as f64).powi(2))
            .sum::<f64>()
            / n
    };
    let ref_var = ms(ya, yb) / 2.0;
    let mean_ref = ya.iter().map(|v| *v as f64).sum::<f64>() / n;
    let measured = (ms(ours, ya) - ref_var).max(0.0).sqrt() / mean_ref;
    let ratio = est / measured;
    assert!(
        (0.75..1.33).contains(&ratio),
        "estimated {est:.4}, measured {measured:.4} (ratio {ratio:.3})"
    );
}

/// The budget and part flags refuse what they cannot do, before rendering anything.
#[test]
fn budget_and_part_flags_are_checked() {
    let dir = tmpdir("flags");
    let scene = cornell();
    let cases: [(&[&str], &str); 5] = [
        (&["--target-error", "2"], "a fraction between 0 and 1"),
        (
            &["--target-error", "0.1", "--integrator", "light"],
            "light integrator has none",
        ),
        (
            &["--part", "0/2", "--time", "10s"],
            "cannot be combined with --time",
        ),
        (
            &["--checkpoint", "ck", "--checkpoint-every", "soon"],
            "--checkpoint-every soon: unknown unit",
        ),
        (&["--part", "1-2"], "expected I/N"),
    ];
    for (extra, want) in cases {
        let mut args = vec!["render", scene.as_str(), "-q", "-o", "x.exr"];
        args.extend_from_slice(extra);
        let (ok, err) = spectrace(&dir, &args);
        assert!(!ok && err.contains(want), "{extra:?}: {err}");
        assert!(
            !dir.join("x.exr").exists() && !dir.join("ck").exists(),
            "{extra:?}"
        );
    }
}
