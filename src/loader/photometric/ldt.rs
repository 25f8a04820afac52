//! EULUMDAT (`.ldt`) photometric files: one value per line, in this order:
//!
//! | line | value |
//! | --- | --- |
//! | 1 | manufacturer |
//! | 2 | type indicator Ityp (0–3) |
//! | 3 | symmetry indicator Isym (0–4) |
//! | 4, 5 | number of C-planes Mc over 0–360°, their spacing Dc (deg) |
//! | 6, 7 | number of intensities per plane Ng, their spacing Dg (deg) |
//! | 8–12 | report number, luminaire name, number, file name, date/user |
//! | 13–21 | luminaire and luminous-area dimensions, mm |
//! | 22, 23 | downward flux fraction, light output ratio LORL (%) |
//! | 24 | conversion factor for the luminous intensities |
//! | 25 | tilt of the luminaire during measurement (deg) |
//! | 26 | number n of standard sets of lamps, then per set six lines: number of lamps, type, total luminous flux (lm), colour, colour rendering, wattage |
//! | then | 10 direct ratios, Mc C-angles, Ng γ-angles |
//! | then | intensities in cd/klm, Ng per stored C-plane |
//!
//! Stored planes (the standard's indices Mc1…Mc2 into the C-angles): Isym 0 all Mc; 1 one; 2
//! C0–C180 (Mc/2 + 1); 3 C270–C0–C90 (Mc/2 + 1, indices 3Mc/4 + 1 to 3Mc/4 + Mc/2 + 1 wrapping
//! past Mc), mirrored about the C90–C270 plane into C90–C180–C270 (C ↦ 540° − C) when read; 4
//! C0–C90 (Mc/4 + 1). Absolute intensity = value × the first lamp set's total flux / 1000 × the
//! conversion factor. Decimal commas are read as points.

use std::path::Path;

use super::{Photometry, Symmetry, intensity, short};
use crate::loader::{LoadError, Loc};

struct Lines<'a, 'p> {
    lines: Vec<&'a str>,
    next: usize,
    path: &'p Path,
}

impl Lines<'_, '_> {
    fn loc(&self, i: usize) -> Loc {
        Loc {
            line: i as u32 + 1,
            col: 1,
        }
    }

    fn err(&self, i: usize, what: &str, m: String) -> LoadError {
        LoadError::new(self.path, self.loc(i), what, m)
    }

    fn text(&mut self, what: &str) -> Result<(&str, usize), LoadError> {
        let i = self.next;
        match self.lines.get(i) {
            Some(l) => {
                self.next += 1;
                Ok((l.trim_end_matches('\r'), i))
            }
            None => Err(self.err(
                i.min(self.lines.len().saturating_sub(1)),
                what,
                "the file ends before this line (too few lines for the counts it declares?)".into(),
            )),
        }
    }

    fn number(&mut self, what: &str) -> Result<(f64, usize), LoadError> {
        let (t, i) = self.text(what)?;
        let t = t.trim().to_string();
        let s = t.replace(',', ".");
        match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((v, i)),
            _ => Err(self.err(
                i,
                what,
                format!("expected a number, found \"{}\"", short(&t)),
            )),
        }
    }

    fn count(&mut self, what: &str, lo: i64, hi: i64) -> Result<(i64, usize), LoadError> {
        let (v, i) = self.number(what)?;
        if v.fract() != 0.0 || v < lo as f64 || v > hi as f64 {
            return Err(self.err(
                i,
                what,
                format!("expected a whole number from {lo} to {hi}, found {v}"),
            ));
        }
        Ok((v as i64, i))
    }
}

