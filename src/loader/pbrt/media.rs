//! pbrt-v4's participating media (`src/pbrt/media.cpp`): `MakeNamedMedium` of type
//! `homogeneous`, and `MediumInterface`, which gives the shapes after it their inside and
//! outside media and the camera (at its `Camera` directive) the medium it sits in.
//!
//! `homogeneous` is read as pbrt-v4 reads it: `sigma_a` and `sigma_s` (1 each; `rgb` values
//! uplifted as unbounded spectra) per unit of scene length (a metre here), both times `scale`;
//! Henyey–Greenstein `g` (0); emission `Le` (none) normalised as pbrt-v4 normalises a light's
//! spectrum, times `Lescale`; or a `preset`, one of pbrt-v4's measured media (its σ_s′ and σ_a,
//! `spectra/pbrt/media_presets.csv`). spectrace's volumetric path tracer renders them (`volpath`).

use std::path::Path;

use super::Reader;
use super::lexer::{Tok, Token};
use super::params::{Params, R};
use super::spectra;
use crate::loader::desc::{Coefficients, MediumDesc, MediumKind};
use crate::loader::{LoadError, Loc};
use crate::medium::PhaseFunction;
use crate::spectrum::{Spectrum, rgb2spec};

/// A coefficient (`sigma_a`, `sigma_s`): an `rgb` (pbrt-v4's unbounded uplift), a spectrum or
/// a blackbody; `default` when absent.
pub(super) fn coefficient(p: &Params, name: &str, default: f32) -> R<Spectrum> {
    match p.get(name) {
        None => Ok(Spectrum::Constant(default)),
        Some(q) if matches!(q.ty.as_str(), "rgb" | "color") && q.nums.len() == 3 => {
            rgb2spec::unbounded([q.nums[0] as f32, q.nums[1] as f32, q.nums[2] as f32])
                .map_err(|e| p.err(q.loc, format!("\"{name}\": {e}")))
        }
        // spectra and blackbodies as pbrt-v4 reads a reflectance's, without its [0, 1] bound
        Some(q) if q.ty == "spectrum" || q.ty == "blackbody" => spectra::reflectance(p, name, 0.0),
        Some(q) => Err(p.err(
            q.loc,
            format!("\"{name}\" must be an rgb, a spectrum or a blackbody"),
        )),
    }
}

/// pbrt-v4's medium preset `name`: its (σ_s′, σ_a), RGB per unit of scene length (the
/// measurements of Jensen et al. 2001 and Narasimhan et al. 2006 in mm⁻¹, as pbrt-v4 reads
/// them), from `spectra/pbrt/media_presets.csv`; None if pbrt-v4 has no such preset.
fn preset(name: &str) -> Option<([f32; 3], [f32; 3])> {
    let (_, text) = crate::data::embedded::PBRT_MEDIA_PRESETS;
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .find_map(|l| {
            let mut f = l.split(',');
            if f.next()? != name {
                return None;
            }
            let v: Vec<f32> = f.map(|x| x.trim().parse().ok()).collect::<Option<_>>()?;
            (v.len() == 6).then(|| ([v[0], v[1], v[2]], [v[3], v[4], v[5]]))
        })
}

