//! Mitsuba media: `<medium type="homogeneous">` and `"heterogeneous"` (its volumes
//! `gridvolume`, read from `.vol` files, and `constvolume`) with its `<phase>` (`isotropic`,
//! `hg`, `rayleigh`), declared at the top level with an id, or inside a shape or sensor with a
//! `name` (`interior`, `exterior`, or a sensor's `medium`).
//!
//! Units: Mitsuba's coefficients are per scene unit, which spectrace reads as metres, so
//! `sigma_t` × `scale` is σt in m⁻¹. Spectra read as for a reflectance: a float is constant
//! and an `<rgb>` is upsampled within [0, 1] (Jakob–Hanika), as Mitsuba's spectral variants
//! read a volume's colour.

use std::sync::Arc;

use super::cx::{Cx, R};
use super::xml::Element;
use crate::loader::desc::{Coefficients, MediumDesc, MediumKind, TransformStep, VolumeDesc};
use crate::medium::{PhaseFunction, Wrap};

/// The media spectrace reads, for messages and the plugin list.
pub(super) const MEDIA: &[&str] = &["homogeneous", "heterogeneous"];

/// The volumes spectrace reads.
pub(super) const VOLUMES: &[&str] = &["gridvolume", "constvolume"];

/// The phase functions spectrace reads.
pub(super) const PHASES: &[&str] = &["isotropic", "hg", "rayleigh"];

/// The index into the scene's media of the `<medium>` (or `<ref>` to one) `e`, read on its
/// first use; `name` identifies an unnamed one in messages.
pub(super) fn medium_index(cx: &Cx<'_>, e: &Element, name: &str) -> R<usize> {
    let m = cx.resolve(e)?;
    let key = (m.src, m.pos);
    if let Some(i) = cx.media.borrow().iter().position(|(k, _)| *k == key) {
        return Ok(i);
    }
    let d = medium(cx, m, name)?;
    let mut media = cx.media.borrow_mut();
    media.push((key, d));
    Ok(media.len() - 1)
}

/// The medium a `<sensor>` sits in (its `<ref name="medium">` or nested `<medium
/// name="medium">`), if any.
pub(super) fn sensor_medium(cx: &Cx<'_>, sensor: &Element) -> R<Option<usize>> {
    sensor
        .children
        .iter()
        .find(|m| matches!(m.tag.as_str(), "ref" | "medium") && m.attr("name") == Some("medium"))
        .map(|m| medium_index(cx, m, "sensor medium"))
        .transpose()
}

/// A `<medium>` element; `name` identifies it in messages.
fn medium(cx: &Cx<'_>, e: &Element, name: &str) -> R<MediumDesc> {
    let e = cx.resolve(e)?;
    if e.tag != "medium" {
        return Err(cx.err(e, format!("expected a <medium>, not <{}>", e.tag)));
    }
    let t = e.attr("type").ok_or_else(|| cx.err(e, "missing type"))?;
    let kind = match t {
        "homogeneous" => homogeneous(cx, e)?,
        "heterogeneous" => heterogeneous(cx, e)?,
        other => return Err(cx.unsupported(e, "medium", other)),
    };
    Ok(MediumDesc {
        name: e.attr("id").unwrap_or(name).to_string(),
        kind,
        loc: cx.loc(e),
    })
}

/// `homogeneous`: `sigma_t` (default 1) × `scale` (default 1), `albedo` (default 0.75), a
/// phase function (default isotropic). `sample_emitters` and `has_spectral_extinction` are
/// sampling hints that do not change the image; they are read and not needed.
fn homogeneous(cx: &Cx<'_>, e: &Element) -> R<MediumKind> {
    let scale = scale(cx, e)?;
    if let Some(c) = cx.child(e, "sigma_t").filter(|c| c.tag == "volume") {
        return Err(cx.err(
            c,
            "a homogeneous medium's sigma_t is one value or spectrum; a <volume> extinction makes it heterogeneous",
        ));
    }
    let sigma_t = cx
        .spectrum_prop(e, "sigma_t", 1.0, false)?
        .scaled(scale as f32);
    let albedo = volume(cx, e, "albedo", 0.75)?;
    note_albedo_above_one(cx, e, &albedo);
    Ok(MediumKind::Homogeneous {
        emission: None,
        coefficients: Coefficients::Extinction { sigma_t, albedo },
        phase: phase(cx, e)?,
    })
}

