//! The conversion context shared by every Mitsuba plugin family: the sources (for located
//! errors), `default` parameters and `$` substitution, ids and `<ref>`, file resolution, and
//! property readers (numbers, vectors, strings). Spectra are read in `spectra.rs`, transforms
//! in `transform.rs`; plugin files import this module, never each other's callers.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::plugins::{kinds, supported};
use super::xml::Element;
use crate::loader::error::{LoadError, SourceMap, line_starts, loc_in};
use crate::spectrum::named::{Named, lookup};
use crate::spectrum::{PiecewiseLinear, Spectrum};

pub(super) type R<T> = Result<T, LoadError>;

/// Mitsuba 3's `MI_CIE_D65_NORMALIZATION` (`include/mitsuba/core/spectrum.h`, 3.9.1): its
/// `d65` spectrum is the CIE D65 relative SPD (100 at 560 nm) times this, so that
/// ∫ D65 ȳ dλ / ∫ ȳ dλ = 1 on its own 5 nm tables (checked against `mi.load_dict({"type": "d65"})`
/// in tests/mitsuba_import.rs).
pub(super) const MITSUBA_D65_NORMALIZATION: f64 = 1.0 / 98.99741751876255;

/// Mitsuba's `d65` spectrum with `scale`: the CIE D65 table × scale × [`MITSUBA_D65_NORMALIZATION`],
/// in the emitter's own units (W·m⁻²·sr⁻¹·nm⁻¹ for radiance).
pub(super) fn mitsuba_d65(scale: f64) -> Arc<PiecewiseLinear> {
    match lookup("cie-d65") {
        Ok(Named::Curve {
            spectrum: Spectrum::Piecewise(t),
            ..
        }) => Arc::new(t.scaled((scale * MITSUBA_D65_NORMALIZATION) as f32)),
        // the table is embedded in the binary; its presence is tested in spectrum::named
        _ => unreachable!("cie-d65 is missing from the embedded data"), // ok: embedded, tested
    }
}

pub(super) struct Cx<'a> {
    /// (file, text) of the scene and every included file.
    pub(super) sources: Vec<(PathBuf, String)>,
    pub(super) defines: &'a HashMap<String, String>,
    pub(super) params: HashMap<String, String>,
    pub(super) ids: HashMap<String, Element>,
    /// Folders searched for relative file names, first to last: those of `<path>` elements,
    /// the latest first (Mitsuba prepends them to its file resolver), then the scene's folder.
    pub(super) search: Vec<PathBuf>,
    /// Things the user should know, once each (message, located line): e.g. a Mitsuba sampler
    /// replaced by spectrace's.
    pub(super) notes: std::cell::RefCell<Vec<(String, String)>>,
    /// BSDFs being converted, nested (through `ref`s too): bounds a reference cycle.
    pub(super) bsdf_depth: std::cell::Cell<u32>,
    /// Line starts of each source (by index into `sources`), found on its first location:
    /// every shape records one, and scanning from the file's start each time was quadratic.
    pub(super) line_starts: std::cell::RefCell<HashMap<usize, Vec<usize>>>,
    /// The property names each element was asked for, by (source, offset): what
    /// [`Cx::check_unreferenced`] holds its properties to.
    pub(super) queried: std::cell::RefCell<HashMap<(usize, usize), Vec<String>>>,
    /// The media read so far, each once, by the (source, offset) of its `<medium>` element.
    pub(super) media: std::cell::RefCell<Vec<((usize, usize), crate::loader::desc::MediumDesc)>>,
}

/// The tags of Mitsuba's plain properties (a nested object such as a texture or a transform is
/// found by other means, so it is not held to the names asked for).
const PROPERTY_TAGS: &[&str] = &[
    "float", "integer", "boolean", "string", "rgb", "spectrum", "point", "vector",
];

use crate::params::nearest;

