//! `principled` and `principledthin`, read as Mitsuba 3.9.1 reads them
//! (`src/bsdfs/principled.cpp`, `principledthin.cpp`): every parameter a texture or a number,
//! the scalar ones through `eval_1`; a lobe's parameter absent or given as the number 0 turns
//! the lobe off (`get_flag`).

use super::super::cx::{Cx, R};
use super::super::xml::Element;
use super::plain;
use crate::loader::desc::{MaterialDesc, MaterialKind, PrincipledDesc, TextureDesc};

/// Reads either plugin (`t` names it).
pub(super) fn principled(cx: &Cx<'_>, b: &Element, name: &str, t: &str) -> R<(MaterialDesc, bool)> {
    let thin = t == "principledthin";
    // a lobe's parameter: absent, or the number 0, is "not given"
    let flag = |key: &str| -> R<Option<TextureDesc>> {
        let Some(c) = cx.child(b, key) else {
            return Ok(None);
        };
        if c.tag == "float" && cx.float(c)? == 0.0 {
            return Ok(None);
        }
        cx.scalar_texture_prop(b, key, 0.0).map(Some)
    };
    let rate = |key: &str| -> R<f64> {
        match cx.child(b, key) {
            None => Ok(1.0),
            Some(c) => {
                let r = cx.float(c)?;
                if r < 0.0 {
                    return Err(cx.err(c, format!("{key} must be ≥ 0, found {r}")));
                }
                Ok(r)
            }
        }
    };
    let number = |key: &str| -> R<Option<f64>> {
        match cx.child(b, key) {
            None => Ok(None),
            Some(c) if c.tag == "float" => Ok(Some(cx.float(c)?)),
            Some(c) => Err(cx.err(
                c,
                format!("{key} must be a number here (a texture is not supported)"),
            )),
        }
    };
    let spec_trans = flag("spec_trans")?;
    let eta = if thin {
        let eta = number("eta")?.unwrap_or(1.5);
        if eta <= 0.0 {
            return Err(cx.err(b, format!("eta must be > 0, found {eta}")));
        }
        eta
    } else {
        match (number("eta")?, number("specular")?) {
            (Some(_), Some(_)) => {
                return Err(cx.err(
                    b,
                    "give either eta or specular, not both (Mitsuba refuses both)",
                ));
            }
            (Some(e), None) if e <= 0.0 => {
                return Err(cx.err(b, format!("eta must be > 0, found {e}")));
            }
            // eta = 1 would make transmission undefined: Mitsuba nudges it
            (Some(e), None) => {
                if spec_trans.is_some() && e == 1.0 {
                    1.001
                } else {
                    e
                }
            }
            (None, s) => {
                let mut s = s.unwrap_or(0.5);
                if !(0.0..12.5).contains(&s) {
                    return Err(cx.err(b, format!("specular must be in [0, 12.5), found {s}")));
                }
                if spec_trans.is_some() && s == 0.0 {
                    s = 1e-3;
                }
                // Mitsuba's: R0 = 0.08·specular = ((η − 1)/(η + 1))², so η = 2/(1 − √R0) − 1
                2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
            }
        }
    };
    let rates = if thin {
        [
            rate("specular_reflectance_sampling_rate")?,
            rate("specular_transmittance_sampling_rate")?,
            rate("diffuse_reflectance_sampling_rate")?,
            rate("diffuse_transmittance_sampling_rate")?,
        ]
    } else {
        [
            rate("diffuse_reflectance_sampling_rate")?,
            rate("main_specular_sampling_rate")?,
            rate("clearcoat_sampling_rate")?,
            1.0,
        ]
    };
    let desc = PrincipledDesc {
        base_color: cx.texture_prop(b, "base_color", 0.5)?,
        roughness: cx.scalar_texture_prop(b, "roughness", 0.5)?,
        anisotropic: flag("anisotropic")?,
        spec_trans,
        metallic: if thin { None } else { flag("metallic")? },
        clearcoat: if thin { None } else { flag("clearcoat")? },
        clearcoat_gloss: if thin {
            TextureDesc::from(crate::spectrum::Spectrum::Constant(0.0))
        } else {
            cx.scalar_texture_prop(b, "clearcoat_gloss", 0.0)?
        },
        sheen: flag("sheen")?,
        sheen_tint: flag("sheen_tint")?,
        flatness: flag("flatness")?,
        spec_tint: flag("spec_tint")?,
        diff_trans: if thin { flag("diff_trans")? } else { None },
        eta,
        rates,
        thin,
    };
    plain(cx, b, name, MaterialKind::Principled(Box::new(desc)))
}
