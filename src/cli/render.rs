//! `spectrace render SCENE …`, and the built-in default scene.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use clap::{Args, ValueEnum};

use super::CliError;
use super::progress::Progress;
use crate::loader::desc::IntegratorKind;
use crate::output::{RenderInfo, write_exr, write_png};
use crate::render::{RenderOptions, render_with};

/// The built-in default scene: `scenes/prism.toml`, embedded in the binary.
pub const DEFAULT_SCENE: &str = include_str!("../../scenes/prism.toml");

#[derive(Clone, Copy, Debug, ValueEnum, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorArg {
    /// Unidirectional path tracing with next-event estimation and MIS.
    Path,
    /// Light (particle) tracing with camera connections: caustics.
    Light,
    /// Bidirectional path tracing: caustics and everything else, combined by MIS.
    Bdpt,
    /// The lecture notes' Phong/Whitted model, per wavelength.
    Whitted,
}

/// What a false-colour image shows.
#[derive(Clone, Copy, Debug, PartialEq, ValueEnum, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FalseColourKind {
    /// Luminance of the rendered image, cd/m².
    Luminance,
    /// Illuminance at the surfaces the pixels see, lx (an extra pass, as `rpict -i`).
    Illuminance,
}

/// The scale of a false-colour image.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, ValueEnum, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum FalseColourScale {
    #[default]
    Log,
    Linear,
}

