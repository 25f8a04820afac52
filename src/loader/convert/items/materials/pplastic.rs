//! `type = "pplastic"`: Mitsuba's polarising plastic (a rough specular reflection plus a diffuse
//! term under two Fresnel transmissions; see `crate::material::PPlastic`): `reflectance` (the
//! diffuse term's), `specular` (a factor on the specular lobe, default 1), `ior` (default 1.49),
//! `exterior_ior`, `roughness` (α, default 0.1; `[α_u, α_v]`), `distribution` ("beckmann", the
//! default as Mitsuba's, or "ggx").

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "pplastic",
    keys: &[
        "reflectance",
        "specular",
        "ior",
        "exterior_ior",
        "roughness",
        "distribution",
    ],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let r = m.required("reflectance", "the diffuse term's reflectance")?;
    let int_ior = match m.get("ior") {
        None => 1.49,
        Some(i) => m.index(i, "ior")?,
    };
    let specular = match m.get("specular") {
        None => 1.0,
        Some(v) => {
            let k = m.number(v, "specular")?;
            if !(k >= 0.0 && k.is_finite()) {
                return Err(m.cx.err(
                    &v.span(),
                    m.field("specular"),
                    format!("expected a factor >= 0, found {k}"),
                ));
            }
            k
        }
    };
    let distribution = match m.string("distribution", "\"beckmann\" or \"ggx\"")? {
        None => Distribution::Beckmann,
        Some(d) => match d.get_ref().as_str() {
            "beckmann" => Distribution::Beckmann,
            "ggx" => Distribution::Ggx,
            o => {
                return Err(m.cx.err(
                    &d.span(),
                    m.field("distribution"),
                    format!("\"{o}\": expected \"beckmann\" or \"ggx\""),
                ));
            }
        },
    };
    Ok(MaterialKind::PPlastic {
        diffuse: m.texture(r, "reflectance")?,
        specular,
        int_ior,
        exterior_ior: m.exterior()?,
        roughness: m.roughness(true)?.unwrap_or([0.1, 0.1]),
        distribution,
    })
}