/// Parses EULUMDAT text read from `path` (for error locations).
pub fn parse_ldt(text: &str, path: &Path) -> Result<Photometry, LoadError> {
    let mut l = Lines {
        lines: text.split('\n').collect(),
        next: 0,
        path,
    };
    l.text("manufacturer")?;
    l.count("type indicator Ityp", 0, 3)?;
    let (isym, _) = l.count("symmetry indicator Isym", 0, 4)?;
    let (mc, mc_line) = l.count("number of C-planes Mc", 1, 10_000)?;
    l.number("C-plane spacing Dc")?;
    let (ng, _) = l.count("number of intensities per C-plane Ng", 1, 10_000)?;
    l.number("intensity spacing Dg")?;
    for what in [
        "measurement report number",
        "luminaire name",
        "luminaire number",
        "file name",
        "date/user",
    ] {
        l.text(what)?;
    }
    for what in [
        "luminaire length",
        "luminaire width",
        "luminaire height",
        "luminous area length",
        "luminous area width",
        "luminous area height C0",
        "luminous area height C90",
        "luminous area height C180",
        "luminous area height C270",
        "downward flux fraction",
    ] {
        l.number(what)?;
    }
    let (lor, _) = l.number("light output ratio LORL")?;
    let (cfli, cf_line) = l.number("conversion factor")?;
    if !(cfli > 0.0) {
        return Err(l.err(
            cf_line,
            "conversion factor",
            format!("expected a positive factor, found {cfli}"),
        ));
    }
    l.number("measurement tilt")?;
    let flux = lamp_sets(&mut l)?;
    for k in 0..10 {
        l.number(&format!("direct ratio {}", k + 1))?;
    }
    let c_angles = angles(&mut l, mc, "C-angles", 360.0, false)?;
    let g_angles = angles(&mut l, ng, "gamma angles", 180.0, true)?;
    let (symmetry, lo, hi, horizontal) = stored_planes(isym, &c_angles);
    let ends_ok = isym <= 1 || (horizontal.first() == Some(&lo) && horizontal.last() == Some(&hi));
    if !ends_ok || (isym == 0 && c_angles[0] != 0.0) {
        return Err(l.err(
            mc_line,
            "C-angles",
            format!(
                "symmetry indicator {isym} stores the planes C{lo}–C{}, but the C-angles do not run from {lo} to {} deg",
                hi % 360.0,
                hi % 360.0
            ),
        ));
    }
    let factor = flux / 1000.0 * cfli;
    // at most one value per remaining line (no huge allocation from the header's counts)
    let mut candela =
        Vec::with_capacity((horizontal.len() * g_angles.len()).min(l.lines.len() - l.next));
    for h in 0..horizontal.len() {
        for g in 0..g_angles.len() {
            let what = format!("intensities[{h}][{g}]");
            let (v, i) = l.number(&what)?;
            candela.push(intensity(v, l.loc(i), &what, path)? * factor);
        }
    }
    // Isym 3: mirror the stored C270–C90 half about the C90–C270 plane into C90–C270
    let (horizontal, candela) = if isym == 3 {
        let ng = g_angles.len();
        let h: Vec<f64> = horizontal.iter().rev().map(|a| 540.0 - a).collect();
        let mut c = Vec::with_capacity(candela.len());
        for plane in (0..horizontal.len()).rev() {
            c.extend_from_slice(&candela[plane * ng..(plane + 1) * ng]);
        }
        (h, c)
    } else {
        (horizontal, candela)
    };
    if let Some((k, extra)) = l.lines[l.next..].iter().enumerate().find(|(_, t)| {
        !t.trim_matches(|c: char| c.is_whitespace() || c == '\u{1a}')
            .is_empty()
    }) {
        return Err(l.err(
            l.next + k,
            "",
            format!(
                "unexpected \"{}\" after the last intensity (do Mc, Ng and Isym match the data?)",
                short(extra.trim())
            ),
        ));
    }
    Ok(Photometry {
        file: path.to_path_buf(),
        vertical_deg: g_angles,
        horizontal_deg: horizontal,
        symmetry,
        candela,
        tilt: Vec::new(),
        lamp_lumens: Some(flux),
        light_output_ratio: Some(lor / 100.0),
    })
}

/// The symmetry of Isym, the range C`lo`–C`hi` of the planes it stores and their angles (deg),
/// C270…C450 (= C90) unwrapped for Isym 3.
fn stored_planes(isym: i64, c_angles: &[f64]) -> (Symmetry, f64, f64, Vec<f64>) {
    // the stored planes: those of the C-angle list inside the symmetry's range
    let (symmetry, lo, hi) = match isym {
        0 => (Symmetry::Full, 0.0, 360.0),
        1 => (Symmetry::Axial, 0.0, 0.0),
        2 => (Symmetry::Bilateral0To180, 0.0, 180.0),
        3 => (Symmetry::Bilateral90To270, 270.0, 450.0),
        _ => (Symmetry::Quadrant, 0.0, 90.0),
    };
    // the stored planes' angles, C270…C450 (= C90) unwrapped for Isym 3
    let horizontal: Vec<f64> = match isym {
        0 => c_angles.to_vec(),
        1 => vec![0.0],
        3 => {
            let mut v: Vec<f64> = c_angles.iter().copied().filter(|&a| a >= 270.0).collect();
            v.extend(c_angles.iter().filter(|&&a| a <= 90.0).map(|a| a + 360.0));
            v
        }
        _ => c_angles
            .iter()
            .copied()
            .filter(|a| (lo..=hi).contains(a))
            .collect(),
    };
    (symmetry, lo, hi, horizontal)
}

/// The lamp sets: the first set's total luminous flux, lm (the intensities are per 1000 lm of
/// it).
fn lamp_sets(l: &mut Lines<'_, '_>) -> Result<f64, LoadError> {
    let (sets, sets_line) = l.count("number of lamp sets", 1, 20)?;
    let mut flux = None;
    for s in 0..sets {
        l.number(&format!("lamp set {}: number of lamps", s + 1))?;
        l.text(&format!("lamp set {}: type", s + 1))?;
        let (f, fl) = l.number(&format!("lamp set {}: total luminous flux", s + 1))?;
        if s == 0 {
            if !(f > 0.0) {
                return Err(l.err(
                    fl,
                    "lamp set 1: total luminous flux",
                    format!("expected a positive flux in lm, found {f}"),
                ));
            }
            flux = Some(f);
        }
        for what in ["colour", "colour rendering", "wattage"] {
            l.text(&format!("lamp set {}: {what}", s + 1))?;
        }
    }
    let Some(flux) = flux else {
        return Err(l.err(sets_line, "number of lamp sets", "no lamp set".into()));
    };
    Ok(flux)
}

