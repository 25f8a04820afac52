//! Raw TOML → [`SceneDesc`]: typed quantities, resolved spectra and paths, located errors.

mod items;
mod params;
mod spectra;

use std::ops::Range;
use std::path::{Path, PathBuf};

use toml::Value;

use super::desc::{Point, SceneDesc};
use super::error::{LoadError, SourceMap};
use super::raw::{RawScene, S};
use crate::units::parse::{Dimension, ParseQuantity, QuantityError, parse_any};
use crate::units::{Angle, Length, angle, length};

pub(crate) use spectra::SpectrumUse;

/// Conversion context: the file, its folder, its text and the scene's length unit.
pub(crate) struct Cx<'a> {
    pub file: &'a Path,
    pub dir: PathBuf,
    pub src: SourceMap<'a>,
    /// Metres per scene length unit.
    pub unit_m: f64,
}

pub(crate) type R<T> = Result<T, LoadError>;

/// Lists the keys of a raw section that are present, with their spans.
macro_rules! present {
    ($raw:expr; $($f:ident),+ $(,)?) => {
        [$( $raw.$f.as_ref().map(|v| (stringify!($f), v.span())) ),+]
            .into_iter()
            .flatten()
            .collect::<Vec<(&'static str, std::ops::Range<usize>)>>()
    };
}
pub(crate) use present;

impl<'a> Cx<'a> {
    pub fn err(
        &self,
        span: &Range<usize>,
        field: impl Into<String>,
        msg: impl Into<String>,
    ) -> LoadError {
        LoadError::new(self.file, self.src.span(span), field, msg)
    }

    /// Rejects keys that do not apply to this `type`.
    pub fn only(
        &self,
        what: &str,
        field: &str,
        present: &[(&str, Range<usize>)],
        allowed: &[&str],
    ) -> R<()> {
        for (key, span) in present {
            if !allowed.contains(key) {
                return Err(self.err(
                    span,
                    format!("{field}.{key}"),
                    format!(
                        "`{key}` does not apply to {what}; allowed keys: {}",
                        allowed.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The index in `names` (a registry's `type` names, in order) of `name`, the `type` of a
    /// `family` ("light") at `span`, the field `field`; else an error naming the types with a
    /// suggestion.
    pub fn kind_index(
        &self,
        name: &str,
        span: &Range<usize>,
        field: &str,
        family: &str,
        names: &[&str],
    ) -> R<usize> {
        names.iter().position(|n| *n == name).ok_or_else(|| {
            self.err(
                span,
                field,
                format!(
                    "unknown {family} type \"{name}\"{}; expected {}",
                    crate::params::did_you_mean(name, names.iter().copied()),
                    names.join(", ")
                ),
            )
        })
    }

    pub fn required<'v, T>(
        &self,
        v: &'v Option<S<T>>,
        span: &Range<usize>,
        field: &str,
        what: &str,
    ) -> R<&'v S<T>> {
        v.as_ref()
            .ok_or_else(|| self.err(span, field, format!("missing; expected {what}")))
    }

    /// A finite number (integer or float).
    pub fn number(&self, v: &S<Value>, field: &str) -> R<f64> {
        let x = match v.get_ref() {
            Value::Integer(i) => *i as f64,
            Value::Float(f) => *f,
            other => {
                return Err(self.err(
                    &v.span(),
                    field,
                    format!("expected a number, found {}", kind(other)),
                ));
            }
        };
        if !x.is_finite() {
            return Err(self.err(
                &v.span(),
                field,
                format!("expected a finite number, found {x}"),
            ));
        }
        Ok(x)
    }

    /// A finite number > 0.
    pub fn positive(&self, v: &S<Value>, field: &str) -> R<f64> {
        let x = self.number(v, field)?;
        if x <= 0.0 {
            return Err(self.err(
                &v.span(),
                field,
                format!("expected a positive number, found {x}"),
            ));
        }
        Ok(x)
    }

    /// An integer in `[lo, hi]`.
    pub fn int(&self, v: &S<Value>, field: &str, lo: i64, hi: i64) -> R<i64> {
        match v.get_ref() {
            Value::Integer(i) if (lo..=hi).contains(i) => Ok(*i),
            Value::Integer(i) => Err(self.err(
                &v.span(),
                field,
                format!("expected an integer from {lo} to {hi}, found {i}"),
            )),
            other => Err(self.err(
                &v.span(),
                field,
                format!("expected an integer, found {}", kind(other)),
            )),
        }
    }

    /// A quantity string of the dimension of `Q`.
    pub fn quantity<Q: ParseQuantity>(&self, v: &S<Value>, field: &str) -> R<Q> {
        let s = self.string(v, field, Q::DIMENSION.describe())?;
        crate::units::parse::parse::<Q>(s).map_err(|e| self.err(&v.span(), field, e.to_string()))
    }

    /// A quantity string of one of several dimensions: (dimension, value in SI base units).
    pub fn quantity_of(
        &self,
        v: &S<Value>,
        field: &str,
        allowed: &[Dimension],
    ) -> R<(Dimension, f64)> {
        let want = allowed
            .iter()
            .map(|d| d.describe())
            .collect::<Vec<_>>()
            .join(" or ");
        let s = self.string(v, field, &want)?;
        let q = parse_any(s, allowed[0]).map_err(|e| {
            let msg = match e {
                QuantityError::UnknownUnit { unit, .. } => {
                    format!("\"{s}\": unknown unit \"{unit}\"; expected {want}")
                }
                other => other.to_string(),
            };
            self.err(&v.span(), field, msg)
        })?;
        if !allowed.contains(&q.dimension) {
            return Err(self.err(
                &v.span(),
                field,
                format!(
                    "\"{s}\" is {}, but {want} was expected",
                    q.dimension.describe()
                ),
            ));
        }
        Ok((q.dimension, q.si))
    }

    pub fn string<'v>(&self, v: &'v S<Value>, field: &str, what: &str) -> R<&'v str> {
        match v.get_ref() {
            Value::String(s) => Ok(s),
            other => Err(self.err(
                &v.span(),
                field,
                format!(
                    "expected {what} as a quoted quantity string, found {}",
                    kind(other)
                ),
            )),
        }
    }

    /// Three finite numbers.
    pub fn vec3(&self, v: &S<Value>, field: &str) -> R<[f64; 3]> {
        let Value::Array(a) = v.get_ref() else {
            return Err(self.err(
                &v.span(),
                field,
                format!("expected [x, y, z], found {}", kind(v.get_ref())),
            ));
        };
        if a.len() != 3 {
            return Err(self.err(
                &v.span(),
                field,
                format!("expected 3 numbers [x, y, z], found {}", a.len()),
            ));
        }
        let mut out = [0.0; 3];
        for (i, x) in a.iter().enumerate() {
            out[i] = match x {
                Value::Integer(n) => *n as f64,
                Value::Float(f) if f.is_finite() => *f,
                other => {
                    return Err(self.err(
                        &v.span(),
                        format!("{field}[{i}]"),
                        format!("expected a finite number, found {}", kind(other)),
                    ));
                }
            };
        }
        Ok(out)
    }

    /// An angle in degrees within [lo, hi]: a number of degrees or a quantity string
    /// ("30 deg", "0.5 rad"); `what` names it in the message ("a tilt").
    pub fn degrees_in(&self, v: &S<Value>, field: &str, what: &str, lo: f64, hi: f64) -> R<f64> {
        let d = match v.get_ref() {
            Value::String(_) => self.quantity::<Angle>(v, field)?.get::<angle::degree>(),
            _ => self.number(v, field)?,
        };
        if !(lo..=hi).contains(&d) {
            return Err(self.err(
                &v.span(),
                field,
                format!(
                    "expected {what} from {lo} to {hi} deg, found {} deg",
                    round9(d)
                ),
            ));
        }
        Ok(d)
    }

    /// A point in the scene's length unit.
    pub fn point(&self, v: &S<Value>, field: &str) -> R<Point> {
        Ok(self
            .vec3(v, field)?
            .map(|x| Length::new::<length::meter>(x * self.unit_m)))
    }

    /// A length: a number in the scene's unit, or a quantity string.
    pub fn length(&self, v: &S<Value>, field: &str) -> R<Length> {
        match v.get_ref() {
            Value::String(_) => self.quantity::<Length>(v, field),
            _ => Ok(Length::new::<length::meter>(
                self.number(v, field)? * self.unit_m,
            )),
        }
    }

    /// A path relative to the scene file's folder.
    pub fn path(&self, p: &str) -> PathBuf {
        let p = Path::new(p);
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.dir.join(p)
        }
    }
}

/// Rounds away binary noise from unit conversions (29.999999999999996 → 30) for messages.
pub(crate) fn round9(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}

/// A word for a TOML value's type, for error messages.
pub(crate) fn kind(v: &Value) -> &'static str {
    match v {
        Value::String(_) => "a string",
        Value::Integer(_) => "an integer",
        Value::Float(_) => "a number",
        Value::Boolean(_) => "a boolean",
        Value::Datetime(_) => "a date",
        Value::Array(_) => "an array",
        Value::Table(_) => "a table",
    }
}

/// Converts a parsed file. `text` is the file's contents, for line numbers.
pub(crate) fn convert(raw: RawScene, file: &Path, text: &str) -> R<SceneDesc> {
    let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut cx = Cx {
        file,
        dir,
        src: SourceMap::new(text),
        unit_m: 1.0,
    };
    items::scene(&mut cx, raw)
}
