//! pbrt-v4's cameras (`src/pbrt/cameras.cpp`): `perspective` (with its thin lens),
//! `orthographic`, `realistic` and `spherical`, each reading its own parameters with pbrt-v4's names and
//! defaults. Lengths are read as metres (pbrt's files have no unit).

use std::path::Path;

use glam::{DMat4, DVec3};

use super::params::{Params, R};
use super::shapes::len;
use crate::loader::Loc;
use crate::loader::desc::*;
use crate::units::{Angle, Length, angle::degree};

/// A `perspective` camera: pbrt-v4's `fov` spans the image's shorter axis; its camera space
/// has +x to the image's right, so the image is spectrace's mirrored left to right.
/// `film` is what the camera needs of the film: its resolution and `diagonal` (mm), and
/// `lens_file` resolves a realistic camera's `lensfile`.
pub(super) fn camera(
    ctm: &DMat4,
    p: &Params,
    kind: &str,
    loc: Loc,
    film: FilmSize,
    lens_file: &dyn Fn(&str) -> std::path::PathBuf,
) -> R<CameraDesc> {
    let (w, h) = (film.width, film.height);
    for unread in ["screenwindow", "frameaspectratio"] {
        if p.get(unread).is_some() {
            return Err(p.err(
                p.loc_of(unread),
                format!("a camera's \"{unread}\" is not read yet"),
            ));
        }
    }
    let world_from_camera = ctm.inverse();
    let kind = match kind {
        "perspective" => {
            let fov = p.float("fov", 90.0)?;
            if !(fov > 0.0 && fov < 180.0) {
                return Err(p.err(
                    p.loc_of("fov"),
                    format!("fov must lie in (0, 180) degrees, not {fov}"),
                ));
            }
            let projection = Projection::Fov {
                fov: Angle::new::<degree>(fov),
                axis: FovAxis::Smaller,
            };
            // pbrt-v4's thin lens: `lensradius` and `focaldistance` (10⁶) in camera space
            let unit = unit_of(&world_from_camera);
            let radius = p.float("lensradius", 0.0)? * unit;
            let focus = p.float("focaldistance", 1e6)? * unit;
            if radius > 0.0 {
                if !(focus > 0.0) {
                    return Err(p.err(
                        p.loc_of("focaldistance"),
                        "\"focaldistance\" must be positive",
                    ));
                }
                // spectrace's thin lens takes an f-number of the focal length that gives the
                // horizontal field of view on a 36 mm wide film (`build`): N = f / 2r
                let half = (fov.to_radians() / 2.0).tan();
                let half_x = if w < h {
                    half
                } else {
                    half * w as f64 / h as f64
                };
                let focal = 0.036 / (2.0 * half_x);
                CameraKind::ThinLens {
                    projection,
                    f_number: focal / (2.0 * radius),
                    focus_distance: len(focus),
                }
            } else {
                CameraKind::Perspective { projection }
            }
        }
        // pbrt-v4's default screen window spans [−1, 1] of camera space across the shorter
        // image axis
        "orthographic" => {
            let aspect = w as f64 / h as f64;
            let unit = unit_of(&world_from_camera);
            CameraKind::Orthographic {
                view_width: len(2.0 * aspect.max(1.0) * unit),
            }
        }
        // pbrt-v4 reads a spherical camera's lens and leaves it unused
        "spherical" => {
            p.float("lensradius", 0.0)?;
            p.float("focaldistance", 1e30)?;
            let equal_area = match p.string("mapping")?.as_deref().unwrap_or("equalarea") {
                "equalarea" => true,
                "equirectangular" => false,
                other => {
                    return Err(p.err(
                        p.loc_of("mapping"),
                        format!("a spherical camera's mapping is \"equalarea\" or \"equirectangular\", not \"{other}\""),
                    ));
                }
            };
            CameraKind::Spherical { equal_area }
        }
        "realistic" => realistic(
            p,
            loc,
            film.diagonal_mm,
            unit_of(&world_from_camera),
            lens_file,
        )?,
        other => {
            return Err(p.err(
                loc,
                format!("the camera \"{other}\" is not read yet (spectrace reads perspective, orthographic, realistic and spherical)"),
            ));
        }
    };
    let eye = world_from_camera.transform_point3(DVec3::ZERO);
    let target = world_from_camera.transform_point3(DVec3::Z);
    let up = world_from_camera.transform_vector3(DVec3::Y);
    Ok(CameraDesc {
        kind,
        eye: [len(eye.x), len(eye.y), len(eye.z)],
        target: [len(target.x), len(target.y), len(target.z)],
        up: up.to_array(),
        // pbrt-v4's camera space is left-handed (x right, y up, z ahead): the image is the
        // mirror image of spectrace's, unless the camera transform mirrors it back (the
        // `Scale -1 1 1` exporters write)
        mirror: world_from_camera.determinant() > 0.0,
        sensor: None,
        loc,
    })
}

