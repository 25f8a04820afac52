//! `type = "diffuse"`: Lambertian, `reflectance` a spectrum or texture in [0, 1].

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "diffuse",
    keys: &["reflectance"],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let r = m.required("reflectance", "a reflectance spectrum")?;
    Ok(MaterialKind::Diffuse {
        reflectance: m.texture(r, "reflectance")?,
    })
}
