//! IES LM-63 photometric files (ANSI/IES LM-63-1986, -1991, -1995, -2002 and -2019).
//!
//! Layout: an optional first line naming the format (`IESNA:LM-63-1995`, `IESNA:LM-63-2002`,
//! `IES:LM-63-2019`; none for 1986), keyword lines, then `TILT=NONE`, `TILT=INCLUDE` (the tilt
//! data follows) or `TILT=<file>` (the tilt data is in that file, beside this one). After it,
//! numbers separated by blanks, commas or line breaks, anywhere on their lines:
//!
//! 1. number of lamps, lumens per lamp (−1: absolute photometry), candela multiplier, number of
//!    vertical angles, number of horizontal angles, photometric type (1 = C, 2 = B, 3 = A),
//!    units type (1 feet, 2 metres), luminous opening width, length, height;
//! 2. ballast factor, the ballast-lamp photometric factor (1986 and 1991; "future use" in 1995
//!    and 2002, the file generation type in 2019, neither of which scales the data, as
//!    Radiance's `ies2rad` reads them), input watts;
//! 3. the vertical angles, the horizontal angles, then the candela values, all vertical angles
//!    of the first horizontal angle, then of the next, and so on.
//!
//! Tilt data: lamp-to-luminaire geometry (1–3), the number of pairs, the angles, the
//! multiplying factors. Absolute intensity = value × candela multiplier × ballast factor
//! (× the ballast-lamp factor for 1986 and 1991 files), as LM-63 defines the values: candela
//! of the luminaire with its rated lamps.
//!
//! Only type C photometry is read; types A and B (floodlights, automotive) are refused by name.

use std::path::Path;

use super::{Numbers, Photometry, Symmetry, intensity, tokens};
use crate::loader::{LoadError, Loc};

/// Parses LM-63 text read from `path` (for error locations and a tilt file's folder).
pub fn parse_ies(text: &str, path: &Path) -> Result<Photometry, LoadError> {
    let lines: Vec<&str> = text.split('\n').collect();
    // a UTF-8 byte-order mark, read byte by byte, is "ï»¿"
    let first = lines
        .first()
        .map(|l| l.trim_start_matches(['\u{feff}', 'ï', '»', '¿']).trim())
        .unwrap_or("");
    // the 1986 and 1991 formats' second line carries a ballast-lamp factor that scales the
    // data; from 1995 on it is "future use" (1995, 2002) or the file generation type (2019)
    let modern = first.starts_with("IESNA:LM-63-") || first.starts_with("IES:LM-63-");
    let Some(tilt_line) = lines
        .iter()
        .position(|l| l.trim_start().starts_with("TILT="))
    else {
        return Err(LoadError::new(
            path,
            Loc { line: 1, col: 1 },
            "TILT",
            "no TILT= line: this is not an IES LM-63 file",
        ));
    };
    let tilt_text = lines[tilt_line].trim().trim_start_matches("TILT=").trim();
    let rest = lines[tilt_line + 1..].join("\n");
    let end = Loc {
        line: lines.len() as u32,
        col: 1,
    };
    let mut n = Numbers {
        toks: tokens(&rest, tilt_line as u32 + 2),
        next: 0,
        path,
        end,
    };
    let tilt = match tilt_text {
        "NONE" => Vec::new(),
        "INCLUDE" => tilt_data(&mut n)?,
        file => tilt_file(path, file, tilt_line)?,
    };

    let Header {
        lamps,
        lumens_per_lamp,
        multiplier,
        nv,
        nh,
        ballast,
        second,
    } = header(&mut n, path, modern)?;
    let (nv, nh) = (nv as usize, nh as usize);
    let vertical_deg = n.angles(nv, "vertical angles", 0.0, 180.0)?;
    let h_loc = n.toks.get(n.next).map_or(end, |t| t.loc);
    let horizontal_deg = n.angles(nh, "horizontal angles", 0.0, 360.0)?;
    let symmetry = symmetry(&horizontal_deg)
        .map_err(|m| LoadError::new(path, h_loc, "horizontal angles", m))?;
    let factor = multiplier * ballast * if modern { 1.0 } else { second };
    // the table cannot hold more values than the file has numbers left (no huge allocation
    // from a header's counts)
    let left = n.toks.len() - n.next;
    if nv * nh > left {
        return Err(LoadError::new(
            path,
            h_loc,
            "candela values",
            format!(
                "the header declares {nv} × {nh} candela values, but only {left} numbers follow"
            ),
        ));
    }
    let mut candela = Vec::with_capacity(nv * nh);
    for h in 0..nh {
        for v in 0..nv {
            let what = format!("candela[{h}][{v}]");
            let (x, loc) = n.number(&what)?;
            candela.push(intensity(x, loc, &what, path)? * factor);
        }
    }
    n.finish()?;
    Ok(Photometry {
        file: path.to_path_buf(),
        vertical_deg,
        horizontal_deg,
        symmetry,
        candela,
        tilt,
        lamp_lumens: (lumens_per_lamp > 0.0).then_some(lumens_per_lamp * lamps as f64),
        light_output_ratio: None,
    })
}

