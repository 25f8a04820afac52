//! `type = "conductor"`: a smooth or rough (GGX) metal, its complex index from `metal` (a
//! name such as "Au") or `eta` and `k` spectra, with optional textured roughness and a lobe
//! factor (see [`lobes`]).

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "conductor",
    keys: &[
        "metal",
        "eta",
        "k",
        "exterior_ior",
        "roughness",
        "specular_reflectance",
        "coating",
    ],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let metal = m.string("metal", "a metal name like \"Au\"")?;
    let ior = match (metal, m.get("eta"), m.get("k")) {
        (Some(mm), None, None) => m.cx.metal(&mm, &m.field("metal"))?,
        (None, Some(e), Some(k)) => m.cx.eta_k(e, k, &m.f)?,
        _ => {
            return Err(m.cx.err(
                &m.sp,
                &m.f,
                "a conductor needs either `metal` (e.g. \"Au\") or both `eta` and `k`",
            ));
        }
    };
    let kind = MaterialKind::Conductor {
        ior,
        exterior_ior: m.exterior()?,
        roughness: m.roughness(true)?,
        distribution: Distribution::Ggx,
        smith: Smith::HeightCorrelated,
    };
    let kind = lobes(m, kind)?;
    coating::coated(m, kind)
}
