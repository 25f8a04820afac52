//! Sections of the scene file: settings, camera, film, integrator, materials, shapes, lights.

mod camera;
mod film;
mod integrator;
mod lights;
mod materials;
mod media;
mod sensors;
mod shapes;

use camera::camera;
use film::film;
use integrator::integrator;
use lights::light;
use materials::material;
use sensors::sensor;
use shapes::{emit_amount, non_negative, one_amount, shape};

use std::ops::Range;

use toml::Value;

use super::{Cx, R, SpectrumUse, present, round9};
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
    let material_names: Vec<&str> = raw.materials.keys().map(|k| k.get_ref().as_str()).collect();
    let mut shapes = raw
        .shapes
        .iter()
        .enumerate()
        .map(|(i, s)| shape(cx, format!("shapes[{i}]"), s, &material_names))
        .collect::<R<Vec<_>>>()?;
    let (groups, instances) = groups_and_instances(cx, &raw, &material_names)?;
    let (media, camera_medium) = scene_media(cx, &raw, &mut shapes, &range)?;
    let lights = raw
        .lights
        .iter()
        .enumerate()
        .map(|(i, l)| light(cx, i, l))
        .collect::<R<Vec<_>>>()?;

    let has_env = lights.iter().any(|l| {
        matches!(
            l.kind,
            LightKind::Environment { .. } | LightKind::EnvMap { .. } | LightKind::Sky { .. }
        )
    });
    if shapes.is_empty() && instances.is_empty() && !has_env {
        let span = raw.camera.as_ref().map(|c| c.span()).unwrap_or(WHOLE_FILE);
        return Err(cx.err(
            &span,
            "camera",
            "the camera sees nothing: the scene has no shapes and no environment light",
        ));
    }
    has_light_source(cx, &lights, &shapes, &media)?;
    Ok(SceneDesc {
        path: cx.file.to_path_buf(),
        wavelength_range: range,
        camera,
        film,
        integrator,
        materials,
        shapes,
        groups,
        instances,
        lights,
        media,
        camera_medium,
        sensors: raw
            .sensors
            .iter()
            .enumerate()
            .map(|(i, s)| sensor(cx, i, s))
            .collect::<R<Vec<_>>>()?,
        notes: range_note(&range).into_iter().collect(),
    })
}

/// A note when the film's wavelength range misses the CIE colour-matching functions (360–830
/// nm) entirely: X, Y, Z, R, G, B are then zero by definition, and only L (and spectral bins)
/// hold radiance.
fn range_note(range: &[Length; 2]) -> Option<String> {
    let (lo, hi) = (
        range[0].get::<length::nanometer>(),
        range[1].get::<length::nanometer>(),
    );
    (hi <= 360.0 || lo >= 830.0).then(|| {
        format!(
            "scene.wavelength_range {lo}–{hi} nm lies outside the CIE colour-matching functions (360–830 nm): X, Y, Z, R, G, B and the PNG are black; the L channel and spectral bins (--spectral-bins) hold the radiance"
        )
    })
}

/// `[[groups.NAME.shapes]]` (shapes without emission, in the group's own space) and
/// `[[instances]]` (`group = "NAME"`, `transform`): Mitsuba's `shapegroup` and `instance`.
fn groups_and_instances(
    cx: &Cx<'_>,
    raw: &RawScene,
    material_names: &[&str],
) -> R<(Vec<GroupDesc>, Vec<InstanceDesc>)> {
    let mut groups = Vec::new();
    for (name, g) in &raw.groups {
        let gf = format!("groups.{}", name.get_ref());
        if g.get_ref().shapes.is_empty() {
            return Err(cx.err(
                &g.span(),
                &gf,
                "a group needs at least one [[groups.NAME.shapes]]",
            ));
        }
        let mut shapes = Vec::new();
        for (i, s) in g.get_ref().shapes.iter().enumerate() {
            let f = format!("{gf}.shapes[{i}]");
            let d = shape(cx, f.clone(), s, material_names)?;
            if d.emission.is_some() {
                return Err(cx.err(
                    &s.span(),
                    format!("{f}.emission"),
                    "a shape in a group cannot emit (each instance would be another lamp); place the emitter outside the group",
                ));
            }
            shapes.push(d);
        }
        groups.push(GroupDesc {
            id: name.get_ref().clone(),
            shapes,
            loc: cx.src.span(&g.span()),
        });
    }
    let mut instances = Vec::new();
    for (i, inst) in raw.instances.iter().enumerate() {
        let f = format!("instances[{i}]");
        let r = inst.get_ref();
        let name = cx.required(
            &r.group,
            &inst.span(),
            &format!("{f}.group"),
            "the name of a [groups.NAME]",
        )?;
        let group = groups
            .iter()
            .position(|g| g.id == *name.get_ref())
            .ok_or_else(|| {
                cx.err(
                    &name.span(),
                    format!("{f}.group"),
                    format!("no group named \"{}\"", name.get_ref()),
                )
            })?;
        let transform = match &r.transform {
            Some(t) => shapes::transform(cx, t, &format!("{f}.transform"))?,
            None => Vec::new(),
        };
        instances.push(InstanceDesc {
            group,
            transform,
            unit_m: cx.unit_m,
            loc: cx.src.span(&inst.span()),
        });
    }
    Ok((groups, instances))
}

