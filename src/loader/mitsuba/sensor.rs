//! Mitsuba sensors → camera and film settings: the field of view as Mitsuba derives it
//! (`fov`, `fov_axis`, `focal_length`), the film, and camera frames from `to_world` (also used
//! to place lights).

use super::cx::{Cx, R};
use super::params::read_kind;
use super::plugins::SAMPLERS;
use super::xml::Element;
use crate::film::filter::KINDS;
use crate::loader::desc::*;
use crate::units::{Angle, Length, angle, length};

/// Mitsuba's horizontal field of view, degrees, for a film of `aspect` = width / height:
/// `fov` on `fov_axis` (x, y, smaller, larger, diagonal; default x), or without `fov` the
/// diagonal field of view of a lens of `focal_length` (default "50mm") on a 36 × 24 mm frame
/// (Mitsuba 3.9.1 `parse_fov`, src/render/sensor.cpp; checked against its `x_fov`).
fn x_fov(cx: &Cx<'_>, s: &Element, aspect: f64) -> R<f64> {
    let fov = cx.opt_float(s, "fov")?;
    let focal = cx.child(s, "focal_length");
    let axis = cx.string(s, "fov_axis");
    let (fov, axis) = match (fov, focal) {
        (Some(_), Some(f)) => {
            return Err(cx.err(
                f,
                "give either focal_length or fov, not both (as Mitsuba requires)",
            ));
        }
        (Some(fov), None) => (fov, axis.unwrap_or_else(|| "x".into()).to_lowercase()),
        (None, f) => {
            if let Some(a) = cx.child(s, "fov_axis") {
                return Err(cx.err(
                    a,
                    "fov_axis needs a fov (Mitsuba rejects it with focal_length)",
                ));
            }
            let text = match f {
                Some(f) => f.attr("value").unwrap_or("").to_string(),
                None => "50mm".to_string(),
            };
            let mm: f64 = text
                .trim()
                .strip_suffix("mm")
                .unwrap_or(text.trim())
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite() && *v > 0.0)
                .ok_or_else(|| {
                    cx.err(
                        f.unwrap_or(s),
                        format!("focal_length \"{text}\" is not of the form <x>mm with x > 0"),
                    )
                })?;
            let diagonal_mm = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            (
                (diagonal_mm / (2.0 * mm)).atan().to_degrees() * 2.0,
                "diagonal".to_string(),
            )
        }
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(cx.err(s, format!("fov {fov}° is outside (0°, 180°)")));
    }
    let axis = match axis.as_str() {
        "smaller" if aspect > 1.0 => "y",
        "smaller" => "x",
        "larger" if aspect > 1.0 => "x",
        "larger" => "y",
        a => a,
    };
    let half_tan = (fov.to_radians() / 2.0).tan();
    let x_half_tan = match axis {
        "x" => half_tan,
        "y" => half_tan * aspect,
        "diagonal" => half_tan / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        o => {
            return Err(cx.err(
                s,
                format!("fov_axis \"{o}\" is not one of x, y, smaller, larger, diagonal"),
            ));
        }
    };
    Ok(2.0 * x_half_tan.atan().to_degrees())
}

