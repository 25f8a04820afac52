//! pbrt-v4 parameter lists (`"type name" value` or `"type name" [values]`,
//! `src/pbrt/paramdict.cpp`): each parameter remembers whether the directive read it, so that
//! one it did not read is an error naming it, as pbrt-v4 reports ("parameter … unused").

use std::cell::Cell;
use std::path::{Path, PathBuf};

use super::lexer::{Tok, Token};
use crate::loader::{LoadError, Loc};

pub(super) type R<T> = Result<T, LoadError>;

/// The types pbrt-v4 declares parameters with (`color` is its older name for `rgb`, `point`,
/// `vector` and `normal` for the 3D ones).
const TYPES: &[&str] = &[
    "integer",
    "float",
    "point2",
    "vector2",
    "point3",
    "vector3",
    "normal3",
    "normal",
    "point",
    "vector",
    "bool",
    "string",
    "texture",
    "spectrum",
    "rgb",
    "color",
    "blackbody",
];

/// One parameter: its type, name, values and location.
#[derive(Clone, Debug)]
pub(super) struct Param {
    pub ty: String,
    pub name: String,
    pub nums: Vec<f64>,
    pub strs: Vec<String>,
    pub loc: Loc,
    used: Cell<bool>,
}

/// A directive's parameters.
#[derive(Debug)]
pub(super) struct Params {
    pub list: Vec<Param>,
    pub file: PathBuf,
}

impl Params {
    /// Reads parameters from `toks` starting at `*i`, while the next token is a quoted
    /// declaration; `*i` ends on the first token after them.
    pub fn parse(toks: &[Token], i: &mut usize, file: &Path) -> R<Params> {
        let err = |loc: Loc, m: String| LoadError::new(file, loc, "", m);
        let mut list = Vec::new();
        while let Some(Token {
            kind: Tok::Str(decl),
            loc,
        }) = toks.get(*i)
        {
            let mut words = decl.split_whitespace();
            let (Some(ty), Some(name), None) = (words.next(), words.next(), words.next()) else {
                // a quoted string that is not "type name" ends the list (it is the next
                // directive's argument only in malformed files)
                return Err(err(
                    *loc,
                    format!("expected a parameter declaration \"type name\", found \"{decl}\""),
                ));
            };
            if !TYPES.contains(&ty) {
                return Err(err(
                    *loc,
                    format!(
                        "unknown parameter type \"{ty}\" (pbrt-v4's are {})",
                        TYPES.join(", ")
                    ),
                ));
            }
            *i += 1;
            let (mut nums, mut strs) = (Vec::new(), Vec::new());
            let mut value = |t: &Token| -> R<()> {
                match &t.kind {
                    Tok::Str(s) => strs.push(s.clone()),
                    Tok::Word(w) if w == "true" || w == "false" => strs.push(w.clone()),
                    Tok::Word(w) => nums.push(w.parse::<f64>().map_err(|_| {
                        err(
                            t.loc,
                            format!("\"{w}\" is not a number (parameter \"{name}\")"),
                        )
                    })?),
                    _ => return Err(err(t.loc, "unexpected bracket".into())),
                }
                Ok(())
            };
            match toks.get(*i) {
                Some(Token {
                    kind: Tok::Open, ..
                }) => {
                    *i += 1;
                    loop {
                        match toks.get(*i) {
                            Some(Token {
                                kind: Tok::Close, ..
                            }) => {
                                *i += 1;
                                break;
                            }
                            Some(t) => {
                                value(t)?;
                                *i += 1;
                            }
                            None => {
                                return Err(err(*loc, format!("\"{name}\": missing ]")));
                            }
                        }
                    }
                }
                Some(
                    t @ Token {
                        kind: Tok::Word(_) | Tok::Str(_),
                        ..
                    },
                ) => {
                    value(t)?;
                    *i += 1;
                }
                _ => return Err(err(*loc, format!("parameter \"{name}\" has no value"))),
            }
            if !nums.is_empty() && !strs.is_empty() {
                return Err(err(*loc, format!("\"{name}\" mixes numbers and strings")));
            }
            list.push(Param {
                ty: ty.to_string(),
                name: name.to_string(),
                nums,
                strs,
                loc: *loc,
                used: Cell::new(false),
            });
        }
        Ok(Params {
            list,
            file: file.to_path_buf(),
        })
    }

    /// An error at `loc` in this list's file.
    pub fn err(&self, loc: Loc, m: impl Into<String>) -> LoadError {
        LoadError::new(&self.file, loc, "", m)
    }

    /// The parameter `name` (marked read), if given.
    /// These parameters followed by `defaults` (an `Attribute` directive's, the latest first),
    /// which a lookup finds only when the directive does not give the name, and which are
    /// never reported unused (pbrt-v4's `mayBeUnused`).
    pub fn with_defaults(mut self, defaults: &[Param]) -> Params {
        for d in defaults.iter().rev() {
            let d = d.clone();
            d.used.set(true);
            self.list.push(d);
        }
        self
    }

    pub fn get(&self, name: &str) -> Option<&Param> {
        let p = self.list.iter().find(|p| p.name == name)?;
        p.used.set(true);
        Some(p)
    }

