//! TOML parameters for a kind's own reader (see [`crate::params`]): an inline table
//! `{ type = "NAME", key = value, … }`, or a name with parameters kept in sibling keys of the
//! section (`filter = "gaussian"` with `filter_radius`). Dispatch by name through the kind's
//! registry, errors located at the key, and every key the reader did not ask for an error.

use std::ops::Range;

use toml::Value;

use super::{Cx, R};
use crate::params::{self, Dialect, Kind, ParamError, Params};

/// One parameter: its name as the reader asks for it, the field path for errors, its value
/// and where it stands.
pub(crate) struct Entry {
    pub name: String,
    pub field: String,
    pub value: Value,
    pub span: Range<usize>,
}

struct TomlParams<'e> {
    entries: &'e [Entry],
    asked: Vec<String>,
    read: Vec<bool>,
}

impl Params for TomlParams<'_> {
    fn dialect(&self) -> Dialect {
        Dialect::Toml
    }

    fn float(&mut self, name: &str) -> Result<Option<f64>, ParamError> {
        self.asked.push(name.to_string());
        let Some(i) = self.entries.iter().position(|e| e.name == name) else {
            return Ok(None);
        };
        self.read[i] = true;
        let x = match &self.entries[i].value {
            Value::Integer(i) => *i as f64,
            Value::Float(f) => *f,
            other => {
                return Err(ParamError::new(
                    name,
                    format!("expected a number, found {}", super::kind(other)),
                ));
            }
        };
        if !x.is_finite() {
            return Err(ParamError::new(
                name,
                format!("expected a finite number, found {x}"),
            ));
        }
        Ok(Some(x))
    }
}

/// Reads the kind of `registry` named `name` (at `name_span`, the field `field`; `what` names
/// the family in messages, e.g. "filter") from `entries`.
pub(crate) fn read_kind<D>(
    cx: &Cx<'_>,
    registry: &[Kind<D>],
    what: &str,
    field: &str,
    name: &str,
    name_span: &Range<usize>,
    entries: &[Entry],
) -> R<D> {
    let Some(kind) = params::find(registry, Dialect::Toml, name) else {
        return Err(cx.err(
            name_span,
            field,
            format!(
                "\"{name}\" is not a {what}{}; expected {}",
                params::did_you_mean(name, params::names(registry, Dialect::Toml).into_iter()),
                params::names(registry, Dialect::Toml).join(", ")
            ),
        ));
    };
    let mut p = TomlParams {
        entries,
        asked: Vec::new(),
        read: vec![false; entries.len()],
    };
    let d = (kind.read)(&mut p).map_err(|e| {
        let at = e
            .param
            .as_deref()
            .and_then(|n| entries.iter().find(|x| x.name == n));
        match at {
            Some(x) => cx.err(&x.span, &x.field, e.message),
            None => cx.err(name_span, field, e.message),
        }
    })?;
    if let Some(i) = p.read.iter().position(|r| !r) {
        let e = &entries[i];
        let mut asked: Vec<&str> = Vec::new();
        for a in &p.asked {
            if !asked.contains(&a.as_str()) {
                asked.push(a);
            }
        }
        let takes = if asked.is_empty() {
            "no parameters".to_string()
        } else {
            asked.join(", ")
        };
        return Err(cx.err(
            &e.span,
            &e.field,
            format!("does not apply to a {name} {what}, which takes {takes}"),
        ));
    }
    Ok(d)
}

/// The name and parameters of an inline table `{ type = "NAME", … }` at `span` (the field
/// `field`): entries carry the table's span, as toml gives no spans inside values.
pub(crate) fn inline_table<'t>(
    cx: &Cx<'_>,
    t: &'t toml::Table,
    span: &Range<usize>,
    field: &str,
) -> R<(&'t str, Vec<Entry>)> {
    let name = match t.get("type") {
        Some(Value::String(s)) => s.as_str(),
        Some(_) => return Err(cx.err(span, format!("{field}.type"), "expected a name")),
        None => return Err(cx.err(span, format!("{field}.type"), "missing; expected a name")),
    };
    let entries = t
        .iter()
        .filter(|(k, _)| *k != "type")
        .map(|(k, v)| Entry {
            name: k.clone(),
            field: format!("{field}.{k}"),
            value: v.clone(),
            span: span.clone(),
        })
        .collect();
    Ok((name, entries))
}
