//! Thin films: `coating = [{ thickness = "99.6 nm", ior = "MgF2" }, …]` on dielectric and
//! conductor materials (the layers from the outside in; `metal = "Ag"` for an absorbing
//! layer), and `type = "thin_film"`, a free-standing film such as a soap bubble's wall:
//!
//! ```toml
//! [materials.bubble]
//! type = "thin_film"
//! layers = [{ thickness = "380 nm", ior = "water" }]
//! ```

use super::*;
use crate::loader::desc::CoatingLayerDesc;
use crate::optics::thin_film::LayerIndex;

pub(super) const THIN_FILM: Kind = Kind {
    name: "thin_film",
    keys: &["layers", "exterior_ior"],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    m.required(
        "layers",
        "the film's layers, e.g. [{ thickness = \"380 nm\", ior = \"water\" }]",
    )?;
    Ok(MaterialKind::ThinFilm {
        layers: layers(m, "layers")?.unwrap_or_default(),
        exterior_ior: m.exterior()?,
    })
}

/// Thicker than this, a film is not coherent in white light (and its fringes are finer than
/// any wavelength sampling): a slab of dielectric is the model for it.
const MAX_THICKNESS_NM: f64 = 10_000.0;

/// The layers at `key`, None if absent.
pub(super) fn layers(m: &Mat<'_>, key: &str) -> R<Option<Vec<CoatingLayerDesc>>> {
    let Some(v) = m.get(key) else {
        return Ok(None);
    };
    let (span, field) = (v.span(), m.field(key));
    let example =
        "a list of layers from the outside in, e.g. [{ thickness = \"99.6 nm\", ior = \"MgF2\" }]";
    let Value::Array(items) = v.get_ref() else {
        return Err(m.cx.err(&span, &field, format!("expected {example}")));
    };
    if items.is_empty() {
        return Err(m
            .cx
            .err(&span, &field, format!("no layers; expected {example}")));
    }
    let mut out = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        let f = format!("{field}[{i}]");
        let Value::Table(t) = item else {
            return Err(m.cx.err(&span, &f, format!("expected a table; {example}")));
        };
        if let Some(k) = t
            .keys()
            .find(|k| !["thickness", "ior", "metal"].contains(&k.as_str()))
        {
            return Err(m.cx.err(
                &span,
                format!("{f}.{k}"),
                "unknown key; a layer takes thickness and ior (a dielectric) or metal",
            ));
        }
        let at = |v: &Value| S::new(span.clone(), v.clone());
        let Some(th) = t.get("thickness") else {
            return Err(m.cx.err(
                &span,
                format!("{f}.thickness"),
                "missing; expected a length, e.g. \"99.6 nm\"",
            ));
        };
        let thickness = m.cx.length(&at(th), &format!("{f}.thickness"))?;
        let nm = thickness.get::<length::nanometer>();
        if !(nm.is_finite() && (0.0..=MAX_THICKNESS_NM).contains(&nm)) {
            return Err(m.cx.err(
                &span,
                format!("{f}.thickness"),
                format!(
                    "expected 0 to {MAX_THICKNESS_NM} nm (a thicker film is not coherent in white \
                     light: model it as a slab of dielectric), found {nm} nm"
                ),
            ));
        }
        let medium = match (t.get("ior"), t.get("metal")) {
            (Some(i), None) => LayerIndex::Dielectric(m.cx.ior(&at(i), &format!("{f}.ior"))?),
            (None, Some(Value::String(s))) => LayerIndex::Absorbing(
                m.cx.metal(&S::new(span.clone(), s.clone()), &format!("{f}.metal"))?,
            ),
            _ => {
                return Err(m.cx.err(
                    &span,
                    &f,
                    "a layer needs either `ior` (a dielectric, e.g. \"MgF2\") or `metal` (e.g. \"Ag\")",
                ));
            }
        };
        out.push(CoatingLayerDesc { medium, thickness });
    }
    Ok(Some(out))
}

/// `kind` under the layers of `coating`, if the material has them.
pub(super) fn coated(m: &Mat<'_>, kind: MaterialKind) -> R<MaterialKind> {
    Ok(match layers(m, "coating")? {
        Some(layers) => MaterialKind::Coated {
            layers,
            inner: Box::new(kind),
        },
        None => kind,
    })
}