    /// Numbers of `name` declared with one of `types`; None when absent.
    pub fn nums(&self, name: &str, types: &[&str]) -> R<Option<&[f64]>> {
        let Some(p) = self.get(name) else {
            return Ok(None);
        };
        if !types.contains(&p.ty.as_str()) {
            return Err(self.err(
                p.loc,
                format!(
                    "\"{name}\" is declared \"{}\"; expected {}",
                    p.ty,
                    types.join(" or ")
                ),
            ));
        }
        if p.nums.is_empty() {
            return Err(self.err(p.loc, format!("\"{name}\" needs numbers")));
        }
        Ok(Some(&p.nums))
    }

    /// A single float (`float`), or `default`.
    pub fn float(&self, name: &str, default: f64) -> R<f64> {
        self.one(name, &["float"]).map(|v| v.unwrap_or(default))
    }

    /// A single integer (`integer`), or `default`.
    pub fn int(&self, name: &str, default: i64) -> R<i64> {
        match self.one(name, &["integer"])? {
            None => Ok(default),
            Some(v) if v.fract() == 0.0 => Ok(v as i64),
            Some(v) => Err(self.err(
                self.loc_of(name),
                format!("\"{name}\" must be a whole number, not {v}"),
            )),
        }
    }

    fn one(&self, name: &str, types: &[&str]) -> R<Option<f64>> {
        match self.nums(name, types)? {
            None => Ok(None),
            Some([v]) => Ok(Some(*v)),
            Some(v) => Err(self.err(
                self.loc_of(name),
                format!("\"{name}\" takes one value, found {}", v.len()),
            )),
        }
    }

    /// A 3-vector (`point3`, `vector3`, `normal3` and their old names), or `default`.
    pub fn vec3(&self, name: &str, default: [f64; 3]) -> R<[f64; 3]> {
        match self.nums(
            name,
            &["point3", "vector3", "normal3", "point", "vector", "normal"],
        )? {
            None => Ok(default),
            Some(&[x, y, z]) => Ok([x, y, z]),
            Some(v) => Err(self.err(
                self.loc_of(name),
                format!("\"{name}\" takes 3 numbers, found {}", v.len()),
            )),
        }
    }

    /// A single string (`string`, or `texture` when `texture` is set), or None.
    pub fn string(&self, name: &str) -> R<Option<String>> {
        let Some(p) = self.get(name) else {
            return Ok(None);
        };
        if p.ty != "string" && p.ty != "texture" {
            return Err(self.err(
                p.loc,
                format!("\"{name}\" is declared \"{}\"; expected string", p.ty),
            ));
        }
        match &p.strs[..] {
            [s] => Ok(Some(s.clone())),
            _ => Err(self.err(p.loc, format!("\"{name}\" takes one string"))),
        }
    }

    /// A single `bool`, or `default`.
    pub fn bool(&self, name: &str, default: bool) -> R<bool> {
        let Some(p) = self.get(name) else {
            return Ok(default);
        };
        match (p.ty.as_str(), &p.strs[..]) {
            ("bool", [s]) if s == "true" => Ok(true),
            ("bool", [s]) if s == "false" => Ok(false),
            _ => Err(self.err(p.loc, format!("\"{name}\" must be a bool, true or false"))),
        }
    }

    /// Where `name` was given (the directive's own location when absent: never used so).
    pub fn loc_of(&self, name: &str) -> Loc {
        self.list
            .iter()
            .find(|p| p.name == name)
            .map_or(Loc { line: 0, col: 0 }, |p| p.loc)
    }

    /// An error for the first parameter no reader asked for (pbrt-v4: "parameter unused").
    pub fn check_unused(&self, what: &str) -> R<()> {
        match self.list.iter().find(|p| !p.used.get()) {
            None => Ok(()),
            Some(p) => Err(self.err(
                p.loc,
                format!(
                    "\"{} {}\": parameter unused by {what} (a misspelt name, or one spectrace does not read)",
                    p.ty, p.name
                ),
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::lexer::tokenize;
    use super::*;

    fn params(s: &str) -> Params {
        let toks = tokenize(s, Path::new("t.pbrt")).unwrap();
        let mut i = 0;
        let p = Params::parse(&toks, &mut i, Path::new("t.pbrt")).unwrap();
        assert_eq!(i, toks.len());
        p
    }

    #[test]
    fn typed_values_and_unused() {
        let p = params(
            "\"float radius\" 2 \"point3 from\" [0 1 2] \"string name\" \"a\" \"bool b\" true \"integer n\" [3]",
        );
        assert_eq!(p.float("radius", 1.0).unwrap(), 2.0);
        assert_eq!(p.vec3("from", [0.0; 3]).unwrap(), [0.0, 1.0, 2.0]);
        assert_eq!(p.string("name").unwrap().as_deref(), Some("a"));
        assert!(p.bool("b", false).unwrap());
        assert!(
            p.check_unused("x")
                .unwrap_err()
                .to_string()
                .contains("integer n")
        );
        assert_eq!(p.int("n", 0).unwrap(), 3);
        p.check_unused("x").unwrap();
        assert!(p.float("n", 0.0).is_err(), "an integer read as a float");
    }

    #[test]
    fn bad_declarations() {
        let toks = tokenize("\"flaot r\" 1", Path::new("t.pbrt")).unwrap();
        let e = Params::parse(&toks, &mut 0, Path::new("t.pbrt")).unwrap_err();
        assert!(
            e.to_string().contains("unknown parameter type \"flaot\""),
            "{e}"
        );
        let toks = tokenize("\"float r\" [1 2", Path::new("t.pbrt")).unwrap();
        assert!(Params::parse(&toks, &mut 0, Path::new("t.pbrt")).is_err());
    }
}