/// The film as the camera sees it: pixels and pbrt-v4's `diagonal`, mm (35 by default).
#[derive(Clone, Copy, Debug)]
pub(super) struct FilmSize {
    pub width: i64,
    pub height: i64,
    pub diagonal_mm: f64,
}

/// The length of camera space's unit x in world units.
fn unit_of(world_from_camera: &DMat4) -> f64 {
    world_from_camera.transform_vector3(DVec3::X).length()
}

/// A `realistic` camera (pbrt-v4 §5.3; `RealisticCamera::Create`): `lensfile` (pbrt-v4's
/// format, mm), `aperturediameter` (mm, 1 by default: pbrt-v4 stops every lens down to it,
/// or keeps the file's stop where that is narrower, with a warning), `focusdistance` (from
/// the film, camera-space units, 10 by default). The pixel is pbrt-v4's: the film irradiance
/// per unit radiance. A shaped `aperture` (gaussian, square, pentagon, star, an image) is
/// not read yet.
fn realistic(
    p: &Params,
    loc: Loc,
    diagonal_mm: f64,
    unit: f64,
    lens_file: &dyn Fn(&str) -> std::path::PathBuf,
) -> R<CameraKind> {
    if p.get("aperture").is_some() {
        return Err(p.err(
            p.loc_of("aperture"),
            "a realistic camera's shaped \"aperture\" is not read yet (the stop is round)",
        ));
    }
    let name = p
        .string("lensfile")?
        .ok_or_else(|| p.err(loc, "a realistic camera needs a \"string lensfile\""))?;
    let path = lens_file(&name);
    let mut lens = crate::loader::lens::read(Path::new(&path))?;
    // pbrt-v4 always sets the film distance from `focusdistance`, so its lens files may give
    // 0 for the last thickness: a placeholder until the focus replaces it
    if let Some(last) = lens.surfaces.last_mut()
        && last.thickness.get::<crate::units::length::millimeter>() == 0.0
    {
        last.thickness = Length::new::<crate::units::length::millimeter>(1.0);
    }
    let positive = |name: &str, default: f64| -> R<f64> {
        let v = p.float(name, default)?;
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(p.err(
                p.loc_of(name),
                format!("\"{name}\" must be positive, not {v}"),
            ))
        }
    };
    let aperture = positive("aperturediameter", 1.0)?;
    let focus = positive("focusdistance", 10.0)? * unit;
    // pbrt-v4 keeps the file's stop where the requested one is wider
    let stop = lens
        .surfaces
        .iter()
        .find(|s| s.radius.get::<crate::units::length::millimeter>() == 0.0)
        .map(|s| s.aperture.get::<crate::units::length::millimeter>());
    let aperture_diameter = match stop {
        Some(d) if aperture >= d => None,
        _ => Some(Length::new::<crate::units::length::millimeter>(aperture)),
    };
    if !(diagonal_mm > 0.0 && diagonal_mm.is_finite()) {
        return Err(p.err(loc, format!("a film diagonal of {diagonal_mm} mm")));
    }
    Ok(CameraKind::Realistic {
        lens,
        film_diagonal: Length::new::<crate::units::length::millimeter>(diagonal_mm),
        aperture_diameter,
        focus: LensFocus::Distance(len(focus)),
        irradiance_pixels: true,
    })
}
