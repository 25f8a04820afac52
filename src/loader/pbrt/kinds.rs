//! The pbrt-v4 scene-wide kinds spectrace reads: film, sampler and integrator (the camera in
//! `camera.rs`), each
//! reading its own parameters (pbrt-v4's names and defaults, `src/pbrt/cameras.cpp`,
//! `film.cpp`, `samplers.cpp`, `integrators.cpp`), and the scene they finish. Materials are in
//! `materials.rs`, lights in `lights.rs`. Lengths are read as metres (pbrt's files have no
//! unit).

use super::Reader;
use super::camera::{FilmSize, camera};
use super::params::{Params, R};
use crate::loader::desc::*;
use crate::loader::{LoadError, Loc};
use crate::units::Length;

/// A `PixelFilter` (pbrt-v4's default: `gaussian`, σ 0.5, radius 1.5 px): `gaussian`
/// (`sigma`, `xradius` = `yradius`), `box` (radius 0.5 px), `triangle` (radius 2 px).
fn pixel_filter(f: &Option<(Params, String, Loc)>) -> R<crate::film::FilterDesc> {
    use crate::film::filter::{box_filter, gaussian, tent};
    let Some((p, kind, loc)) = f else {
        return Ok(gaussian::Desc::pbrt(0.5, 1.5));
    };
    let default = match kind.as_str() {
        "gaussian" => 1.5,
        "box" => 0.5,
        "triangle" => 2.0,
        other => {
            return Err(p.err(
                *loc,
                format!("the pixel filter \"{other}\" is not read yet (spectrace reads gaussian, box and triangle)"),
            ));
        }
    };
    let (rx, ry) = (p.float("xradius", default)?, p.float("yradius", default)?);
    if rx != ry || !(rx > 0.0) {
        return Err(p.err(
            *loc,
            "a pixel filter's xradius and yradius must be equal and positive",
        ));
    }
    let f = match kind.as_str() {
        "gaussian" => gaussian::Desc::pbrt(p.float("sigma", 0.5)?, rx),
        "box" => crate::film::FilterDesc::Box(box_filter::Desc { radius: rx }),
        _ => crate::film::FilterDesc::Tent(tent::Desc {
            radius: rx,
            mitsuba: false,
        }),
    };
    p.check_unused(&format!("pixel filter \"{kind}\""))?;
    Ok(f)
}

/// The samples per pixel a `Sampler` asks for (pbrt-v4's defaults: 16, `independent` 4,
/// `stratified` `xsamples` × `ysamples`, 4 × 4); spectrace samples with its own sequence.
fn sampler_spp(p: &Params, kind: &str) -> R<i64> {
    let n = match kind {
        "zsobol" | "halton" | "sobol" | "paddedsobol" | "pmj02bn" => p.int("pixelsamples", 16)?,
        "independent" => p.int("pixelsamples", 4)?,
        "stratified" => {
            let _ = p.bool("jitter", true)?;
            p.int("xsamples", 4)? * p.int("ysamples", 4)?
        }
        other => {
            return Err(p.err(
                p.loc_of("pixelsamples"),
                format!("unknown sampler \"{other}\""),
            ));
        }
    };
    // read as pbrt-v4 reads them; spectrace's sampler has its own scrambling
    let _ = (p.int("seed", 0)?, p.string("randomization")?);
    p.check_unused(&format!("sampler \"{kind}\""))?;
    Ok(n)
}

