//! The glasses of `glass:NAME`: the curated entries of `spectra/glass/sellmeier.toml`, then the
//! optical glass catalogues of `spectra/glass/catalogues/` (SCHOTT, OHARA, HOYA, CDGM, Sumita
//! and crystals, written by `scripts/gen_glass_catalogues.py` from the refractiveindex.info
//! database).
//!
//! Every catalogue glass is also reachable as `glass:MAKER/NAME` (`glass:cdgm/H-K9L`). Where two
//! makers use one name (SCHOTT's and CDGM's F2 and F5) the bare name is the earlier catalogue's
//! (curated, SCHOTT, OHARA, HOYA, CDGM, Sumita, crystals) and the other is reachable only by its
//! qualified name.

use std::collections::{BTreeMap, BTreeSet};

use serde::Deserialize;

use super::{Glass, Named};
use crate::spectrum::data::embedded;
use crate::spectrum::ior::{Ior, Polynomial, Sellmeier};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CuratedFile {
    glass: Vec<CuratedEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CuratedEntry {
    name: String,
    #[serde(rename = "A")]
    a: f64,
    #[serde(rename = "B")]
    b: Vec<f64>,
    #[serde(rename = "C")]
    c: Vec<f64>,
    range_um: [f64; 2],
    nd: f64,
    nd_source: String,
    vd: Option<f64>,
    source: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CatalogueFile {
    glass: Vec<CatalogueEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CatalogueEntry {
    name: String,
    sellmeier: Option<SellmeierTerms>,
    polynomial: Option<PolynomialTerms>,
    range_um: [f64; 2],
    nd: f64,
    vd: Option<f64>,
    temperature_k: Option<f64>,
    reference: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SellmeierTerms {
    #[serde(rename = "A")]
    a: f64,
    #[serde(rename = "B")]
    b: Vec<f64>,
    #[serde(rename = "C")]
    c: Vec<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PolynomialTerms {
    #[serde(rename = "A")]
    a: f64,
    c: Vec<f64>,
    p: Vec<f64>,
}

fn sellmeier(a: f64, b: &[f64], c: &[f64]) -> Ior {
    let mut s = Sellmeier {
        a,
        b: [0.0; 4],
        c: [0.0; 4],
    };
    for (i, (b, c)) in b.iter().zip(c).take(4).enumerate() {
        s.b[i] = *b;
        s.c[i] = *c;
    }
    Ior::Sellmeier(s)
}

fn parse<'a, T: Deserialize<'a>>(file: (&str, &'a str)) -> T {
    match toml::from_str(file.1) {
        Ok(g) => g,
        Err(e) => panic!("embedded {} is corrupt: {e}", file.0), // ok: build-time invariant, tested
    }
}

fn range_nm(r: [f64; 2]) -> (f32, f32) {
    ((r[0] * 1e3) as f32, (r[1] * 1e3) as f32)
}

/// Adds the curated glasses of `sellmeier.toml` to `entries` (lower-cased key → (display
/// name, value)).
pub(super) fn add_curated(entries: &mut BTreeMap<String, (String, Named)>) {
    let curated: CuratedFile = parse(embedded::GLASSES);
    for g in curated.glass {
        let glass = Glass {
            ior: sellmeier(g.a, &g.b, &g.c),
            range_nm: range_nm(g.range_um),
            nd: g.nd,
            nd_source: g.nd_source,
            vd: g.vd,
            source: g.source,
            catalogue: "spectrace".into(),
            name: g.name,
        };
        let name = format!("glass:{}", glass.name);
        entries.insert(name.to_lowercase(), (name, Named::Dielectric(glass)));
    }
}

/// The catalogues' glasses, keyed as `entries` are, leaving out the names `taken` (the
/// curated glasses' and the other registry's); and the alias keys, which `names()` leaves out.
/// Parsed on the first lookup that needs them (1262 glasses: about 10⁸ instructions, which a
/// scene without catalogue glasses should not pay).
pub(super) fn catalogues(
    taken: &BTreeMap<String, (String, Named)>,
) -> (BTreeMap<String, (String, Named)>, BTreeSet<String>) {
    let mut entries = BTreeMap::new();
    let mut hidden = BTreeSet::new();
    for (maker, file) in embedded::GLASS_CATALOGUES {
        let cat: CatalogueFile = parse(*file);
        for g in cat.glass {
            let ior = match (&g.sellmeier, &g.polynomial) {
                (Some(s), None) => sellmeier(s.a, &s.b, &s.c),
                (None, Some(p)) => {
                    let mut poly = Polynomial {
                        a: p.a,
                        c: [0.0; 6],
                        p: [0.0; 6],
                    };
                    for (i, (c, e)) in p.c.iter().zip(&p.p).take(6).enumerate() {
                        poly.c[i] = *c;
                        poly.p[i] = *e;
                    }
                    Ior::Polynomial(poly)
                }
                _ => panic!("embedded {}: {} needs one formula", file.0, g.name), // ok: tested
            };
            let temperature = g
                .temperature_k
                .map(|t| format!(", at {t} K"))
                .unwrap_or_default();
            let glass = Glass {
                ior,
                range_nm: range_nm(g.range_um),
                nd: g.nd,
                nd_source: format!("{} ({maker} catalogue value)", g.reference),
                vd: g.vd,
                source: format!(
                    "{}{temperature}; via the refractiveindex.info database (CC0), {}",
                    g.reference, file.0
                ),
                catalogue: (*maker).into(),
                name: g.name,
            };
            let qualified = format!("glass:{maker}/{}", glass.name);
            let bare = format!("glass:{}", glass.name);
            let named = Named::Dielectric(glass);
            let key = bare.to_lowercase();
            if entries.contains_key(&key) || taken.contains_key(&key) {
                entries.insert(qualified.to_lowercase(), (qualified, named));
            } else {
                hidden.insert(qualified.to_lowercase());
                entries.insert(qualified.to_lowercase(), (qualified, named.clone()));
                entries.insert(bare.to_lowercase(), (bare, named));
            }
        }
    }
    (entries, hidden)
}
