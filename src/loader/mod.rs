//! Scene files → [`desc::SceneDesc`]: a description with typed `uom` quantities and the source
//! location of every item. The format is TOML (see the README, "Scene format").
//!
//! Every error names the file, line and column, the field and what was expected
//! ([`error::LoadError`]); unknown keys are errors.

mod convert;
pub mod desc;
pub mod error;
pub mod lens;
pub mod mitsuba;
pub mod pbrt;
pub mod photometric;
mod raw;

use std::path::Path;

pub use desc::SceneDesc;
pub use error::{LoadError, Loc};

/// Reads a scene file by its extension: `.xml` is a Mitsuba scene (with `defines` for its
/// parameters), `.pbrt` a pbrt-v4 scene, anything else spectrace's TOML.
pub fn load_any(path: &Path, defines: &[(String, String)]) -> Result<SceneDesc, LoadError> {
    let ext = |x: &str| path.extension().is_some_and(|e| e.eq_ignore_ascii_case(x));
    if ext("xml") {
        mitsuba::load(path, defines)
    } else if ext("pbrt") {
        pbrt::load(path)
    } else {
        load(path)
    }
}

/// Reads and validates a scene file.
pub fn load(path: &Path) -> Result<SceneDesc, LoadError> {
    let text = crate::files::read_text(path, crate::files::MAX_TEXT_BYTES).map_err(|e| {
        LoadError::new(
            path,
            Loc { line: 0, col: 0 },
            "",
            format!("cannot read scene file: {e}"),
        )
    })?;
    load_str(&text, path)
}

/// Validates scene text; `path` names it in errors and anchors relative paths.
pub fn load_str(text: &str, path: &Path) -> Result<SceneDesc, LoadError> {
    let raw: raw::RawScene = toml::from_str(text).map_err(|e| {
        let loc = e
            .span()
            .map(|s| error::SourceMap::new(text).span(&s))
            .unwrap_or(Loc { line: 1, col: 1 });
        let mut msg = e.message().trim().to_string();
        if msg == "duplicate key"
            && let Some(span) = e.span()
        {
            // name the key, and the table when a whole table is repeated
            let start = text[..span.start.min(text.len())]
                .rfind('\n')
                .map_or(0, |i| i + 1);
            let line = text[start..].lines().next().unwrap_or("").trim();
            // the header alone, without a comment after it
            let line = line.find(']').map_or(line, |i| {
                let end = if line[i + 1..].starts_with(']') {
                    i + 2
                } else {
                    i + 1
                };
                &line[..end]
            });
            let key = text.get(span.clone()).unwrap_or("").trim();
            msg = if line.starts_with('[') {
                format!("table {line} is defined twice (also earlier in the file)")
            } else {
                format!("key `{key}` is given twice")
            };
        }
        LoadError::new(path, loc, "", msg)
    })?;
    convert::convert(raw, path, text)
}