pub(super) fn sensor(cx: &Cx<'_>, s: &Element, film: &mut FilmDesc) -> R<CameraDesc> {
    let t = s.attr("type").unwrap_or("");
    if t != "perspective" && t != "thinlens" && t != "orthographic" {
        return Err(cx.unsupported(s, "sensor", t));
    }
    if t == "perspective" {
        // Mitsuba's pinhole reads its projective camera's focus distance, which changes
        // nothing in its image
        let _ = cx.child(s, "focus_distance");
    }
    for c in &s.children {
        // a film or sampler declared at the top level and referred to here
        let c = match c.tag.as_str() {
            "ref" => cx.resolve(c)?,
            _ => c,
        };
        match (c.tag.as_str(), c.attr("type")) {
            ("film", Some("hdrfilm")) => hdrfilm(cx, c, film)?,
            ("film", Some(o)) => return Err(cx.unsupported(c, "film", o)),
            ("sampler", Some(o)) => sampler(cx, c, o, film)?,
            _ => {}
        }
    }
    film.loc = cx.loc(s);
    // the camera frame from to_world: origin, +z forward, +y up
    let steps = match s.children.iter().find(|c| c.tag == "transform") {
        Some(t) => cx.transform(t)?,
        None => Vec::new(),
    };
    let (eye, target, up) = camera_frame(cx, s, &steps)?;
    if t == "orthographic" {
        // Mitsuba's orthographic sensor sees x ∈ [−1, 1] of its local frame (y by the film's
        // aspect), mapped by to_world: the view is 2·|to_world · x̂| wide
        let m = to_world_matrix(&steps);
        let (sx, sy) = (
            m.transform_vector3(glam::DVec3::X).length(),
            m.transform_vector3(glam::DVec3::Y).length(),
        );
        if (sx - sy).abs() > 1e-9 * sx.max(sy) {
            return Err(cx.err(
                s,
                format!("an orthographic to_world must scale x and y alike (found {sx} and {sy}): spectrace's pixels are square"),
            ));
        }
        return Ok(CameraDesc {
            mirror: false,
            sensor: None,
            kind: CameraKind::Orthographic {
                view_width: Length::new::<length::meter>(2.0 * sx),
            },
            eye,
            target,
            up,
            loc: cx.loc(s),
        });
    }
    let fov = x_fov(cx, s, film.width as f64 / film.height as f64)?;
    let projection = Projection::Fov {
        fov: Angle::new::<angle::degree>(fov),
        axis: FovAxis::X,
    };
    let kind = if t == "thinlens" {
        let r = cx.opt_float(s, "aperture_radius")?.unwrap_or(0.03);
        let fd = cx.opt_float(s, "focus_distance")?.unwrap_or(1.0);
        // aperture radius = f/(2N) with the focal length of a 36 mm sensor at this field of view
        let hfov = fov.to_radians();
        let focal = 0.036 / (2.0 * (hfov / 2.0).tan());
        CameraKind::ThinLens {
            projection,
            f_number: focal / (2.0 * r.max(1e-9)),
            focus_distance: Length::new::<length::meter>(fd),
        }
    } else {
        CameraKind::Perspective { projection }
    };
    Ok(CameraDesc {
        mirror: false,
        sensor: None,
        kind,
        eye,
        target,
        up,
        loc: cx.loc(s),
    })
}

/// Eye, target and up of a sensor's `to_world`, by applying it to the camera's own frame.
pub(super) fn camera_frame(
    cx: &Cx<'_>,
    s: &Element,
    steps: &[TransformStep],
) -> R<(Point, Point, [f64; 3])> {
    use glam::DVec3;
    let m = to_world_matrix(steps);
    let eye = m.transform_point3(DVec3::ZERO);
    let fwd = m.transform_vector3(DVec3::Z);
    let up = m.transform_vector3(DVec3::Y);
    if fwd.length() == 0.0 || up.length() == 0.0 || !eye.is_finite() {
        return Err(cx.err(s, "the sensor's to_world is degenerate"));
    }
    let target = eye + fwd.normalize();
    let l = |x: f64| Length::new::<length::meter>(x);
    Ok((
        [l(eye.x), l(eye.y), l(eye.z)],
        [l(target.x), l(target.y), l(target.z)],
        up.normalize().to_array(),
    ))
}

/// The most samples per pixel a scene may ask for, whatever its format (the TOML loader's
/// `film.spp` limit, 2²⁴).
const MAX_SPP: u32 = 1 << 24;

