//! `type = "beam"`: a collimated beam of `radius` from `position` towards `target`, its
//! amount as power or a scale.

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "beam",
    what: "a beam light",
    keys: Some(&["spectrum", "position", "target", "radius", "power", "scale"]),
    default_spectrum: flat,
    read,
};

fn read(l: &Lt<'_>) -> R<(LightKind, Spectrum)> {
    let spectrum = l.spectrum.clone();
    let (position, target) = l.aim("beam")?;
    let r = l.required(&l.l.radius, "radius", "the beam radius, a positive length")?;
    let radius = l.cx.length(r, &l.field("radius"))?;
    if !(radius.get::<length::meter>() > 0.0) {
        return Err(l
            .cx
            .err(&r.span(), l.field("radius"), "expected a positive radius"));
    }
    let kind = LightKind::Beam {
        position,
        target,
        radius,
        amount: l.point_amount()?,
    };
    Ok((kind, spectrum))
}
