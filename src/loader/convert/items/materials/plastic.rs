//! `type = "plastic"`: a diffuse base under a smooth or rough (GGX, isotropic) dielectric
//! coating of index `ior` (default 1.49), Mitsuba's `plastic` and `roughplastic`; a smooth one
//! may carry thin-film layers (`coating`).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "plastic",
    keys: &[
        "reflectance",
        "ior",
        "exterior_ior",
        "roughness",
        "nonlinear",
        "coating",
    ],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let r = m.required("reflectance", "the diffuse base's reflectance")?;
    let int_ior = match m.get("ior") {
        None => 1.49,
        Some(i) => m.index(i, "ior")?,
    };
    let kind = MaterialKind::Plastic {
        diffuse: m.texture(r, "reflectance")?,
        specular: 1.0,
        int_ior,
        exterior_ior: m.exterior()?,
        nonlinear: m.flag("nonlinear")?,
        roughness: m.roughness(false)?.map(|a| a[0]),
        distribution: Distribution::Ggx,
    };
    coating::coated(m, kind)
}
