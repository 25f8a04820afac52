//! Named spectra: `cie-d65`, `glass:N-BK7`, `metal:Au`, `colorchecker:dark-skin`,
//! `blackbody:6500K`, … Looked up case-insensitively; an unknown name suggests the closest ones.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, OnceLock};

use super::blackbody::Blackbody;
use super::curve::Spectrum;
use super::data::{Table, embedded, embedded_table, table_to_curve};
use super::ior::{ComplexIor, Ior};
use mitsuba::conductor;
pub use mitsuba::{MITSUBA_VERSION, mitsuba_conductor};

mod glass;
mod mitsuba;

/// What a named curve means, which sets its unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveKind {
    /// A relative spectral power distribution (CIE illuminants: 100 at 560 nm).
    Illuminant,
    /// A reflectance factor in [0, 1].
    Reflectance,
    /// A CIE colour-matching function (dimensionless, ȳ(555 nm) = 1).
    ColourMatching,
    /// A peak-normalised Planck curve (maximum 1).
    Blackbody,
}

impl CurveKind {
    /// What a curve's values are, with their scale (plot axes, the library's lookups).
    pub fn quantity(self) -> &'static str {
        match self {
            CurveKind::Illuminant => "relative spectral power",
            CurveKind::Reflectance => "reflectance factor",
            CurveKind::ColourMatching => "tristimulus value (ȳ(555 nm) = 1)",
            CurveKind::Blackbody => "relative spectral radiance (peak 1)",
        }
    }
}

/// A dielectric from `spectra/glass/sellmeier.toml` or a catalogue in
/// `spectra/glass/catalogues/`.
#[derive(Clone, Debug, PartialEq)]
pub struct Glass {
    pub name: String,
    /// The catalogue it comes from (`SCHOTT`, `OHARA`, `HOYA`, `CDGM`, `Sumita`, `crystals`), or
    /// `spectrace` for the curated entries of `sellmeier.toml`.
    pub catalogue: String,
    pub ior: Ior,
    /// Validity range of the formula, nm.
    pub range_nm: (f32, f32),
    /// Catalogue n_d at 587.56 nm (or computed, see `nd_source`).
    pub nd: f64,
    pub nd_source: String,
    /// Catalogue Abbe number, when the catalogue gives one.
    pub vd: Option<f64>,
    pub source: String,
}

/// A conductor from `spectra/metals/`.
#[derive(Clone, Debug, PartialEq)]
pub struct Metal {
    pub name: String,
    pub ior: ComplexIor,
    pub source: String,
}

/// The value a name stands for.
#[derive(Clone, Debug, PartialEq)]
pub enum Named {
    Curve {
        spectrum: Spectrum,
        kind: CurveKind,
        source: String,
    },
    Dielectric(Glass),
    Conductor(Metal),
}

/// A name that is not known, with the closest known names.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("unknown spectrum \"{name}\"{}", suggest(.suggestions))]
pub struct UnknownSpectrum {
    pub name: String,
    pub suggestions: Vec<String>,
}