/// `heterogeneous`: `sigma_t` (a volume, or a number, spectrum or colour over the unit cube;
/// default 1) × `scale` (default 1), `albedo` (a volume or a value; default 0.75), a phase
/// function. The medium fills the unit cube of `sigma_t`'s frame.
fn heterogeneous(cx: &Cx<'_>, e: &Element) -> R<MediumKind> {
    let scale = scale(cx, e)?;
    let density = volume(cx, e, "sigma_t", 1.0)?;
    let albedo = volume(cx, e, "albedo", 0.75)?;
    note_albedo_above_one(cx, e, &albedo);
    Ok(MediumKind::Heterogeneous {
        density,
        albedo,
        scale,
        phase: phase(cx, e)?,
    })
}

/// A medium's `scale` (1 by default; finite and not negative), its sampling hints
/// `sample_emitters` and `has_spectral_extinction` read (they do not change the image).
fn scale(cx: &Cx<'_>, e: &Element) -> R<f64> {
    for hint in ["sample_emitters", "has_spectral_extinction"] {
        let _ = cx.child(e, hint);
    }
    let scale = cx.opt_float(e, "scale")?.unwrap_or(1.0);
    if !(scale.is_finite() && scale >= 0.0) {
        let at = cx.child(e, "scale").unwrap_or(e);
        return Err(cx.err(
            at,
            format!("scale must be finite and not negative, not {scale}"),
        ));
    }
    Ok(scale)
}

/// A note when an albedo grid holds values above 1 (Mitsuba's own test grid does): such a
/// medium creates energy, and is read as Mitsuba reads it. A constant albedo above 1 is an
/// error (in the build step).
fn note_albedo_above_one(cx: &Cx<'_>, e: &Element, albedo: &VolumeDesc) {
    if let VolumeDesc::Grid { values, file, .. } = albedo {
        let max = values.iter().copied().fold(0.0f32, f32::max);
        if max > 1.0 {
            cx.note(
                cx.child(e, "albedo").unwrap_or(e),
                format!(
                    "the albedo grid {} holds values up to {max}: above 1 scattering creates energy; read as Mitsuba reads it",
                    file.display()
                ),
            );
        }
    }
}

/// The volume property `name` of `e`: a `<volume>` (`gridvolume`, `constvolume`), or a
/// number, spectrum or colour, constant over the unit cube.
fn volume(cx: &Cx<'_>, e: &Element, name: &str, default: f32) -> R<VolumeDesc> {
    let Some(c) = cx.child(e, name) else {
        return Ok(VolumeDesc::Constant {
            value: crate::spectrum::Spectrum::Constant(default),
            to_world: Vec::new(),
        });
    };
    let c = cx.resolve(c)?;
    if c.tag != "volume" {
        return Ok(VolumeDesc::Constant {
            value: cx.spectrum(c, false)?,
            to_world: Vec::new(),
        });
    }
    let mut to_world = match c.children.iter().find(|t| t.tag == "transform") {
        Some(t) => cx.transform(t)?,
        None => Vec::new(),
    };
    match c.attr("type").unwrap_or("") {
        "constvolume" => Ok(VolumeDesc::Constant {
            value: cx.spectrum_prop(c, "value", 1.0, false)?,
            to_world,
        }),
        "gridvolume" => {
            let file = cx
                .string(c, "filename")
                .ok_or_else(|| cx.err(c, "a gridvolume needs a filename (a .vol file)"))?;
            let path = cx.resolve_file(&file);
            let at = cx.child(c, "filename").unwrap_or(c);
            let vol = super::vol::read(&path).map_err(|m| cx.err(at, m))?;
            let wrap = cx.wrap_mode(c, Wrap::Clamp)?;
            if let Some(f) = cx.string(c, "filter_type")
                && f != "trilinear"
            {
                let at = cx.child(c, "filter_type").unwrap_or(c);
                return Err(cx.err(
                    at,
                    format!("filter_type \"{f}\" is not supported; spectrace interpolates grids trilinearly"),
                ));
            }
            if cx.string(c, "raw").as_deref() == Some("true") && vol.channels == 3 {
                let at = cx.child(c, "raw").unwrap_or(c);
                return Err(cx.err(
                    at,
                    "raw = true on a three-channel grid is not supported: spectrace reads its colours as sRGB",
                ));
            }
            let _ = cx.child(c, "accel");
            if cx.string(c, "use_grid_bbox").as_deref() == Some("true") {
                let [lo, hi] = vol.bounds;
                let size = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
                to_world.insert(
                    0,
                    TransformStep::Translate(lo.map(|v| {
                        crate::units::Length::new::<crate::units::length::meter>(f64::from(v))
                    })),
                );
                to_world.insert(0, TransformStep::Scale(size.map(f64::from)));
            }
            if vol.channels != 1 && vol.channels != 3 {
                return Err(cx.err(
                    at,
                    format!(
                        "{}: {} channels; a grid has 1 (a value) or 3 (a colour)",
                        path.display(),
                        vol.channels
                    ),
                ));
            }
            Ok(VolumeDesc::Grid {
                res: vol.res,
                channels: vol.channels,
                values: Arc::new(vol.values),
                wrap,
                to_world,
                file: path,
            })
        }
        other => Err(cx.unsupported(c, "volume", other)),
    }
}

