//! `type = "thin_dielectric"`: a thin sheet of index `ior`, reflecting and passing light
//! straight through (Mitsuba's `thindielectric`).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "thin_dielectric",
    keys: &["ior", "exterior_ior"],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let i = m.required("ior", "the sheet's index")?;
    Ok(MaterialKind::ThinDielectric {
        int_ior: m.index(i, "ior")?,
        exterior_ior: m.exterior()?,
    })
}
