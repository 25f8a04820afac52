//! `type = "polariser"` and `type = "retarder"`: thin polarising elements crossed undeviated
//! (Mitsuba's `polarizer` and `retarder`). In an unpolarised render a polariser is a grey
//! filter of ½·transmittance and a retarder is clear; a scene holding either renders polarised.

use super::*;
use crate::units::Angle;

pub(super) const POLARISER: Kind = Kind {
    name: "polariser",
    keys: &["angle", "transmittance", "polarising"],
    read: polariser,
};

pub(super) const RETARDER: Kind = Kind {
    name: "retarder",
    keys: &["angle", "retardance"],
    read: retarder,
};

/// `angle` as an angle quantity ("30 deg"), 0 if absent.
fn angle(m: &Mat<'_>) -> R<Angle> {
    match m.get("angle") {
        Some(v) => m.cx.quantity(v, &m.field("angle")),
        None => Ok(Angle::new::<crate::units::angle::degree>(0.0)),
    }
}

fn polariser(m: &Mat<'_>) -> R<MaterialKind> {
    let transmittance = match m.get("transmittance") {
        Some(v) => {
            let t = m.number(v, "transmittance")?;
            if !(0.0..=1.0).contains(&t) {
                return Err(m.cx.err(
                    &v.span(),
                    m.field("transmittance"),
                    format!("expected a transmittance in [0, 1], found {t}"),
                ));
            }
            t
        }
        None => 1.0,
    };
    Ok(MaterialKind::Polariser {
        angle: angle(m)?,
        transmittance,
        polarizing: m.get("polarising").is_none() || m.flag("polarising")?,
    })
}

fn retarder(m: &Mat<'_>) -> R<MaterialKind> {
    let r = m.required(
        "retardance",
        "the phase delay of the slow axis, e.g. \"90 deg\" for a quarter-wave plate",
    )?;
    Ok(MaterialKind::Retarder {
        angle: angle(m)?,
        retardance: m.cx.quantity(r, &m.field("retardance"))?,
    })
}
