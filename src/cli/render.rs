//! `spectrace render SCENE …`, and the built-in default scene.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use super::CliError;
use super::progress::Progress;
use super::view;
use crate::loader::desc::IntegratorKind;
use crate::output::{RenderInfo, write_exr, write_png};
use crate::render::{RenderOptions, render_with};
pub use args::{FalseColourKind, FalseColourScale, RenderArgs};
use false_colour::{check_false_colour_args, false_colour, pixel_cos_theta};

mod args;
mod false_colour;
mod options;

use options::options;

/// The built-in default scene: `scenes/prism.toml`, embedded in the binary.
pub const DEFAULT_SCENE: &str = include_str!("../../scenes/prism.toml");

pub(super) static CANCEL: AtomicBool = AtomicBool::new(false);

pub(super) fn install_ctrl_c() {
    // A second handler cannot be installed in the same process; the first one stays.
    let _ = ctrlc::set_handler(|| {
        if CANCEL.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!(
            "\nstopping: finishing the current tiles and writing the partial image (Ctrl-C again to abort)"
        );
    });
}

/// A load error as the CLI reports it.
pub(super) fn api_error(e: crate::api::Error) -> CliError {
    match e {
        crate::api::Error::Scene(l) => CliError::Scene(l),
        other => CliError::Usage(other.to_string()),
    }
}

/// Renders the default scene to `spectrace.exr` and `spectrace.png` in the current folder.
pub fn run_default() -> Result<(), CliError> {
    let args = RenderArgs {
        output: Some(PathBuf::from("spectrace.exr")),
        png: Some(PathBuf::from("spectrace.png")),
        ..Default::default()
    };
    let path = PathBuf::from("<built-in>/prism.toml");
    let scene = crate::api::Scene::from_toml_as(DEFAULT_SCENE, &path).map_err(api_error)?;
    run_scene(&args, &path, scene, None)
}

pub fn run(args: RenderArgs) -> Result<(), CliError> {
    let (args, resume) = match &args.resume {
        Some(dir) => {
            let given = [
                (args.scene.is_some(), "a scene file"),
                (args.output.is_some(), "--output"),
                (args.png.is_some(), "--png"),
                (args.spp.is_some(), "--spp"),
                (args.seed != 0, "--seed"),
                (args.integrator.is_some(), "--integrator"),
                (args.dispersion.is_some(), "--dispersion"),
                (args.spectral_bins.is_some(), "--spectral-bins"),
                (args.exposure.is_some(), "--exposure"),
                (!args.define.is_empty(), "-D"),
                (args.mitsuba_units, "--mitsuba-units"),
                (args.false_colour.is_some(), "--false-colour"),
                (args.false_colour_png.is_some(), "--false-colour-png"),
                (args.false_colour_max.is_some(), "--false-colour-max"),
                (
                    args.false_colour_decades.is_some(),
                    "--false-colour-decades",
                ),
                (args.bdpt_strategy.is_some(), "--bdpt-strategy"),
                (args.part.is_some(), "--part"),
                (args.time.is_some(), "--time"),
                (args.target_error.is_some(), "--target-error"),
            ];
            if let Some((_, what)) = given.iter().find(|(g, _)| *g) {
                return Err(CliError::Usage(format!(
                    "--resume continues the render as it was started; {what} cannot be given again (only --threads and --quiet)"
                )));
            }
            let ck = super::checkpoint::read_checkpoint(dir)?;
            let mut stored = ck.args.clone();
            stored.threads = args.threads.or(stored.threads);
            stored.quiet = args.quiet;
            stored.checkpoint = Some(dir.clone());
            (stored, Some(ck))
        }
        None => (args, None),
    };
    let Some(scene) = args.scene.clone() else {
        return Err(CliError::Usage("no scene file given".into()));
    };
    let mut defines = Vec::new();
    for d in &args.define {
        let Some((k, v)) = d.split_once('=') else {
            return Err(CliError::Usage(format!("-D {d}: expected NAME=VALUE")));
        };
        defines.push((k.to_string(), v.to_string()));
    }
    let loaded = crate::api::Scene::load_with(&scene, &defines).map_err(api_error)?;
    run_scene(&args, &scene, loaded, resume)
}

