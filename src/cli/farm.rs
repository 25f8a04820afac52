//! Long renders and render farms: checkpoints (`--checkpoint DIR`, `--resume DIR`), render
//! parts (`--part I/N`) and `spectrace merge`.
//!
//! A checkpoint folder holds `args.toml` (the render's arguments, paths made absolute, and the
//! scene file's hash), written once, and `state.exr`, replaced atomically at every checkpoint:
//! the image so far, the film's exact sums as unsigned-integer channels
//! ([`crate::film::STATE_PREFIX`]) and the scheduler's position in header attributes. A part's
//! EXR carries its film's sums the same way, so that `merge` adds them exactly.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::CliError;
use super::render::RenderArgs;
use crate::film::{Film, Filter, STATE_PREFIX};
use crate::image_io::{AttrValue, ExrImage, ImageError, read_exr, write_atomically};
use crate::loader::desc::FilterDesc;
use crate::output::{RenderInfo, State, write_exr_state, write_png};
use crate::render::Snapshot;
use crate::spectrum::WavelengthRange;

/// Prefix of a `bdpt` checkpoint's unfinished pass.
const PASS_PREFIX: &str = "spectrace.pass.";

/// A duration: a number with `ms`, `s`, `m` or `h` (a bare number is seconds).
pub fn parse_duration(text: &str, flag: &str) -> Result<Duration, CliError> {
    let t = text.trim();
    let (num, unit) = t
        .find(|c: char| c.is_ascii_alphabetic())
        .map_or((t, "s"), |i| (&t[..i], &t[i..]));
    let scale = match unit.trim() {
        "ms" => 1e-3,
        "s" => 1.0,
        "m" | "min" => 60.0,
        "h" => 3600.0,
        u => {
            return Err(CliError::Usage(format!(
                "{flag} {text}: unknown unit `{u}` (use ms, s, m or h, e.g. 90s or 10m)"
            )));
        }
    };
    match num.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v * scale < 1e9 => {
            Ok(Duration::from_secs_f64(v * scale))
        }
        _ => Err(CliError::Usage(format!(
            "{flag} {text}: expected a positive time such as 90s, 10m or 2h"
        ))),
    }
}

/// `I/N` with 0 ≤ I < N ≤ `spp`.
pub fn parse_part(text: &str, spp: u32) -> Result<(u32, u32), CliError> {
    let parsed = text
        .split_once('/')
        .and_then(|(i, n)| Some((i.trim().parse::<u32>().ok()?, n.trim().parse::<u32>().ok()?)));
    let Some((i, n)) = parsed else {
        return Err(CliError::Usage(format!(
            "--part {text}: expected I/N, part I (counted from 0) of N, e.g. 0/4"
        )));
    };
    if n == 0 || i >= n {
        return Err(CliError::Usage(format!(
            "--part {text}: the part must be 0 to {} of {n}",
            n.saturating_sub(1)
        )));
    }
    if n > spp {
        return Err(CliError::Usage(format!(
            "--part {text}: the render has {spp} samples per pixel, too few for {n} parts"
        )));
    }
    Ok((i, n))
}

