//! Sections of the scene file: settings, camera, film, integrator, materials, shapes, lights.

use std::ops::Range;

use toml::Value;

use super::{Cx, R, SpectrumUse, present};
use crate::loader::desc::*;
use crate::loader::raw::*;
use crate::spectrum::Spectrum;
use crate::units::parse::Dimension as D;
use crate::units::{
    Angle, Illuminance, Irradiance, Length, Luminance, LuminousFlux, LuminousIntensity, Power,
    Radiance, RadiantIntensity, angle, illuminance, irradiance, length, luminance, luminous_flux,
    luminous_intensity, power, radiance, radiant_intensity,
};

const WHOLE_FILE: Range<usize> = 0..0;

pub(super) fn scene(cx: &mut Cx<'_>, raw: RawScene) -> R<SceneDesc> {
    let mut range = [
        Length::new::<length::nanometer>(360.0),
        Length::new::<length::nanometer>(830.0),
    ];
    if let Some(s) = raw.scene.as_ref().map(|s| s.get_ref()) {
        if let Some(u) = &s.length_unit {
            let l: Length =
                crate::units::parse::parse(&format!("1 {}", u.get_ref())).map_err(|_| {
                    cx.err(
                        &u.span(),
                        "scene.length_unit",
                        format!(
                            "\"{}\" is not a length unit; expected m, cm, mm, um or km",
                            u.get_ref()
                        ),
                    )
                })?;
            cx.unit_m = l.get::<length::meter>();
        }
        if let Some(w) = &s.wavelength_range {
            let f = "scene.wavelength_range";
            if w.get_ref().len() != 2 {
                return Err(cx.err(
                    &w.span(),
                    f,
                    "expected [shortest, longest], e.g. [\"360 nm\", \"830 nm\"]",
                ));
            }
            for i in 0..2 {
                let v = &w.get_ref()[i];
                range[i] = match v.get_ref() {
                    Value::String(_) => cx.quantity::<Length>(v, f)?,
                    _ => Length::new::<length::nanometer>(cx.number(v, f)?),
                };
            }
            let (lo, hi) = (
                range[0].get::<length::nanometer>(),
                range[1].get::<length::nanometer>(),
            );
            if !(lo > 0.0 && hi > lo) {
                return Err(cx.err(
                    &w.span(),
                    f,
                    format!("expected 0 < shortest < longest, found {lo} nm to {hi} nm"),
                ));
            }
        }
    }
    let camera = match &raw.camera {
        Some(c) => camera(cx, c)?,
        None => return Err(cx.err(&WHOLE_FILE, "camera", "missing [camera] section")),
    };
    let film = film(cx, raw.film.as_ref())?;
    let integrator = integrator(cx, raw.integrator.as_ref())?;
    let mut materials = Vec::new();
    for (name, m) in &raw.materials {
        materials.push(material(cx, name, m, &range)?);
    }
    let shapes = raw
        .shapes
        .iter()
        .enumerate()
        .map(|(i, s)| {
            shape(
                cx,
                i,
                s,
                &raw.materials
                    .keys()
                    .map(|k| k.get_ref().as_str())
                    .collect::<Vec<_>>(),
            )
        })
        .collect::<R<Vec<_>>>()?;
    let lights = raw
        .lights
        .iter()
        .enumerate()
        .map(|(i, l)| light(cx, i, l))
        .collect::<R<Vec<_>>>()?;

    let has_env = lights
        .iter()
        .any(|l| matches!(l.kind, LightKind::Environment { .. }));
    if shapes.is_empty() && !has_env {
        let span = raw.camera.as_ref().map(|c| c.span()).unwrap_or(WHOLE_FILE);
        return Err(cx.err(
            &span,
            "camera",
            "the camera sees nothing: the scene has no shapes and no environment light",
        ));
    }
    if lights.is_empty() && !shapes.iter().any(|s| s.emission.is_some()) {
        return Err(cx.err(
            &WHOLE_FILE,
            "lights",
            "the scene has no light source: add a [[lights]] entry or an `emission` to a shape",
        ));
    }
    Ok(SceneDesc {
        path: cx.file.to_path_buf(),
        wavelength_range: range,
        camera,
        film,
        integrator,
        materials,
        shapes,
        lights,
    })
}

