//! A kind's parameters as the kind reads them, whatever file they came from: the seam by which
//! each kind reads its own parameters and the loaders only dispatch by name (pbrt-v4's
//! `ParameterDictionary`, Mitsuba 3's `Properties`).
//!
//! A kind's file (for example `film/filter/tent.rs`) holds a reader
//! `fn(&mut dyn Params) -> Result<Desc, ParamError>` and one line in its family's registry. Each
//! loader wraps its own syntax (a TOML table, a Mitsuba XML element) in a [`Params`] that
//! records what was asked for, so a key no reader asked for is an error naming it, and turns a
//! [`ParamError`] into its own error with the file, line and field.
//!
//! This module is a leaf of the describe phase: it imports nothing from the crate (and only
//! `strsim` from outside), so render-side
//! kind files may use it without importing a loader.

use std::fmt;

/// The file format the parameters come from. A kind reads a format's parameters as that format
/// defines them (Mitsuba's `gaussian` takes a standard deviation and is cut at 4σ; spectrace's
/// takes a radius and is cut there), so a reader may ask.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    /// spectrace's TOML scene files.
    Toml,
    /// Mitsuba 3 XML scenes.
    Mitsuba,
}

/// A parameter that is missing, of the wrong type or out of range.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// The parameter's name as the file spells it; `None` for the element as a whole.
    pub param: Option<String>,
    /// What is wrong and what was expected, for a user.
    pub message: String,
}

impl ParamError {
    /// An error about parameter `param`.
    pub fn new(param: &str, message: impl Into<String>) -> Self {
        Self {
            param: Some(param.to_string()),
            message: message.into(),
        }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.param {
            Some(p) => write!(f, "{p}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for ParamError {}

/// Named parameters of one object of some kind, read by that kind's reader.
pub trait Params {
    /// The format the parameters come from.
    fn dialect(&self) -> Dialect;

    /// The number named `name`, `Ok(None)` if absent; an error if present but not a finite
    /// number. Asking marks the name as read.
    fn float(&mut self, name: &str) -> Result<Option<f64>, ParamError>;

    /// A finite number > 0 named `name`, or `default` if absent.
    fn positive(&mut self, name: &str, default: f64) -> Result<f64, ParamError> {
        match self.float(name)? {
            None => Ok(default),
            Some(x) if x > 0.0 => Ok(x),
            Some(x) => Err(ParamError::new(
                name,
                format!("expected a positive number, found {x}"),
            )),
        }
    }
}

/// A kind as its family's registry lists it: its name in each format that has it (`None`:
/// the format does not name it) and its reader.
pub struct Kind<D> {
    /// The name in spectrace's TOML.
    pub toml: Option<&'static str>,
    /// The plugin name in Mitsuba 3 XML.
    pub mitsuba: Option<&'static str>,
    /// Reads the kind's parameters (all of them: what it does not ask for is an error).
    pub read: fn(&mut dyn Params) -> Result<D, ParamError>,
}

impl<D> Kind<D> {
    /// The kind's name in `dialect`.
    pub fn name(&self, dialect: Dialect) -> Option<&'static str> {
        match dialect {
            Dialect::Toml => self.toml,
            Dialect::Mitsuba => self.mitsuba,
        }
    }
}

/// The kind of `registry` named `name` in `dialect`.
pub fn find<'r, D>(registry: &'r [Kind<D>], dialect: Dialect, name: &str) -> Option<&'r Kind<D>> {
    registry.iter().find(|k| k.name(dialect) == Some(name))
}

/// The names of `registry`'s kinds in `dialect`, in registry order, for "expected …" messages.
pub fn names<D>(registry: &[Kind<D>], dialect: Dialect) -> Vec<&'static str> {
    registry.iter().filter_map(|k| k.name(dialect)).collect()
}

/// The candidate closest to `name` if it is close enough to be a likely misspelling of it
/// (Jaro–Winkler similarity ≥ 0.85), for "did you mean …?" in every loader's errors.
pub fn nearest<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .map(|c| (strsim::jaro_winkler(name, c), c))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .filter(|(s, _)| *s >= 0.85)
        .map(|(_, c)| c)
}

/// ` (did you mean "NAME"?)` for [`nearest`]`(name, candidates)`, else nothing.
pub fn did_you_mean<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    nearest(name, candidates)
        .map(|c| format!(" (did you mean \"{c}\"?)"))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A map of numbers, as a test's stand-in for a loader.
    struct Map(Vec<(&'static str, f64)>);

    impl Params for Map {
        fn dialect(&self) -> Dialect {
            Dialect::Toml
        }
        fn float(&mut self, name: &str) -> Result<Option<f64>, ParamError> {
            Ok(self.0.iter().find(|(k, _)| *k == name).map(|(_, v)| *v))
        }
    }

    #[test]
    fn positive_takes_the_default_and_rejects_zero_and_negatives() {
        assert_eq!(Map(vec![]).positive("r", 2.0), Ok(2.0));
        assert_eq!(Map(vec![("r", 0.5)]).positive("r", 2.0), Ok(0.5));
        for bad in [0.0, -1.0] {
            let e = Map(vec![("r", bad)]).positive("r", 2.0).unwrap_err();
            assert_eq!(e.param.as_deref(), Some("r"));
        }
    }
}
