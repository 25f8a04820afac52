//! Sections of the scene file: settings, camera, film, integrator, materials, shapes, lights.

mod camera;
mod lights;
mod materials;
mod shapes;

use camera::{camera, film, integrator};
use lights::light;
use materials::material;
use shapes::{emit_amount, one_amount, shape};

use std::ops::Range;

use toml::Value;

use super::{Cx, R, SpectrumUse, present};
use crate::loader::desc::*;
use crate::loader::raw::*;
use crate::spectrum::Spectrum;
use crate::units::parse::Dimension as D;
use crate::units::{
    Angle, Illuminance, Irradiance, Length, Luminance, LuminousFlux, LuminousIntensity, Power,
    Radiance, RadiantIntensity, angle, illuminance, irradiance, length, luminance, luminous_flux,
    luminous_intensity, power, radiance, radiant_intensity,
};

const WHOLE_FILE: Range<usize> = 0..0;

pub(super) fn scene(cx: &mut Cx<'_>, raw: RawScene) -> R<SceneDesc> {
    let mut range = [
        Length::new::<length::nanometer>(360.0),
        Length::new::<length::nanometer>(830.0),
    ];
    if let Some(s) = raw.scene.as_ref().map(|s| s.get_ref()) {
        if let Some(u) = &s.length_unit {
            let l: Length =
                crate::units::parse::parse(&format!("1 {}", u.get_ref())).map_err(|_| {
                    cx.err(
                        &u.span(),
                        "scene.length_unit",
                        format!(
                            "\"{}\" is not a length unit; expected m, cm, mm, um or km",
                            u.get_ref()
                        ),
                    )
                })?;
            cx.unit_m = l.get::<length::meter>();
        }
        if let Some(w) = &s.wavelength_range {
            let f = "scene.wavelength_range";
            if w.get_ref().len() != 2 {
                return Err(cx.err(
                    &w.span(),
                    f,
                    "expected [shortest, longest], e.g. [\"360 nm\", \"830 nm\"]",
                ));
            }
            for (slot, v) in range.iter_mut().zip(w.get_ref()) {
                *slot = match v.get_ref() {
                    Value::String(_) => cx.quantity::<Length>(v, f)?,
                    _ => Length::new::<length::nanometer>(cx.number(v, f)?),
                };
            }
            let (lo, hi) = (
                range[0].get::<length::nanometer>(),
                range[1].get::<length::nanometer>(),
            );
            if !(lo > 0.0 && hi > lo) {
                return Err(cx.err(
                    &w.span(),
                    f,
                    format!("expected 0 < shortest < longest, found {lo} nm to {hi} nm"),
                ));
            }
        }
    }
    let camera = match &raw.camera {
        Some(c) => camera(cx, c)?,
        None => return Err(cx.err(&WHOLE_FILE, "camera", "missing [camera] section")),
    };
    let film = film(cx, raw.film.as_ref())?;
    let integrator = integrator(cx, raw.integrator.as_ref())?;
    let mut materials = Vec::new();
    for (name, m) in &raw.materials {
        materials.push(material(cx, name, m, &range, &raw.materials)?);
    }
    let shapes = raw
        .shapes
        .iter()
        .enumerate()
        .map(|(i, s)| {
            shape(
                cx,
                i,
                s,
                &raw.materials
                    .keys()
                    .map(|k| k.get_ref().as_str())
                    .collect::<Vec<_>>(),
            )
        })
        .collect::<R<Vec<_>>>()?;
    let lights = raw
        .lights
        .iter()
        .enumerate()
        .map(|(i, l)| light(cx, i, l))
        .collect::<R<Vec<_>>>()?;

    let has_env = lights
        .iter()
        .any(|l| matches!(l.kind, LightKind::Environment { .. }));
    if shapes.is_empty() && !has_env {
        let span = raw.camera.as_ref().map(|c| c.span()).unwrap_or(WHOLE_FILE);
        return Err(cx.err(
            &span,
            "camera",
            "the camera sees nothing: the scene has no shapes and no environment light",
        ));
    }
    if lights.is_empty() && !shapes.iter().any(|s| s.emission.is_some()) {
        return Err(cx.err(
            &WHOLE_FILE,
            "lights",
            "the scene has no light source: add a [[lights]] entry or an `emission` to a shape",
        ));
    }
    Ok(SceneDesc {
        path: cx.file.to_path_buf(),
        wavelength_range: range,
        camera,
        film,
        integrator,
        materials,
        shapes,
        groups: Vec::new(),
        instances: Vec::new(),
        lights,
        notes: Vec::new(),
    })
}

/// Rounds away binary noise from unit conversions (29.999999999999996 → 30) for messages.
fn round9(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}