#[derive(Args, Debug, Default, Clone, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct RenderArgs {
    /// Scene file: spectrace TOML, or Mitsuba 3 XML (.xml).
    #[arg(required_unless_present = "resume")]
    pub scene: Option<PathBuf>,
    /// Output EXR (float32: X, Y, Z in cd/m², linear sRGB R, G, B, band radiance L in
    /// W·m⁻²·sr⁻¹; spectral channels with --spectral-bins). Default: the scene's name with .exr,
    /// in the current folder.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// 8-bit sRGB PNG preview. Default: the EXR's name with .png.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Samples per pixel (light tracing: light paths per pixel). Default: the scene's.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Worker threads. Default: every core.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Seed of the sampler; the same seed gives the same image for any thread count.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Integrator. Default: the scene's.
    #[arg(long, value_enum)]
    pub integrator: Option<IntegratorArg>,
    /// Spectral EXR bins over the film's wavelength range (Fichet et al. 2021 layout).
    #[arg(long)]
    pub spectral_bins: Option<u32>,
    /// PNG exposure EV₁₀₀ (saturation at 1.2·2^EV cd/m²). Default: automatic.
    #[arg(long, allow_negative_numbers = true)]
    pub exposure: Option<f32>,
    /// Also write a false-colour PNG (viridis, with a legend in its unit) of `luminance` (cd/m²,
    /// the render's Y) or `illuminance` (lx at the surfaces seen: an extra pass at the render's
    /// spp, as Radiance's `rpict -i`).
    #[arg(long, value_name = "KIND", alias = "false-color")]
    pub false_colour: Option<FalseColourKind>,
    /// The false-colour PNG. Default: the EXR's name with .false.png.
    #[arg(long, value_name = "PNG", alias = "false-color-png")]
    pub false_colour_png: Option<PathBuf>,
    /// The false colours' scale.
    #[arg(long, value_enum, default_value_t, alias = "false-color-scale")]
    pub false_colour_scale: FalseColourScale,
    /// The top of the false colours' scale, in cd/m² or lx. Default: the largest value rounded
    /// up to 1, 2 or 5 × 10ⁿ.
    #[arg(long, value_name = "VALUE", alias = "false-color-max")]
    pub false_colour_max: Option<f64>,
    /// Decades below the top on the log scale [default: 3].
    #[arg(long, value_name = "N", alias = "false-color-decades")]
    pub false_colour_decades: Option<u32>,
    /// No progress bar and no summary.
    #[arg(short, long)]
    pub quiet: bool,
    /// Mitsuba XML parameter, NAME=VALUE (overrides a <default>); repeatable.
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    pub define: Vec<String>,
    /// Write X, Y, Z, R, G, B on Mitsuba 3.9.1's scale: divided by 683.002 × 106.7502594
    /// = 72 910.6 (Mitsuba's film normalisation of unitless emitter spectra). L stays in
    /// W·m⁻²·sr⁻¹.
    #[arg(long)]
    pub mitsuba_units: bool,
    /// `bdpt` debugging: render only the connection strategy with S light and T camera
    /// vertices ("S,T"), with its MIS weight (the weighted images of all strategies sum to the
    /// full render).
    #[arg(long, value_name = "S,T")]
    pub bdpt_strategy: Option<String>,
    /// With --bdpt-strategy: without its MIS weight (an estimator of the paths it can sample
    /// by itself).
    #[arg(long, requires = "bdpt_strategy")]
    pub bdpt_unweighted: bool,
    /// Render only part I of N ("I/N", I from 0 to N − 1): a disjoint share of every pixel's
    /// samples. The EXR carries the part's exact sums; `spectrace merge` combines all N parts
    /// into the image one render would give, bit for bit.
    #[arg(long, value_name = "I/N")]
    pub part: Option<String>,
    /// Write checkpoints into folder DIR (created if needed), from which `--resume DIR`
    /// continues to the image an uninterrupted render gives, bit for bit.
    #[arg(long, value_name = "DIR")]
    pub checkpoint: Option<PathBuf>,
    /// Time between checkpoints ("60s", "5m", "500ms"; a bare number is seconds).
    #[arg(
        long,
        value_name = "TIME",
        default_value = "60s",
        requires = "checkpoint"
    )]
    pub checkpoint_every: String,
    /// Continue the render checkpointed in DIR, with the arguments it was started with
    /// (only --threads and --quiet may be given again).
    #[arg(long, value_name = "DIR", conflicts_with = "checkpoint")]
    #[serde(skip)]
    pub resume: Option<PathBuf>,
    /// Render time budget ("90s", "10m", "2h"): stop at the end of the pass after which the
    /// next would end past it. Without --spp, renders as many samples as fit.
    #[arg(long, value_name = "TIME")]
    pub time: Option<String>,
    /// Stop at the end of the first pass whose estimated relative RMS error of luminance is
    /// below this fraction (e.g. 0.01). Without --spp, renders as many samples as it takes.
    #[arg(long, value_name = "FRACTION")]
    pub target_error: Option<f64>,
}

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
    // the library API resolves and checks the options, as for every user of it
    let api_opts = api_options(args)?;
    let mut opts = api_opts.render_options(&api_scene).map_err(|e| match e {
        // "spectral_bins must be …" → "--spectral-bins must be …"
        crate::api::Error::Options(m) => CliError::Usage(format!("--{}", m.replacen('_', "-", 1))),
        other => CliError::Usage(other.to_string()),
    })?;
    let scene = api_scene.inner();
    opts.strategy = bdpt_strategy(args, &opts)?;
    let splats = matches!(
        opts.integrator,
        IntegratorKind::Light | IntegratorKind::Bdpt
    );
    if scene.integrator.moment && splats {
        // light paths splat into many pixels: a per-pixel second moment of samples is not
        // defined for them
        eprintln!(
            "note: light tracing and bdpt write no second moments (m2.*); the scene's moment integrator applies to camera-ray integrators"
        );
    }
    // a camera's sensitivities are integrated over spectral bins: 5 nm unless asked otherwise
    if scene
        .camera_sensor
        .as_ref()
        .is_some_and(|s| s.curves.is_some())
        && opts.spectral_bins == 0
    {
        opts.spectral_bins = (scene.wavelengths.width() / 5.0).ceil().max(1.0) as u32;
        if !args.quiet {
            eprintln!(
                "note: the camera sensor's curves are integrated over {} spectral bins of 5 nm, which the EXR also holds",
                opts.spectral_bins
            );
        }
    }
    let cos_theta = scene.camera_sensor.as_ref().map(|_| pixel_cos_theta(scene));
    let budgets = args.time.is_some() || args.target_error.is_some();
    if let Some(p) = &args.part {
        if budgets {
            return Err(CliError::Usage(
                "--part renders a fixed share of the samples; it cannot be combined with --time or --target-error".into(),
            ));
        }
        opts.part = Some(super::farm::parse_part(p, opts.spp)?);
    }
    let hash = if args.part.is_some() || args.checkpoint.is_some() {
        super::farm::scene_hash(scene_path, &args.define)?
    } else {
        String::new()
    };
    let every = match &args.checkpoint {
        Some(_) => Some(super::farm::parse_duration(
            &args.checkpoint_every,
            "--checkpoint-every",
        )?),
        None => None,
    };
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
    };
    let mut started: Option<&Path> = None;
    let snapshot = match &resume {
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
                crate::film::Filter::from_desc(&scene.film.filter),
                scene.wavelengths,
                opts.spectral_bins,
            );
            ck.snapshot(f)?
        }
        None => {
            if let Some(dir) = &args.checkpoint {
                super::checkpoint::start_checkpoint(dir, args, &hash)?;
                started = Some(dir);
            }
            None
        }
    };
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
    let mut info = base_info();
    info.spp = stats.spp_done;
    info.seconds = stats.elapsed.as_secs_f64();
    info.partial = stats.partial;
    info.nan_samples = stats.nan_samples;
    info.inf_samples = stats.inf_samples;
    info.stop = stats.stop.name();
    info.rel_error = stats.rel_error;
    match opts.part {
        Some(part) => {
            let words = film.state_channels(crate::film::STATE_PREFIX);
            let state = crate::output::State {
                words: &words,
                attributes: super::farm::part_attributes(
                    part,
                    &hash,
                    opts.spp,
                    scene.wavelengths,
                    opts.spectral_bins,
                    info.moment,
                    args.mitsuba_units,
                ),
            };
            crate::output::write_exr_state(&exr, &image, &info, Some(&state))?;
        }
        None => write_exr(&exr, &image, &info)?,
    }
    let ev = write_png(&png, &image, args.exposure.or(scene.film.exposure_ev))?;
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