fn camera(cx: &Cx<'_>, c: &S<RawCamera>) -> R<CameraDesc> {
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
    Ok(CameraDesc {
        kind,
        eye,
        target,
        up,
        loc: cx.src.span(&sp),
    })
}

fn fov_projection(cx: &Cx<'_>, fov: &S<Value>, axis: &Option<S<String>>) -> R<Projection> {
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

fn film(cx: &Cx<'_>, f: Option<&S<RawFilm>>) -> R<FilmDesc> {
    let mut d = FilmDesc {
        width: 512,
        height: 512,
        spp: 16,
        filter: FilterDesc::Gaussian { sigma: 0.5 },
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
    let sigma = match &f.filter_radius {
        Some(r) => cx.positive(r, "film.filter_radius")? / 3.0,
        None => 0.5,
    };
    d.filter = match f.filter.as_ref().map(|s| (s.get_ref().as_str(), s.span())) {
        None | Some(("gaussian", _)) => FilterDesc::Gaussian { sigma },
        Some(("box", _)) => FilterDesc::Box,
        Some((o, span)) => {
            return Err(cx.err(
                &span,
                "film.filter",
                format!("\"{o}\": expected box or gaussian"),
            ));
        }
    };
    Ok(d)
}

fn integrator(cx: &Cx<'_>, i: Option<&S<RawIntegrator>>) -> R<IntegratorDesc> {
    let mut d = IntegratorDesc {
        kind: IntegratorKind::Path,
        max_depth: 16,
    };
    let Some(i) = i else { return Ok(d) };
    let i = i.get_ref();
    if let Some(k) = &i.kind {
        d.kind = match k.get_ref().as_str() {
            "path" => IntegratorKind::Path,
            "light" => IntegratorKind::Light,
            "whitted" => IntegratorKind::Whitted,
            o => {
                return Err(cx.err(
                    &k.span(),
                    "integrator.type",
                    format!("\"{o}\": expected path, light or whitted"),
                ));
            }
        };
    }
    if let Some(m) = &i.max_depth {
        d.max_depth = cx.int(m, "integrator.max_depth", 1, 1024)? as u32;
    }
    Ok(d)
}

/// Checks 0 ≤ S(λ) ≤ 1 over the simulated range and the CIE range at 1 nm.
fn check_reflectance(
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
                format!("reflectance is {v} at {l} nm; it must lie in [0, 1], or the surface would create energy"),
            ));
        }
    }
    Ok(())
}

