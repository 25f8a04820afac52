//! `spectrace merge`: render parts (`--part I/N`, whose EXRs carry their film's exact sums)
//! added into the image one render of all their samples gives, bit for bit.

use std::path::{Path, PathBuf};

use super::CliError;
use super::farm::{num_attr, text_attr};
use super::view;
use crate::film::FilterDesc;
use crate::film::{Film, Filter, STATE_PREFIX};
use crate::image_io::{ExrImage, read_exr};
use crate::output::{RenderInfo, write_png};
use crate::spectrum::WavelengthRange;

/// `spectrace merge PART… -o OUT`: adds the parts' sums exactly and writes the image one render
/// of all their samples would write (same pixels, bit for bit).
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The EXR files of every part of one render (written with --part I/N).
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output EXR.
    #[arg(short, long)]
    pub output: PathBuf,
    /// 8-bit sRGB PNG preview. Default: the EXR's name with .png.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// PNG exposure EV₁₀₀. Default: automatic.
    #[arg(long, allow_negative_numbers = true)]
    pub exposure: Option<f32>,
    /// The PNG's display transform (`standard` or `clip`, as `render --view`).
    #[arg(long, default_value = "standard",
          value_parser = clap::builder::PossibleValuesParser::new(crate::output::View::NAMES))]
    pub view: String,
    /// No summary.
    #[arg(short, long)]
    pub quiet: bool,
}

/// What must agree between parts, read from each file.
#[derive(PartialEq, Debug)]
struct PartKey {
    size: (usize, usize),
    n: u32,
    hash: String,
    seed: String,
    integrator: String,
    spp: u32,
    range: (String, String),
    bins: u32,
    moment: bool,
    mitsuba_units: bool,
    scene: String,
    /// Where a cropped render's parts lie in its full image.
    window: Option<crate::image_io::DataWindow>,
}

pub fn merge(args: MergeArgs) -> Result<(), CliError> {
    let mut key: Option<PartKey> = None;
    let mut seen: Vec<Option<PathBuf>> = Vec::new();
    let mut film: Option<Film> = None;
    let (mut spp, mut secs, mut nan, mut inf) = (0u64, 0.0f64, 0u64, 0u64);
    let mut partial = false;
    let mut stop = "complete".to_string();
    for path in &args.parts {
        let img = read_exr(path)?;
        let (i, n, k) = part_key(&img, path)?;
        match &key {
            None => {
                seen = vec![None; n as usize];
                let range = WavelengthRange {
                    min_nm: num_attr(&img, path, "spectrace:wavelengthMinNm")?,
                    max_nm: num_attr(&img, path, "spectrace:wavelengthMaxNm")?,
                };
                let (w, h) = (img.width as u32, img.height as u32);
                let f = Filter::from_desc(&FilterDesc::BOX);
                // a polarised render's parts carry its Stokes sums
                let polarised = img
                    .words
                    .iter()
                    .any(|(c, _)| c.starts_with(&format!("{STATE_PREFIX}s1X.")));
                film = Some(Film::new(w, h, f, range, k.bins).with_stokes(polarised));
                key = Some(k);
            }
            Some(first) if *first != k => {
                return Err(CliError::Usage(format!(
                    "{} is not a part of the same render as {}: {}",
                    path.display(),
                    args.parts[0].display(),
                    difference(first, &k)
                )));
            }
            Some(_) => {}
        }
        if let Some(other) = &seen[i as usize] {
            return Err(CliError::Usage(format!(
                "{} and {} are both part {i}/{n}",
                other.display(),
                path.display()
            )));
        }
        seen[i as usize] = Some(path.clone());
        if let Some(f) = film.as_mut() {
            f.add_state_channels(STATE_PREFIX, &img.words)
                .map_err(|e| CliError::Usage(format!("{}: {e}", path.display())))?;
        }
        spp += num_attr::<u64>(&img, path, "spectrace:samplesPerPixel")?;
        secs += num_attr::<f64>(&img, path, "spectrace:renderTimeSeconds")?;
        nan += num_attr::<f64>(&img, path, "spectrace:droppedNaNSamples")? as u64;
        inf += num_attr::<f64>(&img, path, "spectrace:droppedInfSamples")? as u64;
        partial |= num_attr::<i32>(&img, path, "spectrace:partial")? != 0;
        let s = text_attr(&img, path, "spectrace:stopReason")?;
        if s != "complete" {
            stop = s;
        }
    }
    let (Some(key), Some(film)) = (key, film) else {
        return Err(CliError::Usage("merge needs at least one part".into()));
    };
    let missing: Vec<String> = (0..key.n)
        .filter(|&i| seen[i as usize].is_none())
        .map(|i| format!("{i}/{}", key.n))
        .collect();
    if !missing.is_empty() {
        return Err(CliError::Usage(format!(
            "parts missing: {} (every part of the render is needed)",
            missing.join(", ")
        )));
    }
    let mut image = film.image();
    if key.mitsuba_units {
        crate::output::to_mitsuba_scale(&mut image);
    }
    let range = film.range;
    let info = RenderInfo {
        // the parts carry no scene: sensor channels and AOVs are not recomputed
        sensor: None,
        aovs: &[],
        scene_file: &key.scene,
        integrator: &key.integrator,
        spp: spp.min(u32::MAX as u64) as u32,
        seed: key.seed.parse::<i32>().map_or(0, |v| v as u32),
        seconds: secs,
        partial,
        nan_samples: nan,
        inf_samples: inf,
        range,
        mitsuba_units: key.mitsuba_units,
        moment: key.moment,
        stop: &stop,
        rel_error: None,
        window: key.window,
    };
    crate::output::write_exr(&args.output, &image, &info)?;
    let png = args
        .png
        .clone()
        .unwrap_or_else(|| args.output.with_extension("png"));
    write_png(&png, &image, args.exposure, view(&args.view))?;
    if !args.quiet {
        eprintln!(
            "merged {} parts ({} samples per pixel) into {} and {}",
            key.n,
            spp,
            args.output.display(),
            png.display()
        );
    }
    Ok(())
}