/// An `Integrator`: `path` and `volpath` (spectrace's path tracer: media are not read yet),
/// `bdpt`, `lightpath` (spectrace's light tracer); `maxdepth` (5), `lightsampler` (`bvh`,
/// `power`, `uniform`).
fn integrator(p: &Params, kind: &str, loc: Loc) -> R<(IntegratorKind, i64, LightSelection)> {
    let k = match kind {
        "path" | "volpath" => IntegratorKind::Path,
        "bdpt" => IntegratorKind::Bdpt,
        "lightpath" => IntegratorKind::Light,
        other => {
            return Err(p.err(
                loc,
                format!("the integrator \"{other}\" is not read yet (spectrace reads path, volpath, bdpt and lightpath)"),
            ));
        }
    };
    let depth = p.int("maxdepth", 5)?;
    let selection = if matches!(kind, "path" | "volpath") {
        match p.string("lightsampler")?.as_deref().unwrap_or("bvh") {
            "bvh" => LightSelection::Tree,
            "power" => LightSelection::Power,
            "uniform" => LightSelection::Uniform,
            other => {
                return Err(p.err(
                    p.loc_of("lightsampler"),
                    format!("the light sampler \"{other}\" is not read (spectrace reads bvh, power and uniform)"),
                ));
            }
        }
    } else {
        LightSelection::Tree
    };
    if p.bool("regularize", false)? {
        return Err(p.err(p.loc_of("regularize"), "\"regularize\" is not read yet"));
    }
    if kind == "bdpt" {
        for v in ["visualizestrategies", "visualizeweights"] {
            if p.bool(v, false)? {
                return Err(p.err(p.loc_of(v), format!("\"{v}\" is not read")));
            }
        }
    }
    p.check_unused(&format!("integrator \"{kind}\""))?;
    Ok((k, depth, selection))
}

/// What [`film`] reads: the spectral bins, the sensor, the clamp (cd/m²) and where it was set.
type FilmRead = (u32, Option<CameraSensorDesc>, Option<(f64, Loc)>);

/// A `Film`'s kind and the settings of its pixel sensor: `rgb`; `gbuffer` (its image; the
/// extra channels are not written, a note says so); `spectral` (its `nbuckets` over 360–830
/// nm as spectrace's spectral EXR bins). Its pixel sensor (`sensor`, `iso`, `whitebalance`,
/// with the camera's exposure time `exposure_s`) is read by `sensor.rs`; `maxcomponentvalue`,
/// pbrt-v4's firefly clamp of each sample's sensor RGB (for the CIE sensor, its XYZ times
/// t·ISO/100 on pbrt-v4's scale, Y = ∫ȳL dλ), becomes the clamp of X, Y, Z in cd/m² at
/// value·K_m/(t·ISO/100) (refused with a camera's curves); `savefp16` is a precision choice,
/// ignored. Returns the spectral bins (0: none), the sensor (None: pbrt-v4's pass-through) and
/// the clamp with its location.
fn film(
    p: &Params,
    (kind, loc): (&str, Loc),
    exposure_s: f64,
    file: &std::path::Path,
    notes: &mut Vec<String>,
) -> R<FilmRead> {
    let bins = match kind {
        "rgb" => 0,
        "gbuffer" => {
            let _ = p.string("coordinatesystem")?;
            notes.push(format!(
                "{}:{loc}: the gbuffer film's extra channels (albedo, position, normals, variance) are not written; the image is the rgb film's",
                file.display()
            ));
            0
        }
        "spectral" => {
            let n = p.int("nbuckets", 16)?;
            let (lo, hi) = (p.float("lambdamin", 360.0)?, p.float("lambdamax", 830.0)?);
            if lo != 360.0 || hi != 830.0 {
                return Err(p.err(
                    loc,
                    "a spectral film's range must be 360–830 nm (spectrace's spectral EXR bins span it)",
                ));
            }
            if !(1..=1024).contains(&n) {
                return Err(p.err(p.loc_of("nbuckets"), "\"nbuckets\" must be from 1 to 1024"));
            }
            n as u32
        }
        other => {
            return Err(p.err(
                loc,
                format!("the film \"{other}\" is not read yet (spectrace reads rgb, gbuffer and spectral)"),
            ));
        }
    };
    let _ = p.bool("savefp16", true)?;
    let sensor = super::sensor::sensor(p, exposure_s)?;
    let max = p.float("maxcomponentvalue", f64::INFINITY)?;
    let clamp = if max.is_infinite() && max > 0.0 {
        None
    } else {
        let at = p.loc_of("maxcomponentvalue");
        if !(max > 0.0) {
            return Err(p.err(at, "\"maxcomponentvalue\" must be positive"));
        }
        let ratio = match &sensor {
            Some(s) if s.curves.is_some() => {
                return Err(p.err(
                    at,
                    "\"maxcomponentvalue\" with a camera's curves is not read yet (spectrace clamps a sample's XYZ, the cie1931 sensor's RGB)",
                ));
            }
            Some(s) => s.iso * s.shutter.get::<crate::units::time::second>() / 100.0,
            None => 1.0,
        };
        notes.push(format!(
            "{}:{at}: \"maxcomponentvalue\" {max}: each camera sample is clamped as pbrt-v4 clamps it (a biased estimate, reproducing pbrt-v4's image)",
            file.display()
        ));
        Some((max * crate::colour::cie::K_M / ratio, at))
    };
    if let Some(s) = &sensor {
        notes.push(format!(
            "{}:{loc}: the film's sensor ({}): pbrt-v4's image is in the EXR's sensor.wb.R, G, B channels; X, Y, Z and R, G, B stay the physical radiance",
            file.display(),
            s.name
        ));
    }
    Ok((bins, sensor, clamp))
}

