//! `type = "null"`: no surface; rays pass straight through (Mitsuba's `null`).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "null",
    keys: &[],
    read,
};

fn read(_: &Mat<'_>) -> R<MaterialKind> {
    Ok(MaterialKind::Null)
}