fn material(
    cx: &Cx<'_>,
    name: &S<String>,
    m: &S<RawMaterial>,
    range: &[Length; 2],
) -> R<MaterialDesc> {
    let sp = m.span();
    let f = format!("materials.{}", name.get_ref());
    let m = m.get_ref();
    let all = present!(m; kind, reflectance, kd, ks, exponent, ior, exterior_ior, metal, eta, k, roughness);
    let ty = cx.required(
        &m.kind,
        &sp,
        &format!("{f}.type"),
        "diffuse, phong, dielectric or conductor",
    )?;
    let roughness = |cx: &Cx<'_>| -> R<Option<f64>> {
        match &m.roughness {
            None => Ok(None),
            Some(r) => {
                let a = cx.number(r, &format!("{f}.roughness"))?;
                if !(0.0..=1.0).contains(&a) {
                    return Err(cx.err(
                        &r.span(),
                        format!("{f}.roughness"),
                        format!("expected a GGX α in [0, 1], found {a}"),
                    ));
                }
                Ok((a > 0.0).then_some(a))
            }
        }
    };
    let exterior = |cx: &Cx<'_>| -> R<f64> {
        match &m.exterior_ior {
            None => Ok(1.0),
            Some(e) => {
                let n = cx.number(e, &format!("{f}.exterior_ior"))?;
                if n < 1.0 {
                    return Err(cx.err(
                        &e.span(),
                        format!("{f}.exterior_ior"),
                        format!("expected an index ≥ 1, found {n}"),
                    ));
                }
                Ok(n)
            }
        }
    };
    let kind = match ty.get_ref().as_str() {
        "diffuse" => {
            cx.only("a diffuse material", &f, &all, &["kind", "reflectance"])?;
            let r = cx.required(
                &m.reflectance,
                &sp,
                &format!("{f}.reflectance"),
                "a reflectance spectrum",
            )?;
            let reflectance =
                cx.spectrum(r, &format!("{f}.reflectance"), SpectrumUse::Reflectance)?;
            check_reflectance(
                cx,
                &reflectance,
                &r.span(),
                &format!("{f}.reflectance"),
                range,
            )?;
            MaterialKind::Diffuse { reflectance }
        }
        "phong" => {
            cx.only(
                "a phong material",
                &f,
                &all,
                &["kind", "kd", "ks", "exponent"],
            )?;
            let kd_v = cx.required(
                &m.kd,
                &sp,
                &format!("{f}.kd"),
                "a diffuse reflectance spectrum",
            )?;
            let ks_v = cx.required(
                &m.ks,
                &sp,
                &format!("{f}.ks"),
                "a specular reflectance spectrum",
            )?;
            let kd = cx.spectrum(kd_v, &format!("{f}.kd"), SpectrumUse::Reflectance)?;
            let ks = cx.spectrum(ks_v, &format!("{f}.ks"), SpectrumUse::Reflectance)?;
            let sum = SumCheck(&kd, &ks);
            check_reflectance(
                cx,
                &sum.spectrum(),
                &ks_v.span(),
                &format!("{f}.kd + {f}.ks"),
                range,
            )?;
            let e = cx.required(
                &m.exponent,
                &sp,
                &format!("{f}.exponent"),
                "a shininess exponent ≥ 0",
            )?;
            let exponent = cx.number(e, &format!("{f}.exponent"))?;
            if !(0.0..=1e6).contains(&exponent) {
                return Err(cx.err(
                    &e.span(),
                    format!("{f}.exponent"),
                    format!("expected 0 to 1e6, found {exponent}"),
                ));
            }
            MaterialKind::Phong { kd, ks, exponent }
        }
        "dielectric" => {
            cx.only(
                "a dielectric material",
                &f,
                &all,
                &["kind", "ior", "exterior_ior", "roughness"],
            )?;
            let i = cx.required(
                &m.ior,
                &sp,
                &format!("{f}.ior"),
                "an index: a number or a glass name like \"N-BK7\"",
            )?;
            MaterialKind::Dielectric {
                ior: cx.ior(i, &format!("{f}.ior"))?,
                exterior_ior: exterior(cx)?,
                roughness: roughness(cx)?,
            }
        }
        "conductor" => {
            cx.only(
                "a conductor material",
                &f,
                &all,
                &["kind", "metal", "eta", "k", "exterior_ior", "roughness"],
            )?;
            let ior = match (&m.metal, &m.eta, &m.k) {
                (Some(mm), None, None) => cx.metal(mm, &format!("{f}.metal"))?,
                (None, Some(e), Some(k)) => cx.eta_k(e, k, &f)?,
                _ => {
                    return Err(cx.err(
                        &sp,
                        &f,
                        "a conductor needs either `metal` (e.g. \"Au\") or both `eta` and `k`",
                    ));
                }
            };
            MaterialKind::Conductor {
                ior,
                exterior_ior: exterior(cx)?,
                roughness: roughness(cx)?,
            }
        }
        o => {
            return Err(cx.err(&ty.span(), format!("{f}.type"), format!("unknown material type \"{o}\"; expected diffuse, phong, dielectric or conductor")));
        }
    };
    Ok(MaterialDesc {
        name: name.get_ref().clone(),
        kind,
        loc: cx.src.span(&sp),
    })
}

