//! Long renders and render farms: what checkpoints (`checkpoint.rs`) and render parts
//! (`merge.rs`) share: durations, `--part I/N`, the scene hash, the header attributes a part
//! carries, and reading attributes back.

use std::path::Path;
use std::time::Duration;

use super::CliError;
use crate::image_io::{AttrValue, ExrImage};
use crate::spectrum::WavelengthRange;

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
    let bytes = crate::files::read_bytes(scene, crate::files::MAX_TEXT_BYTES)
        .map_err(|e| CliError::Usage(format!("cannot read scene {}: {e}", scene.display())))?;
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes.iter().chain(defines.join("\n").as_bytes()) {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    Ok(format!("{h:016x}"))
}

pub(super) fn text_attr(img: &ExrImage, path: &Path, name: &str) -> Result<String, CliError> {
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

pub(super) fn num_attr<T: std::str::FromStr>(
    img: &ExrImage,
    path: &Path,
    name: &str,
) -> Result<T, CliError> {
    let t = text_attr(img, path, name)?;
    t.parse().map_err(|_| {
        CliError::Usage(format!(
            "{}: attribute `{name}` = `{t}` is not a valid number",
            path.display()
        ))
    })
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
