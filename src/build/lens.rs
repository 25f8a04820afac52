//! A lens file's description ([`crate::loader::lens::LensDesc`]) → a checked
//! [`LensSystem`], with errors at the file and line of the surface at fault.

use crate::loader::LoadError;
use crate::loader::desc::LensFocus;
use crate::loader::lens::LensDesc;
use crate::optics::{LensError, LensSystem, Surface};
use crate::units::Length;
use crate::units::length::millimeter;

/// Builds the lens system of `desc` (mm, as lens files are written).
pub fn lens_system(desc: &LensDesc) -> Result<LensSystem, LoadError> {
    let mm = |l: Length| l.get::<millimeter>();
    let surfaces = desc
        .surfaces
        .iter()
        .map(|s| Surface {
            radius: mm(s.radius),
            thickness: mm(s.thickness),
            medium: s.medium.clone(),
            semi_aperture: mm(s.aperture) / 2.0,
        })
        .collect();
    LensSystem::new(surfaces).map_err(|e| located(desc, &e))
}

/// `e` at the line of the surface it names (1-based), and the field at fault.
pub fn located(desc: &LensDesc, e: &LensError) -> LoadError {
    let (surface, field) = match e {
        LensError::Empty => (1, ""),
        LensError::NoStop { .. } => (desc.surfaces.len(), "radius"),
        LensError::TwoStops { second, .. } => (*second, "radius"),
        LensError::ApertureBeyondSphere { surface, .. } => (*surface, "aperture"),
        LensError::Value { surface, what, .. } => (
            *surface,
            if what.contains("thickness") {
                "thickness"
            } else if what.contains("aperture") || what.contains("stop") {
                "aperture"
            } else {
                "radius"
            },
        ),
        LensError::Crossing { surface, .. } => (*surface, "thickness"),
        LensError::NoImage { .. } => (desc.surfaces.len(), "thickness"),
        LensError::FilmBehindNothing { .. } => (desc.surfaces.len(), "thickness"),
        // the stop is the likeliest culprit
        LensError::Opaque { .. } => (
            desc.surfaces
                .iter()
                .position(|s| s.radius.get::<millimeter>() == 0.0)
                .map_or(1, |i| i + 1),
            "aperture",
        ),
    };
    let loc = desc
        .surfaces
        .get(surface.saturating_sub(1))
        .map(|s| s.loc)
        .unwrap_or_default();
    LoadError::new(&desc.path, loc, field, e.to_string())
}

/// The lens system of `desc`, stopped down to `aperture` and focused as `focus` says. A
/// focus distance with no real image is `Ok(Err(message))`, for the caller to locate in the
/// scene that asks for it.
pub fn focused_lens(
    desc: &LensDesc,
    aperture: Option<Length>,
    focus: &LensFocus,
) -> Result<Result<LensSystem, String>, LoadError> {
    let mm = |l: Length| l.get::<millimeter>();
    let mut sys = lens_system(desc)?;
    if let Some(a) = aperture {
        sys = sys
            .with_stop_diameter(mm(a))
            .map_err(|e| located(desc, &e))?;
    }
    let d_line = crate::spectrum::ior::FRAUNHOFER_D_NM as f64;
    match focus {
        LensFocus::AsWritten => {}
        LensFocus::FilmDistance(d) => {
            sys = sys
                .with_film_distance(mm(*d))
                .map_err(|e| located(desc, &e))?;
        }
        LensFocus::Distance(d) => {
            let film = match sys.focus_film_distance(mm(*d), d_line) {
                Ok(f) => f,
                Err(e) => return Ok(Err(e.to_string())),
            };
            sys = sys
                .with_film_distance(film)
                .map_err(|e| located(desc, &e))?;
        }
    }
    Ok(Ok(sys))
}

/// The scene's realistic camera: its lens built, stopped down and focused, placed by the
/// camera's eye, target and up. A lens's errors name the lens file's line; the rest the
/// scene's `[camera]`.
pub(super) fn realistic_camera(
    desc: &crate::loader::SceneDesc,
) -> Result<crate::geometry::Camera, LoadError> {
    use crate::geometry::{Camera, RealisticError};
    let c = &desc.camera;
    let err = |field: &str, msg: String| LoadError::new(&desc.path, c.loc, field, msg);
    let crate::loader::desc::CameraKind::Realistic {
        lens,
        film_diagonal,
        aperture_diameter,
        focus,
        irradiance_pixels,
    } = &c.kind
    else {
        return Err(err("camera.type", "not a realistic camera".into()));
    };
    let sys = focused_lens(lens, *aperture_diameter, focus)?
        .map_err(|e| err("camera.focus_distance", e))?;
    let to_world = super::camera::camera_to_world(c).map_err(|e| err("camera", e))?;
    let diagonal = crate::units::plain::metres(*film_diagonal);
    // a crop window's camera frames the full image
    let full = desc
        .film
        .crop
        .map_or([desc.film.width, desc.film.height], |c| c.full);
    let cam =
        Camera::realistic(to_world, sys, diagonal, full[0], full[1]).map_err(|e| match e {
            RealisticError::Lens(e) => located(lens, &e),
            RealisticError::Geometry(e) => err("camera", e.to_string()),
        })?;
    let cam = match desc.film.crop {
        Some(w) => cam
            .with_window((w.at[0], w.at[1]), (desc.film.width, desc.film.height))
            .map_err(|e| LoadError::new(&desc.path, desc.film.loc, "film", e))?,
        None => cam,
    };
    Ok(if *irradiance_pixels {
        cam.with_irradiance_pixels()
    } else {
        cam
    })
}
