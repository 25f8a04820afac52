//! `[[lights]]`: point, spot, directional and environment lights.

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
                let (_, sun) = sun_placement(cx, &sp, &f, l)?;
                match sun {
                    Some(d) => d.map(|x| -x),
                    None => unreachable_sun(cx, &sp, &f)?,
                }
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

/// The scene's up and north (unit, north made perpendicular to up): defaults +y and −z.
fn up_north(cx: &Cx<'_>, sp: &Range<usize>, f: &str, l: &RawLight) -> R<([f64; 3], [f64; 3])> {
    let unit = |v: &Option<S<Value>>, key: &str, default: [f64; 3]| -> R<[f64; 3]> {
        let Some(x) = v else { return Ok(default) };
        let d = cx.vec3(x, &format!("{f}.{key}"))?;
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(n > 0.0) {
            return Err(cx.err(&x.span(), format!("{f}.{key}"), "the direction is zero"));
        }
        Ok(d.map(|c| c / n))
    };
    let up = unit(&l.up, "up", [0.0, 1.0, 0.0])?;
    let north = unit(&l.north, "north", [0.0, 0.0, -1.0])?;
    let dot = up[0] * north[0] + up[1] * north[1] + up[2] * north[2];
    let n = [0, 1, 2].map(|k| north[k] - dot * up[k]);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if !(len > 1e-3) {
        let span = l.north.as_ref().map_or(sp.clone(), |x| x.span());
        return Err(cx.err(&span, format!("{f}.north"), "north must not be along up"));
    }
    Ok((up, n.map(|c| c / len)))
}

/// The sun's direction (unit, toward the sun) from `time` with `latitude` and `longitude` (NOAA,
/// refracted), or from `sun_elevation` and `sun_azimuth` (default 180°, south); None when
/// neither is given. Also returns `up`.
fn sun_placement(
    cx: &Cx<'_>,
    sp: &Range<usize>,
    f: &str,
    l: &RawLight,
) -> R<([f64; 3], Option<[f64; 3]>)> {
    let (up, north) = up_north(cx, sp, f, l)?;
    let angle = |v: &S<Value>, key: &str, lo: f64, hi: f64| -> R<f64> {
        let a: Angle = match v.get_ref() {
            Value::String(_) => cx.quantity(v, &format!("{f}.{key}"))?,
            _ => Angle::new::<angle::degree>(cx.number(v, &format!("{f}.{key}"))?),
        };
        let d = a.get::<angle::degree>();
        if !(lo..=hi).contains(&d) {
            return Err(cx.err(
                &v.span(),
                format!("{f}.{key}"),
                format!("expected {lo} to {hi} deg, found {} deg", round9(d)),
            ));
        }
        Ok(d)
    };
    if let Some(t) = &l.time {
        if l.sun_elevation.is_some() || l.sun_azimuth.is_some() {
            return Err(cx.err(
                &t.span(),
                format!("{f}.time"),
                "give the sun by time and place or by sun_elevation and sun_azimuth, not both",
            ));
        }
        let time = crate::daylight::solar::UtcTime::parse(t.get_ref())
            .map_err(|m| cx.err(&t.span(), format!("{f}.time"), m))?;
        let lat = cx.required(
            &l.latitude,
            sp,
            &format!("{f}.latitude"),
            "degrees north, e.g. 52.0",
        )?;
        let lon = cx.required(
            &l.longitude,
            sp,
            &format!("{f}.longitude"),
            "degrees east, e.g. 4.36",
        )?;
        let lat = angle(lat, "latitude", -90.0, 90.0)?;
        let lon = angle(lon, "longitude", -180.0, 180.0)?;
        let s = crate::daylight::solar::sun_position(lat, lon, time);
        if s.zenith >= 90.0 {
            return Err(cx.err(
                &t.span(),
                format!("{f}.time"),
                format!(
                    "the sun is below the horizon then (zenith angle {:.2} deg)",
                    s.zenith
                ),
            ));
        }
        return Ok((
            up,
            Some(crate::daylight::sky_direction(
                s.zenith, s.azimuth, up, north,
            )),
        ));
    }
    if l.latitude.is_some() || l.longitude.is_some() {
        let v = l
            .latitude
            .as_ref()
            .or(l.longitude.as_ref())
            .map_or(sp.clone(), |v| v.span());
        return Err(cx.err(
            &v,
            format!("{f}.time"),
            "latitude and longitude place the sun only with a time",
        ));
    }
    match &l.sun_elevation {
        Some(e) => {
            let elev = angle(e, "sun_elevation", 0.0, 90.0)?;
            let az = match &l.sun_azimuth {
                Some(a) => angle(a, "sun_azimuth", -360.0, 360.0)?,
                None => 180.0,
            };
            Ok((
                up,
                Some(crate::daylight::sky_direction(90.0 - elev, az, up, north)),
            ))
        }
        None => {
            if let Some(a) = &l.sun_azimuth {
                return Err(cx.err(
                    &a.span(),
                    format!("{f}.sun_elevation"),
                    "missing: sun_azimuth needs sun_elevation",
                ));
            }
            Ok((up, None))
        }
    }
}

