//! Mitsuba BSDFs → materials, and Mitsuba's named indices of refraction.

use std::sync::Arc;

use super::cx::{Cx, R};
use super::xml::Element;
use crate::loader::desc::*;
use crate::material::microfacet::Distribution;
use crate::spectrum::ior::{ComplexIor, Ior};
use crate::spectrum::named::mitsuba_conductor;
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

/// Mitsuba's conductor with material "none": eta = 0, k = 1, reflectance 1 at every angle.
fn perfect_mirror() -> ComplexIor {
    let flat = |v: f32| {
        Arc::new(
            PiecewiseLinear::new(vec![300.0, 900.0], vec![v, v]).unwrap_or_else(|_| unreachable!()), // ok: two increasing samples
        )
    };
    ComplexIor {
        n: flat(0.0),
        k: flat(1.0),
    }
}

/// A BSDF; returns the material and whether it was wrapped in `twosided`.
pub(super) fn bsdf(cx: &Cx<'_>, b: &Element, name: &str) -> R<(MaterialDesc, bool)> {
    let depth = cx.bsdf_depth.get();
    if depth >= MAX_BSDF_NESTING {
        return Err(cx.err(
            b,
            format!(
                "BSDFs nest more than {MAX_BSDF_NESTING} deep here (do two BSDFs refer to each other?)"
            ),
        ));
    }
    cx.bsdf_depth.set(depth + 1);
    let r = bsdf_inner(cx, b, name);
    cx.bsdf_depth.set(depth);
    r
}

/// BSDFs nested in one another (`twosided`, `blendbsdf`, `mask`, … and `ref`s) at most.
const MAX_BSDF_NESTING: u32 = 32;