/// The false-colour and unit options checked against each other and the scene.
fn check_false_colour_args(args: &RenderArgs, scene: &crate::scene::Scene) -> Result<(), CliError> {
    if args.mitsuba_units && (args.false_colour.is_some() || scene.camera_sensor.is_some()) {
        return Err(CliError::Usage(
            "--mitsuba-units rescales X, Y, Z away from cd/m², which false colour and a camera sensor read; leave it out".into(),
        ));
    }
    if args.false_colour_png.is_some() && args.false_colour.is_none() {
        return Err(CliError::Usage(
            "--false-colour-png needs --false-colour luminance or illuminance".into(),
        ));
    }
    if let Some(m) = args.false_colour_max
        && !(m > 0.0 && m.is_finite())
    {
        return Err(CliError::Usage(format!(
            "--false-colour-max must be a positive number, found {m}"
        )));
    }
    if args
        .false_colour_decades
        .is_some_and(|d| !(1..=12).contains(&d))
    {
        return Err(CliError::Usage(
            "--false-colour-decades must be from 1 to 12".into(),
        ));
    }
    Ok(())
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

/// The library API's options from the command line (the API checks their ranges).
fn api_options(args: &RenderArgs) -> Result<crate::api::Options, CliError> {
    Ok(crate::api::Options {
        spp: args.spp,
        seed: args.seed,
        threads: args.threads,
        integrator: args.integrator.map(|i| match i {
            IntegratorArg::Path => crate::api::Integrator::Path,
            IntegratorArg::Light => crate::api::Integrator::Light,
            IntegratorArg::Bdpt => crate::api::Integrator::Bdpt,
            IntegratorArg::Whitted => crate::api::Integrator::Whitted,
        }),
        spectral_bins: args.spectral_bins,
        time_limit: match &args.time {
            Some(t) => Some(super::farm::parse_duration(t, "--time")?),
            None => None,
        },
        target_error: args.target_error,
    })
}

/// `--bdpt-strategy S,T` checked against the integrator and the scene's depth (None: not given).
fn bdpt_strategy(
    args: &RenderArgs,
    opts: &crate::render::RenderOptions,
) -> Result<Option<crate::integrator::bdpt::Strategy>, CliError> {
    let Some(st) = &args.bdpt_strategy else {
        return Ok(None);
    };
    let parsed = st
        .split_once(',')
        .and_then(|(a, b)| Some((a.trim().parse::<u32>().ok()?, b.trim().parse::<u32>().ok()?)));
    let Some((s, t)) = parsed else {
        return Err(CliError::Usage(format!(
            "--bdpt-strategy {st}: expected S,T (light and camera vertex counts, e.g. 1,2)"
        )));
    };
    if opts.integrator != IntegratorKind::Bdpt {
        return Err(CliError::Usage(
            "--bdpt-strategy needs the bdpt integrator (--integrator bdpt)".into(),
        ));
    }
    if t == 0 || s.saturating_add(t) < 2 || (s, t) == (1, 1) {
        return Err(CliError::Usage(format!(
            "--bdpt-strategy {s},{t}: bdpt has no such strategy (t ≥ 1, s + t ≥ 2, not 1,1)"
        )));
    }
    if s as u64 + t as u64 - 2 > opts.max_depth as u64 {
        return Err(CliError::Usage(format!(
            "--bdpt-strategy {s},{t}: its paths have {} bounces, more than the scene's max_depth {}",
            s as u64 + t as u64 - 2,
            opts.max_depth
        )));
    }
    Ok(Some(crate::integrator::bdpt::Strategy {
        s,
        t,
        weighted: !args.bdpt_unweighted,
    }))
}

/// Per pixel, cos θ between its central ray and the image centre's (for a camera sensor's
/// cos⁴θ fall-off), row by row.
fn pixel_cos_theta(scene: &crate::scene::Scene) -> Vec<f32> {
    let (w, h) = (scene.film.width, scene.film.height);
    let centre = scene
        .camera
        .generate_ray(
            glam::Vec2::new(w as f32 / 2.0, h as f32 / 2.0),
            glam::Vec2::splat(0.5),
        )
        .d;
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d = scene
                .camera
                .generate_ray(
                    glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5),
                    glam::Vec2::splat(0.5),
                )
                .d;
            d.dot(centre).clamp(0.0, 1.0)
        })
        .collect()
}

