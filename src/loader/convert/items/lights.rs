//! `[[lights]]`: point, spot, directional, environment and beam lights; the sun's placement
//! and skies are in `daylight.rs`, luminaires in `luminaire.rs`.

use super::daylight::{sky, sun_placement};
use super::luminaire::luminaire;
use super::*;

pub(super) fn light(cx: &Cx<'_>, i: usize, l: &S<RawLight>) -> R<LightDesc> {
    let sp = l.span();
    let f = format!("lights[{i}]");
    let l = l.get_ref();
    let all = present!(l; kind, spectrum, position, target, direction, power, intensity, radiance, luminance, irradiance, scale, cone_angle, falloff_start, falloff, angular_diameter, radius, image, transform, file, c0, tilt, model, sun_elevation, sun_azimuth, latitude, longitude, time, up, north);
    let ty = cx.required(
        &l.kind,
        &sp,
        &format!("{f}.type"),
        "point, spot, directional, sun, environment, sky, beam or luminaire",
    )?;
    let spectrum = match &l.spectrum {
        Some(s) => cx.spectrum(s, &format!("{f}.spectrum"), SpectrumUse::Emission)?,
        // a luminaire's default: CIE illuminant A, the lamp of classical photometry
        None if ty.get_ref() == "luminaire" => {
            Spectrum::Blackbody(crate::spectrum::blackbody::Blackbody::cie_illuminant_a())
        }
        None => Spectrum::Constant(1.0),
    };
    let pos = |cx: &Cx<'_>| {
        cx.point(
            cx.required(
                &l.position,
                &sp,
                &format!("{f}.position"),
                "a position [x, y, z]",
            )?,
            &format!("{f}.position"),
        )
    };
    // position and a distinct target, for lights that aim
    let aim = |cx: &Cx<'_>, what: &str| -> R<(Point, Point)> {
        let position = pos(cx)?;
        let t = cx.required(
            &l.target,
            &sp,
            &format!("{f}.target"),
            &format!("the point the {what} aims at"),
        )?;
        let target = cx.point(t, &format!("{f}.target"))?;
        if (0..3).all(|k| target[k] == position[k]) {
            return Err(cx.err(
                &t.span(),
                format!("{f}.target"),
                "the target equals the position",
            ));
        }
        Ok((position, target))
    };
    let point_amount = |cx: &Cx<'_>| -> R<PointAmount> {
        let (which, v) = one_amount(
            cx,
            &sp,
            &f,
            &[
                ("power", &l.power),
                ("intensity", &l.intensity),
                ("scale", &l.scale),
            ],
        )?;
        let field = format!("{f}.{which}");
        let (amount, si) = match which {
            "power" => match cx.quantity_of(v, &field, &[D::Power, D::LuminousFlux])? {
                (D::Power, w) => (PointAmount::Power(Power::new::<power::watt>(w)), w),
                (_, lm) => (
                    PointAmount::LuminousFlux(LuminousFlux::new::<luminous_flux::lumen>(lm)),
                    lm,
                ),
            },
            "intensity" => {
                match cx.quantity_of(v, &field, &[D::RadiantIntensity, D::LuminousIntensity])? {
                    (D::RadiantIntensity, w) => (
                        PointAmount::Intensity(RadiantIntensity::new::<
                            radiant_intensity::watt_per_steradian,
                        >(w)),
                        w,
                    ),
                    (_, cd) => (
                        PointAmount::LuminousIntensity(LuminousIntensity::new::<
                            luminous_intensity::candela,
                        >(cd)),
                        cd,
                    ),
                }
            }
            _ => {
                let s = cx.number(v, &field)?;
                (PointAmount::Scale(s), s)
            }
        };
        if si < 0.0 {
            return Err(cx.err(
                &v.span(),
                field,
                format!("light cannot be negative, found {si}"),
            ));
        }
        Ok(amount)
    };
    let kind = match ty.get_ref().as_str() {
        "point" => {
            cx.only(
                "a point light",
                &f,
                &all,
                &[
                    "kind",
                    "spectrum",
                    "position",
                    "power",
                    "intensity",
                    "scale",
                ],
            )?;
            LightKind::Point {
                position: pos(cx)?,
                amount: point_amount(cx)?,
            }
        }
        "spot" => {
            cx.only(
                "a spot light",
                &f,
                &all,
                &[
                    "kind",
                    "spectrum",
                    "position",
                    "target",
                    "power",
                    "intensity",
                    "scale",
                    "cone_angle",
                    "falloff_start",
                    "falloff",
                ],
            )?;
            let (position, target) = aim(cx, "spot")?;
            let c = cx.required(
                &l.cone_angle,
                &sp,
                &format!("{f}.cone_angle"),
                "the cone's half-angle, e.g. \"30 deg\"",
            )?;
            let cone_angle: Angle = cx.quantity(c, &format!("{f}.cone_angle"))?;
            let cd = cone_angle.get::<angle::degree>();
            if !(cd > 0.0 && cd <= 90.0) {
                return Err(cx.err(
                    &c.span(),
                    format!("{f}.cone_angle"),
                    format!(
                        "expected a half-angle in (0, 90] deg, found {} deg",
                        round9(cd)
                    ),
                ));
            }
            let falloff_start = match &l.falloff_start {
                Some(fs) => {
                    let a: Angle = cx.quantity(fs, &format!("{f}.falloff_start"))?;
                    let d = a.get::<angle::degree>();
                    if !(0.0..=cd).contains(&d) {
                        return Err(cx.err(
                            &fs.span(),
                            format!("{f}.falloff_start"),
                            format!(
                                "expected 0 to cone_angle ({} deg), found {} deg",
                                round9(cd),
                                round9(d)
                            ),
                        ));
                    }
                    a
                }
                None => cone_angle,
            };
            let falloff = match &l.falloff {
                None => SpotFalloff::SmoothstepCos,
                Some(v) => {
                    match cx.string(v, &format!("{f}.falloff"), "\"smoothstep\" or \"linear\"")? {
                        "smoothstep" => SpotFalloff::SmoothstepCos,
                        "linear" => SpotFalloff::LinearAngle,
                        o => {
                            return Err(cx.err(
                            &v.span(),
                            format!("{f}.falloff"),
                            format!("\"{o}\": expected \"smoothstep\" (in cos θ) or \"linear\" (in the angle, as Mitsuba's spot)"),
                        ));
                        }
                    }
                }
            };
            LightKind::Spot {
                position,
                target,
                cone_angle,
                falloff_start,
                falloff,
                amount: point_amount(cx)?,
                texture: None,
            }
        }
        "directional" | "sun" => {
            cx.only(
                "a directional light",
                &f,
                &all,
                &[
                    "kind",
                    "spectrum",
                    "direction",
                    "irradiance",
                    "scale",
                    "angular_diameter",
                    "sun_elevation",
                    "sun_azimuth",
                    "latitude",
                    "longitude",
                    "time",
                    "up",
                    "north",
                ],
            )?;
            let placed = l.time.is_some()
                || l.sun_elevation.is_some()
                || l.sun_azimuth.is_some()
                || l.latitude.is_some()
                || l.longitude.is_some();
            if let (Some(d), true) = (&l.direction, placed) {
                return Err(cx.err(
                    &d.span(),
                    format!("{f}.direction"),
                    "give the direction, or the sun's place and time (or angles), not both",
                ));
            }
            let direction = if l.direction.is_none() && placed {
                // every placing key either places the sun or is refused by sun_placement
                let (_, sun) = sun_placement(cx, &sp, &f, l)?;
                let sun = sun.ok_or_else(|| {
                    cx.err(
                        &sp,
                        format!("{f}.time"),
                        "the sun needs a time and place or sun_elevation",
                    )
                })?;
                sun.map(|x| -x)
            } else {
                let d = cx.required(
                    &l.direction,
                    &sp,
                    &format!("{f}.direction"),
                    "the direction light travels, [x, y, z], or the sun's place (latitude, longitude, time) or angles (sun_elevation, sun_azimuth)",
                )?;
                let direction = cx.vec3(d, &format!("{f}.direction"))?;
                if direction == [0.0; 3] {
                    return Err(cx.err(
                        &d.span(),
                        format!("{f}.direction"),
                        "the direction is zero",
                    ));
                }
                direction
            };
            let angular_diameter = match &l.angular_diameter {
                Some(a) => {
                    let q: Angle = cx.quantity(a, &format!("{f}.angular_diameter"))?;
                    let deg = q.get::<angle::degree>();
                    if !(0.0..=30.0).contains(&deg) {
                        return Err(cx.err(
                            &a.span(),
                            format!("{f}.angular_diameter"),
                            format!("expected 0 to 30 deg, found {} deg", round9(deg)),
                        ));
                    }
                    q
                }
                None => Angle::new::<angle::radian>(0.0),
            };
            let (which, v) = one_amount(
                cx,
                &sp,
                &f,
                &[("irradiance", &l.irradiance), ("scale", &l.scale)],
            )?;
            let field = format!("{f}.{which}");
            let amount = if which == "irradiance" {
                match cx.quantity_of(v, &field, &[D::Irradiance, D::Illuminance])? {
                    (D::Irradiance, e) => DirectionalAmount::Irradiance(Irradiance::new::<
                        irradiance::watt_per_square_meter,
                    >(e)),
                    (_, lx) => {
                        DirectionalAmount::Illuminance(Illuminance::new::<illuminance::lux>(lx))
                    }
                }
            } else {
                DirectionalAmount::Scale(cx.number(v, &field)?)
            };
            LightKind::Directional {
                direction,
                angular_diameter,
                amount,
            }
        }
        "environment" if l.image.is_some() => {
            cx.only(
                "an environment map (an environment light with an image)",
                &f,
                &all,
                &[
                    "kind",
                    "image",
                    "transform",
                    "radiance",
                    "luminance",
                    "irradiance",
                    "scale",
                ],
            )?;
            let (file, span) = match &l.image {
                Some(i) => (i.get_ref().as_str(), i.span()),
                None => ("", sp.clone()),
            };
            let path = cx.path(file);
            if !path.is_file() {
                return Err(cx.err(
                    &span,
                    format!("{f}.image"),
                    format!("image file not found: {}", path.display()),
                ));
            }
            LightKind::EnvMap {
                path,
                transform: match &l.transform {
                    Some(t) => shapes::transform(cx, t, &format!("{f}.transform"))?,
                    None => Vec::new(),
                },
                amount: envmap_amount(cx, &sp, &f, l)?,
            }
        }
        "environment" => {
            cx.only(
                "an environment light",
                &f,
                &all,
                &["kind", "spectrum", "radiance", "luminance", "scale"],
            )?;
            LightKind::Environment {
                amount: emit_amount(cx, &sp, &f, &l.radiance, &l.luminance, &None, &l.scale)?,
            }
        }
        "beam" => {
            cx.only(
                "a beam light",
                &f,
                &all,
                &[
                    "kind", "spectrum", "position", "target", "radius", "power", "scale",
                ],
            )?;
            let (position, target) = aim(cx, "beam")?;
            let r = cx.required(
                &l.radius,
                &sp,
                &format!("{f}.radius"),
                "the beam radius, a positive length",
            )?;
            let radius = cx.length(r, &format!("{f}.radius"))?;
            if !(radius.get::<length::meter>() > 0.0) {
                return Err(cx.err(
                    &r.span(),
                    format!("{f}.radius"),
                    "expected a positive radius",
                ));
            }
            LightKind::Beam {
                position,
                target,
                radius,
                amount: point_amount(cx)?,
            }
        }
        "sky" => {
            cx.only(
                "a sky",
                &f,
                &all,
                &[
                    "kind",
                    "spectrum",
                    "model",
                    "luminance",
                    "irradiance",
                    "sun_elevation",
                    "sun_azimuth",
                    "latitude",
                    "longitude",
                    "time",
                    "up",
                    "north",
                ],
            )?;
            sky(cx, &sp, &f, l)?
        }
        "luminaire" => {
            cx.only(
                "a luminaire",
                &f,
                &all,
                &[
                    "kind", "spectrum", "position", "target", "file", "c0", "tilt", "power",
                    "scale",
                ],
            )?;
            luminaire(cx, &sp, &f, l, aim(cx, "luminaire's nadir (0° vertical)")?)?
        }
        o => {
            return Err(cx.err(
                &ty.span(),
                format!("{f}.type"),
                format!(
                    "unknown light type \"{o}\"; expected point, spot, directional, sun, environment, sky, beam or luminaire"
                ),
            ));
        }
    };
    // an environment map's pixels are linear sRGB under D65: RGB (1, 1, 1) is D65 of luminance
    // 1 cd/m² before `scale` (or the luminance or radiance that replaces it)
    let spectrum = match kind {
        LightKind::EnvMap { .. } => Spectrum::Piecewise(std::sync::Arc::new(
            crate::spectrum::rgb2spec::d65_unit_luminance()
                .scaled((1.0 / crate::colour::cie::K_M) as f32),
        )),
        _ => spectrum,
    };
    Ok(LightDesc {
        kind,
        spectrum,
        sampling_weight: 1.0,
        loc: cx.src.span(&sp),
    })
}