/// kd + ks as one spectrum, for the energy check.
struct SumCheck<'a>(&'a Spectrum, &'a Spectrum);
impl SumCheck<'_> {
    fn spectrum(&self) -> Spectrum {
        // tabulate at 1 nm over a wide range; only used for the check
        let l: Vec<f32> = (200..=2000).map(|x| x as f32).collect();
        let v: Vec<f32> = l.iter().map(|&x| self.0.eval(x) + self.1.eval(x)).collect();
        match crate::spectrum::PiecewiseLinear::new(l, v) {
            Ok(t) => Spectrum::Piecewise(std::sync::Arc::new(t)),
            Err(_) => Spectrum::Constant(f32::NAN),
        }
    }
}

fn transform(cx: &Cx<'_>, t: &S<Vec<S<Value>>>, field: &str) -> R<Vec<TransformStep>> {
    let mut out = Vec::new();
    for (i, step) in t.get_ref().iter().enumerate() {
        let f = format!("{field}[{i}]");
        let Value::Table(tab) = step.get_ref() else {
            return Err(cx.err(
                &step.span(),
                &f,
                "expected a table like { translate = [x, y, z] }",
            ));
        };
        if tab.len() != 1 {
            return Err(cx.err(
                &step.span(),
                &f,
                "each transform step has exactly one of translate, rotate, scale, matrix, look_at",
            ));
        }
        let (key, val) = tab
            .iter()
            .next()
            .map(|(k, v)| (k.as_str(), v.clone()))
            .unwrap_or(("", Value::Boolean(false)));
        let v = S::new(step.span(), val);
        let f = format!("{f}.{key}");
        out.push(match key {
            "translate" => TransformStep::Translate(cx.point(&v, &f)?),
            "scale" => {
                let s = match v.get_ref() {
                    Value::Array(_) => cx.vec3(&v, &f)?,
                    _ => [cx.number(&v, &f)?; 3],
                };
                if s.iter().any(|x| *x == 0.0) {
                    return Err(cx.err(&step.span(), &f, "a scale factor of 0 flattens the shape"));
                }
                TransformStep::Scale(s)
            }
            "rotate" => {
                let Value::Table(r) = v.get_ref() else {
                    return Err(cx.err(&step.span(), &f, "expected { axis = [x, y, z], angle = \"30 deg\" }"));
                };
                let get = |k: &str| r.get(k).cloned().map(|x| S::new(step.span(), x));
                if let Some(k) = r.keys().find(|k| *k != "axis" && *k != "angle") {
                    return Err(cx.err(&step.span(), format!("{f}.{k}"), "unknown key; expected axis and angle"));
                }
                let axis = cx.vec3(&get("axis").ok_or_else(|| cx.err(&step.span(), &f, "missing axis"))?, &format!("{f}.axis"))?;
                if axis == [0.0; 3] {
                    return Err(cx.err(&step.span(), format!("{f}.axis"), "the rotation axis is zero"));
                }
                let angle: Angle = cx.quantity(&get("angle").ok_or_else(|| cx.err(&step.span(), &f, "missing angle"))?, &format!("{f}.angle"))?;
                TransformStep::Rotate { axis, angle }
            }
            "matrix" => {
                let Value::Array(a) = v.get_ref() else {
                    return Err(cx.err(&step.span(), &f, "expected 16 numbers, row-major"));
                };
                if a.len() != 16 {
                    return Err(cx.err(&step.span(), &f, format!("expected 16 numbers, row-major; found {}", a.len())));
                }
                let mut m = [0.0; 16];
                for (k, x) in a.iter().enumerate() {
                    m[k] = cx.number(&S::new(step.span(), x.clone()), &format!("{f}[{k}]"))?;
                }
                TransformStep::Matrix(m)
            }
            "look_at" => {
                let Value::Table(r) = v.get_ref() else {
                    return Err(cx.err(&step.span(), &f, "expected { eye = [..], target = [..], up = [..] }"));
                };
                let get = |k: &str| {
                    r.get(k).cloned().map(|x| S::new(step.span(), x)).ok_or_else(|| cx.err(&step.span(), format!("{f}.{k}"), "missing"))
                };
                TransformStep::LookAt {
                    eye: cx.point(&get("eye")?, &format!("{f}.eye"))?,
                    target: cx.point(&get("target")?, &format!("{f}.target"))?,
                    up: cx.vec3(&get("up")?, &format!("{f}.up"))?,
                }
            }
            o => {
                return Err(cx.err(&step.span(), &f, format!("unknown transform `{o}`; expected translate, rotate, scale, matrix or look_at")));
            }
        });
    }
    Ok(out)
}

