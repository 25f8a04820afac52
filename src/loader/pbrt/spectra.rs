//! pbrt-v4's spectrum parameters (`paramdict.cpp`, `GetOneSpectrum`) as spectrace spectra:
//! `rgb` (bounded for reflectances, unbounded for indices, times the colour space's D65 for
//! lights), `blackbody` (peak 1), `spectrum` as λ/value pairs (0 outside them) or a named
//! spectrum (pbrt-v4's `glass-*`, `metal-*-eta`/`-k`, `stdillum-*`).
//!
//! Units: pbrt-v4's radiance numbers are read as W·m⁻²·sr⁻¹·nm⁻¹. Its lights divide their
//! `scale` by ∫ȳ·S dλ (`SpectrumToPhotometric`, raw ȳ), so that ∫ȳ·L dλ = `scale` (times the
//! colour's luminance for an `rgb`), and its film's Y is ∫ȳ·L dλ: spectrace's Y in cd/m² is
//! 683 lm/W times pbrt-v4's pixel Y.

use std::sync::Arc;

use super::params::{Param, Params, R};
use crate::spectrum::ior::{ComplexIor, Ior};
use crate::spectrum::named::{Named, lookup};
use crate::spectrum::{PiecewiseLinear, Spectrum, rgb2spec};

/// spectrace's name for one of pbrt-v4's named spectra (its `Spectra::Init` list).
fn spectrace_name(pbrt: &str) -> Option<String> {
    let glass = |g: &str| Some(format!("glass:{g}"));
    match pbrt {
        "glass-BK7" => glass("N-BK7"),
        "glass-BAF10" => glass("N-BAF10"),
        "glass-FK51A" => glass("N-FK51A"),
        "glass-LASF9" => glass("N-LASF9"),
        // pbrt-v4's F5, F10 and F11 hold Schott's SF5, SF10 and SF11
        "glass-F5" => glass("SF5"),
        "glass-F10" => glass("SF10"),
        "glass-F11" => glass("SF11"),
        "stdillum-A" => Some("cie-a".into()),
        "stdillum-D50" => Some("cie-d50".into()),
        "stdillum-D65" => Some("cie-d65".into()),
        "stdillum-F2" => Some("cie-f2".into()),
        "stdillum-F11" => Some("cie-f11".into()),
        _ => None,
    }
}

/// The metal of a pbrt-v4 `metal-<X>-eta` or `metal-<X>-k` name, as spectrace names it.
fn metal(pbrt: &str) -> Option<(String, bool)> {
    let rest = pbrt.strip_prefix("metal-")?;
    let (m, eta) = match (rest.strip_suffix("-eta"), rest.strip_suffix("-k")) {
        (Some(m), _) => (m, true),
        (None, Some(m)) => (m, false),
        _ => return None,
    };
    let name = ["metal:", "mitsuba:"]
        .iter()
        .map(|p| format!("{p}{m}"))
        .find(|n| matches!(lookup(n), Ok(Named::Conductor(_))))?;
    Some((name, eta))
}

/// A `"spectrum"` parameter's λ/value pairs as a table (0 outside it, as pbrt-v4).
fn pairs(p: &Params, q: &Param) -> R<Arc<PiecewiseLinear>> {
    let v = &q.nums;
    if v.len() < 4 || !v.len().is_multiple_of(2) {
        return Err(p.err(
            q.loc,
            format!(
                "\"{}\": a spectrum needs λ, value pairs (two or more)",
                q.name
            ),
        ));
    }
    let (l, y): (Vec<f32>, Vec<f32>) = v.chunks(2).map(|c| (c[0] as f32, c[1] as f32)).unzip();
    PiecewiseLinear::new(l, y)
        .map(Arc::new)
        .map_err(|e| p.err(q.loc, format!("\"{}\": {e}", q.name)))
}

/// A named spectrum's curve, for a reflectance or an illuminant.
fn named_curve(p: &Params, q: &Param, name: &str) -> R<Spectrum> {
    let ours = spectrace_name(name).unwrap_or_else(|| name.to_string());
    match lookup(&ours) {
        Ok(Named::Curve { spectrum, .. }) => Ok(spectrum),
        Ok(_) => Err(p.err(q.loc, format!("\"{}\": \"{name}\" is an index, not a spectrum of values", q.name))),
        Err(e) => Err(p.err(
            q.loc,
            format!("\"{}\": pbrt-v4's named spectrum or spectrum file \"{name}\" is not read yet ({e})", q.name),
        )),
    }
}

/// A reflectance (`reflectance`): `default` when absent.
pub(super) fn reflectance(p: &Params, name: &str, default: f64) -> R<Spectrum> {
    let Some(q) = p.get(name) else {
        return Ok(Spectrum::Constant(default as f32));
    };
    match (q.ty.as_str(), &q.nums[..], &q.strs[..]) {
        ("rgb" | "color", &[r, g, b], _) => rgb2spec::albedo([r as f32, g as f32, b as f32])
            .map_err(|e| {
                p.err(
                    q.loc,
                    format!(
                        "\"{name}\": {e} (pbrt-v4: an RGB reflectance has no component above 1)"
                    ),
                )
            }),
        ("spectrum", [], [s]) => named_curve(p, q, s),
        ("spectrum", v, []) if !v.is_empty() => Ok(Spectrum::Piecewise(pairs(p, q)?)),
        ("texture", _, _) => Err(p.err(q.loc, format!("\"{name}\": textures are not read yet"))),
        _ => Err(p.err(
            q.loc,
            format!(
                "\"{name}\" must be an rgb or a spectrum here, not \"{}\"",
                q.ty
            ),
        )),
    }
}