/// An environment map's brightness: exactly one of `scale`, `radiance` or `luminance` (means
/// over the sphere), `irradiance` (W/m² or lx on a plane facing the map's zenith).
fn envmap_amount(cx: &Cx<'_>, sp: &Range<usize>, f: &str, l: &RawLight) -> R<EnvMapAmount> {
    let (which, v) = one_amount(
        cx,
        sp,
        f,
        &[
            ("scale", &l.scale),
            ("radiance", &l.radiance),
            ("luminance", &l.luminance),
            ("irradiance", &l.irradiance),
        ],
    )?;
    let field = format!("{f}.{which}");
    let (amount, si) = match which {
        "radiance" => {
            let r: Radiance = cx.quantity(v, &field)?;
            let x = r.get::<radiance::watt_per_square_meter_steradian>();
            (EnvMapAmount::Radiance(r), x)
        }
        "luminance" => {
            let q: Luminance = cx.quantity(v, &field)?;
            let x = q.get::<luminance::candela_per_square_meter>();
            (EnvMapAmount::Luminance(q), x)
        }
        "irradiance" => match cx.quantity_of(v, &field, &[D::Irradiance, D::Illuminance])? {
            (D::Irradiance, e) => (
                EnvMapAmount::Irradiance(Irradiance::new::<irradiance::watt_per_square_meter>(e)),
                e,
            ),
            (_, lx) => (
                EnvMapAmount::Illuminance(Illuminance::new::<illuminance::lux>(lx)),
                lx,
            ),
        },
        _ => {
            let k = cx.number(v, &field)?;
            (EnvMapAmount::Scale(k), k)
        }
    };
    if !(si >= 0.0) {
        return Err(cx.err(
            &v.span(),
            field,
            format!("light cannot be negative, found {si}"),
        ));
    }
    Ok(amount)
}
