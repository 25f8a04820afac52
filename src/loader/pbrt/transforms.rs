//! The directives that change pbrt-v4's current transformation, and the bare arguments of
//! directives (a quoted name, a fixed count of numbers).

use std::path::Path;

use glam::DMat4;

use super::Reader;
use super::lexer::{Tok, Token};
use super::params::R;
use super::shapes;
use crate::loader::{LoadError, Loc};

impl Reader {
    /// The next token as a string argument of directive `d`.
    pub(super) fn string_arg(
        toks: &[Token],
        i: &mut usize,
        file: &Path,
        d: &str,
        loc: Loc,
    ) -> R<String> {
        match toks.get(*i) {
            Some(Token {
                kind: Tok::Str(s), ..
            }) => {
                *i += 1;
                Ok(s.clone())
            }
            _ => Err(LoadError::new(
                file,
                loc,
                "",
                format!("{d} needs a quoted name"),
            )),
        }
    }

    /// `n` numbers after directive `d`, bare or in brackets.
    pub(super) fn numbers(
        toks: &[Token],
        i: &mut usize,
        file: &Path,
        d: &str,
        loc: Loc,
        n: usize,
    ) -> R<Vec<f64>> {
        let bracket = matches!(
            toks.get(*i),
            Some(Token {
                kind: Tok::Open,
                ..
            })
        );
        if bracket {
            *i += 1;
        }
        let mut v = Vec::new();
        while v.len() < n {
            match toks.get(*i) {
                Some(Token {
                    kind: Tok::Word(w),
                    loc: l,
                }) => {
                    v.push(w.parse::<f64>().map_err(|_| {
                        LoadError::new(file, *l, "", format!("{d}: \"{w}\" is not a number"))
                    })?);
                    *i += 1;
                }
                _ => {
                    return Err(LoadError::new(
                        file,
                        loc,
                        "",
                        format!("{d} takes {n} numbers, found {}", v.len()),
                    ));
                }
            }
        }
        if bracket {
            match toks.get(*i) {
                Some(Token {
                    kind: Tok::Close, ..
                }) => *i += 1,
                _ => return Err(LoadError::new(file, loc, "", format!("{d}: missing ]"))),
            }
        }
        Ok(v)
    }

    /// pbrt's CTMs times `m` (post-multiplied: `m` acts first, in object space), those
    /// `ActiveTransform` made active.
    pub(super) fn concat(&mut self, m: DMat4) {
        self.set_ctm(|c| c * m);
    }

    /// The active CTMs replaced by `f` of themselves.
    pub(super) fn set_ctm(&mut self, f: impl Fn(DMat4) -> DMat4) {
        let s = &mut self.state;
        if s.active[0] {
            s.ctm = f(s.ctm);
        }
        if s.active[1] {
            s.ctm_end = f(s.ctm_end);
        }
    }

    /// Err if directive `d` uses the CTM while the CTMs at the shutter's opening and close
    /// differ (motion blur, which spectrace does not render).
    pub(super) fn check_static(&self, d: &str, file: &Path, loc: Loc) -> R<()> {
        let consumes = [
            "Shape",
            "LightSource",
            "Camera",
            "ObjectInstance",
            "Texture",
            "MakeNamedMedium",
        ];
        if consumes.contains(&d) && self.state.ctm != self.state.ctm_end {
            return Err(LoadError::new(
                file,
                loc,
                "",
                format!(
                    "{d} under an animated transformation (ActiveTransform: the transformations at the shutter's opening and close differ) is not read yet: spectrace renders no motion blur"
                ),
            ));
        }
        Ok(())
    }

    /// The directives that change the current transformation.
    pub(super) fn transform(
        &mut self,
        d: &str,
        toks: &[Token],
        i: &mut usize,
        file: &Path,
        loc: Loc,
    ) -> R<()> {
        let err = |m: String| LoadError::new(file, loc, "", m);
        let nums = |i: &mut usize, n: usize| Self::numbers(toks, i, file, d, loc, n);
        match d {
            "Identity" => self.set_ctm(|_| DMat4::IDENTITY),
            "Translate" => {
                let v = nums(i, 3)?;
                self.concat(DMat4::from_translation([v[0], v[1], v[2]].into()));
            }
            "Scale" => {
                let v = nums(i, 3)?;
                self.concat(DMat4::from_scale([v[0], v[1], v[2]].into()));
            }
            "Rotate" => {
                let v = nums(i, 4)?;
                let axis = glam::DVec3::new(v[1], v[2], v[3]);
                let Some(axis) = axis.try_normalize() else {
                    return Err(err("Rotate: the axis is zero".into()));
                };
                self.concat(DMat4::from_axis_angle(axis, v[0].to_radians()));
            }
            "LookAt" => {
                let v = nums(i, 9)?;
                let m = shapes::look_at(&v).map_err(err)?;
                self.concat(m);
            }
            "Transform" | "ConcatTransform" => {
                let v = nums(i, 16)?;
                // pbrt lists the matrix column by column (its `Transpose` of the row-major read)
                let m = DMat4::from_cols_slice(&v);
                if d == "Transform" {
                    self.set_ctm(|_| m);
                } else {
                    self.concat(m);
                }
            }
            "CoordinateSystem" => {
                let n = Self::string_arg(toks, i, file, d, loc)?;
                let s = &self.state;
                self.coordinate_systems.insert(n, [s.ctm, s.ctm_end]);
            }
            "CoordSysTransform" => {
                let n = Self::string_arg(toks, i, file, d, loc)?;
                match self.coordinate_systems.get(&n) {
                    // both, whatever is active (pbrt-v4's `CoordSysTransform`)
                    Some(&[a, b]) => (self.state.ctm, self.state.ctm_end) = (a, b),
                    None => return Err(err(format!("no coordinate system named \"{n}\""))),
                }
            }
            // the shutter times of the two CTMs: only motion blur would use them
            "TransformTimes" => {
                nums(i, 2)?;
            }
            "ActiveTransform" => {
                let which = match toks.get(*i) {
                    Some(Token {
                        kind: Tok::Word(w), ..
                    }) => w.clone(),
                    _ => String::new(),
                };
                self.state.active = match which.as_str() {
                    "StartTime" => [true, false],
                    "EndTime" => [false, true],
                    "All" => [true, true],
                    _ => {
                        return Err(err("ActiveTransform takes StartTime, EndTime or All".into()));
                    }
                };
                *i += 1;
            }
            _ => unreachable!("only transformation directives are passed here"),
        }
        Ok(())
    }
}