fn bsdf_inner(cx: &Cx<'_>, b: &Element, name: &str) -> R<(MaterialDesc, bool)> {
    let b = cx.resolve(b)?;
    let t = b.attr("type").unwrap_or("");
    // Mitsuba's rough BSDFs: `distribution` beckmann (its default) or ggx; `alpha` (default
    // 0.1), or `alpha_u` (along ∂p/∂u) and `alpha_v` for an anisotropic lobe.
    let distribution = || -> R<Distribution> {
        match cx.child(b, "distribution") {
            None => Ok(Distribution::Beckmann),
            Some(d) => match d.attr("value").unwrap_or("") {
                "beckmann" => Ok(Distribution::Beckmann),
                "ggx" => Ok(Distribution::Ggx),
                v => Err(cx.err(
                    d,
                    format!("distribution \"{v}\" is not one of \"beckmann\", \"ggx\""),
                )),
            },
        }
    };
    let alpha = |cx: &Cx<'_>| -> R<Option<[f64; 2]>> {
        if alpha_textures(cx, b)?.is_some() {
            // the textures, looked up at each hit, replace this (see `textured`)
            return Ok(Some([0.1, 0.1]));
        }
        let iso = cx.opt_float(b, "alpha")?;
        let (u, v) = (cx.opt_float(b, "alpha_u")?, cx.opt_float(b, "alpha_v")?);
        let a = match (iso, u, v) {
            (Some(a), None, None) => [a, a],
            (None, None, None) => [0.1, 0.1],
            (None, Some(u), Some(v)) => [u, v],
            (None, _, _) => return Err(cx.err(b, "give both alpha_u and alpha_v")),
            (Some(_), _, _) => {
                return Err(cx.err(b, "give either alpha or alpha_u and alpha_v, not both"));
            }
        };
        if let Some(a) = a.iter().find(|a| !(**a > 0.0)) {
            return Err(cx.err(b, format!("alpha must be positive, not {a}")));
        }
        Ok(Some(a))
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
        // light passes straight through; each crossing still counts toward max_depth
        "null" => MaterialKind::Null,
        // Mitsuba's blend of two nested BSDFs by `weight` (0.5; 0 is the first, 1 the second)
        "blendbsdf" => {
            let mut nested = Vec::new();
            for c in &b.children {
                if c.tag == "bsdf" || (c.tag == "ref" && cx.resolve(c)?.tag == "bsdf") {
                    nested.push(c);
                }
            }
            let [first, second] = nested[..] else {
                return Err(cx.err(
                    b,
                    format!(
                        "a blendbsdf needs exactly two nested BSDFs, found {}",
                        nested.len()
                    ),
                ));
            };
            let (m0, two0) = bsdf(cx, first, name)?;
            let (m1, two1) = bsdf(cx, second, name)?;
            if two0 != two1 {
                return Err(cx.err(
                    b,
                    "a blendbsdf of a twosided and a one-sided BSDF is not supported; wrap the blendbsdf in twosided instead",
                ));
            }
            for m in [&m0.kind, &m1.kind] {
                if matches!(m, MaterialKind::Mask { .. } | MaterialKind::Blend { .. }) {
                    return Err(cx.err(
                        b,
                        "a blendbsdf holding a mask or another blendbsdf is not supported",
                    ));
                }
            }
            if let Some(o) = cx.child(b, "weight")
                && cx.resolve(o)?.attr("type") == Some("checkerboard")
            {
                return Err(cx.err(
                    o,
                    "a checkerboard weight is not supported; use a number or a grey image",
                ));
            }
            return Ok((
                MaterialDesc {
                    name: name.to_string(),
                    kind: MaterialKind::Blend {
                        weight: cx.texture_prop(b, "weight", 0.5)?,
                        a: Box::new(m0.kind),
                        b: Box::new(m1.kind),
                    },
                    loc: cx.loc(b),
                },
                two0,
            ));
        }
        // Mitsuba's normal and bump maps around one nested BSDF (whose twosided flag they
        // keep): `normalmap` reads the texture named "normalmap", `bumpmap` its one nested
        // texture, whatever its name, times `scale` (1)
        "normalmap" | "bumpmap" => {
            let mut nested = Vec::new();
            let mut tex = Vec::new();
            for c in &b.children {
                match (c.tag.as_str(), cx.resolve(c)?.tag.as_str()) {
                    ("bsdf", _) | ("ref", "bsdf") => nested.push(c),
                    ("texture", _) | ("ref", "texture") => tex.push(c),
                    _ => {}
                }
            }
            let [inner] = nested[..] else {
                return Err(cx.err(
                    b,
                    format!(
                        "a {t} needs exactly one nested BSDF, found {}",
                        nested.len()
                    ),
                ));
            };
            let (m, two) = bsdf(cx, inner, name)?;
            if matches!(
                m.kind,
                MaterialKind::NormalMap { .. } | MaterialKind::BumpMap { .. }
            ) {
                return Err(cx.err(
                    inner,
                    format!("a {t} holding another normal or bump map is not supported"),
                ));
            }
            let map = if t == "normalmap" {
                tex.retain(|c| c.attr("name") == Some("normalmap"));
                tex.first().copied().ok_or_else(|| {
                    cx.err(
                        b,
                        "a normalmap needs a <texture name=\"normalmap\" type=\"bitmap\">",
                    )
                })?
            } else {
                let [h] = tex[..] else {
                    return Err(cx.err(
                        b,
                        format!(
                            "a bumpmap needs exactly one nested texture, found {}",
                            tex.len()
                        ),
                    ));
                };
                h
            };
            if cx.resolve(map)?.attr("type") != Some("bitmap") {
                return Err(cx.err(map, format!("a {t}'s texture must be a bitmap here")));
            }
            let texture = cx.texture_of(map)?;
            let inner = Box::new(m.kind);
            let kind = if t == "normalmap" {
                MaterialKind::NormalMap {
                    map: texture,
                    inner,
                }
            } else {
                MaterialKind::BumpMap {
                    height: texture,
                    scale: cx.opt_float(b, "scale")?.unwrap_or(1.0),
                    inner,
                }
            };
            return Ok((
                MaterialDesc {
                    name: name.to_string(),
                    kind,
                    loc: cx.loc(b),
                },
                two,
            ));
        }
        // Mitsuba's opacity mask around one nested BSDF (whose twosided flag it keeps)
        "mask" => {
            let inner = b
                .children
                .iter()
                .find(|c| c.tag == "bsdf" || c.tag == "ref")
                .ok_or_else(|| cx.err(b, "a mask needs a nested <bsdf>"))?;
            let (m, two) = bsdf(cx, inner, name)?;
            if let Some(o) = cx.child(b, "opacity")
                && cx.resolve(o)?.attr("type") == Some("checkerboard")
            {
                return Err(cx.err(
                    o,
                    "a checkerboard opacity is not supported (Mitsuba 3.9.1 swaps its colours for opacities); use a number or a grey image",
                ));
            }
            return Ok((
                MaterialDesc {
                    name: name.to_string(),
                    kind: MaterialKind::Mask {
                        opacity: cx.texture_prop(b, "opacity", 0.5)?,
                        inner: Box::new(m.kind),
                    },
                    loc: cx.loc(b),
                },
                two,
            ));
        }
        "thindielectric" => {
            for k in ["specular_reflectance", "specular_transmittance"] {
                if let Some(c) = cx.child(b, k) {
                    return Err(cx.err(
                        c,
                        format!(
                            "a thindielectric's {k} is not supported (it is 1, Mitsuba's default)"
                        ),
                    ));
                }
            }
            MaterialKind::ThinDielectric {
                int_ior: ior_of(cx, "int_ior", 1.5046)?,
                exterior_ior: ior_of(cx, "ext_ior", 1.000277)?,
            }
        }
        "diffuse" => MaterialKind::Diffuse {
            reflectance: cx.texture_prop(b, "reflectance", 0.5)?,
        },
        "dielectric" | "roughdielectric" => MaterialKind::Dielectric {
            ior: Ior::Constant(ior_of(cx, "int_ior", 1.5046)? as f32),
            exterior_ior: ior_of(cx, "ext_ior", 1.000277)?,
            roughness: if t == "roughdielectric" {
                alpha(cx)?
            } else {
                None
            },
            distribution: distribution()?,
        },
        "conductor" | "roughconductor" => {
            let roughness = if t == "roughconductor" {
                alpha(cx)?
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
            MaterialKind::Conductor {
                ior,
                // Mitsuba's eta, k are the metal's own, relative to vacuum
                exterior_ior: 1.0,
                roughness,
                distribution: distribution()?,
            }
        }
        // Mitsuba's plastics: defaults diffuse_reflectance 0.5, int_ior polypropylene (1.49),
        // ext_ior air, nonlinear false; roughplastic's alpha is isotropic only
        "plastic" | "roughplastic" => {
            let specular = match cx.child(b, "specular_reflectance") {
                None => 1.0,
                Some(c) => match cx.spectrum(c, false)? {
                    Spectrum::Constant(v) if v >= 0.0 => v as f64,
                    _ => {
                        return Err(cx.err(
                            c,
                            "a plastic's specular_reflectance must be one number ≥ 0 here (a spectrum or texture is not supported)",
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
            MaterialKind::Plastic {
                diffuse: cx.texture_prop(b, "diffuse_reflectance", 0.5)?,
                specular,
                int_ior: ior_of(cx, "int_ior", 1.49)?,
                exterior_ior: ior_of(cx, "ext_ior", 1.000277)?,
                nonlinear,
                roughness: if t == "roughplastic" {
                    alpha(cx)?.map(|a| a[0])
                } else {
                    None
                },
                distribution: distribution()?,
            }
        }
        other => return Err(cx.unsupported(b, "bsdf", other)),
    };
    let kind = if matches!(
        t,
        "conductor" | "roughconductor" | "dielectric" | "roughdielectric"
    ) {
        textured(cx, b, t, kind)?
    } else {
        kind
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

/// Whether a property is given as a texture (a `<texture>` or a reference to one).
fn is_texture(cx: &Cx<'_>, b: &Element, name: &str) -> R<bool> {
    match cx.child(b, name) {
        Some(c) => Ok(cx.resolve(c)?.tag == "texture"),
        None => Ok(false),
    }
}

/// A rough BSDF's α as textures ([α_u, α_v]) when `alpha`, `alpha_u` or `alpha_v` is one; a
/// number beside a texture becomes a uniform texture.
fn alpha_textures(cx: &Cx<'_>, b: &Element) -> R<Option<[TextureDesc; 2]>> {
    if is_texture(cx, b, "alpha")? {
        let a = cx.texture_prop(b, "alpha", 0.1)?;
        return Ok(Some([a.clone(), a]));
    }
    if is_texture(cx, b, "alpha_u")? || is_texture(cx, b, "alpha_v")? {
        if cx.child(b, "alpha_u").is_none() || cx.child(b, "alpha_v").is_none() {
            return Err(cx.err(b, "give both alpha_u and alpha_v"));
        }
        return Ok(Some([
            cx.texture_prop(b, "alpha_u", 0.1)?,
            cx.texture_prop(b, "alpha_v", 0.1)?,
        ]));
    }
    Ok(None)
}

/// Wraps a conductor or dielectric in [`MaterialKind::Textured`] when Mitsuba's scene gives it a
/// textured α or a `specular_reflectance` / `specular_transmittance` (1 by default).
fn textured(cx: &Cx<'_>, b: &Element, t: &str, kind: MaterialKind) -> R<MaterialKind> {
    let alpha = if t.starts_with("rough") {
        alpha_textures(cx, b)?
    } else {
        None
    };
    let refl = cx.child(b, "specular_reflectance").is_some();
    let dielectric = t.ends_with("dielectric");
    let trans = cx.child(b, "specular_transmittance").is_some();
    if trans && !dielectric {
        let c = cx.child(b, "specular_transmittance").unwrap_or(b);
        return Err(cx.err(c, "a conductor has no specular_transmittance"));
    }
    if alpha.is_none() && !refl && !trans {
        return Ok(kind);
    }
    Ok(MaterialKind::Textured {
        alpha: alpha.map(Box::new),
        reflectance: cx.texture_prop(b, "specular_reflectance", 1.0)?,
        transmittance: cx.texture_prop(b, "specular_transmittance", 1.0)?,
        inner: Box::new(kind),
    })
}
