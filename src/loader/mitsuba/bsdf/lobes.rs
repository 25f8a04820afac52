//! Mitsuba's conductors (`conductor`, `roughconductor`: named presets or eta and k) and
//! plastics (`plastic`, `roughplastic`, the polarising `pplastic`).

use std::sync::Arc;

use super::super::cx::{Cx, R};
use super::super::xml::Element;
use crate::loader::desc::*;
use crate::spectrum::ior::ComplexIor;
use crate::spectrum::named::mitsuba_conductor;
use crate::spectrum::{PiecewiseLinear, Spectrum};

use super::{alpha, alpha_textures, distribution, ior_of, perfect_mirror};

/// Mitsuba's `conductor` and `roughconductor` (`t`).
pub(super) fn conductor(cx: &Cx<'_>, b: &Element, t: &str) -> R<MaterialKind> {
    let roughness = if t == "roughconductor" {
        alpha(cx, b)?
    } else {
        None
    };
    // material "none" (Mitsuba's default) means eta and k, defaulting to 0 and 1
    let ior = match (
        cx.string(b, "material").filter(|m| m != "none"),
        cx.child(b, "eta"),
        cx.child(b, "k"),
    ) {
        (Some(_), Some(c), _) | (Some(_), None, Some(c)) => {
            return Err(cx.err(
                c,
                "give either material or eta and k, not both (as Mitsuba requires)",
            ));
        }
        // Mitsuba's default: material "none", eta = 0, k = 1, a perfect mirror
        (None, None, None) => perfect_mirror(),
        // Mitsuba's own preset data (spectra/metals/mitsuba/), not spectrace's metal:*
        (Some(m), _, _) => {
            let (ior, note) = mitsuba_conductor(&m).map_err(|e| cx.err(b, e))?;
            if let Some(n) = note {
                cx.note(b, n);
            }
            ior
        }
        (None, eta, k) => {
            let table = |s: Spectrum| -> Arc<PiecewiseLinear> {
                match s {
                    Spectrum::Piecewise(t) => t,
                    other => {
                        let l: Vec<f32> = (300..=900).step_by(5).map(|x| x as f32).collect();
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
            // Mitsuba's defaults with material "none": eta = 0, k = 1
            let spec = |c: Option<&Element>, default: f32| -> R<Spectrum> {
                match c {
                    Some(c) => cx.spectrum(c, false),
                    None => Ok(Spectrum::Constant(default)),
                }
            };
            ComplexIor {
                n: table(spec(eta, 0.0)?),
                k: table(spec(k, 1.0)?),
            }
        }
    };
    if let Some(c) = cx.child(b, "ext_ior") {
        return Err(cx.err(
            c,
            "Mitsuba's conductors take no ext_ior (eta and k are relative to vacuum)",
        ));
    }
    Ok(MaterialKind::Conductor {
        ior,
        // Mitsuba's eta, k are the metal's own, relative to vacuum
        exterior_ior: 1.0,
        roughness,
        distribution: distribution(cx, b)?,
        // Mitsuba's G is G1(wo)·G1(wi) (`MicrofacetDistribution::G`)
        smith: Smith::Separable,
    })
}

/// Mitsuba's `plastic` and `roughplastic` (`t`).
pub(super) fn plastic(cx: &Cx<'_>, b: &Element, t: &str) -> R<MaterialKind> {
    let specular = match cx.child(b, "specular_reflectance") {
        None => 1.0,
        Some(c) => match grey(cx, c)? {
            Some(v) if v >= 0.0 => v,
            _ => {
                return Err(cx.err(
                    c,
                    "a plastic's specular_reflectance must be one number ≥ 0 here, or a grey rgb (a spectrum or texture is not supported)",
                ));
            }
        },
    };
    for k in ["alpha_u", "alpha_v"] {
        if let Some(c) = cx.child(b, k) {
            return Err(cx.err(
                c,
                "roughplastic is isotropic in Mitsuba: give alpha, not alpha_u/alpha_v",
            ));
        }
    }
    let nonlinear = match cx.string(b, "nonlinear").as_deref() {
        None | Some("false") => false,
        Some("true") => true,
        Some(o) => {
            return Err(cx.err(b, format!("nonlinear: expected true or false, found {o}")));
        }
    };
    Ok(MaterialKind::Plastic {
        diffuse: cx.texture_prop(b, "diffuse_reflectance", 0.5)?,
        specular,
        int_ior: ior_of(cx, b, "int_ior", 1.49)?,
        exterior_ior: ior_of(cx, b, "ext_ior", 1.000277)?,
        nonlinear,
        roughness: if t == "roughplastic" {
            alpha(cx, b)?.map(|a| a[0])
        } else {
            None
        },
        distribution: distribution(cx, b)?,
    })
}

/// `pplastic`: `diffuse_reflectance` (0.5), `specular_reflectance` (one number, 1), `int_ior`
/// (polypropylene, 1.49), `ext_ior` (air), `alpha` or `alpha_u`/`alpha_v` (0.1),
/// `distribution` (beckmann), as Mitsuba 3.9.1 reads them.
pub(super) fn pplastic(cx: &Cx<'_>, b: &Element) -> R<MaterialKind> {
    let specular = match cx.child(b, "specular_reflectance") {
        None => 1.0,
        Some(c) => match grey(cx, c)? {
            Some(v) if v >= 0.0 => v,
            _ => {
                return Err(cx.err(
                    c,
                    "a pplastic's specular_reflectance must be one number ≥ 0 here (a spectrum or texture is not supported)",
                ));
            }
        },
    };
    if alpha_textures(cx, b)?.is_some() {
        return Err(cx.err(
            b,
            "a pplastic's alpha must be a number (a texture is not supported)",
        ));
    }
    Ok(MaterialKind::PPlastic {
        diffuse: cx.texture_prop(b, "diffuse_reflectance", 0.5)?,
        specular,
        int_ior: ior_of(cx, b, "int_ior", 1.49)?,
        exterior_ior: ior_of(cx, b, "ext_ior", 1.000277)?,
        roughness: alpha(cx, b)?.unwrap_or([0.1, 0.1]),
        distribution: distribution(cx, b)?,
    })
}

/// A constant factor given as a number, a constant spectrum or a grey `rgb` (three equal
/// values, which Mitsuba's reflectance upsampling turns into that constant); None otherwise.
fn grey(cx: &Cx<'_>, c: &Element) -> R<Option<f64>> {
    if c.tag == "rgb" {
        let v = cx.floats(c, c.attr("value").unwrap_or(""))?;
        return Ok(match v.as_slice() {
            [x] => Some(*x),
            [r, g, b] if r == g && g == b => Some(*r),
            _ => None,
        });
    }
    Ok(match cx.spectrum(c, false)? {
        Spectrum::Constant(v) => Some(v as f64),
        _ => None,
    })
}

/// `measured_polarized`: `filename` (a `.pbsdf` tensor file, found as Mitsuba's file resolver
/// finds it), `alpha_sample` (0.1, > 0), `wavelength` (−1: every wavelength its own; else a
/// wavelength in nm used for all), as Mitsuba 3.9.1 reads them.
pub(super) fn measured_polarized(cx: &Cx<'_>, b: &Element) -> R<MaterialKind> {
    let at = |key: &str| cx.child(b, key).unwrap_or(b);
    let table = table_file(
        cx,
        b,
        ("measured_polarized", "a .pbsdf file", "pBSDF"),
        super::super::tensor::read_pbsdf,
    )?;
    let alpha_sample = cx.opt_float(b, "alpha_sample")?.unwrap_or(0.1);
    if !(alpha_sample > 0.0 && alpha_sample.is_finite()) {
        return Err(cx.err(
            at("alpha_sample"),
            format!("alpha_sample must be a positive number, not {alpha_sample}"),
        ));
    }
    let wavelength = match cx.opt_float(b, "wavelength")? {
        None => None,
        Some(-1.0) => None,
        Some(l) if l > 0.0 && l.is_finite() => Some(l),
        Some(l) => {
            return Err(cx.err(
                at("wavelength"),
                format!("wavelength must be −1 (every wavelength) or a wavelength in nm, not {l}"),
            ));
        }
    };
    Ok(MaterialKind::MeasuredPolarized {
        table,
        alpha_sample,
        wavelength,
    })
}

/// `measured`: `filename` (an RGL `.bsdf` file, Dupuy & Jakob 2018), read as Mitsuba 3.9.1
/// reads it: R·D/(4σ) when the file's `jacobian` flag is set, else R as f·cos θ. Files
/// covering a half or a quarter of the azimuths (Mitsuba's `reduction` 2 and 4) are refused.
pub(super) fn measured(cx: &Cx<'_>, b: &Element) -> R<MaterialKind> {
    let table = table_file(
        cx,
        b,
        ("measured", "an RGL .bsdf file", "RGL BSDF"),
        super::super::rgl::read_rgl_bsdf,
    )?;
    Ok(MaterialKind::Measured {
        jacobian: table.jacobian,
        table: std::sync::Arc::new(table),
    })
}

/// The table a measured BSDF's `filename` names (found as Mitsuba's file resolver finds it),
/// read by `read`; errors located at the BSDF or its `filename`. `names`: the plugin, what
/// its file is, and what the file is called in an error.
fn table_file<T>(
    cx: &Cx<'_>,
    b: &Element,
    (plugin, what, kind): (&str, &str, &str),
    read: fn(&std::path::Path) -> Result<T, String>,
) -> R<T> {
    let at = cx.child(b, "filename").unwrap_or(b);
    let name = cx
        .string(b, "filename")
        .ok_or_else(|| cx.err(b, format!("{plugin} needs a filename ({what})")))?;
    let path = cx.resolve_file(&name);
    if !path.is_file() {
        return Err(cx.err(at, format!("{kind} file {} does not exist", path.display())));
    }
    read(&path).map_err(|e| cx.err(at, e))
}
