//! `type = "luminaire"`: a photometric file (IES LM-63 or EULUMDAT) placed and aimed.

use super::super::*;
use super::{Kind, Lt};

pub(super) const KIND: Kind = Kind {
    name: "luminaire",
    what: "a luminaire",
    keys: Some(&[
        "spectrum", "position", "target", "file", "c0", "tilt", "power", "scale",
    ]),
    // CIE illuminant A, the lamp of classical photometry
    default_spectrum: || {
        Spectrum::Blackbody(crate::spectrum::blackbody::Blackbody::cie_illuminant_a())
    },
    read,
};

fn read(l: &Lt<'_>) -> R<(LightKind, Spectrum)> {
    let spectrum = l.spectrum.clone();
    let aim = l.aim("luminaire's nadir (0° vertical)")?;
    Ok((luminaire(l.cx, &l.sp, &l.f, l.l, aim)?, spectrum))
}

/// A luminaire: its photometric file read, its C0 direction and tilt, and its amount (the
/// file's candela by default, `scale` times them, or `power` in lm or W setting the total).
fn luminaire(
    cx: &Cx<'_>,
    sp: &Range<usize>,
    f: &str,
    l: &RawLight,
    (position, target): (Point, Point),
) -> R<LightKind> {
    let file = cx.required(
        &l.file,
        sp,
        &format!("{f}.file"),
        "a photometric file, IES LM-63 (.ies) or EULUMDAT (.ldt)",
    )?;
    let path = cx.path(file.get_ref());
    if !path.is_file() {
        return Err(cx.err(
            &file.span(),
            format!("{f}.file"),
            format!("photometric file not found: {}", path.display()),
        ));
    }
    let photometry = crate::loader::photometric::load(&path)?;
    let c0 = match &l.c0 {
        None => None,
        Some(v) => {
            let d = cx.vec3(v, &format!("{f}.c0"))?;
            let nadir = [0, 1, 2]
                .map(|k| target[k].get::<length::meter>() - position[k].get::<length::meter>());
            let n2: f64 = nadir.iter().map(|x| x * x).sum();
            let d2: f64 = d.iter().map(|x| x * x).sum();
            let dot: f64 = (0..3).map(|k| nadir[k] * d[k]).sum();
            // the part of c0 perpendicular to the nadir must not vanish
            if !(d2 > 0.0 && d2 - dot * dot / n2 > 1e-6 * d2) {
                return Err(cx.err(
                    &v.span(),
                    format!("{f}.c0"),
                    "the C0 direction must not be zero or along the nadir (position → target)",
                ));
            }
            Some(d)
        }
    };
    let tilt = match &l.tilt {
        None => 0.0,
        Some(t) => cx.degrees_in(t, &format!("{f}.tilt"), "a tilt", 0.0, 180.0)?,
    };
    let tilt = Angle::new::<angle::degree>(tilt);
    let amount = match (&l.power, &l.scale) {
        (Some(_), Some(s)) => {
            return Err(cx.err(
                &s.span(),
                format!("{f}.scale"),
                "give power or scale, not both",
            ));
        }
        (Some(p), None) => {
            let field = format!("{f}.power");
            let (amount, v) = match cx.quantity_of(p, &field, &[D::Power, D::LuminousFlux])? {
                (D::Power, w) => (LuminaireAmount::Power(Power::new::<power::watt>(w)), w),
                (_, lm) => (
                    LuminaireAmount::LuminousFlux(LuminousFlux::new::<luminous_flux::lumen>(lm)),
                    lm,
                ),
            };
            non_negative(cx, p, &field, v)?;
            amount
        }
        (None, Some(s)) => {
            let field = format!("{f}.scale");
            let k = cx.number(s, &field)?;
            non_negative(cx, s, &field, k)?;
            LuminaireAmount::Scale(k)
        }
        (None, None) => LuminaireAmount::File,
    };
    Ok(LightKind::Luminaire {
        position,
        target,
        c0,
        tilt,
        photometry: Box::new(photometry),
        amount,
    })
}
