//! Mitsuba's `<integrator>`: `path`, `volpath`, `volpathmis`, `ptracer`, `direct`, and the
//! wrappers `moment`, `stokes` and `aov`, as integrator settings.

use super::cx::{Cx, R};
use super::xml::Element;
use crate::loader::desc::*;

/// Mitsuba's `max_depth` (path length: 1 = emitters seen directly, 2 = one bounce, −1 =
/// unlimited) as spectrace's number of bounces (0 = emitters seen directly; 1024 = unlimited).
/// Mitsuba's 0 renders black and anything below −1 is an error in Mitsuba: both are refused.
fn max_depth(cx: &Cx<'_>, d: &Element) -> R<u32> {
    let v = cx.float(d)?;
    if v.fract() != 0.0 {
        return Err(cx.err(d, format!("max_depth must be an integer, not {v}")));
    }
    match v as i64 {
        -1 => Ok(1024),
        0 => Err(cx.err(
            d,
            "max_depth 0 renders a black image in Mitsuba; use 1 for emitters seen directly",
        )),
        n if n < -1 => Err(cx.err(
            d,
            format!("max_depth must be -1 (unlimited) or at least 1, not {n}"),
        )),
        // the TOML loader's limit, 1024 bounces, as an error rather than a silent clamp
        n if n > 1025 => Err(cx.err(
            d,
            format!(
                "max_depth {n} is more than spectrace traces: at most 1025 (1024 bounces, as a TOML scene's limit), or -1 for unlimited (1024 bounces, Russian roulette ends paths long before)"
            ),
        )),
        n => Ok((n - 1) as u32),
    }
}

/// An `<integrator>`: `path`, and `volpath` and `volpathmis` (spectrace's volumetric path
/// tracer; the same as `path` in a scene without media) and `ptracer` (spectrace's light
/// tracer) with `max_depth`, `rr_depth`;
/// `direct` with its sample counts; `moment` around one of them (its image plus second
/// moments); `stokes` around one of them (a polarised render). Returns whether the integrator renders media.
pub(super) fn integrator_settings(
    cx: &Cx<'_>,
    c: &Element,
    integrator: &mut IntegratorDesc,
) -> R<bool> {
    let t = c.attr("type").unwrap_or("");
    // `moment` (its image plus second moments) and `stokes` (polarised variants only: the
    // Stokes vector S0–S3 in the sensor's frame) wrap one integrator
    if t == "aov" {
        return aov_integrator(cx, c, integrator);
    }
    if t == "moment" || t == "stokes" {
        let inner = c
            .children
            .iter()
            .find(|i| i.tag == "integrator")
            .ok_or_else(|| cx.err(c, format!("a {t} integrator needs a nested <integrator>")))?;
        if t == "moment" {
            integrator.moment = true;
        } else {
            integrator.polarised = true;
        }
        return integrator_settings(cx, inner, integrator);
    }
    if t == "direct" {
        // Mitsuba's `shading_samples` sets both counts; each count given overrides it
        let count = |key: &str| -> R<Option<u32>> {
            match cx.child(c, key) {
                None => Ok(None),
                Some(e) => {
                    let v = cx.float(e)?;
                    if v.fract() != 0.0 || !(0.0..=1e6).contains(&v) {
                        return Err(cx.err(e, format!("{key} must be an integer ≥ 0, not {v}")));
                    }
                    Ok(Some(v as u32))
                }
            }
        };
        let shading = count("shading_samples")?.unwrap_or(1);
        let emitter_samples = count("emitter_samples")?.unwrap_or(shading);
        let bsdf_samples = count("bsdf_samples")?.unwrap_or(shading);
        if emitter_samples + bsdf_samples == 0 {
            return Err(cx.err(c, "direct needs at least one emitter or BSDF sample"));
        }
        integrator.kind = IntegratorKind::Direct {
            emitter_samples,
            bsdf_samples,
        };
        return Ok(false);
    }
    if !matches!(t, "path" | "volpath" | "volpathmis" | "ptracer") {
        return Err(cx.unsupported(c, "integrator", t));
    }
    if t == "ptracer" {
        // Mitsuba's particle tracer: particles from the emitters, each vertex (the emitter's
        // own included) connected to the sensor; spectrace's light tracer
        integrator.kind = IntegratorKind::Light;
    }
    if let Some(d) = cx.child(c, "max_depth") {
        integrator.max_depth = max_depth(cx, d)?;
    }
    // Mitsuba's rr_depth: roulette may end a path at vertex k > rr_depth (vertex 1 is the
    // first surface hit), the same meaning as spectrace's
    if let Some(d) = cx.child(c, "rr_depth") {
        let v = cx.float(d)?;
        if v.fract() != 0.0 || v <= 0.0 {
            return Err(cx.err(d, format!("rr_depth must be a positive integer, not {v}")));
        }
        integrator.rr_depth = v.min(1024.0) as u32;
    }
    if let Some(h) = cx.child(c, "hide_emitters")
        && h.attr("value") == Some("true")
    {
        return Err(cx.err(
            h,
            "hide_emitters = true is not supported: spectrace always shows emitters seen directly",
        ));
    }
    Ok(!matches!(t, "path" | "ptracer"))
}

/// Mitsuba's `aov`: `aovs` ("name:type, …", the types of [`crate::scene::AovKind`]) written
/// beside the image of its nested integrator (which it needs: without one Mitsuba writes AOVs
/// only, which spectrace does not).
fn aov_integrator(cx: &Cx<'_>, c: &Element, integrator: &mut IntegratorDesc) -> R<bool> {
    let at = cx.child(c, "aovs").unwrap_or(c);
    let spec = cx
        .string(c, "aovs")
        .ok_or_else(|| cx.err(c, "an aov integrator needs aovs (\"name:type, …\")"))?;
    for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let Some((name, kind)) = item.split_once(':') else {
            return Err(cx.err(at, format!("\"{item}\" is not a name:type pair")));
        };
        let Some(kind) = crate::scene::AovKind::from_mitsuba(kind.trim()) else {
            return Err(cx.err(
                at,
                format!(
                    "AOV type \"{}\" is not supported (supported: depth, position, uv, geo_normal, sh_normal, dp_du, dp_dv, prim_index, shape_index)",
                    kind.trim()
                ),
            ));
        };
        integrator.aovs.push(crate::scene::Aov {
            name: name.trim().to_string(),
            kind,
        });
    }
    let nested: Vec<&Element> = c
        .children
        .iter()
        .filter(|i| i.tag == "integrator")
        .collect();
    let [inner] = nested[..] else {
        return Err(cx.err(
            c,
            format!(
                "an aov integrator needs exactly one nested <integrator> for the image, found {}",
                nested.len()
            ),
        ));
    };
    integrator_settings(cx, inner, integrator)
}
