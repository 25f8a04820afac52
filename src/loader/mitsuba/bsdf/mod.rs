//! Mitsuba BSDFs → materials, and Mitsuba's named indices of refraction.

use std::sync::Arc;

use super::cx::{Cx, R};
use super::xml::Element;
use crate::loader::desc::*;
use crate::material::microfacet::Distribution;
use crate::spectrum::ior::{ComplexIor, Ior};

mod hair;
mod lobes;
mod nested;
mod principled;

use crate::spectrum::PiecewiseLinear;
use lobes::{conductor, measured, measured_polarized, plastic, pplastic};
use nested::{blend, mask, perturbed};

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
    match BSDFS.iter().find(|(n, _)| *n == t) {
        Some((_, read)) => read(cx, b, name, t),
        None => Err(cx.unsupported(b, "bsdf", t)),
    }
}

/// A BSDF plugin's reader: the element (resolved), the material's name and the plugin's name;
/// returns the material and whether it is two-sided.
type Reader = fn(&Cx<'_>, &Element, &str, &str) -> R<(MaterialDesc, bool)>;

/// The BSDF plugins the importer reads, one line each: the registry that dispatch, the
/// "supported" lists and the suggestions of its errors come from (`plugins.rs`).
pub(in crate::loader::mitsuba) const BSDFS: &[(&str, Reader)] = &[
    ("diffuse", |cx, b, n, _| {
        let reflectance = cx.texture_prop(b, "reflectance", 0.5)?;
        plain(cx, b, n, MaterialKind::Diffuse { reflectance })
    }),
    ("twosided", twosided),
    ("conductor", conductor_or_dielectric),
    ("roughconductor", conductor_or_dielectric),
    ("dielectric", conductor_or_dielectric),
    ("roughdielectric", conductor_or_dielectric),
    // Mitsuba's plastics: defaults diffuse_reflectance 0.5, int_ior polypropylene (1.49),
    // ext_ior air, nonlinear false; roughplastic's alpha is isotropic only
    ("plastic", |cx, b, n, t| plain(cx, b, n, plastic(cx, b, t)?)),
    ("roughplastic", |cx, b, n, t| {
        plain(cx, b, n, plastic(cx, b, t)?)
    }),
    // the polarising plastic: alpha 0.1, Beckmann, int_ior polypropylene by default
    ("pplastic", |cx, b, n, _| plain(cx, b, n, pplastic(cx, b)?)),
    // a measured pBRDF table (`.pbsdf`); alpha_sample 0.1
    ("measured_polarized", |cx, b, n, _| {
        plain(cx, b, n, measured_polarized(cx, b)?)
    }),
    // an RGL measured BRDF (`.bsdf`), as pbrt-v4's `measured` reads it
    ("measured", |cx, b, n, _| plain(cx, b, n, measured(cx, b)?)),
    // light passes straight through; each crossing still counts toward max_depth
    ("null", |cx, b, n, _| plain(cx, b, n, MaterialKind::Null)),
    ("thindielectric", thindielectric),
    // thin polarising elements crossed undeviated: a scene holding one renders polarised
    ("polarizer", element),
    ("retarder", element),
    // Mitsuba's opacity mask around one nested BSDF (whose twosided flag it keeps)
    ("mask", |cx, b, n, _| mask(cx, b, n)),
    // Mitsuba's blend of two nested BSDFs by `weight` (0.5; 0 is the first, 1 the second)
    ("blendbsdf", |cx, b, n, _| blend(cx, b, n)),
    // Mitsuba's normal and bump maps around one nested BSDF (whose twosided flag they keep):
    // `normalmap` reads the texture named "normalmap", `bumpmap` its one nested texture,
    // whatever its name, times `scale` (1)
    ("normalmap", perturbed),
    ("bumpmap", perturbed),
    // the Disney/Burley model, solid and as a thin sheet
    ("principled", principled::principled),
    ("principledthin", principled::principled),
    // Chiang et al.'s fibre, for curves
    ("hair", hair::hair),
];

/// A one-sided material of `kind` named `name`, located at `b`.
fn plain(cx: &Cx<'_>, b: &Element, name: &str, kind: MaterialKind) -> R<(MaterialDesc, bool)> {
    let m = MaterialDesc {
        name: name.to_string(),
        kind,
        loc: cx.loc(b),
    };
    Ok((m, false))
}

/// `twosided`: its nested BSDF, seen from both sides.
fn twosided(cx: &Cx<'_>, b: &Element, name: &str, _: &str) -> R<(MaterialDesc, bool)> {
    let inner = b
        .children
        .iter()
        .find(|c| c.tag == "bsdf" || c.tag == "ref")
        .ok_or_else(|| cx.err(b, "twosided needs a nested <bsdf>"))?;
    let (m, _) = bsdf(cx, inner, name)?;
    Ok((m, true))
}

/// Conductors and dielectrics, smooth or rough, with their textured roughness and lobe
/// factors (`textured`).
fn conductor_or_dielectric(
    cx: &Cx<'_>,
    b: &Element,
    name: &str,
    t: &str,
) -> R<(MaterialDesc, bool)> {
    let kind = match t {
        "dielectric" | "roughdielectric" => MaterialKind::Dielectric {
            ior: Ior::Constant(ior_of(cx, b, "int_ior", 1.5046)? as f32),
            exterior_ior: ior_of(cx, b, "ext_ior", 1.000277)?,
            roughness: if t == "roughdielectric" {
                alpha(cx, b)?
            } else {
                None
            },
            distribution: distribution(cx, b)?,
            // Mitsuba's G is G1(wo)·G1(wi) (`MicrofacetDistribution::G`)
            smith: Smith::Separable,
        },
        _ => conductor(cx, b, t)?,
    };
    plain(cx, b, name, textured(cx, b, t, kind)?)
}

/// `thindielectric`: its indices (its lobe factors are Mitsuba's default 1 only).
fn thindielectric(cx: &Cx<'_>, b: &Element, name: &str, _: &str) -> R<(MaterialDesc, bool)> {
    for k in ["specular_reflectance", "specular_transmittance"] {
        if let Some(c) = cx.child(b, k) {
            return Err(cx.err(
                c,
                format!("a thindielectric's {k} is not supported (it is 1, Mitsuba's default)"),
            ));
        }
    }
    let kind = MaterialKind::ThinDielectric {
        int_ior: ior_of(cx, b, "int_ior", 1.5046)?,
        exterior_ior: ior_of(cx, b, "ext_ior", 1.000277)?,
    };
    plain(cx, b, name, kind)
}

/// `polarizer` (`theta` in degrees, default 0; `transmittance`, 1; `polarizing`, true) and
/// `retarder` (`theta`, 0; `delta`, the retardance in degrees, 90): constant values only.
fn element(cx: &Cx<'_>, b: &Element, name: &str, t: &str) -> R<(MaterialDesc, bool)> {
    use crate::units::{Angle, angle::degree};
    let number = |key: &str, default: f64| -> R<f64> {
        match cx.child(b, key) {
            None => Ok(default),
            Some(c) if c.tag == "texture" => Err(cx.err(
                c,
                format!("a {t}'s {key} must be a constant (a texture is not supported)"),
            )),
            Some(c) => cx.float(c),
        }
    };
    let theta = Angle::new::<degree>(number("theta", 0.0)?);
    let kind = if t == "polarizer" {
        let transmittance = number("transmittance", 1.0)?;
        if !(0.0..=1.0).contains(&transmittance) {
            let c = cx.child(b, "transmittance").unwrap_or(b);
            return Err(cx.err(
                c,
                format!("a polarizer's transmittance must lie in [0, 1], not {transmittance}"),
            ));
        }
        let polarizing = match cx.child(b, "polarizing") {
            None => true,
            Some(c) => match c.attr("value") {
                Some("true") => true,
                Some("false") => false,
                v => {
                    return Err(cx.err(
                        c,
                        format!("polarizing must be true or false, not {}", v.unwrap_or("")),
                    ));
                }
            },
        };
        MaterialKind::Polariser {
            angle: theta,
            transmittance,
            polarizing,
        }
    } else {
        MaterialKind::Retarder {
            angle: theta,
            retardance: Angle::new::<degree>(number("delta", 90.0)?),
        }
    };
    plain(cx, b, name, kind)
}

/// Mitsuba's rough BSDFs' `distribution`: beckmann (its default) or ggx.
fn distribution(cx: &Cx<'_>, b: &Element) -> R<Distribution> {
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
}

/// Mitsuba's rough BSDFs' roughness: `alpha` (default 0.1), or `alpha_u` (along ∂p/∂u) and
/// `alpha_v` for an anisotropic lobe; a placeholder when textures give it (see `textured`).
fn alpha(cx: &Cx<'_>, b: &Element) -> R<Option<[f64; 2]>> {
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
}

/// An index of refraction `key`: a number or one of Mitsuba's named indices (`default` if
/// absent).
fn ior_of(cx: &Cx<'_>, b: &Element, key: &str, default: f64) -> R<f64> {
    match cx.child(b, key) {
        None => Ok(default),
        Some(e) if e.tag == "float" => cx.float(e),
        Some(e) => {
            let v = e.attr("value").unwrap_or("");
            named_ior(v).ok_or_else(|| {
                cx.err(
                    e,
                    format!(
                        "unknown index name \"{v}\"; use a number or a Mitsuba name such as \"bk7\""
                    ),
                )
            })
        }
    }
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
        let a = cx.scalar_texture_prop(b, "alpha", 0.1)?;
        return Ok(Some([a.clone(), a]));
    }
    if is_texture(cx, b, "alpha_u")? || is_texture(cx, b, "alpha_v")? {
        if cx.child(b, "alpha_u").is_none() || cx.child(b, "alpha_v").is_none() {
            return Err(cx.err(b, "give both alpha_u and alpha_v"));
        }
        return Ok(Some([
            cx.scalar_texture_prop(b, "alpha_u", 0.1)?,
            cx.scalar_texture_prop(b, "alpha_v", 0.1)?,
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
        remap: false,
        reflectance: cx.texture_prop(b, "specular_reflectance", 1.0)?,
        transmittance: cx.texture_prop(b, "specular_transmittance", 1.0)?,
        inner: Box::new(kind),
    })
}