fn unreachable_sun<T>(cx: &Cx<'_>, sp: &Range<usize>, f: &str) -> R<T> {
    Err(cx.err(
        sp,
        format!("{f}.time"),
        "the sun needs a time and place or sun_elevation",
    ))
}

/// A CIE sky: its model, its sun, and its zenith luminance or horizontal illuminance.
fn sky(cx: &Cx<'_>, sp: &Range<usize>, f: &str, l: &RawLight) -> R<LightKind> {
    use crate::daylight::sky::SkyModel;
    let m = cx.required(
        &l.model,
        sp,
        &format!("{f}.model"),
        "\"cie-overcast\" or \"cie-1\" … \"cie-15\"",
    )?;
    let name = m.get_ref().trim().to_ascii_lowercase();
    let model = match name.as_str() {
        "cie-overcast" | "overcast" => SkyModel::Overcast,
        n => match n.strip_prefix("cie-").and_then(|t| t.parse::<u8>().ok()) {
            Some(t) if (1..=15).contains(&t) => SkyModel::General(t),
            _ => {
                return Err(cx.err(
                    &m.span(),
                    format!("{f}.model"),
                    format!("\"{}\": expected \"cie-overcast\" (Moon–Spencer, CIE S 003) or a CIE general sky \"cie-1\" … \"cie-15\" (ISO 15469; 12 is the CIE clear sky)", m.get_ref()),
                ));
            }
        },
    };
    let (up, sun) = sun_placement(cx, sp, f, l)?;
    // types 1, 3 and 5 and the overcast sky do not depend on the sun
    let needs_sun = matches!(model, SkyModel::General(t) if ![1, 3, 5].contains(&t));
    let sun = match sun {
        Some(s) => s,
        None if !needs_sun => up,
        None => {
            return Err(cx.err(
                sp,
                format!("{f}.sun_elevation"),
                "this sky type depends on the sun: give sun_elevation (and sun_azimuth) or latitude, longitude and time",
            ));
        }
    };
    let (which, v) = one_amount(
        cx,
        sp,
        f,
        &[("luminance", &l.luminance), ("irradiance", &l.irradiance)],
    )?;
    let field = format!("{f}.{which}");
    let (amount, x) = if which == "luminance" {
        let q: Luminance = cx.quantity(v, &field)?;
        let x = q.get::<luminance::candela_per_square_meter>();
        (SkyAmount::ZenithLuminance(q), x)
    } else {
        match cx.quantity_of(v, &field, &[D::Illuminance, D::Irradiance])? {
            (D::Illuminance, lx) => (
                SkyAmount::HorizontalIlluminance(Illuminance::new::<illuminance::lux>(lx)),
                lx,
            ),
            (_, e) => (
                SkyAmount::HorizontalIrradiance(
                    Irradiance::new::<irradiance::watt_per_square_meter>(e),
                ),
                e,
            ),
        }
    };
    if !(x >= 0.0) {
        return Err(cx.err(
            &v.span(),
            field,
            format!("light cannot be negative, found {x}"),
        ));
    }
    Ok(LightKind::Sky {
        model,
        sun,
        up,
        amount,
    })
}

