//! Mitsuba emitters that are not shapes (`point`, `spot`, `constant`, `directional`, `projector`,
//! `envmap`, each kind its own function beyond the one-liners); and
//! `sampling_weight`, which area emitters read too.

use super::cx::{Cx, R, mitsuba_d65};
use super::sensor::camera_frame;
use super::xml::Element;
use crate::loader::desc::*;
use crate::spectrum::Spectrum;
use crate::units::{Angle, Length, angle, length};

pub(super) fn emitter(cx: &Cx<'_>, e: &Element) -> R<LightDesc> {
    let t = e.attr("type").unwrap_or("");
    let to_world = e.children.iter().find(|c| c.tag == "transform");
    let Some((_, read)) = EMITTERS.iter().find(|(n, _)| *n == t) else {
        return Err(cx.unsupported(e, "emitter", t));
    };
    let (kind, spectrum) = read(cx, e, to_world)?;
    Ok(LightDesc {
        kind,
        spectrum,
        sampling_weight: sampling_weight(cx, e)?,
        loc: cx.loc(e),
    })
}

/// An emitter plugin's reader: the element and its `to_world`, if any.
type Reader = fn(&Cx<'_>, &Element, Option<&Element>) -> R<(LightKind, Spectrum)>;

/// The emitter plugins the importer reads (besides `area`, which belongs to shapes), one line
/// each: the registry that dispatch and the importer's supported list come from.
pub(super) const EMITTERS: &[(&str, Reader)] = &[
    ("point", point),
    ("spot", |cx, e, _| spot(cx, e)),
    ("constant", |cx, e, _| {
        let amount = EmitAmount::Scale(1.0);
        let radiance = cx.spectrum_prop(e, "radiance", 1.0, true)?;
        Ok((LightKind::Environment { amount }, radiance))
    }),
    ("directional", directional),
    ("envmap", envmap),
    // Mitsuba's projector: an image projected through a pinhole, times scale
    ("projector", |cx, e, _| projector(cx, e)),
];

/// Mitsuba's `point`, placed by `position` or by `to_world` (its image of the origin), never
/// both.
fn point(cx: &Cx<'_>, e: &Element, to_world: Option<&Element>) -> R<(LightKind, Spectrum)> {
    let l = |x: f64| Length::new::<length::meter>(x);
    let position = match (cx.child(e, "position"), to_world) {
        (Some(_), Some(tr)) => {
            return Err(cx.err(
                tr,
                "give either position or to_world, not both (as Mitsuba requires)",
            ));
        }
        (Some(p), None) => cx.vec3(p)?.map(l),
        (None, Some(tr)) => camera_frame(cx, e, &cx.transform(tr)?)?.0,
        (None, None) => [l(0.0), l(0.0), l(0.0)],
    };
    let kind = LightKind::Point {
        position,
        amount: PointAmount::Scale(1.0),
    };
    Ok((kind, cx.spectrum_prop(e, "intensity", 1.0, true)?))
}

/// Mitsuba's `directional`: along `direction`, or the image of +z under `to_world`.
fn directional(cx: &Cx<'_>, e: &Element, to_world: Option<&Element>) -> R<(LightKind, Spectrum)> {
    // Mitsuba: `direction`, or the image of +z under `to_world`, never both
    let d = match (cx.child(e, "direction"), to_world) {
        (Some(_), Some(tr)) => {
            return Err(cx.err(
                tr,
                "give either direction or to_world, not both (as Mitsuba requires)",
            ));
        }
        (Some(d), None) => cx.vec3(d)?,
        (None, Some(tr)) => {
            let (eye, target, _) = camera_frame(cx, e, &cx.transform(tr)?)?;
            [0, 1, 2].map(|i| target[i].value - eye[i].value)
        }
        (None, None) => [0.0, 0.0, 1.0],
    };
    Ok((
        LightKind::Directional {
            direction: d,
            angular_diameter: Angle::new::<angle::radian>(0.0),
            amount: DirectionalAmount::Scale(1.0),
        },
        cx.spectrum_prop(e, "irradiance", 1.0, true)?,
    ))
}

/// Mitsuba's `spot`: placed by `to_world`, linear in angle from `beam_width` to
/// `cutoff_angle`, with an optional bitmap across its cone.
fn spot(cx: &Cx<'_>, e: &Element) -> R<(LightKind, Spectrum)> {
    let cutoff = cx.opt_float(e, "cutoff_angle")?.unwrap_or(20.0);
    let width = cx.opt_float(e, "beam_width")?.unwrap_or(cutoff * 0.75);
    let steps = match e.children.iter().find(|c| c.tag == "transform") {
        Some(tr) => cx.transform(tr)?,
        None => return Err(cx.err(e, "a spot needs a to_world with lookat")),
    };
    let texture = match cx.child(e, "texture") {
        Some(t) if cx.resolve(t)?.attr("type") == Some("bitmap") => {
            Some(Box::new((cx.texture_of(t)?, steps.clone())))
        }
        Some(t) => {
            return Err(cx.err(t, "a spot's texture must be a bitmap here"));
        }
        None => None,
    };
    let (eye, target, _) = camera_frame(cx, e, &steps)?;
    Ok((
        LightKind::Spot {
            position: eye,
            target,
            cone_angle: Angle::new::<angle::degree>(cutoff),
            // Mitsuba's falloff is linear in the angle from beam_width to cutoff_angle
            // (src/emitters/spot.cpp, falloff_curve)
            falloff_start: Angle::new::<angle::degree>(width.min(cutoff)),
            falloff: SpotFalloff::LinearAngle,
            amount: PointAmount::Scale(1.0),
            texture,
        },
        cx.spectrum_prop(e, "intensity", 1.0, true)?,
    ))
}

/// Mitsuba's `projector`: an image projected through a pinhole, times `scale`.
fn projector(cx: &Cx<'_>, e: &Element) -> R<(LightKind, Spectrum)> {
    let steps = match e.children.iter().find(|c| c.tag == "transform") {
        Some(tr) => cx.transform(tr)?,
        None => Vec::new(),
    };
    let fov = match (cx.opt_float(e, "fov")?, cx.child(e, "focal_length")) {
        (Some(f), _) if f > 0.0 && f < 180.0 => f,
        (Some(f), _) => {
            return Err(cx.err(
                e,
                format!("fov must lie strictly between 0 and 180°, not {f}"),
            ));
        }
        (None, Some(c)) => {
            return Err(cx.err(
                c,
                "a projector's focal_length is not supported here; give fov",
            ));
        }
        // Mitsuba's default 50 mm lens on 36 mm: 2·atan(18/50) across x
        (None, None) => 2.0 * (18.0f64 / 50.0).atan().to_degrees(),
    };
    let fov_axis = match cx.string(e, "fov_axis").as_deref() {
        None | Some("x") => FovAxis::X,
        Some("y") => FovAxis::Y,
        Some(o) => {
            return Err(cx.err(
                e,
                format!("a projector's fov_axis \"{o}\" is not supported here; use x or y"),
            ));
        }
    };
    let Some(irradiance) = cx.child(e, "irradiance") else {
        return Err(cx.err(e, "a projector needs an irradiance (a texture or a value)"));
    };
    let scale = cx.opt_float(e, "scale")?.unwrap_or(1.0) as f32;
    let (image, spectrum) = if cx.resolve(irradiance)?.tag == "texture" {
        // measured in Mitsuba 3.9.1: a grey image projects an equal-energy spectrum
        // (X = Y = Z), not D65 (the `D65(scale)` texture in its source notwithstanding)
        (cx.texture_of(irradiance)?, Spectrum::Constant(scale))
    } else {
        // a number or colour is an emission (Mitsuba's `get_emissive_texture`: a `d65`
        // texture in spectral variants, unbounded): D65-shaped, any magnitude
        (
            Spectrum::Constant(1.0).into(),
            cx.spectrum(irradiance, true)?.scaled(scale),
        )
    };
    Ok((
        LightKind::Projector {
            transform: steps,
            fov: Angle::new::<angle::degree>(fov),
            fov_axis,
            image,
            constant_intensity: false,
        },
        spectrum,
    ))
}

/// Mitsuba's `envmap`: a latitude–longitude image at infinity, times `scale`.
fn envmap(cx: &Cx<'_>, e: &Element, to_world: Option<&Element>) -> R<(LightKind, Spectrum)> {
    let f = cx
        .string(e, "filename")
        .ok_or_else(|| cx.err(e, "missing filename (a latitude–longitude image)"))?;
    let path = cx.resolve_file(&f);
    if !path.is_file() {
        return Err(cx.err(e, format!("image file {} does not exist", path.display())));
    }
    let scale = cx.opt_float(e, "scale")?.unwrap_or(1.0);
    if scale < 0.0 {
        return Err(cx.err(e, format!("scale must be ≥ 0, not {scale}")));
    }
    if let Some(m) = cx.child(e, "mis_compensation")
        && m.attr("value") == Some("true")
    {
        cx.note(
            m,
            "mis_compensation changes only how Mitsuba samples the map, not the image; spectrace samples it by luminance",
        );
    }
    Ok((
        LightKind::EnvMap {
            path,
            transform: match to_world {
                Some(tr) => cx.transform(tr)?,
                None => Vec::new(),
            },
            amount: EnvMapAmount::Scale(scale),
        },
        // an RGB (1, 1, 1) pixel is Mitsuba's normalised D65, as for `constant`
        Spectrum::Piecewise(mitsuba_d65(1.0)),
    ))
}

/// An emitter's `sampling_weight`: its relative probability of being chosen for emitter
/// sampling (Mitsuba 3, `Emitter`), finite and ≥ 0, 1 by default.
pub(super) fn sampling_weight(cx: &Cx<'_>, e: &Element) -> R<f64> {
    let Some(c) = cx.child(e, "sampling_weight") else {
        return Ok(1.0);
    };
    let w = cx.float(c)?;
    if !(w.is_finite() && w >= 0.0) {
        return Err(cx.err(
            c,
            format!("sampling_weight must be a finite number ≥ 0, not {w}"),
        ));
    }
    Ok(w)
}
