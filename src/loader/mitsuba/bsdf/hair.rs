//! `hair`, read as Mitsuba 3.9.1 reads it (`src/bsdfs/hair.cpp`): pigment concentrations
//! (`eumelanin` 1.3, `pheomelanin` 0.2) or an absorption `sigma_a` (an unbounded colour or
//! spectrum, per fibre radius) times `scale` (1), but not both; `int_ior` (amber, 1.55) over
//! `ext_ior` (air); `longitudinal_roughness` and `azimuthal_roughness` (0.3); `scale_tilt`
//! (2°).

use super::super::cx::{Cx, R};
use super::super::xml::Element;
use super::{ior_of, plain};
use crate::loader::desc::{HairAbsorption, HairDesc, MaterialDesc, MaterialKind};
use crate::spectrum::{Spectrum, rgb2spec};
use crate::units::{Angle, angle::degree};

/// Reads the plugin.
pub(super) fn hair(cx: &Cx<'_>, b: &Element, name: &str, _: &str) -> R<(MaterialDesc, bool)> {
    let number = |key: &str, default: f64| -> R<f64> {
        match cx.child(b, key) {
            None => Ok(default),
            Some(c) if c.tag == "float" || c.tag == "integer" => cx.float(c),
            Some(c) => Err(cx.err(c, format!("a hair's {key} must be a <float>"))),
        }
    };
    let absorption = match cx.child(b, "sigma_a") {
        Some(c) => {
            for k in ["eumelanin", "pheomelanin"] {
                if cx.child(b, k).is_some() {
                    return Err(cx.err(
                        c,
                        format!("give either sigma_a or the pigments, not both (found {k}; Mitsuba refuses both)"),
                    ));
                }
            }
            HairAbsorption::Sigma {
                sigma_a: sigma_a(cx, c)?,
                scale: number("scale", 1.0)?,
            }
        }
        None => HairAbsorption::Pigments {
            eumelanin: number("eumelanin", 1.3)?,
            pheomelanin: number("pheomelanin", 0.2)?,
        },
    };
    let roughness = |key: &str| -> R<f64> {
        let r = number(key, 0.3)?;
        if !(r > 0.0 && r <= 1.0) {
            let at = cx.child(b, key).unwrap_or(b);
            return Err(cx.err(
                at,
                format!("{key} must be in (0, 1], found {r} (at 0 Mitsuba's lobes are degenerate and the fibre renders black)"),
            ));
        }
        Ok(r)
    };
    let (int_ior, ext_ior) = (
        ior_of(cx, b, "int_ior", 1.55)?,
        ior_of(cx, b, "ext_ior", 1.000277)?,
    );
    if !(int_ior > 0.0 && ext_ior > 0.0) || int_ior == ext_ior {
        return Err(cx.err(
            b,
            format!("the interior and exterior indices must be positive and differ, found {int_ior} and {ext_ior}"),
        ));
    }
    let desc = HairDesc {
        absorption,
        eta: int_ior / ext_ior,
        roughness: [
            roughness("longitudinal_roughness")?,
            roughness("azimuthal_roughness")?,
        ],
        scale_tilt: Angle::new::<degree>(number("scale_tilt", 2.0)?),
        pbrt: false,
    };
    plain(cx, b, name, MaterialKind::Hair(Box::new(desc)))
}

/// `sigma_a`: a number, an unbounded `<rgb>` (Mitsuba's `get_unbounded_texture`: the table's
/// spectrum of rgb/2m times 2m) or a `<spectrum>` of numbers; ≥ 0.
fn sigma_a(cx: &Cx<'_>, c: &Element) -> R<Spectrum> {
    let c = cx.resolve(c)?;
    let s = match c.tag.as_str() {
        "rgb" => {
            let v = cx.floats(c, c.attr("value").unwrap_or(""))?;
            let rgb = match v[..] {
                [g] => [g as f32; 3],
                [r, g, b] => [r as f32, g as f32, b as f32],
                _ => return Err(cx.err(c, "expected 3 numbers")),
            };
            rgb2spec::unbounded_table(rgb).map_err(|e| cx.err(c, e.to_string()))?
        }
        "float" | "spectrum" if c.attr("type").is_none() => cx.spectrum(c, false)?,
        _ => {
            return Err(cx.err(
                c,
                "a hair's sigma_a must be a <float>, <rgb> or <spectrum> of values (a texture is not supported)",
            ));
        }
    };
    let negative = match &s {
        Spectrum::Constant(v) => *v < 0.0,
        Spectrum::Piecewise(t) => t.values().iter().any(|v| *v < 0.0),
        _ => false,
    };
    if negative {
        return Err(cx.err(c, "a hair's sigma_a must be ≥ 0"));
    }
    Ok(s)
}
