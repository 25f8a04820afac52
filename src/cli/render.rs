//! `spectrace render SCENE …`, and the built-in default scene.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use clap::{Args, ValueEnum};

use super::CliError;
use super::progress::Progress;
use crate::loader::desc::IntegratorKind;
use crate::output::{RenderInfo, write_exr, write_png};
use crate::render::{RenderOptions, render};

/// The built-in default scene: `scenes/prism.toml`, embedded in the binary.
pub const DEFAULT_SCENE: &str = include_str!("../../scenes/prism.toml");

#[derive(Clone, Copy, Debug, ValueEnum)]
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

#[derive(Args, Debug, Default)]
pub struct RenderArgs {
    /// Scene file: spectrace TOML, or Mitsuba 3 XML (.xml).
    pub scene: PathBuf,
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
}

static CANCEL: AtomicBool = AtomicBool::new(false);

fn install_ctrl_c() {
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

/// Renders the default scene to `spectrace.exr` and `spectrace.png` in the current folder.
pub fn run_default() -> Result<(), CliError> {
    let args = RenderArgs {
        scene: PathBuf::from("<built-in>/prism.toml"),
        output: Some(PathBuf::from("spectrace.exr")),
        png: Some(PathBuf::from("spectrace.png")),
        ..Default::default()
    };
    let desc = crate::loader::load_str(DEFAULT_SCENE, &args.scene)?;
    run_desc(&args, desc)
}

pub fn run(args: RenderArgs) -> Result<(), CliError> {
    let mut defines = Vec::new();
    for d in &args.define {
        let Some((k, v)) = d.split_once('=') else {
            return Err(CliError::Usage(format!("-D {d}: expected NAME=VALUE")));
        };
        defines.push((k.to_string(), v.to_string()));
    }
    let desc = crate::loader::load_any(&args.scene, &defines)?;
    run_desc(&args, desc)
}

fn run_desc(args: &RenderArgs, desc: crate::loader::SceneDesc) -> Result<(), CliError> {
    for n in &desc.notes {
        eprintln!("note: {n}");
    }
    let scene = crate::scene::build(&desc)?;
    let mut opts = RenderOptions::from_scene(&scene);
    if let Some(s) = args.spp {
        if s == 0 {
            return Err(CliError::Usage("--spp must be at least 1".into()));
        }
        opts.spp = s;
    }
    if let Some(t) = args.threads {
        if t == 0 {
            return Err(CliError::Usage("--threads must be at least 1".into()));
        }
        opts.threads = Some(t);
    }
    opts.seed = args.seed;
    if let Some(i) = args.integrator {
        opts.integrator = match i {
            IntegratorArg::Path => IntegratorKind::Path,
            IntegratorArg::Light => IntegratorKind::Light,
            IntegratorArg::Bdpt => IntegratorKind::Bdpt,
            IntegratorArg::Whitted => IntegratorKind::Whitted,
        };
    }
    if let Some(st) = &args.bdpt_strategy {
        let parsed = st.split_once(',').and_then(|(a, b)| {
            Some((a.trim().parse::<u32>().ok()?, b.trim().parse::<u32>().ok()?))
        });
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
        opts.strategy = Some(crate::integrator::bdpt::Strategy {
            s,
            t,
            weighted: !args.bdpt_unweighted,
        });
    }
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
    if let Some(b) = args.spectral_bins {
        if b > 1000 {
            return Err(CliError::Usage(
                "--spectral-bins must be at most 1000".into(),
            ));
        }
        opts.spectral_bins = b;
    }
    let stem = args
        .scene
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
    for p in [&exr, &png] {
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

    install_ctrl_c();
    let total = scene.film.width as u64 * scene.film.height as u64 * opts.spp as u64;
    let bar = Progress::new(total, args.quiet);
    let (film, stats) = render(&scene, &opts, &CANCEL, &|done, _| bar.set(done))
        .map_err(|e| CliError::Usage(e.to_string()))?;
    bar.finish();
    let mut image = film.image();
    if args.mitsuba_units {
        crate::output::to_mitsuba_scale(&mut image);
    }
    let integrator = match opts.integrator {
        IntegratorKind::Path => "path",
        IntegratorKind::Light => "light",
        IntegratorKind::Bdpt => "bdpt",
        IntegratorKind::Whitted => "whitted",
        IntegratorKind::Direct { .. } => "direct",
    };
    let info = RenderInfo {
        scene_file: &args.scene.display().to_string(),
        integrator,
        spp: if stats.partial {
            stats.spp_done
        } else {
            opts.spp
        },
        seed: opts.seed,
        seconds: stats.elapsed.as_secs_f64(),
        partial: stats.partial,
        nan_samples: stats.nan_samples,
        inf_samples: stats.inf_samples,
        range: scene.wavelengths,
        mitsuba_units: args.mitsuba_units,
        moment: scene.integrator.moment && !splats,
    };
    write_exr(&exr, &image, &info)?;
    let ev = write_png(&png, &image, args.exposure.or(scene.film.exposure_ev))?;
    if !args.quiet {
        let secs = stats.elapsed.as_secs_f64();
        eprintln!(
            "{} samples in {:.1} s ({:.2} M samples/s){}",
            stats.samples,
            secs,
            stats.samples as f64 / secs.max(1e-9) / 1e6,
            if stats.partial {
                ", stopped early: the image is partial"
            } else {
                ""
            }
        );
        if stats.nan_samples + stats.inf_samples > 0 {
            eprintln!(
                "dropped {} NaN and {} infinite samples",
                stats.nan_samples, stats.inf_samples
            );
        }
        eprintln!(
            "wrote {} and {} (EV100 {:.2})",
            shown(&exr),
            shown(&png),
            ev
        );
    }
    Ok(())
}

fn shown(p: &Path) -> String {
    std::path::absolute(p)
        .unwrap_or_else(|_| p.to_path_buf())
        .display()
        .to_string()
}
