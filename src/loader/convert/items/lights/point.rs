//! `type = "point"`: an isotropic point at `position`, its amount as power (W or lm),
//! intensity (W/sr or cd) or a scale.

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "point",
    what: "a point light",
    keys: Some(&["spectrum", "position", "power", "intensity", "scale"]),
    default_spectrum: flat,
    read,
};

fn read(l: &Lt<'_>) -> R<(LightKind, Spectrum)> {
    let kind = LightKind::Point {
        position: l.position()?,
        amount: l.point_amount()?,
    };
    Ok((kind, l.spectrum.clone()))
}
