//! `type = "directional"` and `"sun"`: light from one `direction` (or the sun's, placed by
//! latitude, longitude and time or by angles; see `daylight.rs`) within `angular_diameter`
//! (0 to 30 deg), its amount as irradiance (W/m² or lx on a plane facing the light) or a scale.

use super::daylight::sun_placement;
use super::*;

const KEYS: &[&str] = &[
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
];

pub(super) const DIRECTIONAL: Kind = Kind {
    name: "directional",
    what: "a directional light",
    keys: Some(KEYS),
    default_spectrum: flat,
    read,
};

pub(super) const SUN: Kind = Kind {
    name: "sun",
    what: "a directional light",
    keys: Some(KEYS),
    default_spectrum: flat,
    read,
};

fn read(l: &Lt<'_>) -> R<(LightKind, Spectrum)> {
    let (cx, raw) = (l.cx, l.l);
    let spectrum = l.spectrum.clone();
    let direction = direction(l)?;
    let angular_diameter = match &raw.angular_diameter {
        Some(a) => {
            let q: Angle = cx.quantity(a, &l.field("angular_diameter"))?;
            let deg = q.get::<angle::degree>();
            if !(0.0..=30.0).contains(&deg) {
                return Err(cx.err(
                    &a.span(),
                    l.field("angular_diameter"),
                    format!("expected 0 to 30 deg, found {} deg", round9(deg)),
                ));
            }
            q
        }
        None => Angle::new::<angle::radian>(0.0),
    };
    let (which, v) = one_amount(
        cx,
        &l.sp,
        &l.f,
        &[("irradiance", &raw.irradiance), ("scale", &raw.scale)],
    )?;
    let field = l.field(which);
    let amount = if which == "irradiance" {
        match cx.quantity_of(v, &field, &[D::Irradiance, D::Illuminance])? {
            (D::Irradiance, e) => DirectionalAmount::Irradiance(Irradiance::new::<
                irradiance::watt_per_square_meter,
            >(e)),
            (_, lx) => DirectionalAmount::Illuminance(Illuminance::new::<illuminance::lux>(lx)),
        }
    } else {
        DirectionalAmount::Scale(cx.number(v, &field)?)
    };
    let kind = LightKind::Directional {
        direction,
        angular_diameter,
        amount,
    };
    Ok((kind, spectrum))
}

/// The direction light travels: `direction`, or away from the sun placed by time and place
/// or angles (not both).
fn direction(l: &Lt<'_>) -> R<[f64; 3]> {
    let (cx, raw) = (l.cx, l.l);
    let placed = raw.time.is_some()
        || raw.sun_elevation.is_some()
        || raw.sun_azimuth.is_some()
        || raw.latitude.is_some()
        || raw.longitude.is_some();
    if let (Some(d), true) = (&raw.direction, placed) {
        return Err(cx.err(
            &d.span(),
            l.field("direction"),
            "give the direction, or the sun's place and time (or angles), not both",
        ));
    }
    if raw.direction.is_none() && placed {
        // every placing key either places the sun or is refused by sun_placement
        let (_, sun) = sun_placement(cx, &l.sp, &l.f, raw)?;
        let sun = sun.ok_or_else(|| {
            cx.err(
                &l.sp,
                l.field("time"),
                "the sun needs a time and place or sun_elevation",
            )
        })?;
        return Ok(sun.map(|x| -x));
    }
    let d = l.required(
        &raw.direction,
        "direction",
        "the direction light travels, [x, y, z], or the sun's place (latitude, longitude, time) or angles (sun_elevation, sun_azimuth)",
    )?;
    let direction = cx.vec3(d, &l.field("direction"))?;
    if direction == [0.0; 3] {
        return Err(cx.err(&d.span(), l.field("direction"), "the direction is zero"));
    }
    Ok(direction)
}
