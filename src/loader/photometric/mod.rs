//! Photometric luminaire files: IES LM-63 (`ies.rs`) and EULUMDAT (`ldt.rs`) read into one
//! description of a type C intensity distribution in absolute candela.
//!
//! Type C photometry (the one both formats share for interior and road luminaires): the polar
//! axis is the luminaire's vertical axis, the vertical angle γ runs from 0° at nadir to 180° at
//! zenith, and the horizontal angle C (the C-plane) runs counterclockwise seen from above, from
//! C = 0° (along the luminaire's length in LM-63, its C0 plane in EULUMDAT) through C = 90°.
//! Errors name the file, the line and column of the offending value, and what it is.

mod ies;
mod ldt;

pub use ies::parse_ies;
pub use ldt::parse_ldt;

use std::path::{Path, PathBuf};

use super::{LoadError, Loc};

/// Which horizontal angles a file stores and how the rest of the circle follows from them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Symmetry {
    /// One plane: the same in every C-plane (LM-63 last angle 0°, EULUMDAT Isym 1).
    Axial,
    /// C = 0–90° stored, mirrored about the C0–C180 and C90–C270 planes (LM-63 last angle 90°,
    /// EULUMDAT Isym 4).
    Quadrant,
    /// C = 0–180° stored, mirrored about the C0–C180 plane (LM-63 last angle 180°, EULUMDAT
    /// Isym 2).
    Bilateral0To180,
    /// C = 90–270° stored, mirrored about the C90–C270 plane (LM-63 first 90°, last 270°;
    /// EULUMDAT Isym 3, which stores C270–C0–C90 and is mirrored into this half when read).
    Bilateral90To270,
    /// The whole circle is stored (LM-63 last angle 360°, EULUMDAT Isym 0); between the last
    /// angle and 360° the distribution wraps to the first.
    Full,
}

/// A luminaire's measured distribution, as read from its file (describe phase).
#[derive(Clone, Debug)]
pub struct Photometry {
    pub file: PathBuf,
    /// Vertical angles γ, degrees, strictly ascending in [0, 180]; 0° is nadir. Outside the
    /// first–last range the luminaire emits nothing.
    pub vertical_deg: Vec<f64>,
    /// Horizontal angles C, degrees, strictly ascending, as `symmetry` stores them.
    pub horizontal_deg: Vec<f64>,
    pub symmetry: Symmetry,
    /// Absolute luminous intensity, cd: `candela[h * vertical_deg.len() + v]` at horizontal
    /// angle `h` and vertical angle `v`, with every factor of the file applied (LM-63: candela
    /// multiplier × ballast factor [× the 1986/1991 ballast-lamp factor]; EULUMDAT: cd/klm × lamp
    /// flux / 1000 × the conversion factor).
    pub candela: Vec<f64>,
    /// LM-63 `TILT=INCLUDE` (or a tilt file): multiplying factors at tilt angles, (deg, factor),
    /// angles ascending. Empty for `TILT=NONE` and EULUMDAT.
    pub tilt: Vec<(f64, f64)>,
    /// What the file declares of its lamps: the rated luminous flux of all lamps, lm (None for
    /// absolute photometry, LM-63's lumens per lamp −1).
    pub lamp_lumens: Option<f64>,
    /// EULUMDAT's light output ratio of the luminaire, a fraction (LORL / 100).
    pub light_output_ratio: Option<f64>,
}

impl Photometry {
    /// The tilt factor at `tilt_deg` (linear between the table's angles, the end values beyond
    /// them); 1 without a table.
    pub fn tilt_factor(&self, tilt_deg: f64) -> f64 {
        let t = &self.tilt;
        match t.len() {
            0 => 1.0,
            _ if tilt_deg <= t[0].0 => t[0].1,
            _ if tilt_deg >= t[t.len() - 1].0 => t[t.len() - 1].1,
            _ => {
                let i = t.partition_point(|p| p.0 <= tilt_deg) - 1;
                let (a, b) = (t[i], t[i + 1]);
                a.1 + (b.1 - a.1) * (tilt_deg - a.0) / (b.0 - a.0)
            }
        }
    }
}

/// Reads a photometric file by its extension: `.ies` (LM-63) or `.ldt` (EULUMDAT), any case.
pub fn load(path: &Path) -> Result<Photometry, LoadError> {
    let whole = |m: String| LoadError::new(path, Loc::default(), "", m);
    let bytes = crate::files::read_bytes(path, crate::files::MAX_TEXT_BYTES)
        .map_err(|e| whole(format!("cannot read the photometric file: {e}")))?;
    // both formats are 8-bit text, often Latin-1 or Windows-1252: keep every byte as a char
    let text: String = bytes.iter().map(|&b| b as char).collect();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("ies") => parse_ies(&text, path),
        Some("ldt") => parse_ldt(&text, path),
        _ => Err(whole(
            "expected an IES LM-63 file (.ies) or a EULUMDAT file (.ldt)".into(),
        )),
    }
}

/// A whitespace- or comma-separated token with its place in the file.
#[derive(Clone, Copy, Debug)]
struct Token<'a> {
    text: &'a str,
    loc: Loc,
}