/// The samples per pixel Mitsuba 3.9.1's sampler `name` renders for `sample_count` n (each
/// rounds up to the structure it needs; measured in Mitsuba with `sampler.sample_count()`):
/// `stratified` ⌈√n⌉², `multijitter` r·⌈n/r⌉ with r = ⌊√n⌋, `orthogonal` p² for the smallest
/// prime p ≥ ⌈√n⌉ (at least 4), `ldsampler` the next power of 4 (at least 4), `independent` n.
fn mitsuba_sample_count(name: &str, n: u32) -> u32 {
    let root = (n as f64).sqrt().ceil() as u32;
    match name {
        "stratified" => root * root,
        "multijitter" => {
            let r = ((n as f64).sqrt().floor() as u32).max(1);
            r * n.div_ceil(r)
        }
        "orthogonal" => {
            let is_prime = |p: u32| {
                p >= 2
                    && (2..)
                        .take_while(|d| d * d <= p)
                        .all(|d| !p.is_multiple_of(d))
            };
            let p = (root.max(2)..).find(|&p| is_prime(p)).unwrap_or(root);
            p * p
        }
        "ldsampler" => {
            let mut s = 4;
            while s < n {
                s *= 4;
            }
            s
        }
        _ => n,
    }
}

/// The matrix of `to_world` steps applied in order.
fn to_world_matrix(steps: &[TransformStep]) -> glam::DMat4 {
    use glam::{DMat4, DVec3};
    let mut m = DMat4::IDENTITY;
    for st in steps {
        let next = match st {
            TransformStep::Translate(p) => {
                DMat4::from_translation(DVec3::new(p[0].value, p[1].value, p[2].value))
            }
            TransformStep::Scale(k) => DMat4::from_scale(DVec3::from(*k)),
            TransformStep::Rotate { axis, angle } => {
                DMat4::from_axis_angle(DVec3::from(*axis).normalize(), angle.value)
            }
            TransformStep::Matrix(a) => DMat4::from_cols_array(a).transpose(),
            TransformStep::LookAt { eye, target, up } => {
                let e = DVec3::new(eye[0].value, eye[1].value, eye[2].value);
                let t = DVec3::new(target[0].value, target[1].value, target[2].value);
                let d = (t - e).normalize();
                let left = DVec3::from(*up).cross(d).normalize();
                let new_up = d.cross(left);
                DMat4::from_cols(
                    left.extend(0.0),
                    new_up.extend(0.0),
                    d.extend(0.0),
                    e.extend(1.0),
                )
            }
        };
        m = next * m;
    }
    m
}

/// An `hdrfilm`'s size and reconstruction filter (its pixel and file formats are read: the
/// output is spectrace's own).
fn hdrfilm(cx: &Cx<'_>, c: &Element, film: &mut FilmDesc) -> R<()> {
    // the output's channels and file format are spectrace's own (XYZ, luminance and
    // band radiance in 32-bit float EXR, whatever these ask), so they are read and
    // have nothing to change
    for name in ["pixel_format", "component_format", "file_format"] {
        let _ = cx.child(c, name);
    }
    for (name, slot) in [("width", &mut film.width), ("height", &mut film.height)] {
        let Some(e) = cx.child(c, name) else { continue };
        let v = cx.float(e)?;
        if !(v.fract() == 0.0 && (1.0..=32768.0).contains(&v)) {
            return Err(cx.err(
                e,
                format!("expected an integer from 1 to 32768 pixels, found {v}"),
            ));
        }
        *slot = v as u32;
    }
    for f in c.children.iter().filter(|f| f.tag == "rfilter") {
        film.filter = read_kind(cx, KINDS, "rfilter", f)?;
    }
    crop(cx, c, film)
}

