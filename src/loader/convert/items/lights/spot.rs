//! `type = "spot"`: a point at `position` aimed at `target`, lit within `cone_angle` (a
//! half-angle in (0, 90] deg), fading from `falloff_start` by `falloff` ("smoothstep" in cos θ,
//! or "linear" in the angle as Mitsuba's spot).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "spot",
    what: "a spot light",
    keys: Some(&[
        "spectrum",
        "position",
        "target",
        "power",
        "intensity",
        "scale",
        "cone_angle",
        "falloff_start",
        "falloff",
    ]),
    default_spectrum: flat,
    read,
};

fn read(l: &Lt<'_>) -> R<(LightKind, Spectrum)> {
    let (cx, raw) = (l.cx, l.l);
    let spectrum = l.spectrum.clone();
    let (position, target) = l.aim("spot")?;
    let c = l.required(
        &raw.cone_angle,
        "cone_angle",
        "the cone's half-angle, e.g. \"30 deg\"",
    )?;
    let cone_angle: Angle = cx.quantity(c, &l.field("cone_angle"))?;
    let cd = cone_angle.get::<angle::degree>();
    if !(cd > 0.0 && cd <= 90.0) {
        return Err(cx.err(
            &c.span(),
            l.field("cone_angle"),
            format!(
                "expected a half-angle in (0, 90] deg, found {} deg",
                round9(cd)
            ),
        ));
    }
    let falloff_start = match &raw.falloff_start {
        Some(fs) => {
            let a: Angle = cx.quantity(fs, &l.field("falloff_start"))?;
            let d = a.get::<angle::degree>();
            if !(0.0..=cd).contains(&d) {
                return Err(cx.err(
                    &fs.span(),
                    l.field("falloff_start"),
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
    let kind = LightKind::Spot {
        position,
        target,
        cone_angle,
        falloff_start,
        falloff: falloff(l)?,
        amount: l.point_amount()?,
        texture: None,
    };
    Ok((kind, spectrum))
}

fn falloff(l: &Lt<'_>) -> R<SpotFalloff> {
    let Some(v) = &l.l.falloff else {
        return Ok(SpotFalloff::SmoothstepCos);
    };
    match l
        .cx
        .string(v, &l.field("falloff"), "\"smoothstep\" or \"linear\"")?
    {
        "smoothstep" => Ok(SpotFalloff::SmoothstepCos),
        "linear" => Ok(SpotFalloff::LinearAngle),
        o => Err(l.cx.err(
            &v.span(),
            l.field("falloff"),
            format!(
                "\"{o}\": expected \"smoothstep\" (in cos θ) or \"linear\" (in the angle, as Mitsuba's spot)"
            ),
        )),
    }
}