fn shape(cx: &Cx<'_>, i: usize, s: &S<RawShape>, material_names: &[&str]) -> R<ShapeDesc> {
    let sp = s.span();
    let f = format!("shapes[{i}]");
    let s = s.get_ref();
    let all = present!(s; kind, material, file, center, radius, transform, two_sided, emission);
    let ty = cx.required(
        &s.kind,
        &sp,
        &format!("{f}.type"),
        "sphere, rectangle, box, disk or obj",
    )?;
    let common = ["kind", "material", "transform", "two_sided", "emission"];
    let with = |extra: &[&'static str]| -> Vec<&'static str> {
        common.iter().chain(extra).copied().collect()
    };
    let kind = match ty.get_ref().as_str() {
        "sphere" => {
            cx.only("a sphere", &f, &all, &with(&["center", "radius"]))?;
            let center = match &s.center {
                Some(c) => cx.point(c, &format!("{f}.center"))?,
                None => [Length::new::<length::meter>(0.0); 3],
            };
            let r = cx.required(&s.radius, &sp, &format!("{f}.radius"), "a positive length")?;
            let radius = cx.length(r, &format!("{f}.radius"))?;
            if !(radius.get::<length::meter>() > 0.0) {
                return Err(cx.err(
                    &r.span(),
                    format!("{f}.radius"),
                    format!(
                        "expected a positive radius, found {}",
                        radius.get::<length::meter>() / cx.unit_m
                    ),
                ));
            }
            ShapeKind::Sphere { center, radius }
        }
        "rectangle" => {
            cx.only("a rectangle", &f, &all, &with(&[]))?;
            ShapeKind::Rectangle
        }
        "box" => {
            cx.only("a box", &f, &all, &with(&[]))?;
            ShapeKind::Box
        }
        "disk" => {
            cx.only("a disk", &f, &all, &with(&[]))?;
            ShapeKind::Disk
        }
        "obj" => {
            cx.only("an obj mesh", &f, &all, &with(&["file"]))?;
            let p = cx.required(&s.file, &sp, &format!("{f}.file"), "a path to a .obj file")?;
            ShapeKind::Obj {
                path: cx.path(p.get_ref()),
            }
        }
        o => {
            return Err(cx.err(
                &ty.span(),
                format!("{f}.type"),
                format!("unknown shape type \"{o}\"; expected sphere, rectangle, box, disk or obj"),
            ));
        }
    };
    let transform = match &s.transform {
        Some(t) => transform(cx, t, &format!("{f}.transform"))?,
        None => Vec::new(),
    };
    let material = match &s.material {
        Some(m) => Some(
            material_names
                .iter()
                .position(|n| *n == m.get_ref())
                .ok_or_else(|| {
                    cx.err(
                        &m.span(),
                        format!("{f}.material"),
                        format!(
                            "refers to material \"{}\", which is not defined; defined: {}",
                            m.get_ref(),
                            if material_names.is_empty() {
                                "none".to_string()
                            } else {
                                material_names.join(", ")
                            }
                        ),
                    )
                })?,
        ),
        None => None,
    };
    let emission = match &s.emission {
        Some(e) => Some(emission(cx, e, &format!("{f}.emission"))?),
        None => None,
    };
    if material.is_none() && emission.is_none() {
        return Err(cx.err(
            &sp,
            &f,
            "a shape needs a `material`, an `emission`, or both",
        ));
    }
    Ok(ShapeDesc {
        kind,
        transform,
        material,
        two_sided: s.two_sided.as_ref().is_some_and(|b| *b.get_ref()),
        emission,
        unit_m: cx.unit_m,
        loc: cx.src.span(&sp),
    })
}

/// Exactly one of the listed amount keys.
fn one_amount<'v>(
    cx: &Cx<'_>,
    span: &Range<usize>,
    field: &str,
    opts: &[(&'static str, &'v Option<S<Value>>)],
) -> R<(&'static str, &'v S<Value>)> {
    let given: Vec<_> = opts
        .iter()
        .filter_map(|(n, v)| v.as_ref().map(|v| (*n, v)))
        .collect();
    let names = opts.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ");
    match given.as_slice() {
        [one] => Ok(*one),
        [] => Err(cx.err(span, field, format!("missing; give exactly one of {names}"))),
        [_, second, ..] => Err(cx.err(
            &second.1.span(),
            format!("{field}.{}", second.0),
            format!("give exactly one of {names}"),
        )),
    }
}

