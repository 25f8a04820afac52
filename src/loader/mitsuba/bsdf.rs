//! Mitsuba BSDFs → materials, and Mitsuba's named indices of refraction.

use std::sync::Arc;

use super::convert::{Cx, R};
use super::xml::Element;
use crate::loader::desc::*;
use crate::spectrum::ior::{ComplexIor, Ior};
use crate::spectrum::named::{Named, lookup, mitsuba_conductor};
use crate::spectrum::{PiecewiseLinear, Spectrum};

/// Mitsuba's named indices of refraction (constants, as Mitsuba tabulates them).
pub(super) fn named_ior(name: &str) -> Option<f64> {
    Some(match name {
        "vacuum" => 1.0,
        "helium" => 1.000036,
        "hydrogen" => 1.000132,
        "air" => 1.000277,
        "carbon dioxide" => 1.00045,
        "water" => 1.3330,
        "acetone" => 1.36,
        "ethanol" => 1.361,
        "carbon tetrachloride" => 1.461,
        "glycerol" => 1.4729,
        "benzene" => 1.501,
        "silicone oil" => 1.52045,
        "bromine" => 1.661,
        "water ice" => 1.31,
        "fused quartz" => 1.458,
        "pyrex" => 1.470,
        "acrylic glass" => 1.49,
        "polypropylene" => 1.49,
        "bk7" => 1.5046,
        "sodium chloride" => 1.544,
        "amber" => 1.55,
        "pet" => 1.5750,
        "diamond" => 2.419,
        _ => return None,
    })
}

/// A BSDF; returns the material and whether it was wrapped in `twosided`.
pub(super) fn bsdf(cx: &Cx<'_>, b: &Element, name: &str) -> R<(MaterialDesc, bool)> {
    let b = cx.resolve(b)?;
    let t = b.attr("type").unwrap_or("");
    let alpha = |cx: &Cx<'_>| -> R<Option<f64>> {
        if let Some(d) = cx.string(b, "distribution") {
            if d != "ggx" {
                return Err(cx.err(
                    b,
                    format!("distribution \"{d}\" is not supported; use \"ggx\""),
                ));
            }
        }
        Ok(Some(cx.opt_float(b, "alpha")?.unwrap_or(0.1)))
    };
    let ior_of = |cx: &Cx<'_>, key: &str, default: f64| -> R<f64> {
        match cx.child(b, key) {
            None => Ok(default),
            Some(e) if e.tag == "float" => cx.float(e),
            Some(e) => {
                let v = e.attr("value").unwrap_or("");
                named_ior(v).ok_or_else(|| cx.err(e, format!("unknown index name \"{v}\"; use a number or a Mitsuba name such as \"bk7\"")))
            }
        }
    };
    let kind = match t {
        "twosided" => {
            let inner = b
                .children
                .iter()
                .find(|c| c.tag == "bsdf" || c.tag == "ref")
                .ok_or_else(|| cx.err(b, "twosided needs a nested <bsdf>"))?;
            let (m, _) = bsdf(cx, inner, name)?;
            return Ok((m, true));
        }
        "diffuse" => MaterialKind::Diffuse {
            reflectance: cx.spectrum_prop(b, "reflectance", 0.5, false)?,
        },
        "dielectric" | "roughdielectric" => MaterialKind::Dielectric {
            ior: Ior::Constant(ior_of(cx, "int_ior", 1.5046)? as f32),
            exterior_ior: ior_of(cx, "ext_ior", 1.000277)?,
            roughness: if t == "roughdielectric" {
                alpha(cx)?
            } else {
                None
            },
        },
        "conductor" | "roughconductor" => {
            let roughness = if t == "roughconductor" {
                alpha(cx)?
            } else {
                None
            };
            let ior = match (
                cx.string(b, "material"),
                cx.child(b, "eta"),
                cx.child(b, "k"),
            ) {
                // Mitsuba's own preset data (spectra/metals/mitsuba/), not spectrace's metal:*
                (Some(m), _, _) => mitsuba_conductor(&m).map_err(|e| cx.err(b, e))?,
                (None, Some(eta), Some(k)) => {
                    let table = |s: Spectrum| -> Arc<PiecewiseLinear> {
                        match s {
                            Spectrum::Piecewise(t) => t,
                            other => {
                                let l: Vec<f32> =
                                    (300..=900).step_by(5).map(|x| x as f32).collect();
                                let v = l.iter().map(|&x| other.eval(x)).collect();
                                match PiecewiseLinear::new(l, v) {
                                    Ok(t) => Arc::new(t),
                                    Err(_) => Arc::new(
                                        PiecewiseLinear::new(vec![300.0, 900.0], vec![1.0, 1.0])
                                            .unwrap_or_else(|_| unreachable!()),
                                    ), // ok: two valid samples
                                }
                            }
                        }
                    };
                    ComplexIor {
                        n: table(cx.spectrum(eta, false)?),
                        k: table(cx.spectrum(k, false)?),
                    }
                }
                _ => match lookup("metal:Al") {
                    // Mitsuba's default conductor is a perfect mirror; the closest table is Al
                    Ok(Named::Conductor(metal)) => metal.ior,
                    _ => return Err(cx.err(b, "give material, or eta and k")),
                },
            };
            MaterialKind::Conductor {
                ior,
                exterior_ior: ior_of(cx, "ext_ior", 1.000277)?,
                roughness,
            }
        }
        "plastic" | "roughplastic" => {
            return Err(cx.err(b, "plastic has no faithful mapping in spectrace yet; use \"diffuse\", or \"dielectric\" over a \"diffuse\" base in a later version"));
        }
        other => return Err(cx.unsupported(b, "bsdf", other)),
    };
    Ok((
        MaterialDesc {
            name: name.to_string(),
            kind,
            loc: cx.loc(b),
        },
        false,
    ))
}
