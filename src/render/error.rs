//! Why a render does not start: [`RenderError`], and the check that the chosen integrator
//! renders everything the scene holds.

use crate::integrator::IntegratorKind;
use crate::scene::Scene;

use super::RenderOptions;

/// Why a render could not start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("cannot start {threads} render threads: {message}")]
    Threads { threads: usize, message: String },
    #[error(
        "the `{0}` integrator connects paths to the camera's lens, which an orthographic camera \
         does not have; use a perspective or thin-lens camera"
    )]
    Camera(&'static str),
    #[error(
        "the `{0}` integrator {1}, which the realistic (lens-system) camera does not support yet \
         (nor does pbrt-v4's); use path, whitted or direct"
    )]
    LensCamera(&'static str, &'static str),
    #[error(
        "the `{0}` integrator connects paths to the camera, whose importance the spherical \
         camera does not model (nor does pbrt-v4's); use path, whitted or direct"
    )]
    SphericalCamera(&'static str),
    #[error("cannot resume: {0}")]
    Resume(String),
    #[error("--target-error needs passes of camera samples; the light integrator has none")]
    TargetErrorLight,
    #[error(
        "the scene has participating media, which the `{0}` integrator does not render; use path, \
         light or bdpt"
    )]
    Media(&'static str),
    #[error(
        "the scene renders polarised (it holds a polariser or retarder, or asks for Stokes \
         vectors), which the path, light and bdpt integrators do, in scenes without media; `{0}` \
         was asked{1}"
    )]
    Polarised(&'static str, &'static str),
}

/// Refuses an integrator that would render the scene as something else: light tracing, BDPT or
/// polarised rendering through a realistic camera (its importance and its lens's Mueller
/// matrices are not modelled), one without media in
/// a scene with media (it would drop them), one other than `path`, `light` or `bdpt` in a
/// polarised scene (it carries no Stokes vectors), or any in a polarised scene with media (not
/// yet rendered).
pub(super) fn check_integrator(scene: &Scene, opts: &RenderOptions) -> Result<(), RenderError> {
    if matches!(scene.camera, crate::geometry::Camera::Realistic(_)) {
        let why = match opts.integrator {
            IntegratorKind::Light | IntegratorKind::Bdpt => Some("connects paths to the camera"),
            _ if scene.integrator.polarised => {
                Some("renders this scene polarised, through a lens that carries no Stokes vectors")
            }
            _ => None,
        };
        if let Some(why) = why {
            return Err(RenderError::LensCamera(opts.integrator.name(), why));
        }
    }
    if matches!(scene.camera, crate::geometry::Camera::Spherical(_))
        && matches!(
            opts.integrator,
            IntegratorKind::Light | IntegratorKind::Bdpt
        )
    {
        return Err(RenderError::SphericalCamera(opts.integrator.name()));
    }
    if !scene.media.is_empty()
        && !matches!(
            opts.integrator,
            IntegratorKind::Path | IntegratorKind::Light | IntegratorKind::Bdpt
        )
    {
        return Err(RenderError::Media(opts.integrator.name()));
    }
    let carries_stokes = matches!(
        opts.integrator,
        IntegratorKind::Path | IntegratorKind::Light | IntegratorKind::Bdpt
    );
    if scene.integrator.polarised && (!carries_stokes || !scene.media.is_empty()) {
        let media = if scene.media.is_empty() {
            ""
        } else {
            " in a scene with media"
        };
        return Err(RenderError::Polarised(opts.integrator.name(), media));
    }
    Ok(())
}
