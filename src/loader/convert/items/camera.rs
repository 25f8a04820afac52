//! `[camera]`, `[film]` and `[integrator]`.

use super::*;
use crate::film::filter::{KINDS, gaussian};
use crate::loader::convert::params::{Entry, inline_table, read_kind};

pub(super) fn camera(cx: &Cx<'_>, c: &S<RawCamera>) -> R<CameraDesc> {
    let sp = c.span();
    let c = c.get_ref();
    let kind_s = c
        .kind
        .as_ref()
        .map(|k| k.get_ref().as_str())
        .unwrap_or("perspective");
    let all = present!(c; kind, eye, target, up, fov, fov_axis, focal_length, sensor_width, f_number, focus_distance, view_width);
    let projection = |cx: &Cx<'_>| -> R<Projection> {
        match (&c.fov, &c.focal_length) {
            (Some(_), Some(f)) => Err(cx.err(
                &f.span(),
                "camera.focal_length",
                "give either `fov` or `focal_length` (with `sensor_width`), not both",
            )),
            (Some(fov), None) => fov_projection(cx, fov, &c.fov_axis),
            (None, Some(f)) => {
                let focal_length = cx.length(f, "camera.focal_length")?;
                let sensor_width = match &c.sensor_width {
                    Some(w) => cx.length(w, "camera.sensor_width")?,
                    None => Length::new::<length::millimeter>(36.0),
                };
                for (l, v, n) in [
                    (focal_length, f, "focal_length"),
                    (
                        sensor_width,
                        c.sensor_width.as_ref().unwrap_or(f),
                        "sensor_width",
                    ),
                ] {
                    if !(l.get::<length::meter>() > 0.0) {
                        return Err(cx.err(
                            &v.span(),
                            format!("camera.{n}"),
                            "expected a positive length",
                        ));
                    }
                }
                Ok(Projection::Focal {
                    focal_length,
                    sensor_width,
                })
            }
            (None, None) => Err(cx.err(
                &sp,
                "camera.fov",
                "missing; expected `fov` (e.g. \"40 deg\") or `focal_length` (e.g. \"50 mm\")",
            )),
        }
    };
    let kind = match kind_s {
        "perspective" => {
            cx.only(
                "a perspective camera",
                "camera",
                &all,
                &[
                    "kind",
                    "eye",
                    "target",
                    "up",
                    "fov",
                    "fov_axis",
                    "focal_length",
                    "sensor_width",
                ],
            )?;
            CameraKind::Perspective {
                projection: projection(cx)?,
            }
        }
        "thinlens" => {
            cx.only(
                "a thinlens camera",
                "camera",
                &all,
                &[
                    "kind",
                    "eye",
                    "target",
                    "up",
                    "fov",
                    "fov_axis",
                    "focal_length",
                    "sensor_width",
                    "f_number",
                    "focus_distance",
                ],
            )?;
            let projection = projection(cx)?;
            let n = cx.required(
                &c.f_number,
                &sp,
                "camera.f_number",
                "a positive number, e.g. 2.8",
            )?;
            let f_number = cx.positive(n, "camera.f_number")?;
            let fd = cx.required(
                &c.focus_distance,
                &sp,
                "camera.focus_distance",
                "a positive length, e.g. \"3 m\"",
            )?;
            let focus_distance = cx.length(fd, "camera.focus_distance")?;
            if !(focus_distance.get::<length::meter>() > 0.0) {
                return Err(cx.err(
                    &fd.span(),
                    "camera.focus_distance",
                    "expected a positive length",
                ));
            }
            CameraKind::ThinLens {
                projection,
                f_number,
                focus_distance,
            }
        }
        "orthographic" => {
            cx.only(
                "an orthographic camera",
                "camera",
                &all,
                &["kind", "eye", "target", "up", "view_width"],
            )?;
            let w = cx.required(&c.view_width, &sp, "camera.view_width", "a positive length")?;
            let view_width = cx.length(w, "camera.view_width")?;
            if !(view_width.get::<length::meter>() > 0.0) {
                return Err(cx.err(&w.span(), "camera.view_width", "expected a positive length"));
            }
            CameraKind::Orthographic { view_width }
        }
        other => {
            let span = c.kind.as_ref().map(|k| k.span()).unwrap_or(sp.clone());
            return Err(cx.err(&span, "camera.type", format!("unknown camera type \"{other}\"; expected perspective, thinlens or orthographic")));
        }
    };
    let eye = cx.point(
        cx.required(&c.eye, &sp, "camera.eye", "a position [x, y, z]")?,
        "camera.eye",
    )?;
    let target = cx.point(
        cx.required(&c.target, &sp, "camera.target", "a position [x, y, z]")?,
        "camera.target",
    )?;
    let up = match &c.up {
        Some(u) => cx.vec3(u, "camera.up")?,
        None => [0.0, 1.0, 0.0],
    };
    let d: Vec<f64> = (0..3)
        .map(|i| (target[i] - eye[i]).get::<length::meter>())
        .collect();
    let dl = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if dl == 0.0 {
        let span = c.target.as_ref().map(|t| t.span()).unwrap_or(sp.clone());
        return Err(cx.err(
            &span,
            "camera.target",
            "the target equals the eye; the camera has no view direction",
        ));
    }
    let ul = (up[0] * up[0] + up[1] * up[1] + up[2] * up[2]).sqrt();
    let cross = [
        d[1] * up[2] - d[2] * up[1],
        d[2] * up[0] - d[0] * up[2],
        d[0] * up[1] - d[1] * up[0],
    ];
    let cl = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
    if ul == 0.0 || cl <= 1e-6 * dl * ul {
        let span = c.up.as_ref().map(|u| u.span()).unwrap_or(sp.clone());
        return Err(cx.err(
            &span,
            "camera.up",
            "`up` is zero or parallel to the view direction",
        ));
    }
    let lens_f = match &kind {
        CameraKind::ThinLens { f_number, .. } => Some(*f_number),
        _ => None,
    };
    let sensor = match &c.sensor {
        Some(s) => Some(camera_sensor(cx, s, lens_f)?),
        None => None,
    };
    Ok(CameraDesc {
        kind,
        eye,
        target,
        up,
        sensor,
        loc: cx.src.span(&sp),
    })
}

