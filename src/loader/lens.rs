//! pbrt-v4's lens files: one interface per line, object side first, four columns
//!
//! ```text
//! # radius  thickness  index  aperture      (mm, mm, -, mm)
//! 29.475    3.76       1.67   25.2
//! 0         4.5        0      17.1          # radius 0: the aperture stop
//! ```
//!
//! `radius` is the radius of curvature (positive with its centre on the film side; 0 for the
//! stop; `inf` for a flat refracting surface), `thickness` the axial distance to the next
//! surface (on the last line: to the film), `index` the medium behind the surface and
//! `aperture` the clear **diameter**. `#` starts a comment. As pbrt-v4 reads them, 0 (or 1) in
//! the index column is air. spectrace also reads a glass there, so that every element disperses:
//! a catalogue name (`N-BK7`, `glass:OHARA/S-LAH66`) or a model glass `nd/vd` (`1.67003/47.11`).
//!
//! The reader checks each line; the build step ([`crate::build::lens_system`]) checks the
//! system as a whole, and both name the file and line.

use std::path::{Path, PathBuf};

use crate::loader::error::{LoadError, Loc};
use crate::spectrum::ior::Ior;
use crate::spectrum::named::{Named, lookup};
use crate::units::Length;
use crate::units::length::millimeter;

/// A lens file's interfaces, as read.
#[derive(Clone, Debug, PartialEq)]
pub struct LensDesc {
    pub path: PathBuf,
    pub surfaces: Vec<LensSurfaceDesc>,
}

/// One line of a lens file.
#[derive(Clone, Debug, PartialEq)]
pub struct LensSurfaceDesc {
    /// Radius of curvature (0: the stop; infinite: flat).
    pub radius: Length,
    /// Axial distance to the next surface, or to the film.
    pub thickness: Length,
    /// The medium behind the surface; `Ior::Constant(1.0)` for air.
    pub medium: Ior,
    /// The index column as written.
    pub medium_name: String,
    /// Clear diameter.
    pub aperture: Length,
    pub loc: Loc,
}

/// Reads a lens file (at most 1 MiB: a prescription has tens of lines).
pub fn read(path: &Path) -> Result<LensDesc, LoadError> {
    let text = crate::files::read_text(path, 1 << 20).map_err(|e| {
        LoadError::new(
            path,
            Loc::default(),
            "",
            format!("cannot read lens file: {e}"),
        )
    })?;
    parse(&text, path)
}

/// Parses lens-file text; `path` names it in errors.
pub fn parse(text: &str, path: &Path) -> Result<LensDesc, LoadError> {
    let mut surfaces = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let body = line.split('#').next().unwrap_or("");
        let tokens: Vec<(usize, &str)> = body
            .split_whitespace()
            .map(|t| (t.as_ptr() as usize - line.as_ptr() as usize, t))
            .collect();
        if tokens.is_empty() {
            continue;
        }
        let at = |k: usize| Loc {
            line: i as u32 + 1,
            col: line[..tokens[k.min(tokens.len() - 1)].0].chars().count() as u32 + 1,
        };
        let err = |k: usize, field: &str, msg: String| LoadError::new(path, at(k), field, msg);
        if tokens.len() != 4 {
            return Err(err(
                tokens.len().min(3),
                "",
                format!(
                    "expected 4 columns (radius, thickness, index, aperture diameter; mm), found {}",
                    tokens.len()
                ),
            ));
        }
        let number = |k: usize, field: &str| -> Result<f64, LoadError> {
            let t = tokens[k].1;
            let v = match t.to_ascii_lowercase().as_str() {
                "inf" | "infinity" | "+inf" => f64::INFINITY,
                "-inf" | "-infinity" => f64::NEG_INFINITY,
                _ => t
                    .parse::<f64>()
                    .map_err(|_| err(k, field, format!("\"{t}\" is not a number (mm)")))?,
            };
            if v.is_nan() {
                return Err(err(k, field, "NaN is not a length".into()));
            }
            Ok(v)
        };
        let radius = number(0, "radius")?;
        let thickness = number(1, "thickness")?;
        if !(thickness.is_finite() && thickness >= 0.0) {
            return Err(err(
                1,
                "thickness",
                format!("expected a finite length ≥ 0 mm, found {thickness}"),
            ));
        }
        let aperture = number(3, "aperture")?;
        if !(aperture.is_finite() && aperture > 0.0) {
            return Err(err(
                3,
                "aperture",
                format!("expected a positive diameter in mm, found {aperture}"),
            ));
        }
        let medium = medium(tokens[2].1).map_err(|m| err(2, "index", m))?;
        surfaces.push(LensSurfaceDesc {
            radius: Length::new::<millimeter>(radius),
            thickness: Length::new::<millimeter>(thickness),
            medium,
            medium_name: tokens[2].1.to_string(),
            aperture: Length::new::<millimeter>(aperture),
            loc: at(0),
        });
    }
    if surfaces.is_empty() {
        return Err(LoadError::new(
            path,
            Loc { line: 1, col: 1 },
            "",
            "the lens file has no surfaces (one line per interface: radius thickness index aperture)",
        ));
    }
    Ok(LensDesc {
        path: path.to_path_buf(),
        surfaces,
    })
}

/// The index column: a number (0 or 1: air), a glass name, or `nd/vd`.
fn medium(t: &str) -> Result<Ior, String> {
    if let Ok(n) = t.parse::<f64>() {
        return if n == 0.0 || n == 1.0 {
            Ok(Ior::Constant(1.0))
        } else if n > 1.0 && n.is_finite() {
            Ok(Ior::Constant(n as f32))
        } else {
            Err(format!("an index must be 0 (air) or ≥ 1, found {t}"))
        };
    }
    if let Some((nd, vd)) = t.split_once('/')
        && let (Ok(nd), Ok(vd)) = (nd.parse::<f64>(), vd.parse::<f64>())
    {
        return Ior::model(nd, vd)
            .ok_or_else(|| format!("a model glass nd/vd needs nd ≥ 1 and vd > 0, found {t}"));
    }
    let name = if t.contains(':') {
        t.to_string()
    } else {
        format!("glass:{t}")
    };
    match lookup(&name) {
        Ok(Named::Dielectric(g)) => Ok(g.ior),
        Ok(_) => Err(format!("\"{t}\" is not a glass")),
        Err(e) => Err(format!(
            "{e} (an index column holds a number, a glass name or a model glass nd/vd)"
        )),
    }
}
