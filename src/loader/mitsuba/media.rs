//! Mitsuba media: `<medium type="homogeneous">` with its `<phase>` (`isotropic`, `hg`,
//! `rayleigh`), declared at the top level with an id, or inside a shape or sensor with a
//! `name` (`interior`, `exterior`, or a sensor's `medium`).
//!
//! Units: Mitsuba's coefficients are per scene unit, which spectrace reads as metres, so
//! `sigma_t` × `scale` is σt in m⁻¹. Spectra read as for a reflectance: a float is constant
//! and an `<rgb>` is upsampled within [0, 1] (Jakob–Hanika), as Mitsuba's spectral variants
//! read a volume's colour.

use super::cx::{Cx, R};
use super::xml::Element;
use crate::loader::desc::{Coefficients, MediumDesc, MediumKind};
use crate::medium::PhaseFunction;

/// The media spectrace reads, for messages and the plugin list.
pub(super) const MEDIA: &[&str] = &["homogeneous"];

/// The phase functions spectrace reads.
pub(super) const PHASES: &[&str] = &["isotropic", "hg", "rayleigh"];

/// The index into the scene's media of the `<medium>` (or `<ref>` to one) `e`, read on its
/// first use; `name` identifies an unnamed one in messages.
pub(super) fn medium_index(cx: &Cx<'_>, e: &Element, name: &str) -> R<usize> {
    let m = cx.resolve(e)?;
    let key = (m.src, m.pos);
    if let Some(i) = cx.media.borrow().iter().position(|(k, _)| *k == key) {
        return Ok(i);
    }
    let d = medium(cx, m, name)?;
    let mut media = cx.media.borrow_mut();
    media.push((key, d));
    Ok(media.len() - 1)
}

/// A `<medium>` element; `name` identifies it in messages.
fn medium(cx: &Cx<'_>, e: &Element, name: &str) -> R<MediumDesc> {
    let e = cx.resolve(e)?;
    if e.tag != "medium" {
        return Err(cx.err(e, format!("expected a <medium>, not <{}>", e.tag)));
    }
    let t = e.attr("type").ok_or_else(|| cx.err(e, "missing type"))?;
    let kind = match t {
        "homogeneous" => homogeneous(cx, e)?,
        other => return Err(cx.unsupported(e, "medium", other)),
    };
    Ok(MediumDesc {
        name: e.attr("id").unwrap_or(name).to_string(),
        kind,
        loc: cx.loc(e),
    })
}

/// `homogeneous`: `sigma_t` (default 1) × `scale` (default 1), `albedo` (default 0.75), a
/// phase function (default isotropic). `sample_emitters` and `has_spectral_extinction` are
/// sampling hints that do not change the image; they are read and not needed.
fn homogeneous(cx: &Cx<'_>, e: &Element) -> R<MediumKind> {
    for hint in ["sample_emitters", "has_spectral_extinction"] {
        let _ = cx.child(e, hint);
    }
    let scale = cx.opt_float(e, "scale")?.unwrap_or(1.0);
    if !(scale.is_finite() && scale >= 0.0) {
        let at = cx.child(e, "scale").unwrap_or(e);
        return Err(cx.err(
            at,
            format!("scale must be finite and not negative, not {scale}"),
        ));
    }
    for (name, c) in ["sigma_t", "albedo"].map(|n| (n, cx.child(e, n))) {
        if let Some(c) = c.filter(|c| c.tag == "volume") {
            let what = c.attr("type").unwrap_or("?");
            return Err(cx.err(
                c,
                format!("{name} as a <volume type=\"{what}\"> is not supported yet; give a <float>, <spectrum> or <rgb>"),
            ));
        }
    }
    let sigma_t = cx
        .spectrum_prop(e, "sigma_t", 1.0, false)?
        .scaled(scale as f32);
    let albedo = cx.spectrum_prop(e, "albedo", 0.75, false)?;
    Ok(MediumKind::Homogeneous {
        coefficients: Coefficients::Extinction { sigma_t, albedo },
        phase: phase(cx, e)?,
    })
}

/// The medium's `<phase>` child (isotropic when it has none).
fn phase(cx: &Cx<'_>, e: &Element) -> R<PhaseFunction> {
    let Some(p) = e.children.iter().find(|c| c.tag == "phase") else {
        return Ok(PhaseFunction::Isotropic);
    };
    let p = cx.resolve(p)?;
    match p.attr("type").unwrap_or("") {
        "isotropic" => Ok(PhaseFunction::Isotropic),
        "rayleigh" => Ok(PhaseFunction::Rayleigh),
        "hg" => {
            let g = cx.opt_float(p, "g")?.unwrap_or(0.8);
            if !(g.abs() < 1.0) {
                let at = cx.child(p, "g").unwrap_or(p);
                return Err(cx.err(
                    at,
                    format!("Henyey–Greenstein's g must lie strictly between -1 and 1, not {g}"),
                ));
            }
            Ok(PhaseFunction::HenyeyGreenstein { g: g as f32 })
        }
        other => Err(cx.unsupported(p, "phase", other)),
    }
}
