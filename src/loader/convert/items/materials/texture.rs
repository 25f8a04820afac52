//! Reflectances of materials, checked to conserve energy, and the textures that may stand for
//! them (checkerboards and images).

use super::super::*;

/// Checks 0 ≤ S(λ) ≤ 1 over the simulated range and the CIE range at 1 nm.
pub(super) fn check_reflectance(
    cx: &Cx<'_>,
    s: &Spectrum,
    span: &Range<usize>,
    field: &str,
    range: &[Length; 2],
) -> R<()> {
    let lo = range[0].get::<length::nanometer>().min(360.0) as i64;
    let hi = range[1].get::<length::nanometer>().max(830.0) as i64;
    for l in lo..=hi {
        let v = s.eval(l as f32);
        if !(0.0..=1.0 + 1e-6).contains(&v) {
            return Err(cx.err(
                span,
                field,
                match field.rsplit('.').next() {
                    Some(what @ ("opacity" | "weight")) => {
                        format!("{what} is {v} at {l} nm; it must lie in [0, 1]")
                    }
                    _ => format!("reflectance is {v} at {l} nm; it must lie in [0, 1], or the surface would create energy"),
                },
            ));
        }
    }
    Ok(())
}

/// A reflectance that may vary over the surface: a spectrum (checked to lie in [0, 1]), or a
/// table with `checkerboard = [a, b]` (two reflectance spectra; `a` on the checks containing
/// uv = (¼, ¼), checks of ½ in uv as Mitsuba's checkerboard) or `image = "file.png"` (PNG, EXR
/// or HDR; `filter` = "bilinear" (default) or "nearest", `wrap` = "repeat" (default), "mirror"
/// or "clamp"), each with an optional `scale = [su, sv]` applied to uv before the lookup.
pub(super) fn reflectance_texture(
    cx: &Cx<'_>,
    r: &S<Value>,
    field: &str,
    range: &[Length; 2],
) -> R<TextureDesc> {
    let span = r.span();
    // entries of an inline table carry the table's span
    let at = |v: &Value| S::new(span.clone(), v.clone());
    let Value::Table(t) = r.get_ref() else {
        let s = cx.spectrum(r, field, SpectrumUse::Reflectance)?;
        check_reflectance(cx, &s, &span, field, range)?;
        return Ok(s.into());
    };
    if !t.contains_key("checkerboard") && !t.contains_key("image") {
        let s = cx.spectrum(r, field, SpectrumUse::Reflectance)?;
        check_reflectance(cx, &s, &span, field, range)?;
        return Ok(s.into());
    }
    let allowed: &[&str] = if t.contains_key("checkerboard") {
        &["checkerboard", "scale"]
    } else {
        &["image", "filter", "wrap", "scale"]
    };
    if let Some(k) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(cx.err(
            &span,
            format!("{field}.{k}"),
            format!("unknown key; a texture here takes {}", allowed.join(", ")),
        ));
    }
    let to_uv = uv_scale(cx, t, &span, field)?;
    if let Some(c) = t.get("checkerboard") {
        let Value::Array(ab) = c else {
            return Err(cx.err(
                &span,
                format!("{field}.checkerboard"),
                "expected [a, b], two reflectance spectra",
            ));
        };
        if ab.len() != 2 {
            return Err(cx.err(
                &span,
                format!("{field}.checkerboard"),
                format!(
                    "expected [a, b], two reflectance spectra, found {}",
                    ab.len()
                ),
            ));
        }
        let mut ends = Vec::new();
        for (i, v) in ab.iter().enumerate() {
            let sub = format!("{field}.checkerboard[{i}]");
            let s = cx.spectrum(&at(v), &sub, SpectrumUse::Reflectance)?;
            check_reflectance(cx, &s, &span, &sub, range)?;
            ends.push(s);
        }
        let b = ends.pop().unwrap_or(Spectrum::Constant(0.0));
        let a = ends.pop().unwrap_or(Spectrum::Constant(0.0));
        return Ok(TextureDesc::Checkerboard { a, b, to_uv });
    }
    let word = |key: &str, options: &[&str]| -> R<Option<String>> {
        match t.get(key) {
            None => Ok(None),
            Some(v) => match v {
                Value::String(s) if options.contains(&s.as_str()) => Ok(Some(s.clone())),
                _ => Err(cx.err(
                    &span,
                    format!("{field}.{key}"),
                    format!("expected one of {}", options.join(", ")),
                )),
            },
        }
    };
    let img = &t["image"];
    let Value::String(file) = img else {
        return Err(cx.err(&span, format!("{field}.image"), "expected a file name"));
    };
    let path = cx.path(file);
    if !path.is_file() {
        return Err(cx.err(
            &span,
            format!("{field}.image"),
            format!("image file not found: {}", path.display()),
        ));
    }
    let filter = match word("filter", &["bilinear", "nearest"])?.as_deref() {
        Some("nearest") => TexFilter::Nearest,
        _ => TexFilter::Bilinear,
    };
    let wrap = match word("wrap", &["repeat", "mirror", "clamp"])?.as_deref() {
        Some("mirror") => Wrap::Mirror,
        Some("clamp") => Wrap::Clamp,
        _ => Wrap::Repeat,
    };
    Ok(TextureDesc::Bitmap {
        path,
        filter,
        wrap,
        raw: false,
        to_uv,
        loc: cx.src.span(&span),
    })
}

/// A texture table's `scale = [su, sv]` (or one number for both) as the step applied to uv
/// before the lookup; none if absent.
fn uv_scale(
    cx: &Cx<'_>,
    t: &toml::Table,
    span: &Range<usize>,
    field: &str,
) -> R<Vec<TransformStep>> {
    // entries of an inline table carry the table's span
    let at = |v: &Value| S::new(span.clone(), v.clone());
    Ok(match t.get("scale") {
        None => Vec::new(),
        Some(v) => {
            let sub = format!("{field}.scale");
            let k = match v {
                Value::Array(a) if a.len() == 2 => {
                    [cx.number(&at(&a[0]), &sub)?, cx.number(&at(&a[1]), &sub)?]
                }
                _ => [cx.number(&at(v), &sub)?; 2],
            };
            if !(k[0].is_finite() && k[1].is_finite() && k[0] != 0.0 && k[1] != 0.0) {
                return Err(cx.err(
                    span,
                    format!("{field}.scale"),
                    "expected a non-zero number or [su, sv]",
                ));
            }
            vec![TransformStep::Scale([k[0], k[1], 1.0])]
        }
    })
}
