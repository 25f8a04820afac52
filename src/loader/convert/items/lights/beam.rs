//! `type = "beam"`: a collimated beam from `position` towards `target`, round (`radius`) or a
//! slit (`slit = [width, height]`, its height along `up`, default +y), its amount as power or
//! a scale.

use super::*;
use glam::DVec3;

use crate::loader::desc::BeamSection;

pub(super) const KIND: Kind = Kind {
    name: "beam",
    what: "a beam light",
    keys: Some(&[
        "spectrum", "position", "target", "radius", "slit", "up", "power", "scale",
    ]),
    default_spectrum: flat,
    read,
};

fn read(l: &Lt<'_>) -> R<(LightKind, Spectrum)> {
    let spectrum = l.spectrum.clone();
    let (position, target) = l.aim("beam")?;
    let section = match (&l.l.radius, &l.l.slit) {
        (Some(_), Some(s)) => {
            return Err(l.cx.err(
                &s.span(),
                l.field("slit"),
                "a beam has a radius or a slit, not both",
            ));
        }
        (None, Some(s)) => slit(l, s, (position, target))?,
        (r, None) => {
            let r = l.required(
                r,
                "radius",
                "the beam radius, a positive length (or a slit)",
            )?;
            BeamSection::Disk(positive(l, r, "radius")?)
        }
    };
    if let (Some(u), BeamSection::Disk(_)) = (&l.l.up, &section) {
        return Err(l
            .cx
            .err(&u.span(), l.field("up"), "applies to a slit beam only"));
    }
    let kind = LightKind::Beam {
        position,
        target,
        section,
        amount: l.point_amount()?,
    };
    Ok((kind, spectrum))
}

fn positive(l: &Lt<'_>, v: &S<Value>, key: &str) -> R<Length> {
    let x = l.cx.length(v, &l.field(key))?;
    if !(x.get::<length::meter>() > 0.0) {
        return Err(l
            .cx
            .err(&v.span(), l.field(key), "expected a positive length"));
    }
    Ok(x)
}

/// `slit = [width, height]`, its height along `up` (default +y) made perpendicular to the
/// beam.
fn slit(l: &Lt<'_>, s: &S<Value>, (p, t): (Point, Point)) -> R<BeamSection> {
    let span = s.span();
    let items = match s.get_ref() {
        Value::Array(a) if a.len() == 2 => a,
        _ => {
            return Err(l.cx.err(
                &span,
                l.field("slit"),
                "expected [width, height], two positive lengths",
            ));
        }
    };
    let at = |v: &Value| S::new(span.clone(), v.clone());
    let width = positive(l, &at(&items[0]), "slit")?;
    let height = positive(l, &at(&items[1]), "slit")?;
    let up = match &l.l.up {
        Some(u) => l.cx.vec3(u, &l.field("up"))?,
        None => [0.0, 1.0, 0.0],
    };
    let m = |q: Point| DVec3::from(q.map(|c| c.get::<length::meter>()));
    let (d, u) = (m(t) - m(p), DVec3::from(up));
    let perp = u - d * (u.dot(d) / d.length_squared());
    if !(perp.length() > 1e-6 * u.length().max(1e-300)) {
        let at = l.l.up.as_ref().map_or(span.clone(), |u| u.span());
        return Err(l.cx.err(
            &at,
            l.field("up"),
            "the slit's up direction is along the beam (or zero): give an `up` across it",
        ));
    }
    Ok(BeamSection::Slit {
        width,
        height,
        up: perp.normalize().to_array(),
    })
}