/// An `hdrfilm`'s crop window (`crop_offset_x`, `crop_offset_y`, `crop_width`,
/// `crop_height`; by default the whole film): only it is rendered and written, as Mitsuba
/// writes it, each pixel as in the whole image.
fn crop(cx: &Cx<'_>, c: &Element, film: &mut FilmDesc) -> R<()> {
    let names = [
        "crop_offset_x",
        "crop_offset_y",
        "crop_width",
        "crop_height",
    ];
    if names.iter().all(|n| cx.child(c, n).is_none()) {
        return Ok(());
    }
    let (w, h) = (film.width, film.height);
    let mut v = [0u32, 0, w, h];
    for (name, slot) in names.iter().zip(&mut v) {
        let Some(e) = cx.child(c, name) else { continue };
        let x = cx.float(e)?;
        if !(x.fract() == 0.0 && (0.0..=32768.0).contains(&x)) {
            return Err(cx.err(e, format!("expected a whole number of pixels, found {x}")));
        }
        *slot = x as u32;
    }
    let [x0, y0, cw, ch] = v;
    if cw == 0 || ch == 0 || x0 + cw > w || y0 + ch > h {
        let at = cx.child(c, "crop_width").unwrap_or(c);
        return Err(cx.err(
            at,
            format!("the crop window of {cw} × {ch} pixels at ({x0}, {y0}) is not inside the {w} × {h} film"),
        ));
    }
    (film.width, film.height) = (cw, ch);
    film.crop = Some(crate::loader::desc::CropDesc {
        at: [x0, y0],
        full: [w, h],
        // Mitsuba 3.9.1 writes a cropped film as an image of its own (no data window offset)
        data_window: false,
    });
    Ok(())
}

/// A sampler's `sample_count`, as the sample count the Mitsuba sampler `o` would render.
fn sampler(cx: &Cx<'_>, c: &Element, o: &str, film: &mut FilmDesc) -> R<()> {
    if !SAMPLERS.contains(&o) {
        return Err(cx.unsupported(c, "sampler", o));
    }
    let asked = match cx.opt_float(c, "sample_count")? {
        // the TOML film's limit, an error rather than a silent clamp
        Some(n) if n > MAX_SPP as f64 && n.fract() == 0.0 => {
            return Err(cx.err(
                cx.child(c, "sample_count").unwrap_or(c),
                format!(
                    "sample_count {n} is more than spectrace renders: at most {MAX_SPP} samples per pixel (as a TOML film's spp)"
                ),
            ));
        }
        Some(n) if n >= 1.0 && n.fract() == 0.0 => n as u32,
        Some(n) => {
            return Err(cx.err(
                c,
                format!("sample_count must be a positive integer, not {n}"),
            ));
        }
        // Mitsuba's default sample count
        None => 4,
    };
    film.spp = mitsuba_sample_count(o, asked);
    cx.note(
        c,
        if film.spp == asked {
            format!("Mitsuba's \"{o}\" sampler: spectrace renders {asked} samples per pixel with its own Owen-scrambled Sobol sampler")
        } else {
            format!("Mitsuba's \"{o}\" sampler renders {} samples per pixel for sample_count {asked}; spectrace renders as many, with its own Owen-scrambled Sobol sampler", film.spp)
        },
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::mitsuba_sample_count as c;

    /// The counts Mitsuba 3.9.1 reports for these requests (`mi.load_dict({"type": name,
    /// "sample_count": n}).sample_count()`).
    #[test]
    fn sample_counts_round_as_mitsuba() {
        let asked = [1, 2, 3, 4, 5, 10, 16, 17, 64, 100];
        for (name, got) in [
            ("stratified", [1, 4, 4, 4, 9, 16, 16, 25, 64, 100]),
            ("multijitter", [1, 2, 3, 4, 6, 12, 16, 20, 64, 100]),
            ("orthogonal", [4, 4, 4, 4, 9, 25, 25, 25, 121, 121]),
            ("ldsampler", [4, 4, 4, 4, 16, 16, 16, 64, 64, 256]),
        ] {
            for (n, want) in asked.iter().zip(got) {
                assert_eq!(c(name, *n), want, "{name} {n}");
            }
        }
        assert_eq!(c("independent", 7), 7);
    }
}
