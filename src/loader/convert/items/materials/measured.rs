//! `type = "measured_polarized"`: Mitsuba's measured pBRDF (see
//! `crate::material::MeasuredPolarized`): `file` (a `.pbsdf` tensor file, relative to the scene
//! file), `alpha_sample` (the GGX roughness its sampling uses, default 0.1) and `wavelength`
//! (a length, e.g. "550 nm": the table read at that wavelength for every wavelength; default:
//! each its own).

use super::*;
use crate::units::Length;

pub(super) const KIND: Kind = Kind {
    name: "measured_polarized",
    keys: &["file", "alpha_sample", "wavelength"],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let v = m.required("file", "a .pbsdf file")?;
    let name = m.cx.string(v, &m.field("file"), "a .pbsdf file")?;
    let path = m.cx.path(name);
    let table = crate::loader::mitsuba::tensor::read_pbsdf(&path)
        .map_err(|e| m.cx.err(&v.span(), m.field("file"), e))?;
    let alpha_sample = match m.get("alpha_sample") {
        None => 0.1,
        Some(a) => {
            let x = m.number(a, "alpha_sample")?;
            if !(x > 0.0 && x.is_finite()) {
                return Err(m.cx.err(
                    &a.span(),
                    m.field("alpha_sample"),
                    format!("expected a roughness > 0, found {x}"),
                ));
            }
            x
        }
    };
    let wavelength = match m.get("wavelength") {
        None => None,
        Some(l) => {
            let nm = m.cx.quantity::<Length>(l, &m.field("wavelength"))?.value * 1e9;
            if !(nm > 0.0 && nm.is_finite()) {
                return Err(m.cx.err(
                    &l.span(),
                    m.field("wavelength"),
                    "expected a positive wavelength, e.g. \"550 nm\"".to_string(),
                ));
            }
            Some(nm)
        }
    };
    Ok(MaterialKind::MeasuredPolarized {
        table,
        alpha_sample,
        wavelength,
    })
}
