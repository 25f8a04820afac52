//! The sun's placement (by time and place, or by angles) and `type = "sky"` lights.

use super::super::*;
use super::{Kind, flat};

pub(super) const SKY: Kind = Kind {
    name: "sky",
    what: "a sky",
    keys: Some(&[
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
    ]),
    default_spectrum: flat,
    read: |l| Ok((sky(l.cx, &l.sp, &l.f, l.l)?, l.spectrum.clone())),
};

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
pub(super) fn sun_placement(
    cx: &Cx<'_>,
    sp: &Range<usize>,
    f: &str,
    l: &RawLight,
) -> R<([f64; 3], Option<[f64; 3]>)> {
    let (up, north) = up_north(cx, sp, f, l)?;
    let angle = |v: &S<Value>, key: &str, lo: f64, hi: f64| {
        cx.degrees_in(v, &format!("{f}.{key}"), "an angle", lo, hi)
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
    non_negative(cx, v, &field, x)?;
    Ok(LightKind::Sky {
        model,
        sun,
        up,
        amount,
    })
}