/// pbrt-v4's `cropwindow` (fractions of the image, [x0 x1 y0 y1], rounded up to pixels as
/// pbrt-v4 rounds them) or `pixelbounds` ([x0 x1 y0 y1] pixels; the crop window wins, as in
/// pbrt-v4) on a `w` × `h` film: the window's top-left pixel and size, or None for the whole.
#[allow(clippy::type_complexity)]
fn crop(p: &Params, w: i64, h: i64) -> R<Option<([u32; 2], [u32; 2])>> {
    let four = |name: &str, ty: &str| -> R<Option<Vec<f64>>> {
        match p.nums(name, &[ty])? {
            None => Ok(None),
            Some(v) if v.len() == 4 => Ok(Some(v.to_vec())),
            Some(v) => Err(p.err(
                p.loc_of(name),
                format!("\"{name}\" takes 4 values, not {}", v.len()),
            )),
        }
    };
    let (cw, pb) = (
        four("cropwindow", "float")?,
        four("pixelbounds", "integer")?,
    );
    let bounds = if let Some(c) = cw {
        let (x0, x1) = (
            c[0].min(c[1]).clamp(0.0, 1.0),
            c[0].max(c[1]).clamp(0.0, 1.0),
        );
        let (y0, y1) = (
            c[2].min(c[3]).clamp(0.0, 1.0),
            c[2].max(c[3]).clamp(0.0, 1.0),
        );
        let (w, h) = (w as f64, h as f64);
        [
            (w * x0).ceil(),
            (w * x1).ceil(),
            (h * y0).ceil(),
            (h * y1).ceil(),
        ]
    } else if let Some(b) = pb {
        // pbrt-v4 clamps the bounds to the image
        [
            b[0].clamp(0.0, w as f64),
            b[1].clamp(0.0, w as f64),
            b[2].clamp(0.0, h as f64),
            b[3].clamp(0.0, h as f64),
        ]
    } else {
        return Ok(None);
    };
    let at = if p.get("cropwindow").is_some() {
        "cropwindow"
    } else {
        "pixelbounds"
    };
    if !(bounds[1] > bounds[0] && bounds[3] > bounds[2]) {
        return Err(p.err(
            p.loc_of(at),
            format!("\"{at}\" leaves no pixel of the image"),
        ));
    }
    let [x0, x1, y0, y1] = bounds.map(|v| v as u32);
    Ok(Some(([x0, y0], [x1 - x0, y1 - y0])))
}