impl Cx<'_> {
    pub(super) fn err(&self, e: &Element, msg: impl Into<String>) -> LoadError {
        let file = &self.sources[e.src].0;
        let field = match e.attr("name") {
            Some(n) => format!("<{} name=\"{n}\">", e.tag),
            None => format!("<{}>", e.tag),
        };
        LoadError::new(file, self.loc(e), field, msg)
    }

    pub(super) fn loc(&self, e: &Element) -> crate::loader::Loc {
        let text = &self.sources[e.src].1;
        let mut cache = self.line_starts.borrow_mut();
        let starts = cache.entry(e.src).or_insert_with(|| line_starts(text));
        loc_in(text, starts, e.pos)
    }

    /// A relative file name as Mitsuba's file resolver finds it: the first of the search
    /// folders where it exists, else the scene's folder (where the error will then name it).
    /// Absolute names are kept.
    pub(super) fn resolve_file(&self, name: &str) -> PathBuf {
        let p = Path::new(name);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        self.search
            .iter()
            .map(|d| d.join(p))
            .find(|c| c.exists())
            .unwrap_or_else(|| self.search.last().cloned().unwrap_or_default().join(p))
    }

    /// Records a note for the user, located at `e`, once per distinct message.
    pub(super) fn note(&self, e: &Element, msg: impl Into<String>) {
        let msg = msg.into();
        let mut notes = self.notes.borrow_mut();
        if notes.iter().any(|(m, _)| *m == msg) {
            return;
        }
        let (file, text) = &self.sources[e.src];
        let loc = SourceMap::new(text).loc(e.pos);
        let line = format!("{}:{}: {msg}", file.display(), loc.line);
        notes.push((msg, line));
    }

    pub(super) fn unsupported(&self, e: &Element, what: &str, kind: &str) -> LoadError {
        let same_kind = supported(what);
        // a suggestion only when it is close (Jaro–Winkler ≥ 0.85), and only of the same
        // kind; a plugin of another kind is named as such
        let near = nearest(kind, same_kind.iter().copied());
        let other = kinds().find(|k| *k != what && supported(k).contains(&kind));
        let supported = same_kind.join(", ");
        let msg = match (other, near) {
            (Some(k), _) => {
                let a = |w: &str| {
                    if w.starts_with(['a', 'e', 'i', 'o', 'u']) {
                        "an"
                    } else {
                        "a"
                    }
                };
                format!(
                    "\"{kind}\" is {} {k} type, not {} {what} type; write <{k} type=\"{kind}\"> (supported {what} types: {supported})",
                    a(k),
                    a(what)
                )
            }
            (None, Some(near)) => format!(
                "{what} type \"{kind}\" is not supported; did you mean \"{near}\"? (supported: {supported})"
            ),
            (None, None) => {
                format!("{what} type \"{kind}\" is not supported (supported: {supported})")
            }
        };
        self.err(e, msg)
    }

    /// `$name` substitution in every attribute value, recursively.
    pub(super) fn substitute(&self, e: &mut Element) -> R<()> {
        for (k, v) in e.attrs.iter_mut() {
            // one pass, left to right, as Mitsuba substitutes: an inserted value is not
            // scanned again (so a value that names itself cannot loop)
            let mut from = 0;
            while let Some(i) = v[from..].find('$').map(|i| i + from) {
                let rest = &v[i + 1..];
                let end = rest
                    .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .unwrap_or(rest.len());
                let name = &rest[..end];
                let Some(value) = self.defines.get(name).or_else(|| self.params.get(name)) else {
                    let (file, text) = &self.sources[e.src];
                    return Err(LoadError::new(
                        file,
                        SourceMap::new(text).loc(e.pos),
                        format!("<{}> {k}", e.tag),
                        format!(
                            "${name} is not defined: add <default name=\"{name}\" value=\"…\"/> or -D {name}=…"
                        ),
                    ));
                };
                from = i + value.len();
                *v = format!("{}{}{}", &v[..i], value, &rest[end..]);
            }
        }
        for c in &mut e.children {
            self.substitute(c)?;
        }
        Ok(())
    }

    pub(super) fn float(&self, e: &Element) -> R<f64> {
        let v = e
            .attr("value")
            .ok_or_else(|| self.err(e, "missing value"))?;
        let x: f64 = v
            .trim()
            .parse()
            .map_err(|_| self.err(e, format!("\"{v}\" is not a number")))?;
        if !x.is_finite() {
            return Err(self.err(e, format!("\"{v}\" is not finite")));
        }
        Ok(x)
    }

    pub(super) fn floats(&self, e: &Element, s: &str) -> R<Vec<f64>> {
        s.split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .map(|t| {
                t.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| self.err(e, format!("\"{t}\" is not a number")))
            })
            .collect()
    }

    /// A `point`/`vector` from x, y, z or value attributes.
    pub(super) fn vec3(&self, e: &Element) -> R<[f64; 3]> {
        if let Some(v) = e.attr("value") {
            let f = self.floats(e, v)?;
            return match f.len() {
                1 => Ok([f[0]; 3]),
                3 => Ok([f[0], f[1], f[2]]),
                _ => Err(self.err(e, format!("expected 1 or 3 numbers, found {}", f.len()))),
            };
        }
        let mut out = [0.0; 3];
        for (i, k) in ["x", "y", "z"].iter().enumerate() {
            if let Some(v) = e.attr(k) {
                out[i] = self.floats(e, v)?.first().copied().unwrap_or(0.0);
            }
        }
        Ok(out)
    }

    pub(super) fn child<'e>(&self, e: &'e Element, name: &str) -> Option<&'e Element> {
        let mut q = self.queried.borrow_mut();
        let names = q.entry((e.src, e.pos)).or_default();
        if !names.iter().any(|n| n == name) {
            names.push(name.to_string());
        }
        e.children.iter().find(|c| c.attr("name") == Some(name))
    }

    /// Mitsuba 3 refuses a plugin with a property it never reads ("unreferenced property"). For
    /// every element under `root` (and every element stored by id) whose reader asked for
    /// properties: a plain property (`<float name="…">` and the like) it did not ask for is an
    /// error when its name is close to one it did ask for (a misspelling: Jaro–Winkler ≥ 0.85,
    /// named with the likely intent), and otherwise a note that spectrace ignored it (a
    /// parameter Mitsuba reads and spectrace does not, such as an integrator's `hide_emitters`,
    /// which must not stop a scene Mitsuba renders).
    pub(super) fn check_unreferenced(&self, root: &Element) -> R<()> {
        let mut seen = std::collections::HashSet::new();
        let mut stack: Vec<&Element> = vec![root];
        stack.extend(self.ids.values());
        while let Some(e) = stack.pop() {
            if !seen.insert((e.src, e.pos)) {
                continue;
            }
            stack.extend(e.children.iter());
            let q = self.queried.borrow();
            let Some(asked) = q.get(&(e.src, e.pos)) else {
                continue;
            };
            for c in &e.children {
                let Some(name) = c.attr("name") else { continue };
                if !PROPERTY_TAGS.contains(&c.tag.as_str()) || asked.iter().any(|a| a == name) {
                    continue;
                }
                let kind = e
                    .attr("type")
                    .map(|t| format!(" \"{t}\""))
                    .unwrap_or_default();
                match nearest(name, asked.iter().map(String::as_str)) {
                    Some(a) => {
                        return Err(self.err(
                            c,
                            format!(
                                "unknown property \"{name}\" of <{}{kind}>; did you mean \"{a}\"? \
                                 (Mitsuba 3 refuses a property its plugin does not read)",
                                e.tag
                            ),
                        ));
                    }
                    None => self.note(
                        c,
                        format!(
                            "<{} name=\"{name}\"> of <{}{kind}> is not read by spectrace and has no effect",
                            c.tag, e.tag
                        ),
                    ),
                }
            }
        }
        Ok(())
    }

    pub(super) fn opt_float(&self, e: &Element, name: &str) -> R<Option<f64>> {
        self.child(e, name).map(|c| self.float(c)).transpose()
    }

    pub(super) fn string(&self, e: &Element, name: &str) -> Option<String> {
        self.child(e, name)
            .and_then(|c| c.attr("value"))
            .map(str::to_string)
    }

    pub(super) fn resolve<'e>(&'e self, e: &'e Element) -> R<&'e Element> {
        if e.tag == "ref" {
            let id = e.attr("id").ok_or_else(|| self.err(e, "missing id"))?;
            return self.ids.get(id).ok_or_else(|| {
                self.err(e, format!("refers to id \"{id}\", which is not defined"))
            });
        }
        Ok(e)
    }
}