/// FNV-1a (64 bits) of the scene file's bytes and the -D definitions, as hex: a checkpoint or
/// part made from another scene file is refused.
pub fn scene_hash(scene: &Path, defines: &[String]) -> Result<String, CliError> {
    let bytes = std::fs::read(scene)
        .map_err(|e| CliError::Usage(format!("cannot read scene {}: {e}", scene.display())))?;
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes.iter().chain(defines.join("\n").as_bytes()) {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    Ok(format!("{h:016x}"))
}

fn text_attr(img: &ExrImage, path: &Path, name: &str) -> Result<String, CliError> {
    match img.attribute(name) {
        Some(AttrValue::Text(t)) => Ok(t.clone()),
        Some(AttrValue::Int(i)) => Ok(i.to_string()),
        Some(AttrValue::Double(d)) => Ok(d.to_string()),
        _ => Err(CliError::Usage(format!(
            "{}: no `{name}` attribute: not a spectrace checkpoint or render part",
            path.display()
        ))),
    }
}

fn num_attr<T: std::str::FromStr>(img: &ExrImage, path: &Path, name: &str) -> Result<T, CliError> {
    let t = text_attr(img, path, name)?;
    t.parse().map_err(|_| {
        CliError::Usage(format!(
            "{}: attribute `{name}` = `{t}` is not a valid number",
            path.display()
        ))
    })
}

/// The checkpoint folder's two files.
fn files(dir: &Path) -> (PathBuf, PathBuf) {
    (dir.join("args.toml"), dir.join("state.exr"))
}

/// Starts a checkpoint folder: creates it if needed and writes `args.toml`. Refuses a folder
/// that already holds a checkpoint.
pub fn start_checkpoint(dir: &Path, args: &RenderArgs, hash: &str) -> Result<(), CliError> {
    let (a, s) = files(dir);
    if a.exists() || s.exists() {
        return Err(CliError::Usage(format!(
            "--checkpoint {}: the folder already holds a checkpoint; continue it with \
             `spectrace render --resume {}`, or choose another folder",
            dir.display(),
            dir.display()
        )));
    }
    std::fs::create_dir_all(dir).map_err(|e| {
        CliError::Usage(format!(
            "cannot create checkpoint folder {}: {e}",
            dir.display()
        ))
    })?;
    let stored = Stored {
        scene_hash: hash.to_string(),
        args: absolute(args),
    };
    let text = toml::to_string(&stored)
        .map_err(|e| CliError::Usage(format!("cannot write {}: {e}", a.display())))?;
    write_atomically(&a, |out| {
        std::io::Write::write_all(out, text.as_bytes()).map_err(|source| ImageError::Io {
            path: a.clone(),
            action: "cannot write".into(),
            source,
        })
    })?;
    Ok(())
}

/// Removes a checkpoint folder's `args.toml` (and the folder, if then empty) after a render
/// that could not start.
pub fn abandon_checkpoint(dir: &Path) {
    let (a, _) = files(dir);
    let _ = std::fs::remove_file(a);
    let _ = std::fs::remove_dir(dir);
}

/// `args.toml`.
#[derive(serde::Serialize, serde::Deserialize)]
struct Stored {
    scene_hash: String,
    args: RenderArgs,
}

/// The arguments with the scene, output and PNG paths made absolute (a resumed render may run
/// from another folder).
fn absolute(args: &RenderArgs) -> RenderArgs {
    let abs = |p: &PathBuf| std::path::absolute(p).unwrap_or_else(|_| p.clone());
    let mut a = args.clone();
    a.scene = a.scene.as_ref().map(abs);
    a.output = a.output.as_ref().map(abs);
    a.png = a.png.as_ref().map(abs);
    a.checkpoint = a.checkpoint.as_ref().map(abs);
    a
}

/// Writes `state.exr` for `snap`, atomically. `info` describes the render.
pub fn write_checkpoint(
    dir: &Path,
    snap: &Snapshot,
    info: &RenderInfo<'_>,
    hash: &str,
) -> Result<(), CliError> {
    let (_, path) = files(dir);
    let mut words = snap.film.state_channels(STATE_PREFIX);
    if let Some(p) = &snap.pass_film {
        words.extend(p.state_channels(PASS_PREFIX));
    }
    let done: String = snap
        .tiles_done
        .iter()
        .map(|&d| if d { '1' } else { '0' })
        .collect();
    let state = State {
        words: &words,
        attributes: vec![
            ("spectrace:sceneHash", AttrValue::Text(hash.to_string())),
            ("spectrace:checkpointPass", AttrValue::Int(snap.pass as i32)),
            ("spectrace:checkpointTilesDone", AttrValue::Text(done)),
            (
                "spectrace:checkpointPathsDone",
                AttrValue::Text(snap.paths_done.to_string()),
            ),
            (
                "spectrace:checkpointNaNSamples",
                AttrValue::Text(snap.nan_samples.to_string()),
            ),
            (
                "spectrace:checkpointInfSamples",
                AttrValue::Text(snap.inf_samples.to_string()),
            ),
            (
                "spectrace:checkpointSeconds",
                AttrValue::Double(snap.elapsed.as_secs_f64()),
            ),
            (
                "spectrace:checkpointPassFilm",
                AttrValue::Int(snap.pass_film.is_some() as i32),
            ),
        ],
    };
    write_exr_state(&path, &snap.film.image(), info, Some(&state))?;
    Ok(())
}

/// A checkpoint read back: the arguments it was started with, its scene hash, and the file.
pub struct Checkpoint {
    pub args: RenderArgs,
    pub scene_hash: String,
    state: Option<(PathBuf, ExrImage)>,
}

/// Reads a checkpoint folder. A folder with `args.toml` but no `state.exr` yet (killed before
/// its first checkpoint) resumes from the start.
pub fn read_checkpoint(dir: &Path) -> Result<Checkpoint, CliError> {
    let (a, s) = files(dir);
    let text = std::fs::read_to_string(&a).map_err(|e| {
        CliError::Usage(format!(
            "--resume {}: cannot read {}: {e} (is it a folder written by --checkpoint?)",
            dir.display(),
            a.display()
        ))
    })?;
    let stored: Stored =
        toml::from_str(&text).map_err(|e| CliError::Usage(format!("{}: {e}", a.display())))?;
    // temporary files of sessions killed while writing a checkpoint (never the state itself)
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            if e.file_name()
                .to_string_lossy()
                .starts_with("state.exr.tmp-")
            {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
    let state = if s.exists() {
        Some((s.clone(), read_exr(&s)?))
    } else {
        None
    };
    Ok(Checkpoint {
        args: stored.args,
        scene_hash: stored.scene_hash,
        state,
    })
}

impl Checkpoint {
    /// The render's state, into an empty `film` of the scene (None: start from the beginning).
    pub fn snapshot(&self, film: Film) -> Result<Option<Snapshot>, CliError> {
        let Some((path, img)) = &self.state else {
            return Ok(None);
        };
        let bad = |e: String| CliError::Usage(format!("{}: {e}", path.display()));
        if (img.width, img.height) != (film.width as usize, film.height as usize) {
            return Err(bad(format!(
                "the checkpoint is {}×{}, the scene's film {}×{}",
                img.width, img.height, film.width, film.height
            )));
        }
        let hash = text_attr(img, path, "spectrace:sceneHash")?;
        if hash != self.scene_hash {
            return Err(bad("the state belongs to another render".into()));
        }
        let mut f = film.empty_like();
        f.add_state_channels(STATE_PREFIX, &img.words)
            .map_err(bad)?;
        let pass_film = if num_attr::<i32>(img, path, "spectrace:checkpointPassFilm")? != 0 {
            let mut p = film.empty_like();
            p.add_state_channels(PASS_PREFIX, &img.words).map_err(bad)?;
            Some(p)
        } else {
            None
        };
        let done = text_attr(img, path, "spectrace:checkpointTilesDone")?;
        if done.chars().any(|c| c != '0' && c != '1') {
            return Err(bad(
                "attribute `spectrace:checkpointTilesDone` is not 0s and 1s".into(),
            ));
        }
        let secs: f64 = num_attr(img, path, "spectrace:checkpointSeconds")?;
        Ok(Some(Snapshot {
            film: f,
            pass_film,
            pass: num_attr::<u32>(img, path, "spectrace:checkpointPass")?,
            tiles_done: done.chars().map(|c| c == '1').collect(),
            paths_done: num_attr(img, path, "spectrace:checkpointPathsDone")?,
            nan_samples: num_attr(img, path, "spectrace:checkpointNaNSamples")?,
            inf_samples: num_attr(img, path, "spectrace:checkpointInfSamples")?,
            elapsed: Duration::from_secs_f64(secs.clamp(0.0, 1e12)),
        }))
    }
}

/// The attributes a render part adds to its EXR, beside its film's sums.
pub fn part_attributes(
    part: (u32, u32),
    hash: &str,
    spp: u32,
    range: WavelengthRange,
    bins: u32,
    moment: bool,
    mitsuba_units: bool,
) -> Vec<(&'static str, AttrValue)> {
    vec![
        (
            "spectrace:part",
            AttrValue::Text(format!("{}/{}", part.0, part.1)),
        ),
        ("spectrace:sceneHash", AttrValue::Text(hash.to_string())),
        ("spectrace:partsSamplesPerPixel", AttrValue::Int(spp as i32)),
        (
            "spectrace:wavelengthMinNm",
            AttrValue::Double(range.min_nm as f64),
        ),
        (
            "spectrace:wavelengthMaxNm",
            AttrValue::Double(range.max_nm as f64),
        ),
        ("spectrace:spectralBins", AttrValue::Int(bins as i32)),
        ("spectrace:moment", AttrValue::Int(moment as i32)),
        (
            "spectrace:mitsubaUnits",
            AttrValue::Int(mitsuba_units as i32),
        ),
    ]
}

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
        let part = text_attr(&img, path, "spectrace:part")?;
        let (i, n) = part
            .split_once('/')
            .and_then(|(i, n)| Some((i.parse::<u32>().ok()?, n.parse::<u32>().ok()?)))
            .filter(|(i, n)| i < n && *n <= 1 << 24)
            .ok_or_else(|| {
                CliError::Usage(format!("{}: part `{part}` is not I/N", path.display()))
            })?;
        let k = PartKey {
            size: (img.width, img.height),
            n,
            hash: text_attr(&img, path, "spectrace:sceneHash")?,
            seed: text_attr(&img, path, "spectrace:seed")?,
            integrator: text_attr(&img, path, "spectrace:integrator")?,
            spp: num_attr(&img, path, "spectrace:partsSamplesPerPixel")?,
            range: (
                text_attr(&img, path, "spectrace:wavelengthMinNm")?,
                text_attr(&img, path, "spectrace:wavelengthMaxNm")?,
            ),
            bins: num_attr(&img, path, "spectrace:spectralBins")?,
            moment: num_attr::<i32>(&img, path, "spectrace:moment")? != 0,
            mitsuba_units: num_attr::<i32>(&img, path, "spectrace:mitsubaUnits")? != 0,
            scene: text_attr(&img, path, "spectrace:scene")?,
        };
        match &key {
            None => {
                seen = vec![None; n as usize];
                let range = WavelengthRange {
                    min_nm: num_attr(&img, path, "spectrace:wavelengthMinNm")?,
                    max_nm: num_attr(&img, path, "spectrace:wavelengthMaxNm")?,
                };
                let (w, h) = (img.width as u32, img.height as u32);
                let f = Filter::from_desc(&FilterDesc::Box);
                film = Some(Film::new(w, h, f, range, k.bins));
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
    };
    crate::output::write_exr(&args.output, &image, &info)?;
    let png = args
        .png
        .clone()
        .unwrap_or_else(|| args.output.with_extension("png"));
    write_png(&png, &image, args.exposure)?;
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
        "other film settings (wavelength range, spectral bins, moments or Mitsuba units)".into()
    }
}