/// Writes the false-colour PNG of `kind` (see [`RenderArgs::false_colour`]).
fn false_colour(
    args: &RenderArgs,
    scene: &crate::scene::Scene,
    opts: &RenderOptions,
    spp: u32,
    image: &crate::film::Image,
    kind: FalseColourKind,
    path: &Path,
) -> Result<(), CliError> {
    let (values, unit): (Vec<f32>, &str) = match kind {
        FalseColourKind::Luminance => (image.xyz.iter().map(|p| p[1]).collect(), "cd/m²"),
        FalseColourKind::Illuminance => {
            let m = crate::render::measure::MeasureOptions {
                samples: spp,
                threads: opts.threads,
                seed: opts.seed,
                max_depth: opts.max_depth,
                spectral_bins: 0,
            };
            let bar = super::progress::Progress::new(scene.film.height as u64, args.quiet);
            let v = crate::render::measure::illuminance_image(scene, opts.spp, &m, &CANCEL, &|d| {
                bar.set(d)
            })
            .map_err(|e| CliError::Usage(e.to_string()))?;
            bar.finish();
            if CANCEL.load(Ordering::Relaxed) {
                return Ok(());
            }
            (v, "lx")
        }
    };
    let log = args.false_colour_scale == FalseColourScale::Log;
    let decades = args.false_colour_decades.unwrap_or(3);
    let scale = match args.false_colour_max {
        Some(hi) if log => crate::falsecolour::Scale::Log {
            lo: hi / 10f64.powi(decades as i32),
            hi,
        },
        Some(hi) => crate::falsecolour::Scale::Linear { lo: 0.0, hi },
        None => crate::falsecolour::Scale::auto(&values, log, decades)
            .unwrap_or(crate::falsecolour::Scale::Linear { lo: 0.0, hi: 1.0 }),
    };
    let (w, h) = (scene.film.width as usize, scene.film.height as usize);
    let (img, fw, fh) = crate::falsecolour::image(&values, w, h, scale, unit);
    crate::image_io::write_png_srgb8(path, fw, fh, &img)?;
    if !args.quiet {
        eprintln!("wrote {} ({unit}, {scale:?})", shown(path));
    }
    Ok(())
}

fn shown(p: &Path) -> String {
    std::path::absolute(p)
        .unwrap_or_else(|_| p.to_path_buf())
        .display()
        .to_string()
}