/// A part's index, its count and the fields every part of one render shares.
fn part_key(img: &ExrImage, path: &Path) -> Result<(u32, u32, PartKey), CliError> {
    let part = text_attr(img, path, "spectrace:part")?;
    let (i, n) = part
        .split_once('/')
        .and_then(|(i, n)| Some((i.parse::<u32>().ok()?, n.parse::<u32>().ok()?)))
        .filter(|(i, n)| i < n && *n <= 1 << 24)
        .ok_or_else(|| CliError::Usage(format!("{}: part `{part}` is not I/N", path.display())))?;
    let k = PartKey {
        size: (img.width, img.height),
        n,
        hash: text_attr(img, path, "spectrace:sceneHash")?,
        seed: text_attr(img, path, "spectrace:seed")?,
        integrator: text_attr(img, path, "spectrace:integrator")?,
        spp: num_attr(img, path, "spectrace:partsSamplesPerPixel")?,
        range: (
            text_attr(img, path, "spectrace:wavelengthMinNm")?,
            text_attr(img, path, "spectrace:wavelengthMaxNm")?,
        ),
        bins: num_attr(img, path, "spectrace:spectralBins")?,
        moment: num_attr::<i32>(img, path, "spectrace:moment")? != 0,
        mitsuba_units: num_attr::<i32>(img, path, "spectrace:mitsubaUnits")? != 0,
        scene: text_attr(img, path, "spectrace:scene")?,
        window: img.window,
    };
    Ok((i, n, k))
}

/// The first field in which two parts differ, for the error message.
fn difference(a: &PartKey, b: &PartKey) -> String {
    if a.size != b.size {
        format!(
            "{}×{} against {}×{} pixels",
            b.size.0, b.size.1, a.size.0, a.size.1
        )
    } else if a.n != b.n {
        format!("a part of {} against a part of {}", b.n, a.n)
    } else if a.hash != b.hash || a.scene != b.scene {
        "another scene file or -D definitions".into()
    } else if a.seed != b.seed {
        format!("seed {} against {}", b.seed, a.seed)
    } else if a.integrator != b.integrator {
        format!("integrator {} against {}", b.integrator, a.integrator)
    } else if a.spp != b.spp {
        format!("{} against {} samples per pixel in all", b.spp, a.spp)
    } else {
        "other film settings (wavelength range, spectral bins, moments, Mitsuba units or data window)".into()
    }
}