/// `[camera.sensor]`: curves (`cie-1931`, a camera, or a CSV `file`), ISO, shutter (s, "1/100 s"
/// or "10 ms"), f-number (default: the thin lens's), white balance.
fn camera_sensor(cx: &Cx<'_>, s: &S<RawCameraSensor>, lens_f: Option<f64>) -> R<CameraSensorDesc> {
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

pub(super) fn fov_projection(
    cx: &Cx<'_>,
    fov: &S<Value>,
    axis: &Option<S<String>>,
) -> R<Projection> {
    let a: Angle = cx.quantity(fov, "camera.fov")?;
    let deg = a.get::<angle::degree>();
    if !(deg > 0.0 && deg < 180.0) {
        return Err(cx.err(
            &fov.span(),
            "camera.fov",
            format!(
                "expected an angle between 0 and 180 deg, found {} deg",
                round9(deg)
            ),
        ));
    }
    let axis = match axis.as_ref().map(|a| (a.get_ref().as_str(), a.span())) {
        None | Some(("x", _)) => FovAxis::X,
        Some(("y", _)) => FovAxis::Y,
        Some(("larger", _)) => FovAxis::Larger,
        Some(("smaller", _)) => FovAxis::Smaller,
        Some((other, span)) => {
            return Err(cx.err(
                &span,
                "camera.fov_axis",
                format!("\"{other}\": expected x, y, larger or smaller"),
            ));
        }
    };
    Ok(Projection::Fov { fov: a, axis })
}

/// Largest accepted image side and pixel count.
const MAX_SIDE: i64 = 32_768;
const MAX_PIXELS: i64 = 1 << 28;

pub(super) fn film(cx: &Cx<'_>, f: Option<&S<RawFilm>>) -> R<FilmDesc> {
    let mut d = FilmDesc {
        width: 512,
        height: 512,
        spp: 16,
        filter: gaussian::Desc::native(1.5),
        spectral_bins: 0,
        exposure_ev: None,
        loc: Default::default(),
    };
    let Some(f) = f else { return Ok(d) };
    d.loc = cx.src.span(&f.span());
    let f = f.get_ref();
    if let Some(w) = &f.width {
        d.width = cx.int(w, "film.width", 1, MAX_SIDE)? as u32;
    }
    if let Some(h) = &f.height {
        d.height = cx.int(h, "film.height", 1, MAX_SIDE)? as u32;
    }
    if (d.width as i64) * (d.height as i64) > MAX_PIXELS {
        let span = f
            .height
            .as_ref()
            .or(f.width.as_ref())
            .map(|v| v.span())
            .unwrap_or(WHOLE_FILE);
        return Err(cx.err(
            &span,
            "film",
            format!(
                "{}×{} pixels is more than the {MAX_PIXELS} supported",
                d.width, d.height
            ),
        ));
    }
    if let Some(s) = &f.spp {
        d.spp = cx.int(s, "film.spp", 1, 1 << 24)? as u32;
    }
    if let Some(b) = &f.spectral_bins {
        d.spectral_bins = cx.int(b, "film.spectral_bins", 0, 1000)? as u32;
    }
    if let Some(e) = &f.exposure {
        d.exposure_ev = Some(cx.number(e, "film.exposure")?);
    }
    d.filter = filter(cx, f)?;
    Ok(d)
}

/// `film.filter`: a kind's name with its radius in `filter_radius`, or an inline table
/// `{ type = "NAME", … }` of the kind's own parameters; spectrace's Gaussian if absent.
fn filter(cx: &Cx<'_>, f: &RawFilm) -> R<FilterDesc> {
    let (name, name_span, entries) = match &f.filter {
        None => ("gaussian", WHOLE_FILE, Vec::new()),
        Some(v) => match v.get_ref() {
            Value::String(s) => (s.as_str(), v.span(), Vec::new()),
            Value::Table(t) => {
                let (name, entries) = inline_table(cx, t, &v.span(), "film.filter")?;
                (name, v.span(), entries)
            }
            _ => {
                return Err(cx.err(
                    &v.span(),
                    "film.filter",
                    "expected a filter name or a table { type = \"NAME\", … }",
                ));
            }
        },
    };
    let mut entries = entries;
    if let Some(r) = &f.filter_radius {
        if entries.iter().any(|e| e.name == "radius") {
            return Err(cx.err(
                &r.span(),
                "film.filter_radius",
                "the filter's table gives its radius already",
            ));
        }
        entries.push(Entry {
            name: "radius".into(),
            field: "film.filter_radius".into(),
            value: r.get_ref().clone(),
            span: r.span(),
        });
    }
    read_kind(
        cx,
        KINDS,
        "filter",
        "film.filter",
        name,
        &name_span,
        &entries,
    )
}

pub(super) fn integrator(cx: &Cx<'_>, i: Option<&S<RawIntegrator>>) -> R<IntegratorDesc> {
    let mut d = IntegratorDesc {
        kind: IntegratorKind::Path,
        max_depth: 16,
        rr_depth: DEFAULT_RR_DEPTH,
        light_selection: LightSelection::Tree,
        moment: false,
    };
    let Some(i) = i else { return Ok(d) };
    let i = i.get_ref();
    if let Some(k) = &i.kind {
        d.kind = match k.get_ref().as_str() {
            "path" => IntegratorKind::Path,
            "light" => IntegratorKind::Light,
            "bdpt" => IntegratorKind::Bdpt,
            "whitted" => IntegratorKind::Whitted,
            "direct" => IntegratorKind::Direct {
                emitter_samples: match &i.emitter_samples {
                    Some(v) => cx.int(v, "integrator.emitter_samples", 0, 1 << 16)? as u32,
                    None => 1,
                },
                bsdf_samples: match &i.bsdf_samples {
                    Some(v) => cx.int(v, "integrator.bsdf_samples", 0, 1 << 16)? as u32,
                    None => 1,
                },
            },
            o => {
                return Err(cx.err(
                    &k.span(),
                    "integrator.type",
                    format!("\"{o}\": expected path, bdpt, light, whitted or direct"),
                ));
            }
        };
        if let IntegratorKind::Direct {
            emitter_samples: 0,
            bsdf_samples: 0,
        } = d.kind
        {
            return Err(cx.err(
                &k.span(),
                "integrator",
                "direct needs at least one emitter or BSDF sample",
            ));
        }
    }
    for (key, v) in [
        ("emitter_samples", &i.emitter_samples),
        ("bsdf_samples", &i.bsdf_samples),
    ] {
        if let Some(v) = v
            && !matches!(d.kind, IntegratorKind::Direct { .. })
        {
            return Err(cx.err(
                &v.span(),
                format!("integrator.{key}"),
                "applies to type = \"direct\" only",
            ));
        }
    }
    d.moment = i.second_moment.as_ref().is_some_and(|b| *b.get_ref());
    if let Some(m) = &i.max_depth {
        d.max_depth = cx.int(m, "integrator.max_depth", 1, 1024)? as u32;
    }
    if let Some(r) = &i.rr_depth {
        d.rr_depth = cx.int(r, "integrator.rr_depth", 1, 1024)? as u32;
    }
    if let Some(k) = &i.light_selection {
        d.light_selection = match k.get_ref().as_str() {
            "tree" => LightSelection::Tree,
            "power" => LightSelection::Power,
            "uniform" => LightSelection::Uniform,
            o => {
                return Err(cx.err(
                    &k.span(),
                    "integrator.light_selection",
                    format!("\"{o}\": expected tree, power or uniform"),
                ));
            }
        };
    }
    Ok(d)
}
