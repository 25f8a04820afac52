//! Checkpoint folders (`--checkpoint DIR`, `--resume DIR`): `args.toml` (the render's
//! arguments, paths made absolute, and the scene file's hash), written once, and `state.exr`,
//! replaced atomically at every checkpoint: the image so far, the film's exact sums as
//! unsigned-integer channels ([`crate::film::STATE_PREFIX`]) and the scheduler's position in
//! header attributes.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::CliError;
use super::farm::{num_attr, text_attr};
use super::render::RenderArgs;
use crate::film::{Film, STATE_PREFIX};
use crate::image_io::{AttrValue, ExrImage, ImageError, read_exr, write_atomically};
use crate::output::{RenderInfo, State, write_exr_state};
use crate::render::Snapshot;

/// Prefix of a `bdpt` checkpoint's unfinished pass.
const PASS_PREFIX: &str = "spectrace.pass.";

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