fn emission(cx: &Cx<'_>, e: &S<RawEmission>, f: &str) -> R<EmissionDesc> {
    let sp = e.span();
    let e = e.get_ref();
    let spectrum = match &e.spectrum {
        Some(s) => cx.spectrum(s, &format!("{f}.spectrum"), SpectrumUse::Emission)?,
        None => Spectrum::Constant(1.0),
    };
    let amount = emit_amount(cx, &sp, f, &e.radiance, &e.luminance, &e.power, &e.scale)?;
    Ok(EmissionDesc {
        spectrum,
        amount,
        two_sided: e.two_sided.as_ref().is_some_and(|b| *b.get_ref()),
        loc: cx.src.span(&sp),
    })
}

fn emit_amount(
    cx: &Cx<'_>,
    sp: &Range<usize>,
    f: &str,
    radiance: &Option<S<Value>>,
    luminance: &Option<S<Value>>,
    power: &Option<S<Value>>,
    scale: &Option<S<Value>>,
) -> R<EmitAmount> {
    let (which, v) = one_amount(
        cx,
        sp,
        f,
        &[
            ("radiance", radiance),
            ("luminance", luminance),
            ("power", power),
            ("scale", scale),
        ],
    )?;
    let field = format!("{f}.{which}");
    let amount = match which {
        "radiance" => EmitAmount::Radiance(cx.quantity::<Radiance>(v, &field)?),
        "luminance" => EmitAmount::Luminance(cx.quantity::<Luminance>(v, &field)?),
        "power" => match cx.quantity_of(v, &field, &[D::Power, D::LuminousFlux])? {
            (D::Power, w) => EmitAmount::Power(Power::new::<power::watt>(w)),
            (_, lm) => EmitAmount::LuminousFlux(LuminousFlux::new::<luminous_flux::lumen>(lm)),
        },
        _ => EmitAmount::Scale(cx.number(v, &field)?),
    };
    let si = match &amount {
        EmitAmount::Radiance(r) => r.get::<radiance::watt_per_square_meter_steradian>(),
        EmitAmount::Luminance(l) => l.get::<luminance::candela_per_square_meter>(),
        EmitAmount::Power(p) => p.get::<power::watt>(),
        EmitAmount::LuminousFlux(p) => p.get::<luminous_flux::lumen>(),
        EmitAmount::Scale(s) => *s,
    };
    if si < 0.0 {
        return Err(cx.err(
            &v.span(),
            field,
            format!("light cannot be negative, found {si}"),
        ));
    }
    Ok(amount)
}