fn run_scene(
    args: &RenderArgs,
    scene_path: &Path,
    api_scene: crate::api::Scene,
    resume: Option<super::checkpoint::Checkpoint>,
) -> Result<(), CliError> {
    for n in api_scene.notes() {
        eprintln!("note: {n}");
    }
    let scene = api_scene.inner();
    let opts = options(args, &api_scene)?;
    let splats = matches!(
        opts.integrator,
        IntegratorKind::Light | IntegratorKind::Bdpt
    );
    let cos_theta = scene.camera_sensor.as_ref().map(|_| pixel_cos_theta(scene));
    let hash = args.scene_hash(scene_path)?;
    let every = match &args.checkpoint {
        Some(_) => Some(super::farm::parse_duration(
            &args.checkpoint_every,
            "--checkpoint-every",
        )?),
        None => None,
    };
    let (exr, png, false_png) = outputs(args, scene_path);
    check_false_colour_args(args, scene)?;
    check_output_folders(&[&exr, &png, &false_png])?;

    let integrator = opts.integrator.name();
    let scene_file = scene_path.display().to_string();
    let base_info = || RenderInfo {
        scene_file: &scene_file,
        integrator,
        spp: 0,
        seed: opts.seed,
        seconds: 0.0,
        partial: true,
        nan_samples: 0,
        inf_samples: 0,
        range: scene.wavelengths,
        mitsuba_units: args.mitsuba_units,
        moment: scene.integrator.moment && !splats,
        stop: "checkpoint",
        rel_error: None,
        sensor: scene.camera_sensor.as_ref().zip(cos_theta.as_deref()),
        aovs: &[],
        window: scene
            .film
            .data_window
            .map(|(at, full)| crate::image_io::DataWindow { at, full }),
    };
    let (snapshot, started) =
        resume_or_start(args, scene_path, scene, opts.spectral_bins, &resume, &hash)?;
    let warned = AtomicBool::new(false);
    let write_checkpoint = |snap: &crate::render::Snapshot| {
        let Some(dir) = &args.checkpoint else { return };
        let mut info = base_info();
        info.seconds = snap.elapsed.as_secs_f64();
        info.nan_samples = snap.nan_samples;
        info.inf_samples = snap.inf_samples;
        if let Err(e) = super::checkpoint::write_checkpoint(dir, snap, &info, &hash)
            && !warned.swap(true, Ordering::Relaxed)
        {
            eprintln!("\nwarning: checkpoint not written (the render goes on): {e}");
        }
    };

    install_ctrl_c();
    let (first, end) = opts.sample_range();
    let total = scene.film.width as u64 * scene.film.height as u64 * (end - first) as u64;
    let bar = match opts.time_limit {
        Some(t) => Progress::timed(t, args.quiet),
        None => Progress::new(total, args.quiet),
    };
    let ctl = crate::render::Control {
        cancel: &CANCEL,
        progress: &|done, _| bar.set(done),
        checkpoint: every.map(|e| (e, &write_checkpoint as &(dyn Fn(&_) + Sync))),
        resume: snapshot,
    };
    let (film, stats) = render_with(scene, &opts, ctl).map_err(|e| {
        // a render that could not start leaves no checkpoint folder behind
        if let Some(dir) = started {
            super::checkpoint::abandon_checkpoint(dir);
        }
        CliError::Usage(e.to_string())
    })?;
    bar.finish();
    let mut image = film.image();
    if args.mitsuba_units {
        crate::output::to_mitsuba_scale(&mut image);
    }
    // AOVs of the whole image only (a part's are not merged)
    let aovs = match opts.part {
        None => crate::render::aov::render_aovs(scene, opts.seed, stats.spp_done),
        Some(_) => Vec::new(),
    };
    let info = finished(base_info(), &stats, &aovs);
    write_exr_or_part(&exr, &image, &info, &film, &opts, &hash, args.mitsuba_units)?;
    let ev = write_png(
        &png,
        &image,
        args.exposure.or(scene.film.exposure_ev),
        view(&args.view),
    )?;
    if let Some(kind) = args.false_colour
        && stats.stop != crate::render::StopReason::Cancelled
    {
        // the illuminance pass takes the samples the render took (not a time budget's cap)
        let spp = stats.spp_done.clamp(1, opts.spp.max(1));
        false_colour(args, scene, &opts, spp, &image, kind, &false_png)?;
    }
    if !args.quiet {
        print_summary(&stats, &exr, &png, ev);
    }
    Ok(())
}