/// The media (`[media.NAME]`) and the names that refer to them: each shape's `interior` and
/// `exterior`, the camera's `medium`. A name no medium has, a medium nothing refers to, and a
/// medium named in a group's shape are errors.
fn scene_media(
    cx: &Cx<'_>,
    raw: &RawScene,
    shapes: &mut [ShapeDesc],
    range: &[Length; 2],
) -> R<(Vec<MediumDesc>, Option<usize>)> {
    let media = raw
        .media
        .iter()
        .map(|(n, m)| media::medium(cx, n, m, range))
        .collect::<R<Vec<_>>>()?;
    let names: Vec<&str> = raw.media.keys().map(|k| k.get_ref().as_str()).collect();
    let mut used = vec![false; names.len()];
    let mut index = |v: &S<String>, field: String| -> R<usize> {
        let name = v.get_ref().as_str();
        let Some(i) = names.iter().position(|n| *n == name) else {
            return Err(cx.err(
                &v.span(),
                field,
                format!(
                    "no medium is named \"{name}\"{}; the scene's media: {}",
                    crate::params::did_you_mean(name, names.iter().copied()),
                    if names.is_empty() {
                        "none (declare one as [media.NAME])".to_string()
                    } else {
                        names.join(", ")
                    }
                ),
            ));
        };
        used[i] = true;
        Ok(i)
    };
    for (i, (s, d)) in raw.shapes.iter().zip(shapes.iter_mut()).enumerate() {
        if let Some(v) = &s.get_ref().interior {
            d.interior = Some(index(v, format!("shapes[{i}].interior"))?);
        }
        if let Some(v) = &s.get_ref().exterior {
            d.exterior = Some(index(v, format!("shapes[{i}].exterior"))?);
        }
    }
    let camera_medium = match raw
        .camera
        .as_ref()
        .and_then(|c| c.get_ref().medium.as_ref())
    {
        Some(v) => Some(index(v, "camera.medium".into())?),
        None => None,
    };
    for (name, g) in &raw.groups {
        for (i, s) in g.get_ref().shapes.iter().enumerate() {
            if let Some(v) = s
                .get_ref()
                .interior
                .as_ref()
                .or(s.get_ref().exterior.as_ref())
            {
                return Err(cx.err(
                    &v.span(),
                    format!("groups.{}.shapes[{i}]", name.get_ref()),
                    "a group's shapes cannot bound media yet; place the shape in [[shapes]]",
                ));
            }
        }
    }
    if let Some((k, _)) = raw.media.iter().zip(&used).find(|(_, u)| !**u) {
        return Err(cx.err(
            &k.0.span(),
            format!("media.{}", k.0.get_ref()),
            "no shape names this medium as its interior or exterior, and the camera is not in it",
        ));
    }
    Ok((media, camera_medium))
}

/// A scene needs something that emits: a light, a shape's emission or an emitting medium.
fn has_light_source(
    cx: &Cx<'_>,
    lights: &[LightDesc],
    shapes: &[ShapeDesc],
    media: &[MediumDesc],
) -> R<()> {
    let emitting_medium = media.iter().any(|m| {
        matches!(
            m.kind,
            MediumKind::Homogeneous {
                emission: Some(_),
                ..
            }
        )
    });
    if lights.is_empty() && !shapes.iter().any(|s| s.emission.is_some()) && !emitting_medium {
        return Err(cx.err(
            &WHOLE_FILE,
            "lights",
            "the scene has no light source: add a [[lights]] entry, or an `emission` to a shape or a medium",
        ));
    }
    Ok(())
}