fn light(cx: &Cx<'_>, i: usize, l: &S<RawLight>) -> R<LightDesc> {
    let sp = l.span();
    let f = format!("lights[{i}]");
    let l = l.get_ref();
    let all = present!(l; kind, spectrum, position, target, direction, power, intensity, radiance, luminance, irradiance, scale, cone_angle, falloff_start, angular_diameter);
    let ty = cx.required(
        &l.kind,
        &sp,
        &format!("{f}.type"),
        "point, spot, directional or environment",
    )?;
    let spectrum = match &l.spectrum {
        Some(s) => cx.spectrum(s, &format!("{f}.spectrum"), SpectrumUse::Emission)?,
        None => Spectrum::Constant(1.0),
    };
    let pos = |cx: &Cx<'_>| {
        cx.point(
            cx.required(
                &l.position,
                &sp,
                &format!("{f}.position"),
                "a position [x, y, z]",
            )?,
            &format!("{f}.position"),
        )
    };
    let point_amount = |cx: &Cx<'_>| -> R<PointAmount> {
        let (which, v) = one_amount(
            cx,
            &sp,
            &f,
            &[
                ("power", &l.power),
                ("intensity", &l.intensity),
                ("scale", &l.scale),
            ],
        )?;
        let field = format!("{f}.{which}");
        let (amount, si) = match which {
            "power" => match cx.quantity_of(v, &field, &[D::Power, D::LuminousFlux])? {
                (D::Power, w) => (PointAmount::Power(Power::new::<power::watt>(w)), w),
                (_, lm) => (
                    PointAmount::LuminousFlux(LuminousFlux::new::<luminous_flux::lumen>(lm)),
                    lm,
                ),
            },
            "intensity" => {
                match cx.quantity_of(v, &field, &[D::RadiantIntensity, D::LuminousIntensity])? {
                    (D::RadiantIntensity, w) => (
                        PointAmount::Intensity(RadiantIntensity::new::<
                            radiant_intensity::watt_per_steradian,
                        >(w)),
                        w,
                    ),
                    (_, cd) => (
                        PointAmount::LuminousIntensity(LuminousIntensity::new::<
                            luminous_intensity::candela,
                        >(cd)),
                        cd,
                    ),
                }
            }
            _ => {
                let s = cx.number(v, &field)?;
                (PointAmount::Scale(s), s)
            }
        };
        if si < 0.0 {
            return Err(cx.err(
                &v.span(),
                field,
                format!("light cannot be negative, found {si}"),
            ));
        }
        Ok(amount)
    };
    let kind = match ty.get_ref().as_str() {
        "point" => {
            cx.only(
                "a point light",
                &f,
                &all,
                &[
                    "kind",
                    "spectrum",
                    "position",
                    "power",
                    "intensity",
                    "scale",
                ],
            )?;
            LightKind::Point {
                position: pos(cx)?,
                amount: point_amount(cx)?,
            }
        }
        "spot" => {
            cx.only(
                "a spot light",
                &f,
                &all,
                &[
                    "kind",
                    "spectrum",
                    "position",
                    "target",
                    "power",
                    "intensity",
                    "scale",
                    "cone_angle",
                    "falloff_start",
                ],
            )?;
            let position = pos(cx)?;
            let t = cx.required(
                &l.target,
                &sp,
                &format!("{f}.target"),
                "the point the spot aims at",
            )?;
            let target = cx.point(t, &format!("{f}.target"))?;
            if (0..3).all(|k| target[k] == position[k]) {
                return Err(cx.err(
                    &t.span(),
                    format!("{f}.target"),
                    "the target equals the position",
                ));
            }
            let c = cx.required(
                &l.cone_angle,
                &sp,
                &format!("{f}.cone_angle"),
                "the cone's half-angle, e.g. \"30 deg\"",
            )?;
            let cone_angle: Angle = cx.quantity(c, &format!("{f}.cone_angle"))?;
            let cd = cone_angle.get::<angle::degree>();
            if !(cd > 0.0 && cd <= 90.0) {
                return Err(cx.err(
                    &c.span(),
                    format!("{f}.cone_angle"),
                    format!(
                        "expected a half-angle in (0, 90] deg, found {} deg",
                        round9(cd)
                    ),
                ));
            }
            let falloff_start = match &l.falloff_start {
                Some(fs) => {
                    let a: Angle = cx.quantity(fs, &format!("{f}.falloff_start"))?;
                    let d = a.get::<angle::degree>();
                    if !(0.0..=cd).contains(&d) {
                        return Err(cx.err(
                            &fs.span(),
                            format!("{f}.falloff_start"),
                            format!(
                                "expected 0 to cone_angle ({} deg), found {} deg",
                                round9(cd),
                                round9(d)
                            ),
                        ));
                    }
                    a
                }
                None => cone_angle,
            };
            LightKind::Spot {
                position,
                target,
                cone_angle,
                falloff_start,
                amount: point_amount(cx)?,
            }
        }
        "directional" | "sun" => {
            cx.only(
                "a directional light",
                &f,
                &all,
                &[
                    "kind",
                    "spectrum",
                    "direction",
                    "irradiance",
                    "scale",
                    "angular_diameter",
                ],
            )?;
            let d = cx.required(
                &l.direction,
                &sp,
                &format!("{f}.direction"),
                "the direction light travels, [x, y, z]",
            )?;
            let direction = cx.vec3(d, &format!("{f}.direction"))?;
            if direction == [0.0; 3] {
                return Err(cx.err(&d.span(), format!("{f}.direction"), "the direction is zero"));
            }
            let angular_diameter = match &l.angular_diameter {
                Some(a) => {
                    let q: Angle = cx.quantity(a, &format!("{f}.angular_diameter"))?;
                    let deg = q.get::<angle::degree>();
                    if !(0.0..=30.0).contains(&deg) {
                        return Err(cx.err(
                            &a.span(),
                            format!("{f}.angular_diameter"),
                            format!("expected 0 to 30 deg, found {} deg", round9(deg)),
                        ));
                    }
                    q
                }
                None => Angle::new::<angle::radian>(0.0),
            };
            let (which, v) = one_amount(
                cx,
                &sp,
                &f,
                &[("irradiance", &l.irradiance), ("scale", &l.scale)],
            )?;
            let field = format!("{f}.{which}");
            let amount = if which == "irradiance" {
                match cx.quantity_of(v, &field, &[D::Irradiance, D::Illuminance])? {
                    (D::Irradiance, e) => DirectionalAmount::Irradiance(Irradiance::new::<
                        irradiance::watt_per_square_meter,
                    >(e)),
                    (_, lx) => {
                        DirectionalAmount::Illuminance(Illuminance::new::<illuminance::lux>(lx))
                    }
                }
            } else {
                DirectionalAmount::Scale(cx.number(v, &field)?)
            };
            LightKind::Directional {
                direction,
                angular_diameter,
                amount,
            }
        }
        "environment" => {
            cx.only(
                "an environment light",
                &f,
                &all,
                &["kind", "spectrum", "radiance", "luminance", "scale"],
            )?;
            LightKind::Environment {
                amount: emit_amount(cx, &sp, &f, &l.radiance, &l.luminance, &None, &l.scale)?,
            }
        }
        o => {
            return Err(cx.err(
                &ty.span(),
                format!("{f}.type"),
                format!(
                    "unknown light type \"{o}\"; expected point, spot, directional or environment"
                ),
            ));
        }
    };
    Ok(LightDesc {
        kind,
        spectrum,
        loc: cx.src.span(&sp),
    })
}

/// Rounds away binary noise from unit conversions (29.999999999999996 → 30) for messages.
fn round9(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}
