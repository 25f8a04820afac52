//! Mitsuba's BSDFs around nested ones: `blendbsdf`, `normalmap` and `bumpmap`, `mask`. Each
//! keeps its nested BSDF's sidedness (the flag returned beside the material).

use super::super::cx::{Cx, R};
use super::super::xml::Element;
use super::bsdf;
use crate::loader::desc::*;

/// Mitsuba's `blendbsdf`: (1 − w)·a + w·b of two nested BSDFs of the same sidedness.
pub(super) fn blend(cx: &Cx<'_>, b: &Element, name: &str) -> R<(MaterialDesc, bool)> {
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
    Ok((
        MaterialDesc {
            name: name.to_string(),
            kind: MaterialKind::Blend {
                weight: cx.scalar_texture_prop(b, "weight", 0.5)?,
                a: Box::new(m0.kind),
                b: Box::new(m1.kind),
            },
            loc: cx.loc(b),
        },
        two0,
    ))
}

/// Mitsuba's `normalmap` and `bumpmap` (`t`) around one nested BSDF.
pub(super) fn perturbed(cx: &Cx<'_>, b: &Element, name: &str, t: &str) -> R<(MaterialDesc, bool)> {
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
    let map_type = cx.resolve(map)?.attr("type");
    if !(map_type == Some("bitmap") || (t == "normalmap" && map_type == Some("rawconstant"))) {
        return Err(cx.err(
            map,
            format!("a {t}'s texture must be a bitmap here (or a normalmap's rawconstant)"),
        ));
    }
    let texture = cx.texture_of(map)?;
    let inner = Box::new(m.kind);
    let kind = if t == "normalmap" {
        MaterialKind::NormalMap {
            map: texture,
            inner,
            pbrt: false,
        }
    } else {
        MaterialKind::BumpMap {
            height: texture,
            scale: cx.opt_float(b, "scale")?.unwrap_or(1.0),
            inner,
            pbrt: false,
        }
    };
    Ok((
        MaterialDesc {
            name: name.to_string(),
            kind,
            loc: cx.loc(b),
        },
        two,
    ))
}

/// Mitsuba's `mask` around one nested BSDF.
pub(super) fn mask(cx: &Cx<'_>, b: &Element, name: &str) -> R<(MaterialDesc, bool)> {
    let inner = b
        .children
        .iter()
        .find(|c| c.tag == "bsdf" || c.tag == "ref")
        .ok_or_else(|| cx.err(b, "a mask needs a nested <bsdf>"))?;
    let (m, two) = bsdf(cx, inner, name)?;
    Ok((
        MaterialDesc {
            name: name.to_string(),
            kind: MaterialKind::Mask {
                opacity: cx.scalar_texture_prop(b, "opacity", 0.5)?,
                inner: Box::new(m.kind),
            },
            loc: cx.loc(b),
        },
        two,
    ))
}