/// The medium's `<phase>` child (isotropic when it has none).
fn phase(cx: &Cx<'_>, e: &Element) -> R<PhaseFunction> {
    let Some(p) = e.children.iter().find(|c| c.tag == "phase") else {
        return Ok(PhaseFunction::Isotropic);
    };
    let p = cx.resolve(p)?;
    match p.attr("type").unwrap_or("") {
        "isotropic" => Ok(PhaseFunction::Isotropic),
        "rayleigh" => Ok(PhaseFunction::Rayleigh),
        "hg" => {
            let g = cx.opt_float(p, "g")?.unwrap_or(0.8);
            if !(g.abs() < 1.0) {
                let at = cx.child(p, "g").unwrap_or(p);
                return Err(cx.err(
                    at,
                    format!("Henyey–Greenstein's g must lie strictly between -1 and 1, not {g}"),
                ));
            }
            Ok(PhaseFunction::HenyeyGreenstein { g: g as f32 })
        }
        other => Err(cx.unsupported(p, "phase", other)),
    }
}

/// The media the shapes and the sensor refer to. A top-level medium nobody refers to is an
/// error (a scene that declares a fog and shows none is a mistake). Mitsuba's `path` and
/// `direct` integrators ignore media, so under them (`volumetric` false) the media are
/// dropped, with a note.
pub(super) fn scene_media(
    cx: &Cx<'_>,
    root: &Element,
    volumetric: bool,
    shapes: &mut [crate::loader::desc::ShapeDesc],
    camera_medium: &mut Option<usize>,
) -> R<Vec<crate::loader::desc::MediumDesc>> {
    let read = cx.media.borrow();
    for c in root.children.iter().filter(|c| c.tag == "medium") {
        if !read.iter().any(|(k, _)| *k == (c.src, c.pos)) {
            return Err(cx.err(
                c,
                format!(
                    "medium \"{}\" is declared but no shape or sensor refers to it (give a shape <ref id=\"{}\" name=\"interior\"/>)",
                    c.attr("id").unwrap_or_default(),
                    c.attr("id").unwrap_or_default()
                ),
            ));
        }
    }
    if read.is_empty() {
        return Ok(Vec::new());
    }
    if !volumetric {
        let first = &read[0].1;
        cx.note(
            root,
            format!(
                "the scene's media (first: \"{}\") are ignored: Mitsuba's path and direct integrators render surfaces only (use volpath)",
                first.name
            ),
        );
        for s in shapes.iter_mut() {
            s.interior = None;
            s.exterior = None;
        }
        *camera_medium = None;
        return Ok(Vec::new());
    }
    Ok(read.iter().map(|(_, d)| d.clone()).collect())
}
