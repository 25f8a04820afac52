//! Data files: the tables in `spectra/` (embedded in the binary, so that it runs from any
//! folder) and user files in the same CSV form. A leaf: the colour-matching functions
//! (`colour`) and the spectra (`spectrum`, which turns tables into curves) both read it.
//!
//! A data file starts with `#` comment lines (what it is, source, licence, units), then one CSV
//! header line, then rows of numbers. The first column is the wavelength in nm.

/// Why a data file could not be read. Names the file, the 1-based line, and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct DataError {
    pub file: String,
    pub line: usize,
    pub message: String,
}

/// A parsed CSV data file.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// The leading `#` comment lines, without the `#`.
    pub comments: Vec<String>,
    /// Column names from the header line.
    pub columns: Vec<String>,
    /// One entry per data row, `columns.len()` values each.
    pub rows: Vec<Vec<f64>>,
    /// Line number of each row, for error messages.
    pub row_lines: Vec<usize>,
}

impl Table {
    /// Index of the column called `name`.
    pub fn column_index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }
    /// All values of column `i`.
    pub fn column(&self, i: usize) -> Vec<f64> {
        self.rows.iter().map(|r| r[i]).collect()
    }
    /// The comment line that starts with `prefix` (e.g. "Source:"), trimmed, if any.
    pub fn comment_starting(&self, prefix: &str) -> Option<&str> {
        self.comments
            .iter()
            .map(|c| c.trim())
            .find(|c| c.starts_with(prefix))
    }
}

/// Parses the CSV data format. `file` names the origin in errors.
pub fn parse_csv(text: &str, file: &str) -> Result<Table, DataError> {
    let err = |line: usize, message: String| DataError {
        file: file.to_string(),
        line,
        message,
    };
    let mut comments = Vec::new();
    let mut columns: Option<Vec<String>> = None;
    let mut rows = Vec::new();
    let mut row_lines = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = raw.trim();
        if let Some(c) = line.strip_prefix('#') {
            if columns.is_none() {
                comments.push(c.trim().to_string());
            }
            continue;
        }
        if line.is_empty() {
            continue;
        }
        let Some(cols) = &columns else {
            columns = Some(line.split(',').map(|s| s.trim().to_string()).collect());
            continue;
        };
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != cols.len() {
            return Err(err(
                line_no,
                format!(
                    "expected {} comma-separated values ({}), found {}",
                    cols.len(),
                    cols.join(","),
                    fields.len()
                ),
            ));
        }
        let mut row = Vec::with_capacity(fields.len());
        for (f, name) in fields.iter().zip(cols) {
            let v: f64 = f
                .parse()
                .map_err(|_| err(line_no, format!("column '{name}': '{f}' is not a number")))?;
            if !v.is_finite() {
                return Err(err(
                    line_no,
                    format!("column '{name}': '{f}' is not finite"),
                ));
            }
            row.push(v);
        }
        rows.push(row);
        row_lines.push(line_no);
    }
    let columns = columns.ok_or_else(|| {
        err(
            text.lines().count().max(1),
            "no header line and no data".into(),
        )
    })?;
    if rows.is_empty() {
        return Err(err(
            text.lines().count().max(1),
            "a header line but no data rows".into(),
        ));
    }
    Ok(Table {
        comments,
        columns,
        rows,
        row_lines,
    })
}

/// The data files shipped in `spectra/`, embedded at compile time: (path, contents).
pub mod embedded {
    macro_rules! data {
        ($($name:ident = $path:literal;)+) => {$(
            pub const $name: (&str, &str) = ($path, include_str!(concat!("../", $path)));
        )+};
    }
    data! {
        CIE_1931_2DEG = "spectra/cie/cie1931_2deg.csv";
        CIE_D65 = "spectra/illuminants/cie_d65.csv";
        CIE_D50 = "spectra/illuminants/cie_d50.csv";
        CIE_A = "spectra/illuminants/cie_a.csv";
        CIE_E = "spectra/illuminants/cie_e.csv";
        CIE_F2 = "spectra/illuminants/cie_f2.csv";
        CIE_F11 = "spectra/illuminants/cie_f11.csv";
        COLORCHECKER = "spectra/colorchecker/colorchecker_n_ohta.csv";
        GLASSES = "spectra/glass/sellmeier.toml";
        METAL_AU = "spectra/metals/au.csv";
        METAL_AG = "spectra/metals/ag.csv";
        METAL_CU = "spectra/metals/cu.csv";
        METAL_AL = "spectra/metals/al.csv";
        CIE_LED = "spectra/illuminants/cie_led.csv";
        CIE_DAYLIGHT_BASIS = "spectra/illuminants/cie_daylight_basis.csv";
        CAMERA_NIKON_D5100 = "spectra/cameras/nikon_d5100.csv";
        PBRT_SWATCHES = "spectra/pbrt/swatches_babelcolor.csv";
        PBRT_MEDIA_PRESETS = "spectra/pbrt/media_presets.csv";
        CAMERA_SIGMA_SD_MERRILL = "spectra/cameras/sigma_sd_merrill.csv";
    }

