//! `type = "phong"`: the notes' energy-conserving Phong lobes, `kd` + `ks` ≤ 1 at every
//! wavelength, shininess `exponent` in [0, 1e6].

use super::*;

pub(super) const KIND: Kind = Kind {
    name: "phong",
    keys: &["kd", "ks", "exponent"],
    read,
};

fn read(m: &Mat<'_>) -> R<MaterialKind> {
    let kd_v = m.required("kd", "a diffuse reflectance spectrum")?;
    let ks_v = m.required("ks", "a specular reflectance spectrum")?;
    let kd =
        m.cx.spectrum(kd_v, &m.field("kd"), SpectrumUse::Reflectance)?;
    let ks =
        m.cx.spectrum(ks_v, &m.field("ks"), SpectrumUse::Reflectance)?;
    check_reflectance(
        m.cx,
        &sum(&kd, &ks),
        &ks_v.span(),
        &format!("{} + {}", m.field("kd"), m.field("ks")),
        m.range,
    )?;
    let e = m.required("exponent", "a shininess exponent ≥ 0")?;
    let exponent = m.number(e, "exponent")?;
    if !(0.0..=1e6).contains(&exponent) {
        return Err(m.cx.err(
            &e.span(),
            m.field("exponent"),
            format!("expected 0 to 1e6, found {exponent}"),
        ));
    }
    Ok(MaterialKind::Phong { kd, ks, exponent })
}

/// kd + ks as one spectrum, tabulated at 1 nm over 200–2000 nm, for the energy check only.
fn sum(kd: &Spectrum, ks: &Spectrum) -> Spectrum {
    let l: Vec<f32> = (200..=2000).map(|x| x as f32).collect();
    let v: Vec<f32> = l.iter().map(|&x| kd.eval(x) + ks.eval(x)).collect();
    match crate::spectrum::PiecewiseLinear::new(l, v) {
        Ok(t) => Spectrum::Piecewise(std::sync::Arc::new(t)),
        Err(_) => Spectrum::Constant(f32::NAN),
    }
}