/// A `MakeNamedMedium`'s description.
fn medium(name: &str, p: &Params, loc: Loc) -> R<MediumDesc> {
    let ty = p.string("type")?.ok_or_else(|| {
        p.err(
            loc,
            format!("MakeNamedMedium \"{name}\" needs a \"string type\""),
        )
    })?;
    if ty != "homogeneous" {
        return Err(p.err(
            p.loc_of("type"),
            format!("the medium \"{ty}\" is not read yet (spectrace reads homogeneous)"),
        ));
    }
    let scale = p.float("scale", 1.0)? as f32;
    let (sigma_a, sigma_s) = match p.string("preset")? {
        // pbrt-v4 then reads neither coefficient (one given too is unused)
        Some(name) => {
            let Some((s, a)) = preset(&name) else {
                return Err(p.err(
                    p.loc_of("preset"),
                    format!("no medium preset \"{name}\" (pbrt-v4's are listed in spectra/pbrt/media_presets.csv)"),
                ));
            };
            let uplift = |rgb: [f32; 3]| {
                rgb2spec::unbounded(rgb).map_err(|e| p.err(p.loc_of("preset"), e.to_string()))
            };
            (uplift(a)?, uplift(s)?)
        }
        None => (
            coefficient(p, "sigma_a", 1.0)?,
            coefficient(p, "sigma_s", 1.0)?,
        ),
    };
    let (sigma_a, sigma_s) = (sigma_a.scaled(scale), sigma_s.scaled(scale));
    let g = p.float("g", 0.0)?;
    if !(g > -1.0 && g < 1.0) {
        return Err(p.err(p.loc_of("g"), "\"g\" must lie in (−1, 1)"));
    }
    let emission = match p.get("Le") {
        None => None,
        Some(_) => {
            let (s, k) = spectra::illuminant(p, "Le")?;
            Some(s.scaled((k * p.float("Lescale", 1.0)?) as f32))
        }
    };
    Ok(MediumDesc {
        name: name.to_string(),
        kind: MediumKind::Homogeneous {
            coefficients: Coefficients::AbsorptionScattering { sigma_a, sigma_s },
            phase: PhaseFunction::HenyeyGreenstein { g: g as f32 },
            emission,
        },
        loc,
    })
}

impl Reader {
    /// `MakeNamedMedium "name" …` and `MediumInterface "inside" ["outside"]` (one name: both
    /// sides; "" is vacuum).
    pub(super) fn medium_directive(
        &mut self,
        d: &str,
        toks: &[Token],
        i: &mut usize,
        file: &Path,
        loc: Loc,
    ) -> R<()> {
        if d == "MakeNamedMedium" {
            let name = Self::string_arg(toks, i, file, d, loc)?;
            let p = Params::parse(toks, i, file)?;
            let m = medium(&name, &p, loc)?;
            p.check_unused(&format!("medium \"{name}\""))?;
            self.named_media.insert(name, self.media.len());
            self.media.push(m);
            return Ok(());
        }
        let mut names = Vec::new();
        while let Some(Token {
            kind: Tok::Str(s),
            loc: l,
        }) = toks.get(*i)
        {
            if names.len() == 2 || s.contains(' ') {
                break;
            }
            names.push((s.clone(), *l));
            *i += 1;
        }
        let look = |(n, l): &(String, Loc)| -> R<Option<usize>> {
            if n.is_empty() {
                return Ok(None);
            }
            self.named_media.get(n).copied().map(Some).ok_or_else(|| {
                LoadError::new(
                    file,
                    *l,
                    "",
                    format!("no medium named \"{n}\" (MakeNamedMedium it first)"),
                )
            })
        };
        self.state.media = match &names[..] {
            [one] => (look(one)?, look(one)?),
            [inside, outside] => (look(inside)?, look(outside)?),
            _ => {
                return Err(LoadError::new(
                    file,
                    loc,
                    "",
                    "MediumInterface needs the inside and outside media's names",
                ));
            }
        };
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    /// Every row of the table reads (pbrt-v4 has 47 presets), with pbrt-v4's numbers: Skin1's
    /// σ_s′ (0.74, 0.88, 1.01) and σ_a (0.032, 0.17, 0.48) mm⁻¹ (Jensen et al. 2001, table 2).
    #[test]
    fn presets_are_pbrts_table() {
        let (_, text) = crate::data::embedded::PBRT_MEDIA_PRESETS;
        let names: Vec<&str> = text
            .lines()
            .filter(|l| !l.starts_with('#'))
            .skip(1)
            .filter_map(|l| l.split(',').next())
            .collect();
        assert_eq!(names.len(), 47);
        assert!(names.iter().all(|n| super::preset(n).is_some()));
        assert_eq!(
            super::preset("Skin1"),
            Some(([0.74, 0.88, 1.01], [0.032, 0.17, 0.48]))
        );
        assert_eq!(super::preset("skin1"), None);
    }
}
