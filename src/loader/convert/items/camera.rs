//! `[camera]`: the projection (`camera_sensor.rs`: `[camera.sensor]`; `realistic.rs`: a lens
//! system).

use super::*;
use camera_sensor::camera_sensor;

mod camera_sensor;
mod realistic;

pub(super) fn camera(cx: &Cx<'_>, c: &S<RawCamera>) -> R<CameraDesc> {
    let sp = c.span();
    let c = c.get_ref();
    let kind = kind(cx, c, &sp)?;
    let (eye, target, up) = placement(cx, c, &sp)?;
    let lens_f = match &kind {
        CameraKind::ThinLens { f_number, .. } => Some(*f_number),
        _ => None,
    };
    let sensor = match &c.sensor {
        Some(s) => Some(camera_sensor(cx, s, lens_f)?),
        None => None,
    };
    Ok(CameraDesc {
        mirror: false,
        kind,
        eye,
        target,
        up,
        sensor,
        loc: cx.src.span(&sp),
    })
}

/// The camera's type and its own keys (`type` perspective, thinlens or orthographic).
fn kind(cx: &Cx<'_>, c: &RawCamera, sp: &Range<usize>) -> R<CameraKind> {
    let kind_s = c
        .kind
        .as_ref()
        .map(|k| k.get_ref().as_str())
        .unwrap_or("perspective");
    let all = present!(c; kind, eye, target, up, fov, fov_axis, focal_length, sensor_width, f_number, focus_distance, view_width, medium, lens_file, film_diagonal, aperture_diameter, film_distance);
    Ok(match kind_s {
        "perspective" => {
            cx.only(
                "a perspective camera",
                "camera",
                &all,
                &[
                    "kind",
                    "medium",
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
                projection: projection(cx, c, sp)?,
            }
        }
        "thinlens" => {
            cx.only(
                "a thinlens camera",
                "camera",
                &all,
                &[
                    "kind",
                    "medium",
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
            let projection = projection(cx, c, sp)?;
            let n = cx.required(
                &c.f_number,
                sp,
                "camera.f_number",
                "a positive number, e.g. 2.8",
            )?;
            let f_number = cx.positive(n, "camera.f_number")?;
            let fd = cx.required(
                &c.focus_distance,
                sp,
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
            let w = cx.required(&c.view_width, sp, "camera.view_width", "a positive length")?;
            let view_width = cx.length(w, "camera.view_width")?;
            if !(view_width.get::<length::meter>() > 0.0) {
                return Err(cx.err(&w.span(), "camera.view_width", "expected a positive length"));
            }
            CameraKind::Orthographic { view_width }
        }
        "realistic" => {
            cx.only(
                "a realistic camera",
                "camera",
                &all,
                &[
                    "kind",
                    "eye",
                    "target",
                    "up",
                    "lens_file",
                    "film_diagonal",
                    "aperture_diameter",
                    "focus_distance",
                    "film_distance",
                ],
            )?;
            realistic::realistic(cx, c, sp)?
        }
        other => {
            let span = c.kind.as_ref().map(|k| k.span()).unwrap_or(sp.clone());
            return Err(cx.err(&span, "camera.type", format!("unknown camera type \"{other}\"; expected perspective, thinlens, orthographic or realistic")));
        }
    })
}

/// `fov` (with `fov_axis`) or `focal_length` (with `sensor_width`, default 36 mm).
fn projection(cx: &Cx<'_>, c: &RawCamera, sp: &Range<usize>) -> R<Projection> {
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
            sp,
            "camera.fov",
            "missing; expected `fov` (e.g. \"40 deg\") or `focal_length` (e.g. \"50 mm\")",
        )),
    }
}

/// `eye`, `target` and `up` (default +y), checked to give a view direction and a roll.
fn placement(cx: &Cx<'_>, c: &RawCamera, sp: &Range<usize>) -> R<(Point, Point, [f64; 3])> {
    let eye = cx.point(
        cx.required(&c.eye, sp, "camera.eye", "a position [x, y, z]")?,
        "camera.eye",
    )?;
    let target = cx.point(
        cx.required(&c.target, sp, "camera.target", "a position [x, y, z]")?,
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
    Ok((eye, target, up))
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