/// The closing lines on stderr: samples, rate and why the render stopped, the error estimate,
/// dropped samples and the files written (with the PNG's exposure, EV100).
fn print_summary(stats: &crate::render::RenderStats, exr: &Path, png: &Path, ev: f32) {
    let secs = stats.elapsed.as_secs_f64();
    let why = match stats.stop {
        crate::render::StopReason::Complete => String::new(),
        crate::render::StopReason::Cancelled => ", stopped early: the image is partial".into(),
        crate::render::StopReason::TimeLimit => {
            format!(", {} spp within the time limit", stats.spp_done)
        }
        crate::render::StopReason::TargetError => {
            format!(", {} spp reached the target error", stats.spp_done)
        }
    };
    eprintln!(
        "{} samples in {:.1} s ({:.2} M samples/s){why}",
        stats.samples,
        secs,
        stats.samples as f64 / secs.max(1e-9) / 1e6,
    );
    if let Some(e) = stats.rel_error {
        eprintln!("estimated relative error of luminance: {:.2} %", e * 100.0);
    }
    if stats.nan_samples + stats.inf_samples > 0 {
        eprintln!(
            "dropped {} NaN and {} infinite samples",
            stats.nan_samples, stats.inf_samples
        );
    }
    eprintln!("wrote {} and {} (EV100 {:.2})", shown(exr), shown(png), ev);
}

/// Every output's folder exists (checked before rendering, not after).
fn check_output_folders(paths: &[&Path]) -> Result<(), CliError> {
    for p in paths {
        if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty())
            && !dir.is_dir()
        {
            return Err(CliError::Usage(format!(
                "cannot write {}: folder {} does not exist",
                p.display(),
                dir.display()
            )));
        }
    }
    Ok(())
}

fn shown(p: &Path) -> String {
    std::path::absolute(p)
        .unwrap_or_else(|_| p.to_path_buf())
        .display()
        .to_string()
}

/// The EXR, PNG and false-colour PNG to write: as asked, else the scene's name in the current
/// folder.
fn outputs(args: &RenderArgs, scene_path: &Path) -> (PathBuf, PathBuf, PathBuf) {
    let stem = scene_path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "render".into());
    let exr = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{stem}.exr")));
    let png = args
        .png
        .clone()
        .unwrap_or_else(|| exr.with_extension("png"));
    let false_png = args
        .false_colour_png
        .clone()
        .unwrap_or_else(|| exr.with_extension("false.png"));
    (exr, png, false_png)
}

/// The state to resume from (`--resume`, whose scene must be unchanged), or none after starting
/// the `--checkpoint` folder, which is returned so that a render that cannot start removes it.
fn resume_or_start<'a>(
    args: &'a RenderArgs,
    scene_path: &Path,
    scene: &crate::scene::Scene,
    spectral_bins: u32,
    resume: &Option<super::checkpoint::Checkpoint>,
    hash: &str,
) -> Result<(Option<crate::render::Snapshot>, Option<&'a Path>), CliError> {
    Ok(match resume {
        Some(ck) => {
            if super::farm::scene_hash(scene_path, &args.define)? != ck.scene_hash {
                return Err(CliError::Usage(format!(
                    "--resume: {} changed since the checkpoint was started",
                    scene_path.display()
                )));
            }
            let f = crate::film::Film::new(
                scene.film.width,
                scene.film.height,
                scene.film.filter.clone(),
                scene.wavelengths,
                spectral_bins,
            )
            .with_stokes(scene.integrator.polarised);
            (ck.snapshot(f)?, None)
        }
        None => {
            if let Some(dir) = &args.checkpoint {
                super::checkpoint::start_checkpoint(dir, args, hash)?;
                return Ok((None, Some(dir)));
            }
            (None, None)
        }
    })
}

/// `info` of a finished render: its statistics and AOV channels.
fn finished<'a>(
    mut info: RenderInfo<'a>,
    stats: &'a crate::render::RenderStats,
    aovs: &'a [crate::render::aov::AovChannel],
) -> RenderInfo<'a> {
    info.spp = stats.spp_done;
    info.seconds = stats.elapsed.as_secs_f64();
    info.partial = stats.partial;
    info.nan_samples = stats.nan_samples;
    info.inf_samples = stats.inf_samples;
    info.stop = stats.stop.name();
    info.rel_error = stats.rel_error;
    info.aovs = aovs;
    info
}

/// The EXR: the image, with the exact sums and the part's attributes for `--part`.
fn write_exr_or_part(
    exr: &Path,
    image: &crate::film::Image,
    info: &RenderInfo,
    film: &crate::film::Film,
    opts: &RenderOptions,
    hash: &str,
    mitsuba_units: bool,
) -> Result<(), CliError> {
    match opts.part {
        Some(part) => {
            let words = film.state_channels(crate::film::STATE_PREFIX);
            let state = crate::output::State {
                words: &words,
                attributes: super::farm::part_attributes(
                    part,
                    hash,
                    opts.spp,
                    info.range,
                    opts.spectral_bins,
                    info.moment,
                    mitsuba_units,
                ),
            };
            crate::output::write_exr_state(exr, image, info, Some(&state))?;
        }
        None => write_exr(exr, image, info)?,
    }
    Ok(())
}