/// A luminaire: its photometric file read, its C0 direction and tilt, and its amount (the
/// file's candela by default, `scale` times them, or `power` in lm or W setting the total).
fn luminaire(
    cx: &Cx<'_>,
    sp: &Range<usize>,
    f: &str,
    l: &RawLight,
    (position, target): (Point, Point),
) -> R<LightKind> {
    let file = cx.required(
        &l.file,
        sp,
        &format!("{f}.file"),
        "a photometric file, IES LM-63 (.ies) or EULUMDAT (.ldt)",
    )?;
    let path = cx.path(file.get_ref());
    if !path.is_file() {
        return Err(cx.err(
            &file.span(),
            format!("{f}.file"),
            format!("photometric file not found: {}", path.display()),
        ));
    }
    let photometry = crate::loader::photometric::load(&path)?;
    let c0 = match &l.c0 {
        None => None,
        Some(v) => {
            let d = cx.vec3(v, &format!("{f}.c0"))?;
            let nadir = [0, 1, 2]
                .map(|k| target[k].get::<length::meter>() - position[k].get::<length::meter>());
            let n2: f64 = nadir.iter().map(|x| x * x).sum();
            let d2: f64 = d.iter().map(|x| x * x).sum();
            let dot: f64 = (0..3).map(|k| nadir[k] * d[k]).sum();
            // the part of c0 perpendicular to the nadir must not vanish
            if !(d2 > 0.0 && d2 - dot * dot / n2 > 1e-6 * d2) {
                return Err(cx.err(
                    &v.span(),
                    format!("{f}.c0"),
                    "the C0 direction must not be zero or along the nadir (position → target)",
                ));
            }
            Some(d)
        }
    };
    let tilt = match &l.tilt {
        None => Angle::new::<angle::degree>(0.0),
        Some(t) => {
            let a: Angle = cx.quantity(t, &format!("{f}.tilt"))?;
            let d = a.get::<angle::degree>();
            if !(0.0..=180.0).contains(&d) {
                return Err(cx.err(
                    &t.span(),
                    format!("{f}.tilt"),
                    format!("expected a tilt from 0 to 180 deg, found {} deg", round9(d)),
                ));
            }
            a
        }
    };
    let amount = match (&l.power, &l.scale) {
        (Some(_), Some(s)) => {
            return Err(cx.err(
                &s.span(),
                format!("{f}.scale"),
                "give power or scale, not both",
            ));
        }
        (Some(p), None) => {
            let field = format!("{f}.power");
            let (amount, v) = match cx.quantity_of(p, &field, &[D::Power, D::LuminousFlux])? {
                (D::Power, w) => (LuminaireAmount::Power(Power::new::<power::watt>(w)), w),
                (_, lm) => (
                    LuminaireAmount::LuminousFlux(LuminousFlux::new::<luminous_flux::lumen>(lm)),
                    lm,
                ),
            };
            if !(v >= 0.0) {
                return Err(cx.err(
                    &p.span(),
                    field,
                    format!("light cannot be negative, found {v}"),
                ));
            }
            amount
        }
        (None, Some(s)) => {
            let field = format!("{f}.scale");
            let k = cx.number(s, &field)?;
            if !(k >= 0.0) {
                return Err(cx.err(
                    &s.span(),
                    field,
                    format!("light cannot be negative, found {k}"),
                ));
            }
            LuminaireAmount::Scale(k)
        }
        (None, None) => LuminaireAmount::File,
    };
    Ok(LightKind::Luminaire {
        position,
        target,
        c0,
        tilt,
        photometry: Box::new(photometry),
        amount,
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
