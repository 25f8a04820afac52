//! A lens file's description ([`crate::loader::lens::LensDesc`]) → a checked
//! [`LensSystem`], with errors at the file and line of the surface at fault.

use crate::loader::LoadError;
use crate::loader::desc::LensFocus;
use crate::loader::lens::LensDesc;
use crate::units::Length;
use crate::optics::{LensError, LensSystem, Surface};
use crate::units::plain;

/// Builds the lens system of `desc` (mm, as lens files are written).
pub fn lens_system(desc: &LensDesc) -> Result<LensSystem, LoadError> {
    let mm = |l| plain::metres(l) as f64 * 1e3;
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
            if what.contains("thickness") || what.contains("focus") {
                "thickness"
            } else if what.contains("aperture") || what.contains("stop") {
                "aperture"
            } else {
                "radius"
            },
        ),
        LensError::Crossing { surface, .. } => (*surface, "thickness"),
        LensError::FilmBehindNothing { .. } => (desc.surfaces.len(), "thickness"),
        LensError::Opaque { .. } => (1, ""),
    };
    let loc = desc
        .surfaces
        .get(surface.saturating_sub(1))
        .map(|s| s.loc)
        .unwrap_or_default();
    LoadError::new(&desc.path, loc, field, e.to_string())
}

/// The lens system of `desc`, stopped down to `aperture` and focused as `focus` says.
pub fn focused_lens(
    desc: &LensDesc,
    aperture: Option<Length>,
    focus: &LensFocus,
) -> Result<LensSystem, LoadError> {
    let mm = |l| plain::metres(l) as f64 * 1e3;
    let mut sys = lens_system(desc)?;
    if let Some(a) = aperture {
        sys = sys.with_stop_diameter(mm(a)).map_err(|e| located(desc, &e))?;
    }
    let d_line = crate::spectrum::ior::FRAUNHOFER_D_NM as f64;
    match focus {
        LensFocus::AsWritten => {}
        LensFocus::FilmDistance(d) => {
            sys = sys.with_film_distance(mm(*d)).map_err(|e| located(desc, &e))?;
        }
        LensFocus::Distance(d) => {
            let film = sys
                .focus_film_distance(mm(*d), d_line)
                .map_err(|e| located(desc, &e))?;
            sys = sys.with_film_distance(film).map_err(|e| located(desc, &e))?;
        }
    }
    Ok(sys)
}