/// The numbers between the tilt data and the angles.
struct Header {
    lamps: i64,
    /// lm, or −1 for absolute photometry.
    lumens_per_lamp: f64,
    multiplier: f64,
    nv: i64,
    nh: i64,
    ballast: f64,
    /// The ballast-lamp photometric factor (1986 and 1991 files; later files' field is unused).
    second: f64,
}

/// Reads and checks the header after the tilt data (type C photometry only).
fn header(n: &mut Numbers<'_, '_>, path: &Path, modern: bool) -> Result<Header, LoadError> {
    let (lamps, _) = n.count("number of lamps", 0, 1_000_000)?;
    let (lumens_per_lamp, lum_loc) = n.number("lumens per lamp")?;
    if !(lumens_per_lamp > 0.0 || lumens_per_lamp == -1.0) {
        return Err(LoadError::new(
            path,
            lum_loc,
            "lumens per lamp",
            format!(
                "expected a positive flux, or −1 for absolute photometry, found {lumens_per_lamp}"
            ),
        ));
    }
    let (multiplier, m_loc) = n.number("candela multiplier")?;
    if !(multiplier > 0.0) {
        return Err(LoadError::new(
            path,
            m_loc,
            "candela multiplier",
            format!("expected a positive multiplier, found {multiplier}"),
        ));
    }
    let (nv, _) = n.count("number of vertical angles", 1, 10_000)?;
    let (nh, _) = n.count("number of horizontal angles", 1, 10_000)?;
    let (ptype, p_loc) = n.count("photometric type", 1, 3)?;
    if ptype != 1 {
        let name = if ptype == 2 { "B" } else { "A" };
        return Err(LoadError::new(
            path,
            p_loc,
            "photometric type",
            format!(
                "type {name} photometry is not supported; spectrace reads type C (1), the type of interior and road luminaires"
            ),
        ));
    }
    let _units = n.count("units type", 1, 2)?;
    for what in ["width", "length", "height"] {
        n.number(&format!("luminous opening {what}"))?;
    }
    let (ballast, b_loc) = n.number("ballast factor")?;
    if !(ballast > 0.0) {
        return Err(LoadError::new(
            path,
            b_loc,
            "ballast factor",
            format!("expected a positive factor, found {ballast}"),
        ));
    }
    let (second, s_loc) = n.number("ballast-lamp photometric factor")?;
    if !modern && !(second > 0.0) {
        return Err(LoadError::new(
            path,
            s_loc,
            "ballast-lamp photometric factor",
            format!("expected a positive factor, found {second}"),
        ));
    }
    n.number("input watts")?;
    Ok(Header {
        lamps,
        lumens_per_lamp,
        multiplier,
        nv,
        nh,
        ballast,
        second,
    })
}

/// The tilt data of `TILT=file` (on line `tilt_line` + 1 of `path`), read from `file` beside
/// the photometric file.
fn tilt_file(path: &Path, file: &str, tilt_line: usize) -> Result<Vec<(f64, f64)>, LoadError> {
    let tilt_path = path.parent().unwrap_or(Path::new(".")).join(file);
    let at = Loc {
        line: tilt_line as u32 + 1,
        col: 1,
    };
    let bytes =
        crate::files::read_bytes(&tilt_path, crate::files::MAX_TEXT_BYTES).map_err(|e| {
            LoadError::new(
                path,
                at,
                "TILT",
                format!("cannot read the tilt file {}: {e}", tilt_path.display()),
            )
        })?;
    let t: String = bytes.iter().map(|&b| b as char).collect();
    let mut tn = Numbers {
        end: Loc {
            line: t.split('\n').count() as u32,
            col: 1,
        },
        toks: tokens(&t, 1),
        next: 0,
        path: &tilt_path,
    };
    let data = tilt_data(&mut tn)?;
    tn.finish()?;
    Ok(data)
}

/// Tilt data: geometry, pair count, angles, factors.
fn tilt_data(n: &mut Numbers<'_, '_>) -> Result<Vec<(f64, f64)>, LoadError> {
    n.count("lamp-to-luminaire geometry", 1, 3)?;
    let (pairs, _) = n.count("number of tilt angles", 1, 100_000)?;
    let angles = n.angles(pairs as usize, "tilt angles", 0.0, 180.0)?;
    let mut out = Vec::with_capacity(angles.len());
    for (i, a) in angles.into_iter().enumerate() {
        let what = format!("tilt factors[{i}]");
        let (f, loc) = n.number(&what)?;
        if f < 0.0 {
            return Err(n.err(
                loc,
                &what,
                format!("a tilt factor cannot be negative, found {f}"),
            ));
        }
        out.push((a, f));
    }
    Ok(out)
}