/// `n` ascending angles named `what`, in [0, max) (or [0, max] when `inclusive`), deg.
fn angles(
    l: &mut Lines<'_, '_>,
    n: i64,
    what: &str,
    max: f64,
    inclusive: bool,
) -> Result<Vec<f64>, LoadError> {
    let mut out: Vec<f64> = Vec::with_capacity(n as usize);
    for k in 0..n as usize {
        let name = format!("{what}[{k}]");
        let (a, i) = l.number(&name)?;
        let inside = a >= 0.0 && (a < max || (inclusive && a == max));
        if !inside || out.last().is_some_and(|&p| a <= p) {
            let close = if inclusive { ']' } else { ')' };
            return Err(l.err(
                i,
                &name,
                format!("expected ascending angles in [0, {max}{close} deg, found {a}"),
            ));
        }
        out.push(a);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A EULUMDAT file with quadrant symmetry (Isym 4), Mc = 4, Ng = 3.
    pub(crate) fn sample() -> String {
        let mut s = vec![
            "Test", "1", "4", "4", "90", "3", "45", "r", "n", "1", "t.ldt", "d", "100", "100",
            "10", "90", "90", "0", "0", "0", "0", "100", "80,5", "1", "0", "1", "2", "LED", "2000",
            "3000K", "80", "20",
        ];
        s.extend(["0.5"; 10]);
        s.extend(["0", "90", "180", "270"]);
        s.extend(["0", "45", "90"]);
        s.extend(["300", "200", "0", "300", "150", "0"]);
        s.join("\r\n") + "\r\n"
    }

    #[test]
    fn reads_a_quadrant_file() {
        let p = parse_ldt(&sample(), Path::new("a.ldt")).unwrap();
        assert_eq!(p.symmetry, Symmetry::Quadrant);
        assert_eq!(p.horizontal_deg, vec![0.0, 90.0]);
        assert_eq!(p.vertical_deg, vec![0.0, 45.0, 90.0]);
        // cd/klm × 2000 lm / 1000
        assert_eq!(p.candela, vec![600.0, 400.0, 0.0, 600.0, 300.0, 0.0]);
        assert_eq!(p.lamp_lumens, Some(2000.0));
        assert_eq!(p.light_output_ratio, Some(0.805));
    }

    #[test]
    fn isym_3_stores_c270_to_c90() {
        // Mc = 4: stored C270, C0, C90 with 1, 2, 3 cd/klm at both γ
        let s = sample()
            .replacen("\r\n4\r\n4\r\n90\r\n", "\r\n3\r\n4\r\n90\r\n", 1)
            .replace(
                "\r\n300\r\n200\r\n0\r\n300\r\n150\r\n0\r\n",
                "\r\n1\r\n1\r\n1\r\n2\r\n2\r\n2\r\n3\r\n3\r\n3\r\n",
            );
        let p = parse_ldt(&s, Path::new("a.ldt")).unwrap();
        assert_eq!(p.symmetry, Symmetry::Bilateral90To270);
        // C90 (3), C180 = mirror of C0 (2), C270 (1)
        assert_eq!(p.horizontal_deg, vec![90.0, 180.0, 270.0]);
        assert_eq!(p.candela, vec![6.0, 6.0, 6.0, 4.0, 4.0, 4.0, 2.0, 2.0, 2.0]);
    }

    #[test]
    fn errors_are_located() {
        let bad = sample().replace("\r\n150\r\n", "\r\n-150\r\n");
        let e = parse_ldt(&bad, Path::new("a.ldt")).unwrap_err().to_string();
        assert!(
            e.contains("a.ldt:54:1: intensities[1][1]: a luminous intensity cannot be negative"),
            "{e}"
        );
        let text = sample();
        let mut lines: Vec<&str> = text.split("\r\n").collect();
        lines.truncate(50);
        let e = parse_ldt(&lines.join("\r\n"), Path::new("a.ldt"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("intensities[0][1]: the file ends"), "{e}");
        let bad = sample().replacen("\r\n4\r\n4\r\n", "\r\n7\r\n4\r\n", 1);
        let e = parse_ldt(&bad, Path::new("a.ldt")).unwrap_err().to_string();
        assert!(e.contains("a.ldt:3:1: symmetry indicator Isym"), "{e}");
        let e = parse_ldt(&format!("{}5\r\n", sample()), Path::new("a.ldt"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("a.ldt:56:1: unexpected \"5\""), "{e}");
    }
}