fn suggest(s: &[String]) -> String {
    if s.is_empty() {
        "; run `spectrace spectrum --list` for the names".into()
    } else {
        format!(
            "; did you mean {}?",
            s.iter()
                .map(|n| format!("\"{n}\""))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

struct Registry {
    /// Lower-cased name → (display name, value).
    entries: BTreeMap<String, (String, Named)>,
    /// Keys that are aliases (`glass:schott/n-bk7`), left out of [`names`].
    hidden: BTreeSet<String>,
}

fn source_line(t: &Table) -> String {
    ["Source:", "Dataset:", "Paper:"]
        .iter()
        .find_map(|p| t.comment_starting(p))
        .or_else(|| t.comments.first().map(String::as_str))
        .unwrap_or("")
        .to_string()
}

fn curve(file: (&str, &str), col: &str, kind: CurveKind) -> Named {
    let t = embedded_table(file);
    let i = t.column_index(col).unwrap_or(1);
    let spectrum = match table_to_curve(&t, 0, i, file.0) {
        Ok(c) => Spectrum::Piecewise(Arc::new(c)),
        Err(e) => panic!("embedded data file is corrupt: {e}"), // ok: build-time invariant, tested
    };
    Named::Curve {
        spectrum,
        kind,
        source: source_line(&t),
    }
}

fn build() -> Registry {
    let mut entries = BTreeMap::new();
    let mut add = |name: String, v: Named| {
        entries.insert(name.to_lowercase(), (name, v));
    };
    use embedded::*;
    // Each illuminant over its whole defined range: D65 and D50 are the CIE tables, 300–830 nm;
    // F2 and F11 the CIE tables, 380–780 nm (zero outside). A and E are defined by formulas for
    // every wavelength, so they are evaluated exactly rather than read from their tables
    // (`spectra/illuminants/cie_a.csv`, `cie_e.csv` hold the same values, for reference).
    for (name, f) in [
        ("cie-d65", CIE_D65),
        ("cie-d50", CIE_D50),
        ("cie-f2", CIE_F2),
        ("cie-f11", CIE_F11),
    ] {
        add(name.into(), curve(f, "value", CurveKind::Illuminant));
    }
    add(
        "cie-a".into(),
        Named::Curve {
            spectrum: Spectrum::Blackbody(Blackbody::cie_illuminant_a()),
            kind: CurveKind::Illuminant,
            source:
                "CIE 015:2018 eq. (4.1): Planck's law, c2 = 1.435e7 nm K, 2848 K, 100 at 560 nm"
                    .into(),
        },
    );
    add(
        "cie-e".into(),
        Named::Curve {
            spectrum: Spectrum::Constant(100.0),
            kind: CurveKind::Illuminant,
            source: "CIE 015:2018: equal-energy illuminant, the constant 100".into(),
        },
    );
    for led in ["b1", "b2", "b3", "b4", "b5", "bh1", "rgb1", "v1", "v2"] {
        add(
            format!("cie-led-{led}"),
            curve(CIE_LED, led, CurveKind::Illuminant),
        );
    }
    for (name, col) in [("cie-x", "xbar"), ("cie-y", "ybar"), ("cie-z", "zbar")] {
        add(
            name.into(),
            curve(CIE_1931_2DEG, col, CurveKind::ColourMatching),
        );
    }
    let cc = embedded_table(COLORCHECKER);
    for (i, patch) in cc.columns.iter().enumerate().skip(1) {
        let spectrum = match table_to_curve(&cc, 0, i, COLORCHECKER.0) {
            Ok(c) => Spectrum::Piecewise(Arc::new(c)),
            Err(e) => panic!("embedded data file is corrupt: {e}"), // ok: build-time invariant
        };
        add(
            format!("colorchecker:{patch}"),
            Named::Curve {
                spectrum,
                kind: CurveKind::Reflectance,
                source: source_line(&cc),
            },
        );
    }
    // spectrace's own metals: Johnson & Christy (1972) for the noble metals, Rakić (1995) for Al
    for (name, f) in [
        ("Au", METAL_AU),
        ("Ag", METAL_AG),
        ("Cu", METAL_CU),
        ("Al", METAL_AL),
    ] {
        add(format!("metal:{name}"), conductor(name, f));
    }
    // Mitsuba 3.9.1's conductor presets, digit for digit (Palik via the Luxpop database)
    for (name, f) in MITSUBA_METALS {
        add(format!("mitsuba:{name}"), conductor(name, *f));
    }
    glass::add_curated(&mut entries);
    Registry {
        entries,
        hidden: BTreeSet::new(),
    }
}

fn registry() -> &'static Registry {
    static R: OnceLock<Registry> = OnceLock::new();
    R.get_or_init(build)
}

/// The glass catalogues, read on first use (`named/glass.rs`).
fn catalogues() -> &'static Registry {
    static C: OnceLock<Registry> = OnceLock::new();
    C.get_or_init(|| {
        let (entries, hidden) = glass::catalogues(&registry().entries);
        Registry { entries, hidden }
    })
}

/// Both registries' entries (lookups that must see every name: listing, suggestions).
fn all_entries() -> impl Iterator<Item = (&'static String, &'static (String, Named), bool)> {
    let (r, c) = (registry(), catalogues());
    r.entries
        .iter()
        .map(move |(k, v)| (k, v, r.hidden.contains(k)))
        .chain(
            c.entries
                .iter()
                .map(move |(k, v)| (k, v, c.hidden.contains(k))),
        )
}

/// Every fixed name, in sorted order, with one word for its kind. `blackbody:<T>K` is listed as
/// a pattern.
pub fn names() -> Vec<(String, &'static str)> {
    let mut v: Vec<(String, &'static str)> = all_entries()
        .filter(|(_, _, hidden)| !hidden)
        .map(|(_, (n, v), _)| {
            let kind = match v {
                Named::Curve {
                    kind: CurveKind::Illuminant,
                    ..
                } => "illuminant (relative SPD)",
                Named::Curve {
                    kind: CurveKind::Reflectance,
                    ..
                } => "reflectance",
                Named::Curve {
                    kind: CurveKind::ColourMatching,
                    ..
                } => "CIE 1931 2° colour-matching function",
                Named::Curve {
                    kind: CurveKind::Blackbody,
                    ..
                } => "blackbody",
                Named::Dielectric(_) => "dielectric index n(λ)",
                Named::Conductor(_) => "conductor index n(λ), k(λ)",
            };
            (n.clone(), kind)
        })
        .collect();
    v.sort_by_key(|(n, _)| n.to_lowercase());
    v.push((
        "blackbody:<T>K".into(),
        "Planck curve at temperature T, peak-normalised",
    ));
    v.push((
        "cie-d:<T>K".into(),
        "CIE daylight of correlated colour temperature T (4000–25000 K)",
    ));
    v
}

/// Looks a name up (case-insensitive).
pub fn lookup(name: &str) -> Result<Named, UnknownSpectrum> {
    let key = name.trim().to_lowercase();
    if let Some((_, v)) = registry().entries.get(&key) {
        return Ok(v.clone());
    }
    if key.starts_with("glass:")
        && let Some((_, v)) = catalogues().entries.get(&key)
    {
        return Ok(v.clone());
    }
    if let Some(t) = name.trim().strip_prefix("blackbody:")
        && let Ok(temp) = crate::units::parse::parse::<crate::units::ThermodynamicTemperature>(t)
    {
        let k = crate::units::plain::kelvin_f32(temp);
        if k > 0.0 {
            return Ok(Named::Curve {
                spectrum: Spectrum::Blackbody(Blackbody::normalized(k)),
                kind: CurveKind::Blackbody,
                source: "Planck's law, 2019 SI constants".into(),
            });
        }
    }
    if key.starts_with("cie-d:")
        && let Some(t) = name.trim().get(6..)
        && let Ok(temp) = crate::units::parse::parse::<crate::units::ThermodynamicTemperature>(t)
        && let Some(spectrum) = cie_daylight(crate::units::plain::kelvin_f32(temp) as f64)
    {
        return Ok(Named::Curve {
            spectrum,
            kind: CurveKind::Illuminant,
            source: "CIE 015:2018 §4.1.2: daylight from its correlated colour temperature (x_D(T), M1 and M2 rounded to three decimals as for the standard D illuminants), S0, S1, S2 of Table 6".into(),
        });
    }
    Err(UnknownSpectrum {
        name: name.to_string(),
        suggestions: closest(&key),
    })
}

/// M1 and M2 of CIE daylight at the correlated colour temperature `t` (K), unrounded: from the
/// chromaticity x_D(T) of CIE 015:2018 eq. 4.7/4.8 and y_D = −3 x_D² + 2.87 x_D − 0.275.
pub fn daylight_m1_m2(t: f64) -> [f64; 2] {
    let xd = if t <= 7000.0 {
        -4.6070e9 / t.powi(3) + 2.9678e6 / t.powi(2) + 0.09911e3 / t + 0.244063
    } else {
        -2.0064e9 / t.powi(3) + 1.9018e6 / t.powi(2) + 0.24748e3 / t + 0.237040
    };
    let yd = -3.0 * xd * xd + 2.870 * xd - 0.275;
    let m = 0.0241 + 0.2562 * xd - 0.7341 * yd;
    [
        (-1.3515 - 1.7703 * xd + 5.9114 * yd) / m,
        (0.0300 - 31.4424 * xd + 30.0717 * yd) / m,
    ]
}

/// CIE daylight of correlated colour temperature `t` (K, 4000–25000): S0 + M1·S1 + M2·S2 with
/// the chromaticity x_D(T) of CIE 015:2018 eq. 4.7/4.8, y_D = −3 x_D² + 2.87 x_D − 0.275, M1 and
/// M2 rounded to three decimals, tabulated at 5 nm over 300–830 nm and scaled to 100 at 560 nm.
/// None outside the temperature range.
pub fn cie_daylight(t: f64) -> Option<Spectrum> {
    if !(4000.0..=25000.0).contains(&t) {
        return None;
    }
    let round3 = |v: f64| (v * 1000.0).round() / 1000.0;
    let [m1, m2] = daylight_m1_m2(t).map(round3);
    let b = embedded_table(crate::spectrum::data::embedded::CIE_DAYLIGHT_BASIS);
    let (l, s0, s1, s2) = (b.column(0), b.column(1), b.column(2), b.column(3));
    let v: Vec<f64> = (0..l.len())
        .map(|i| s0[i] + m1 * s1[i] + m2 * s2[i])
        .collect();
    let at560 = l.iter().position(|&x| x == 560.0).map(|i| v[i])?;
    let curve = crate::spectrum::curve::PiecewiseLinear::new(
        l.iter().map(|&x| x as f32).collect(),
        v.iter().map(|&x| (x / at560 * 100.0) as f32).collect(),
    )
    .ok()?;
    Some(Spectrum::Piecewise(Arc::new(curve)))
}

/// Longest name, in characters, for which suggestions are looked for: the longest known name
/// is under 40 characters, and the comparison costs the product of the two lengths for each
/// of some 1400 names (a 20 000-character string took 2 s).
const MAX_SUGGESTED: usize = 100;

fn closest(key: &str) -> Vec<String> {
    if key.chars().count() > MAX_SUGGESTED {
        return Vec::new();
    }
    let key_short = key.split_once(':').map_or(key, |(_, s)| s);
    let mut scored: Vec<(f64, &String)> = all_entries()
        .map(|(k, (n, _), _)| {
            // compare with and without the "family:" prefix, so "bk7" finds "glass:N-BK7"
            let short = k.split_once(':').map_or(k.as_str(), |(_, s)| s);
            let mut s = strsim::jaro_winkler(key, k).max(strsim::jaro_winkler(key, short));
            // a name that contains the one asked for ("BK7" in "N-BK7") comes first
            if key_short.len() >= 2 && short.contains(key_short) {
                s += 1.0;
            }
            (s, n)
        })
        .collect();
    scored.sort_by(|a, b| b.0.total_cmp(&a.0));
    scored
        .into_iter()
        .filter(|(s, _)| *s > 0.7)
        .take(3)
        .map(|(_, n)| n.clone())
        .collect()
}

#[cfg(test)]
mod tests;