/// The symmetry LM-63 type C horizontal angles imply: last 0° (one plane), 90° (quadrants),
/// 180° (bilateral about C0–C180), first 90° and last 270° (bilateral about C90–C270), last
/// 360° (none).
fn symmetry(h: &[f64]) -> Result<Symmetry, String> {
    let (first, last) = (h[0], h[h.len() - 1]);
    Ok(match (first, last) {
        (0.0, 0.0) => Symmetry::Axial,
        (0.0, 90.0) => Symmetry::Quadrant,
        (0.0, 180.0) => Symmetry::Bilateral0To180,
        (90.0, 270.0) => Symmetry::Bilateral90To270,
        (0.0, 360.0) => Symmetry::Full,
        _ => {
            return Err(format!(
                "type C horizontal angles from {first} to {last} deg: LM-63 allows 0 (one plane), 0–90, 0–180, 90–270 or 0–360 deg"
            ));
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = "IESNA:LM-63-2002\n[TEST] x\n[MANUFAC] y\nTILT=NONE\n\
        1 1000 2 3 2 1 2 0.1 0.1 0\n0.5 1 40\n0 45 90\n0 90\n100 80 0\n90 70 0\n";

    #[test]
    fn reads_a_2002_file() {
        let p = parse_ies(FILE, Path::new("a.ies")).unwrap();
        assert_eq!(p.vertical_deg, vec![0.0, 45.0, 90.0]);
        assert_eq!(p.horizontal_deg, vec![0.0, 90.0]);
        assert_eq!(p.symmetry, Symmetry::Quadrant);
        // multiplier 2 × ballast 0.5; the 2002 "future use" field does not scale
        assert_eq!(p.candela, vec![100.0, 80.0, 0.0, 90.0, 70.0, 0.0]);
        assert_eq!(p.lamp_lumens, Some(1000.0));
    }

    #[test]
    fn the_1991_ballast_lamp_factor_scales() {
        let f = FILE
            .replace("IESNA:LM-63-2002", "IESNA91")
            .replace("0.5 1 40", "1 0.5 40");
        let p = parse_ies(&f, Path::new("a.ies")).unwrap();
        assert_eq!(p.candela[0], 100.0);
    }

    /// A UTF-8 byte-order mark (read as Latin-1) does not hide the version: the 2002 file's
    /// "future use" field still does not scale the data.
    #[test]
    fn a_byte_order_mark_keeps_the_version() {
        let f = format!("ï»¿{}", FILE.replace("0.5 1 40", "0.5 1.1 40"));
        let p = parse_ies(&f, Path::new("a.ies")).unwrap();
        assert_eq!(p.candela[0], 100.0);
    }

    #[test]
    fn tilt_include_is_read() {
        let f = FILE.replace("TILT=NONE\n", "TILT=INCLUDE\n1\n3\n0 45 90\n1 0.9\n0.5\n");
        let p = parse_ies(&f, Path::new("a.ies")).unwrap();
        assert_eq!(p.tilt, vec![(0.0, 1.0), (45.0, 0.9), (90.0, 0.5)]);
    }

    #[test]
    fn errors_are_located() {
        let f = FILE.replace("100 80 0", "100 -80 0");
        let e = parse_ies(&f, Path::new("a.ies")).unwrap_err().to_string();
        assert!(e.contains("a.ies:9:5: candela[0][1]"), "{e}");
        let f = FILE.replace("1 1000 2 3 2 1 2", "1 1000 2 3 2 2 2");
        let e = parse_ies(&f, Path::new("a.ies")).unwrap_err().to_string();
        assert!(e.contains("a.ies:5:14: photometric type: type B"), "{e}");
        let f = FILE.replace("0 45 90\n", "0 90 45\n");
        let e = parse_ies(&f, Path::new("a.ies")).unwrap_err().to_string();
        assert!(
            e.contains("7:6: vertical angles[2]: angles must ascend"),
            "{e}"
        );
        let f = FILE.replace("90 70 0\n", "90 70\n");
        let e = parse_ies(&f, Path::new("a.ies")).unwrap_err().to_string();
        assert!(
            e.contains("declares 3 × 2 candela values, but only 5 numbers follow"),
            "{e}"
        );
        // counts far beyond the data are refused before anything is allocated for them
        let f = FILE.replace("1 1000 2 3 2 1 2", "1 1000 2 3 100000 1 2");
        let e = parse_ies(&f, Path::new("a.ies")).unwrap_err().to_string();
        assert!(e.contains("horizontal angles"), "{e}");
        let f = FILE.replace("0 90\n", "0 120\n");
        let e = parse_ies(&f, Path::new("a.ies")).unwrap_err().to_string();
        assert!(e.contains("8:1: horizontal angles: type C"), "{e}");
        let e = parse_ies("hello\n1 2 3", Path::new("a.ies"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no TILT= line"), "{e}");
        let f = format!("{FILE}5\n");
        let e = parse_ies(&f, Path::new("a.ies")).unwrap_err().to_string();
        assert!(e.contains("11:1: unexpected \"5\""), "{e}");
    }
}