    /// The optical glass catalogues of `spectra/glass/catalogues/` (written by
    /// `scripts/gen_glass_catalogues.py`): (maker, (path, contents)), in the order in which a
    /// name two makers share resolves.
    pub const GLASS_CATALOGUES: &[(&str, (&str, &str))] = &[
        (
            "SCHOTT",
            (
                "spectra/glass/catalogues/schott.toml",
                include_str!("../spectra/glass/catalogues/schott.toml"),
            ),
        ),
        (
            "OHARA",
            (
                "spectra/glass/catalogues/ohara.toml",
                include_str!("../spectra/glass/catalogues/ohara.toml"),
            ),
        ),
        (
            "HOYA",
            (
                "spectra/glass/catalogues/hoya.toml",
                include_str!("../spectra/glass/catalogues/hoya.toml"),
            ),
        ),
        (
            "CDGM",
            (
                "spectra/glass/catalogues/cdgm.toml",
                include_str!("../spectra/glass/catalogues/cdgm.toml"),
            ),
        ),
        (
            "Sumita",
            (
                "spectra/glass/catalogues/sumita.toml",
                include_str!("../spectra/glass/catalogues/sumita.toml"),
            ),
        ),
        (
            "crystals",
            (
                "spectra/glass/catalogues/crystals.toml",
                include_str!("../spectra/glass/catalogues/crystals.toml"),
            ),
        ),
    ];

    macro_rules! mitsuba_metals {
        ($($name:literal)+) => {
            /// Mitsuba 3.9.1's conductor presets (`material="Au"` …): (preset name, (path,
            /// contents)) of `spectra/metals/mitsuba/<name>.csv`, written by
            /// `scripts/gen_spectra.py` from Mitsuba's own `data/ior/<name>.{eta,k}.spd`.
            pub const MITSUBA_METALS: &[(&str, (&str, &str))] = &[$((
                $name,
                (
                    concat!("spectra/metals/mitsuba/", $name, ".csv"),
                    include_str!(concat!("../spectra/metals/mitsuba/", $name, ".csv")),
                ),
            )),+];
        };
    }
    mitsuba_metals! {
        "Ag" "Al" "AlAs" "AlAs_palik" "AlSb" "AlSb_palik" "Au" "Be" "Be_palik" "Cr" "CsI"
        "CsI_palik" "Cu" "Cu2O" "Cu2O_palik" "CuO" "CuO_palik" "Cu_palik" "Hg" "HgTe"
        "HgTe_palik" "Hg_palik" "Ir" "Ir_palik" "K" "K_palik" "Li" "Li_palik" "MgO"
        "MgO_palik" "Mo" "Mo_palik" "Na_palik" "Nb" "Nb_palik" "Ni_palik" "Rh" "Rh_palik"
        "Se-e" "Se-e_palik" "Se" "Se_palik" "SiC" "SiC_palik" "SnTe" "SnTe_palik" "Ta"
        "Ta_palik" "Te-e" "Te-e_palik" "Te" "Te_palik" "ThF4" "ThF4_palik" "TiC"
        "TiC_palik" "TiN" "TiN_palik" "TiO2-e" "TiO2-e_palik" "TiO2" "TiO2_palik" "VC"
        "VC_palik" "VN" "VN_palik" "V_palik" "W" "a-C" "d-C" "d-C_palik"
    }
    macro_rules! pbrt_spectra {
        ($($name:literal)+) => {
            /// pbrt-v4's named glass and metal spectra (`glass-BK7`, `metal-Au-eta`, …): (name,
            /// (path, contents)) of `spectra/pbrt/<name>.csv`, written by
            /// `scripts/gen_pbrt_spectra.py` from pbrt-v4's `src/pbrt/util/spectrum.cpp`.
            pub const PBRT_SPECTRA: &[(&str, (&str, &str))] = &[$((
                $name,
                (
                    concat!("spectra/pbrt/", $name, ".csv"),
                    include_str!(concat!("../spectra/pbrt/", $name, ".csv")),
                ),
            )),+];
        };
    }
    macro_rules! pbrt_cameras {
        ($($name:literal)+) => {
            /// pbrt-v4's named camera sensors (`canon_eos_5d_mkiv`, …): (name, (path, contents))
            /// of `spectra/pbrt/cameras/<name>.csv` (wavelength_nm, r, g, b), written by
            /// `scripts/gen_pbrt_sensor_data.py` from pbrt-v4's `src/pbrt/util/spectrum.cpp`.
            pub const PBRT_CAMERAS: &[(&str, (&str, &str))] = &[$((
                $name,
                (
                    concat!("spectra/pbrt/cameras/", $name, ".csv"),
                    include_str!(concat!("../spectra/pbrt/cameras/", $name, ".csv")),
                ),
            )),+];
        };
    }
    pbrt_cameras! {
        "canon_eos_100d" "canon_eos_1dx_mkii" "canon_eos_200d" "canon_eos_200d_mkii" "canon_eos_5d"
        "canon_eos_5d_mkii" "canon_eos_5d_mkiii" "canon_eos_5d_mkiv" "canon_eos_5ds" "canon_eos_m"
        "hasselblad_l1d_20c" "nikon_d810" "nikon_d850" "sony_ilce_6400" "sony_ilce_7m3"
        "sony_ilce_7rm3" "sony_ilce_9"
    }
    pbrt_spectra! {
        "glass-BK7" "glass-BAF10" "glass-FK51A" "glass-LASF9" "glass-F5" "glass-F10" "glass-F11"
        "metal-Ag-eta" "metal-Ag-k" "metal-Al-eta" "metal-Al-k" "metal-Au-eta" "metal-Au-k"
        "metal-Cu-eta" "metal-Cu-k" "metal-CuZn-eta" "metal-CuZn-k" "metal-MgO-eta" "metal-MgO-k"
        "metal-TiO2-eta" "metal-TiO2-k"
    }
}