/// An index of refraction (`eta`): a number, a spectrum of pairs or a named glass.
pub(super) fn ior(p: &Params, name: &str, default: f64) -> R<Ior> {
    let Some(q) = p.get(name) else {
        return Ok(Ior::Constant(default as f32));
    };
    match (q.ty.as_str(), &q.nums[..], &q.strs[..]) {
        ("float", &[n], _) if n > 0.0 => Ok(Ior::Constant(n as f32)),
        ("spectrum", [], [s]) => {
            let ours = spectrace_name(s).unwrap_or_else(|| s.clone());
            match lookup(&ours) {
                Ok(Named::Dielectric(g)) => Ok(g.ior),
                _ => Err(p.err(
                    q.loc,
                    format!("\"{name}\": \"{s}\" is not a glass spectrace knows"),
                )),
            }
        }
        ("spectrum", v, []) if !v.is_empty() => Ok(Ior::Table(pairs(p, q)?)),
        _ => Err(p.err(
            q.loc,
            format!("\"{name}\" must be a positive float or a spectrum"),
        )),
    }
}

/// A conductor's `eta` and `k` (pbrt-v4's defaults: copper); `reflectance` is not read yet.
pub(super) fn conductor(p: &Params) -> R<ComplexIor> {
    if let Some(q) = p.get("reflectance") {
        return Err(p.err(
            q.loc,
            "a conductor's \"reflectance\" is not read yet; give eta and k",
        ));
    }
    let part = |name: &str, default: &str| -> R<Arc<PiecewiseLinear>> {
        let (named, q) = match p.get(name) {
            None => (default.to_string(), None),
            Some(q) => match (q.ty.as_str(), &q.nums[..], &q.strs[..]) {
                ("spectrum", [], [s]) => (s.clone(), Some(q)),
                ("spectrum", v, []) if !v.is_empty() => return pairs(p, q),
                ("float", &[x], _) => {
                    return PiecewiseLinear::new(vec![360.0, 830.0], vec![x as f32; 2])
                        .map(Arc::new)
                        .map_err(|e| p.err(q.loc, e.to_string()));
                }
                _ => return Err(p.err(q.loc, format!("\"{name}\" must be a float or a spectrum"))),
            },
        };
        let loc = q.map_or(p.loc_of(name), |q| q.loc);
        let Some((ours, is_eta)) = metal(&named) else {
            return Err(p.err(
                loc,
                format!("\"{name}\": \"{named}\" is not a metal spectrace knows"),
            ));
        };
        if is_eta != (name == "eta") {
            return Err(p.err(loc, format!("\"{name}\" given \"{named}\"")));
        }
        match lookup(&ours) {
            Ok(Named::Conductor(m)) => Ok(if is_eta { m.ior.n } else { m.ior.k }),
            _ => Err(p.err(loc, format!("\"{named}\" is not a metal spectrace knows"))),
        }
    };
    Ok(ComplexIor {
        n: part("eta", "metal-Cu-eta")?,
        k: part("k", "metal-Cu-k")?,
    })
}

/// A light's spectrum (`I` or `L`; pbrt-v4's default, the colour space's D65) and the factor
/// pbrt-v4 multiplies its `scale` by: 1/∫ȳ·S dλ, for an `rgb` that of the illuminant alone.
pub(super) fn illuminant(p: &Params, name: &str) -> R<(Spectrum, f64)> {
    let unit_d65 = || Spectrum::Piecewise(rgb2spec::d65_unit_luminance());
    let Some(q) = p.get(name) else {
        return Ok((unit_d65(), 1.0));
    };
    let curve = match (q.ty.as_str(), &q.nums[..], &q.strs[..]) {
        // rsp(λ)·2m times the colour space's D65 of luminance 1 (spectrace's `illuminant`)
        ("rgb" | "color", &[r, g, b], _) => {
            let s = rgb2spec::illuminant([r as f32, g as f32, b as f32])
                .map_err(|e| p.err(q.loc, format!("\"{name}\": {e}")))?;
            return Ok((s, 1.0));
        }
        ("blackbody", &[t], _) if t > 0.0 => {
            Spectrum::Blackbody(crate::spectrum::blackbody::Blackbody::normalized(t as f32))
        }
        ("spectrum", [], [s]) => named_curve(p, q, s)?,
        ("spectrum", v, []) if !v.is_empty() => Spectrum::Piecewise(pairs(p, q)?),
        _ => {
            return Err(p.err(
                q.loc,
                format!("\"{name}\" must be an rgb, a blackbody temperature or a spectrum"),
            ));
        }
    };
    let y = crate::colour::cie::integrate_xyz(|l| f64::from(curve.eval(l)))[1];
    if !(y > 0.0) {
        return Err(p.err(q.loc, format!("\"{name}\" has no luminance (∫ȳ·S dλ = 0)")));
    }
    Ok((curve, 1.0 / y))
}
