//! `type = "mask"`: Mitsuba's `mask`, `opacity` (a number or a grey texture in [0, 1],
//! default 0.5) of the material named by `material`, the rest straight through.

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "mask",
    keys: &["opacity", "material"],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let (_, inner) = m.named_at(
        "material",
        "the name of the masked material",
        "a mask",
        &["mask", "blend"],
        "another mask or blend",
    )?;
    Ok(MaterialKind::Mask {
        opacity: m.texture_or("opacity", 0.5)?,
        inner: Box::new(inner),
    })
}