/// Parses an embedded table. The files are part of the build and covered by tests, so a parse
/// failure is a packaging bug, not user input.
pub(crate) fn embedded_table(file: (&str, &str)) -> Table {
    match parse_csv(file.1, file.0) {
        Ok(t) => t,
        Err(e) => panic!("embedded data file is corrupt: {e}"), // ok: build-time invariant, tested
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_comments_header_rows() {
        let t = parse_csv(
            "# a\n# Source: x\nwavelength_nm,value\n400,1\n\n500,2.5\n",
            "t.csv",
        )
        .unwrap();
        assert_eq!(t.columns, ["wavelength_nm", "value"]);
        assert_eq!(t.rows, vec![vec![400.0, 1.0], vec![500.0, 2.5]]);
        assert_eq!(t.row_lines, vec![4, 6]);
        assert_eq!(t.comment_starting("Source:"), Some("Source: x"));
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = parse_csv("wavelength_nm,value\n400,1\n500,x\n", "s.csv").unwrap_err();
        assert_eq!((e.file.as_str(), e.line), ("s.csv", 3));
        assert!(e.message.contains("'x' is not a number"), "{e}");
        let e = parse_csv("wavelength_nm,value\n400,1,2\n", "s.csv").unwrap_err();
        assert_eq!(e.line, 2);
        assert!(parse_csv("# only\n", "s.csv").is_err());
    }

    #[test]
    fn every_embedded_file_parses() {
        use embedded::*;
        for f in [
            CIE_1931_2DEG,
            CIE_D65,
            CIE_D50,
            CIE_A,
            CIE_E,
            CIE_F2,
            CIE_F11,
            COLORCHECKER,
        ] {
            let t = embedded_table(f);
            assert!(t.rows.len() > 40, "{}", f.0);
        }
        for f in [METAL_AU, METAL_AG, METAL_CU, METAL_AL]
            .into_iter()
            .chain(MITSUBA_METALS.iter().map(|m| m.1))
        {
            let t = embedded_table(f);
            assert_eq!(t.columns, ["wavelength_nm", "n", "k"], "{}", f.0);
        }
        // every file the generator wrote is embedded
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/spectra/metals/mitsuba");
        let mut on_disk: Vec<String> = std::fs::read_dir(dir)
            .map(|r| {
                r.filter_map(|e| e.ok())
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .filter(|n| n.ends_with(".csv"))
                    .collect()
            })
            .unwrap_or_default();
        on_disk.sort();
        let mut listed: Vec<String> = MITSUBA_METALS
            .iter()
            .map(|m| format!("{}.csv", m.0))
            .collect();
        listed.sort();
        assert_eq!(on_disk, listed);
    }
}
