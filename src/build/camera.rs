//! The scene's pinhole, thin-lens, orthographic or spherical camera made render-ready, and every
//! camera's placement (the realistic camera's lens is built in `lens.rs`).

use glam::Vec3;

use super::v3;
use crate::geometry::Transform;
use crate::geometry::camera::{Camera, FovAxis as CamAxis, Spherical};
use crate::loader::desc::{CameraKind, FovAxis, Projection, SceneDesc};
use crate::units::plain;

/// The camera's placement: from its eye toward its target with its up, camera-space x
/// reversed first when the camera is mirrored.
pub(super) fn camera_to_world(c: &crate::loader::desc::CameraDesc) -> Result<Transform, String> {
    let up = Vec3::new(c.up[0] as f32, c.up[1] as f32, c.up[2] as f32);
    let look = Transform::look_at(v3(&c.eye), v3(&c.target), up).map_err(|e| e.to_string())?;
    let flip = Transform::scale(Vec3::new(if c.mirror { -1.0 } else { 1.0 }, 1.0, 1.0));
    Ok(flip.map_err(|e| e.to_string())?.then(&look))
}

pub(super) fn camera(desc: &SceneDesc) -> Result<Camera, String> {
    let c = &desc.camera;
    let to_world = camera_to_world(c)?;
    // a crop window's camera frames the full image
    let (w, h) = desc
        .film
        .crop
        .map_or((desc.film.width, desc.film.height), |c| {
            (c.full[0], c.full[1])
        });
    let axis = |a: FovAxis| match a {
        FovAxis::X => CamAxis::X,
        FovAxis::Y => CamAxis::Y,
        FovAxis::Larger => CamAxis::Larger,
        FovAxis::Smaller => CamAxis::Smaller,
    };
    // Horizontal field of view of a projection, radians.
    let horizontal = |fov: f32, a: FovAxis| -> f32 {
        let aspect = w as f32 / h as f32;
        let along_x = match a {
            FovAxis::X => true,
            FovAxis::Y => false,
            FovAxis::Larger => w >= h,
            FovAxis::Smaller => w < h,
        };
        if along_x {
            fov
        } else {
            2.0 * ((fov / 2.0).tan() * aspect).atan()
        }
    };
    let r = match &c.kind {
        CameraKind::Perspective {
            projection: Projection::Fov { fov, axis: a },
        } => Camera::perspective(to_world, plain::radians(*fov), axis(*a), w, h),
        CameraKind::Perspective {
            projection:
                Projection::Focal {
                    focal_length,
                    sensor_width,
                },
        } => Camera::perspective_focal(
            to_world,
            plain::metres(*focal_length),
            plain::metres(*sensor_width),
            w,
            h,
        ),
        CameraKind::ThinLens {
            projection,
            f_number,
            focus_distance,
        } => {
            let (hfov, focal) = match projection {
                Projection::Fov { fov, axis: a } => {
                    let hf = horizontal(plain::radians(*fov), *a);
                    (hf, 0.036 / (2.0 * (hf / 2.0).tan()))
                }
                Projection::Focal {
                    focal_length,
                    sensor_width,
                } => {
                    let f = plain::metres(*focal_length);
                    (2.0 * (plain::metres(*sensor_width) / (2.0 * f)).atan(), f)
                }
            };
            Camera::thin_lens(
                to_world,
                hfov,
                CamAxis::X,
                *f_number as f32,
                focal,
                plain::metres(*focus_distance),
                w,
                h,
            )
        }
        CameraKind::Orthographic { view_width } => {
            Camera::orthographic(to_world, plain::metres(*view_width), w, h)
        }
        CameraKind::Spherical { equal_area } => {
            Spherical::new(to_world, *equal_area, w, h).map(Camera::Spherical)
        }
        // built in `build`, where its lens file's errors are located
        CameraKind::Realistic { .. } => return Err("a realistic camera needs its lens file".into()),
    };
    let r = r.map_err(|e| e.to_string())?;
    match desc.film.crop {
        Some(c) => r.with_window((c.at[0], c.at[1]), (desc.film.width, desc.film.height)),
        None => Ok(r),
    }
}
