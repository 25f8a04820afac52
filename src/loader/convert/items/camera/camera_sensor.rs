//! `[camera.sensor]`: spectral sensitivities, exposure and white balance.

use super::super::*;

/// `[camera.sensor]`: curves (`cie-1931`, a camera, or a CSV `file`), ISO, shutter (s, "1/100 s"
/// or "10 ms"), f-number (default: the thin lens's), white balance.
pub(super) fn camera_sensor(
    cx: &Cx<'_>,
    s: &S<RawCameraSensor>,
    lens_f: Option<f64>,
) -> R<CameraSensorDesc> {
    let sp = s.span();
    let s = s.get_ref();
    let f = "camera.sensor";
    let (name, curves) = match (&s.curves, &s.file) {
        (Some(_), Some(file)) => {
            return Err(cx.err(
                &file.span(),
                format!("{f}.file"),
                "give curves or file, not both",
            ));
        }
        (_, Some(file)) => {
            let path = cx.path(file.get_ref());
            let text =
                crate::files::read_text(&path, crate::files::MAX_TEXT_BYTES).map_err(|e| {
                    cx.err(
                        &file.span(),
                        format!("{f}.file"),
                        format!("cannot read {}: {e}", path.display()),
                    )
                })?;
            let c = crate::sensor::curves_from_text(&text, &path.display().to_string())
                .map_err(|m| cx.err(&file.span(), format!("{f}.file"), m))?;
            (file.get_ref().clone(), Some(c))
        }
        (Some(c), None) if c.get_ref() == "cie-1931" => ("cie-1931".to_string(), None),
        (Some(c), None) => match crate::sensor::named_curves(c.get_ref()) {
            Some(curves) => (c.get_ref().clone(), Some(curves)),
            None => {
                return Err(cx.err(
                    &c.span(),
                    format!("{f}.curves"),
                    format!("unknown sensor \"{}\": expected \"cie-1931\", \"nikon-d5100\" or \"sigma-sd-merrill\" (or a CSV `file` of wavelength_nm and three sensitivities)", c.get_ref()),
                ));
            }
        },
        (None, None) => ("cie-1931".to_string(), None),
    };
    let iso = match &s.iso {
        Some(v) => cx.positive(v, &format!("{f}.iso"))?,
        None => 100.0,
    };
    let shutter_s = match &s.shutter {
        None => {
            return Err(cx.err(
                &sp,
                format!("{f}.shutter"),
                "missing: the exposure time, e.g. \"1/100 s\" or 0.01",
            ));
        }
        Some(v) => {
            let secs = match v.get_ref() {
                Value::String(t) => parse_shutter(t),
                _ => cx.number(v, &format!("{f}.shutter")).ok(),
            };
            match secs {
                Some(x) if x > 0.0 && x.is_finite() => x,
                _ => {
                    return Err(cx.err(
                        &v.span(),
                        format!("{f}.shutter"),
                        "expected a positive time: seconds, \"1/100 s\" or \"10 ms\"",
                    ));
                }
            }
        }
    };
    let f_number = match (&s.f_number, lens_f) {
        (Some(v), _) => cx.positive(v, &format!("{f}.f_number"))?,
        (None, Some(n)) => n,
        (None, None) => {
            return Err(cx.err(
                &sp,
                format!("{f}.f_number"),
                "missing: the aperture's f-number, e.g. 4",
            ));
        }
    };
    let adaptation = match s
        .adaptation
        .as_ref()
        .map(|a| (a.get_ref().as_str(), a.span()))
    {
        None | Some(("von-kries", _)) => crate::sensor::Adaptation::VonKries,
        Some(("bradford", _)) => crate::sensor::Adaptation::Bradford,
        Some((o, span)) => {
            return Err(cx.err(
                &span,
                format!("{f}.adaptation"),
                format!("\"{o}\": expected \"von-kries\" or \"bradford\""),
            ));
        }
    };
    let white_balance = match &s.white_balance {
        None => None,
        Some(w) => {
            let spec = cx.spectrum(
                &S::new(w.span(), Value::String(w.get_ref().clone())),
                &format!("{f}.white_balance"),
                SpectrumUse::Emission,
            )?;
            Some((w.get_ref().clone(), spec, adaptation))
        }
    };
    Ok(CameraSensorDesc {
        name,
        curves,
        iso,
        shutter: crate::units::Time::new::<crate::units::time::second>(shutter_s),
        f_number,
        white_balance,
        calibration: crate::sensor::Calibration::Iso12232,
    })
}

/// "1/100 s", "1/100", "10 ms", "0.5 s", "2": seconds.
fn parse_shutter(t: &str) -> Option<f64> {
    let t = t.trim();
    let (num, scale) = if let Some(x) = t.strip_suffix("ms") {
        (x.trim(), 1e-3)
    } else if let Some(x) = t.strip_suffix('s') {
        (x.trim(), 1.0)
    } else {
        (t, 1.0)
    };
    let v = match num.split_once('/') {
        Some((a, b)) => a.trim().parse::<f64>().ok()? / b.trim().parse::<f64>().ok()?,
        None => num.parse::<f64>().ok()?,
    };
    Some(v * scale)
}
