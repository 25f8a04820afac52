//! `spectrace measure`: the scene's `[[sensors]]` read as illuminance and irradiance meters,
//! written to a CSV file (atomically) with a standard error per point.

use std::io::Write;
use std::path::PathBuf;
use std::sync::atomic::Ordering;

use clap::Args;

use super::CliError;
use crate::render::measure::{MeasureOptions, REPLICAS, Reading, measure};

#[derive(Args, Debug)]
pub struct MeasureArgs {
    /// The scene file (TOML) with `[[sensors]]`.
    pub scene: PathBuf,
    /// The CSV file to write: one row per point.
    #[arg(short, long, value_name = "CSV")]
    pub output: PathBuf,
    /// Samples per point (rounded up to a multiple of 16, the independent replicas behind the
    /// standard error).
    #[arg(long, default_value_t = 4096)]
    pub samples: u32,
    /// Also write the spectral irradiance, W·m⁻²·nm⁻¹, in 10 nm bins over the scene's
    /// wavelength range (or `--spectral-bins`).
    #[arg(long)]
    pub spectral: bool,
    /// Number of spectral bins (implies --spectral).
    #[arg(long, value_name = "N")]
    pub spectral_bins: Option<u32>,
    /// Path length bound (default: the scene's max_depth).
    #[arg(long)]
    pub max_depth: Option<u32>,
    #[arg(long)]
    pub threads: Option<usize>,
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// No progress bar.
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(args: MeasureArgs) -> Result<(), CliError> {
    let loaded = crate::api::Scene::load(&args.scene).map_err(super::render::api_error)?;
    for n in loaded.notes() {
        eprintln!("note: {n}");
    }
    let scene = loaded.inner();
    if scene.meters.is_empty() {
        return Err(CliError::Usage(format!(
            "{}: the scene has no [[sensors]] to measure",
            args.scene.display()
        )));
    }
    if args.samples == 0 || args.samples > 1 << 24 {
        return Err(CliError::Usage(
            "--samples must be from 1 to 16777216".into(),
        ));
    }
    if args.threads == Some(0) {
        return Err(CliError::Usage("--threads must be at least 1".into()));
    }
    let bins = match (args.spectral_bins, args.spectral) {
        (Some(0), _) => return Err(CliError::Usage("--spectral-bins must be at least 1".into())),
        (Some(n), _) if n > 10_000 => {
            return Err(CliError::Usage(
                "--spectral-bins must be at most 10000".into(),
            ));
        }
        (Some(n), _) => n,
        (None, true) => (scene.wavelengths.width() / 10.0).ceil().max(1.0) as u32,
        (None, false) => 0,
    };
    let opts = MeasureOptions {
        samples: args.samples,
        threads: args.threads,
        seed: args.seed,
        max_depth: args.max_depth.unwrap_or(scene.integrator.max_depth),
        spectral_bins: bins,
    };
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        return Err(CliError::Usage(format!(
            "cannot write {}: folder {} does not exist",
            args.output.display(),
            dir.display()
        )));
    }
    super::render::install_ctrl_c();
    let points = scene.meter_points();
    let bar = super::progress::Progress::new(points.len() as u64 * REPLICAS as u64, args.quiet);
    let readings = measure(scene, &points, &opts, &super::render::CANCEL, &|d| {
        bar.set(d)
    })
    .map_err(|e| CliError::Usage(e.to_string()))?;
    bar.finish();
    let missing = readings.iter().filter(|r| r.is_none()).count();
    write_csv(&args.output, scene, &readings, bins)?;
    if missing > 0 {
        eprintln!(
            "stopped: {missing} of {} points unfinished are left out of {}",
            points.len(),
            args.output.display()
        );
    }
    // a summary per sensor: illuminance min, mean, max and uniformity U0 = min/mean
    let mut at = 0;
    for m in &scene.meters {
        let r: Vec<&Reading> = readings[at..at + m.points.len()].iter().flatten().collect();
        at += m.points.len();
        if r.is_empty() {
            continue;
        }
        let e: Vec<f64> = r.iter().map(|r| r.illuminance_lx).collect();
        let mean = e.iter().sum::<f64>() / e.len() as f64;
        let min = e.iter().copied().fold(f64::INFINITY, f64::min);
        let max = e.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if e.len() == 1 {
            eprintln!(
                "{}: {:.6} lx (± {:.2} lx)",
                m.name, mean, r[0].illuminance_se_lx
            );
        } else {
            eprintln!(
                "{}: {} points, illuminance min {min:.6} lx, mean {mean:.6} lx, max {max:.6} lx, uniformity U0 = min/mean {:.4}",
                m.name,
                e.len(),
                if mean > 0.0 { min / mean } else { 0.0 }
            );
        }
    }
    let dropped: u64 = readings.iter().flatten().map(|r| r.dropped).sum();
    if dropped > 0 {
        eprintln!("warning: {dropped} samples were NaN or infinite and counted as zero");
    }
    if super::render::CANCEL.load(Ordering::Relaxed) {
        return Err(CliError::Usage("interrupted".into()));
    }
    Ok(())
}

fn write_csv(
    path: &std::path::Path,
    scene: &crate::scene::Scene,
    readings: &[Option<Reading>],
    bins: u32,
) -> Result<(), CliError> {
    let r = scene.wavelengths;
    let width = r.width() / bins.max(1) as f32;
    use std::fmt::Write as _;
    let mut w = String::new();
    let w = &mut w;
    {
        write!(
            w,
            "sensor,i,j,x_m,y_m,z_m,nx,ny,nz,illuminance_lx,illuminance_stderr_lx,irradiance_W_m2,irradiance_stderr_W_m2"
        ).ok();
        for b in 0..bins {
            write!(w, ",E_{}nm_W_m2_nm", r.min_nm + (b as f32 + 0.5) * width).ok();
        }
        writeln!(w).ok();
        let mut at = 0;
        for m in &scene.meters {
            for (k, p) in m.points.iter().enumerate() {
                let reading = &readings[at + k];
                let Some(x) = reading else { continue };
                let [i, j] = m.cell(k);
                write!(
                    w,
                    "{},{i},{j},{},{},{},{},{},{},{:e},{:e},{:e},{:e}",
                    m.name,
                    p.p.x,
                    p.p.y,
                    p.p.z,
                    p.n.x,
                    p.n.y,
                    p.n.z,
                    x.illuminance_lx,
                    x.illuminance_se_lx,
                    x.irradiance_w_m2,
                    x.irradiance_se_w_m2
                )
                .ok();
                for v in &x.spectral_w_m2_nm {
                    write!(w, ",{v:e}").ok();
                }
                writeln!(w).ok();
            }
            at += m.points.len();
        }
    }
    crate::image_io::write_atomically(path, |f| {
        f.write_all(w.as_bytes())
            .map_err(|e| crate::image_io::ImageError::Io {
                path: path.to_path_buf(),
                action: "write".into(),
                source: e,
            })
    })?;
    Ok(())
}
