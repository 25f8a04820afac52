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

/// spectrace's name for one of pbrt-v4's standard illuminants (the CIE's tables, the same data).
fn spectrace_name(pbrt: &str) -> Option<&'static str> {
    Some(match pbrt {
        "stdillum-A" => "cie-a",
        "stdillum-D50" => "cie-d50",
        "stdillum-D65" => "cie-d65",
        "stdillum-F2" => "cie-f2",
        "stdillum-F11" => "cie-f11",
        _ => return None,
    })
}

/// One of pbrt-v4's named glass or metal tables (`spectra/pbrt/`, pbrt-v4's own arrays),
/// extended with its end values to 359 and 831 nm as pbrt-v4's `FromInterleaved` does.
fn pbrt_table(name: &str) -> Option<Arc<PiecewiseLinear>> {
    let (_, file) = crate::data::embedded::PBRT_SPECTRA
        .iter()
        .find(|(n, _)| *n == name)?;
    let t = crate::data::embedded_table(*file);
    let curve = crate::spectrum::data::table_to_curve(&t, 0, 1, file.0).ok()?;
    let (l, v) = (curve.wavelengths().to_vec(), curve.values().to_vec());
    crate::sensor::pbrt::extended_table(l, v).map(Arc::new)
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
    if let Some(t) = pbrt_table(name) {
        return Ok(Spectrum::Piecewise(t));
    }
    let ours = spectrace_name(name).unwrap_or(name);
    match lookup(ours) {
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
        // Planck's curve of peak 1, a reflectance in [0, 1]
        ("blackbody", &[t], _) if t > 0.0 => Ok(Spectrum::Blackbody(
            crate::spectrum::blackbody::Blackbody::normalized(t as f32),
        )),
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
        // pbrt-v4's glass-* names, with its own tables
        ("spectrum", [], [s]) => match pbrt_table(s) {
            Some(t) if s.starts_with("glass-") => Ok(Ior::Table(t)),
            _ => Err(p.err(
                q.loc,
                format!("\"{name}\": \"{s}\" is not one of pbrt-v4's glasses (glass-BK7, glass-BAF10, glass-FK51A, glass-LASF9, glass-F5, glass-F10, glass-F11)"),
            )),
        },
        ("spectrum", v, []) if !v.is_empty() => Ok(Ior::Table(pairs(p, q)?)),
        _ => Err(p.err(
            q.loc,
            format!("\"{name}\" must be a positive float or a spectrum"),
        )),
    }
}

/// A conductor's index: `<prefix>eta` and `<prefix>k` (pbrt-v4's defaults: copper), or, when
/// `reflectance` r is given (with neither, as pbrt-v4 requires), None: pbrt-v4 then takes
/// n = 1, k = 2√r/√(1 − r).
pub(super) fn conductor(p: &Params, prefix: &str) -> R<Option<ComplexIor>> {
    let (eta_name, k_name) = (format!("{prefix}eta"), format!("{prefix}k"));
    if let Some(q) = p.get("reflectance") {
        if p.get(&eta_name).is_some() || p.get(&k_name).is_some() {
            return Err(p.err(
                q.loc,
                format!(
                    "\"reflectance\" and \"{eta_name}\"/\"{k_name}\" cannot both be given (pbrt-v4)"
                ),
            ));
        }
        return Ok(None);
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
        match pbrt_table(&named) {
            Some(t) if named.starts_with("metal-") => Ok(t),
            _ => Err(p.err(
                loc,
                format!("\"{name}\": \"{named}\" is not one of pbrt-v4's metals (metal-<Ag, Al, Au, Cu, CuZn, MgO or TiO2>-eta and -k)"),
            )),
        }
    };
    Ok(Some(ComplexIor {
        n: part(&eta_name, "metal-Cu-eta")?,
        k: part(&k_name, "metal-Cu-k")?,
    }))
}

/// The index pbrt-v4 makes of a conductor's reflectance r: n = 1, k = 2√r/√(1 − r) with r
/// clamped to [0, 0.9999], tabulated every nanometre from 360 to 830 nm.
pub(super) fn conductor_of_reflectance(r: &Spectrum) -> ComplexIor {
    let lambda: Vec<f32> = (360..=830).map(|l| l as f32).collect();
    let k = lambda
        .iter()
        .map(|&l| {
            let x = r.eval(l).clamp(0.0, 0.9999);
            2.0 * x.sqrt() / (1.0 - x).sqrt()
        })
        .collect();
    let table = |v| Arc::new(PiecewiseLinear::new(lambda.clone(), v).expect("increasing"));
    ComplexIor {
        n: table(vec![1.0; lambda.len()]),
        k: table(k),
    }
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