/// The scene: camera, film, sampler and integrator from their directives, and what the world
/// block made.
pub(super) fn finish(mut r: Reader) -> Result<SceneDesc, LoadError> {
    let file = r.root.clone();
    let Some((ctm, cam, kind, cam_loc)) = &r.camera else {
        return Err(LoadError::new(
            &file,
            Loc { line: 1, col: 1 },
            "",
            "the scene has no Camera",
        ));
    };
    let exposure_s = super::sensor::exposure_time(cam, *cam_loc)?;
    let (width, height, film_loc, spectral_bins, diagonal_mm, sensor, clamp, crop) = match &r.film {
        Some((p, kind, loc)) => {
            let (bins, sensor, clamp) = film(p, (kind, *loc), exposure_s, &file, &mut r.notes)?;
            let w = p.int("xresolution", 1280)?;
            let h = p.int("yresolution", 720)?;
            let crop = crop(p, w, h)?;
            let _ = p.string("filename")?;
            // the film's size in mm, which the realistic camera reads
            let diagonal = p.float("diagonal", 35.0)?;
            p.check_unused(&format!("film \"{kind}\""))?;
            (w, h, *loc, bins, diagonal, sensor, clamp, crop)
        }
        None => (
            1280,
            720,
            Loc { line: 0, col: 0 },
            0,
            35.0,
            None,
            None,
            None,
        ),
    };
    if !(1..=32768).contains(&width) || !(1..=32768).contains(&height) {
        return Err(LoadError::new(
            &file,
            film_loc,
            "",
            format!("a film of {width} × {height} pixels"),
        ));
    }
    let spp = match &r.sampler {
        Some((p, kind, _)) => sampler_spp(p, kind)?,
        None => 16,
    };
    let (integrator, max_depth, light_selection) = match &r.integrator {
        Some((p, kind, loc)) => {
            if !r.media.is_empty() && kind != "volpath" {
                return Err(p.err(
                    *loc,
                    format!("the scene has media, which pbrt-v4's \"{kind}\" does not render (use volpath)"),
                ));
            }
            integrator(p, kind, *loc)?
        }
        // pbrt-v4's default, `volpath`: `path` where there are no media
        None => (IntegratorKind::Path, 5, LightSelection::Tree),
    };
    if let (Some((_, at)), IntegratorKind::Light | IntegratorKind::Bdpt) = (clamp, integrator) {
        return Err(LoadError::new(
            &file,
            at,
            "",
            "\"maxcomponentvalue\" with a bdpt or lightpath integrator is not read yet (spectrace clamps camera samples only)",
        ));
    }
    let size = FilmSize {
        width,
        height,
        diagonal_mm,
    };
    let mut camera = camera(ctm, cam, kind, *cam_loc, size, &|name| {
        r.resolve(&r.root, name)
    })?;
    camera.sensor = sensor;
    cam.check_unused(&format!("camera \"{kind}\""))?;
    let nm = |x: f64| Length::new::<crate::units::length::nanometer>(x);
    Ok(SceneDesc {
        path: file.clone(),
        wavelength_range: [nm(360.0), nm(830.0)],
        camera,
        film: FilmDesc {
            width: crop.map_or(width as u32, |c| c.1[0]),
            height: crop.map_or(height as u32, |c| c.1[1]),
            spp: spp.clamp(1, 1 << 24) as u32,
            filter: pixel_filter(&r.filter)?,
            spectral_bins,
            exposure_ev: None,
            max_component: clamp.map(|c| c.0),
            crop: crop.map(|(at, _)| CropDesc {
                at,
                full: [width as u32, height as u32],
                data_window: true,
            }),
            loc: film_loc,
        },
        integrator: IntegratorDesc {
            kind: integrator,
            max_depth: max_depth.clamp(0, 1 << 16) as u32,
            rr_depth: 1,
            light_selection,
            moment: false,
            polarised: false,
            split_dispersion: true,
            aovs: Vec::new(),
            // pbrt-v4's integrators skip `interface` surfaces without a bounce
            skip_null: true,
        },
        materials: r.materials,
        shapes: r.shapes,
        groups: r.groups,
        instances: r.instances,
        lights: r.lights,
        media: r.media,
        camera_medium: r.camera_medium,
        sensors: Vec::new(),
        notes: r.notes,
    })
}
