//! `type = "dielectric"`: a smooth or rough (GGX) dispersive interface, `ior` a number or a
//! glass name, with optional textured roughness and lobe factors (see [`lobes`]).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "dielectric",
    keys: &[
        "ior",
        "exterior_ior",
        "roughness",
        "specular_reflectance",
        "specular_transmittance",
        "coating",
    ],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let i = m.required("ior", "an index: a number or a glass name like \"N-BK7\"")?;
    let kind = MaterialKind::Dielectric {
        ior: m.cx.ior(i, &m.field("ior"))?,
        exterior_ior: m.exterior()?,
        roughness: m.roughness(true)?,
        distribution: Distribution::Ggx,
        smith: Smith::HeightCorrelated,
    };
    let kind = lobes(m, kind)?;
    coating::coated(m, kind)
}