/// The tokens of `text` from byte `start` on, split at whitespace and commas, with 1-based
/// lines counted from `first_line`.
fn tokens(text: &str, first_line: u32) -> Vec<Token<'_>> {
    let mut out = Vec::new();
    for (i, line) in text.split('\n').enumerate() {
        let mut col = 0usize;
        // the character column, kept as the scan advances (not recounted per token)
        let mut chars = 0usize;
        let bytes = line.as_bytes();
        let is_sep = |b: u8| b.is_ascii_whitespace() || b == b',' || b == 0x1a;
        // a character starts at every byte that is not a UTF-8 continuation byte
        let starts = |s: &[u8]| s.iter().filter(|&&b| b & 0xc0 != 0x80).count();
        while col < bytes.len() {
            if is_sep(bytes[col]) {
                col += 1;
                chars += 1;
                continue;
            }
            let start = col;
            while col < bytes.len() && !is_sep(bytes[col]) {
                col += 1;
            }
            out.push(Token {
                text: &line[start..col],
                loc: Loc {
                    line: first_line + i as u32,
                    col: chars as u32 + 1,
                },
            });
            chars += starts(&bytes[start..col]);
        }
    }
    out
}

/// Reads numbers from a token list in order, naming what each is on failure.
struct Numbers<'a, 'p> {
    toks: Vec<Token<'a>>,
    next: usize,
    path: &'p Path,
    /// Where the data ended (for "the file ends before …" errors).
    end: Loc,
}

impl<'a, 'p> Numbers<'a, 'p> {
    fn err(&self, loc: Loc, what: &str, msg: String) -> LoadError {
        LoadError::new(self.path, loc, what, msg)
    }

    fn number(&mut self, what: &str) -> Result<(f64, Loc), LoadError> {
        let Some(t) = self.toks.get(self.next).copied() else {
            return Err(self.err(
                self.end,
                what,
                "the file ends before this value (too few numbers for the counts it declares?)"
                    .into(),
            ));
        };
        self.next += 1;
        match t.text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((v, t.loc)),
            _ => Err(self.err(
                t.loc,
                what,
                format!("expected a number, found \"{}\"", short(t.text)),
            )),
        }
    }

    /// A whole number in [lo, hi].
    fn count(&mut self, what: &str, lo: i64, hi: i64) -> Result<(i64, Loc), LoadError> {
        let (v, loc) = self.number(what)?;
        if v.fract() != 0.0 || v < lo as f64 || v > hi as f64 {
            return Err(self.err(
                loc,
                what,
                format!("expected a whole number from {lo} to {hi}, found {v}"),
            ));
        }
        Ok((v as i64, loc))
    }

    /// `n` angles, strictly ascending within [lo, hi] degrees.
    fn angles(&mut self, n: usize, what: &str, lo: f64, hi: f64) -> Result<Vec<f64>, LoadError> {
        let mut out: Vec<f64> = Vec::with_capacity(n);
        for i in 0..n {
            let field = format!("{what}[{i}]");
            let (a, loc) = self.number(&field)?;
            if !(lo..=hi).contains(&a) {
                return Err(self.err(
                    loc,
                    &field,
                    format!("expected an angle from {lo} to {hi} deg, found {a}"),
                ));
            }
            if let Some(&p) = out.last()
                && a <= p
            {
                return Err(self.err(
                    loc,
                    &field,
                    format!("angles must ascend, but {a} deg follows {p} deg"),
                ));
            }
            out.push(a);
        }
        Ok(out)
    }

    /// Fails if numbers remain (a count in the header disagrees with the data).
    fn finish(&self) -> Result<(), LoadError> {
        match self.toks.get(self.next) {
            None => Ok(()),
            Some(t) => Err(self.err(
                t.loc,
                "",
                format!(
                    "unexpected \"{}\" after the last intensity value (do the header's counts match the data?)",
                    short(t.text)
                ),
            )),
        }
    }
}

fn short(s: &str) -> String {
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s.to_string()
    }
}

/// Checks an intensity value: finite (already) and not negative.
fn intensity(v: f64, loc: Loc, what: &str, path: &Path) -> Result<f64, LoadError> {
    if v < 0.0 {
        return Err(LoadError::new(
            path,
            loc,
            what,
            format!("a luminous intensity cannot be negative, found {v}"),
        ));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_carry_lines_and_columns() {
        let t = tokens("1 2,3\n\n  4.5\r\n", 7);
        let v: Vec<_> = t.iter().map(|t| (t.text, t.loc.line, t.loc.col)).collect();
        assert_eq!(
            v,
            vec![("1", 7, 1), ("2", 7, 3), ("3", 7, 5), ("4.5", 9, 3)]
        );
    }

    #[test]
    fn tilt_factor_interpolates_and_clamps() {
        let p = Photometry {
            file: PathBuf::new(),
            vertical_deg: vec![],
            horizontal_deg: vec![],
            symmetry: Symmetry::Axial,
            candela: vec![],
            tilt: vec![(0.0, 1.0), (30.0, 0.9), (90.0, 0.6)],
            lamp_lumens: None,
            light_output_ratio: None,
        };
        assert_eq!(p.tilt_factor(-5.0), 1.0);
        assert!((p.tilt_factor(15.0) - 0.95).abs() < 1e-12);
        assert!((p.tilt_factor(60.0) - 0.75).abs() < 1e-12);
        assert_eq!(p.tilt_factor(120.0), 0.6);
    }
}
