//! Cameras: pinhole perspective, thin lens and orthographic.
//!
//! Camera space follows Mitsuba (and is right-handed): the camera looks along **+z**, **+y** is
//! up and **+x** points to the camera's *left*; see [`Transform::look_at`]. Raster space is in
//! pixels with (0, 0) at the top-left corner of the image, x to the right and y down, so raster
//! +x is camera −x and raster +y is camera −y. Pixels are square.
//!
//! `camera_to_world` should be rigid (rotation and translation). Any scale in it also scales the
//! image plane and the lens in world space; directions are renormalised.

use super::error::{GeometryError, check_finite, check_positive};
use super::ray::Ray;
use super::transform::Transform;
use crate::sampling::concentric_disk;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Which image axis a field of view spans.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    /// Horizontal.
    X,
    /// Vertical.
    Y,
    /// The longer side of the image.
    Larger,
    /// The shorter side of the image.
    Smaller,
}

/// Raster → camera-plane mapping shared by all cameras.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    /// Half extents of the image on the camera plane: at z = 1 for perspective cameras
    /// (tangents of the half angles), at z = 0 in metres for the orthographic camera.
    half: Vec2,
}

impl Film {
    fn new(width: u32, height: u32) -> Result<Film, GeometryError> {
        let pixels = u64::from(width) * u64::from(height);
        if width == 0 || height == 0 || width > 32768 || height > 32768 || pixels > 1 << 28 {
            return Err(GeometryError::Resolution { width, height });
        }
        Ok(Film {
            width,
            height,
            half: Vec2::ONE,
        })
    }

    /// Sets the half extents from a full field of view on `axis`.
    fn with_fov(mut self, fov_rad: f32, axis: FovAxis) -> Result<Film, GeometryError> {
        check_finite("field of view", fov_rad)?;
        if !(fov_rad > 0.0 && fov_rad < PI) {
            return Err(GeometryError::OutOfRange {
                what: "field of view (rad)",
                value: fov_rad,
                allowed: "(0, π)",
            });
        }
        let half = (fov_rad / 2.0).tan();
        let aspect = self.width as f32 / self.height as f32;
        let horizontal = match axis {
            FovAxis::X => true,
            FovAxis::Y => false,
            FovAxis::Larger => self.width >= self.height,
            FovAxis::Smaller => self.width <= self.height,
        };
        self.half = if horizontal {
            Vec2::new(half, half / aspect)
        } else {
            Vec2::new(half * aspect, half)
        };
        Ok(self)
    }

    /// Camera-plane (x, y) of a raster position.
    #[inline]
    fn plane(&self, raster: Vec2) -> Vec2 {
        let ndc = raster / Vec2::new(self.width as f32, self.height as f32) * 2.0 - Vec2::ONE;
        -ndc * self.half
    }
}

/// How a world point connects to a pinhole camera, for light tracing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraConnection {
    /// Raster position where the point appears, pixels.
    pub raster: Vec2,
    /// Unit direction from the point toward the pinhole (world).
    pub wi: Vec3,
    /// Distance to the pinhole, m.
    pub distance: f32,
    /// Pixel measurement weight: N_pixels / (A · cos³θ · d²), with A the image area on the
    /// plane z = 1 and θ the angle to the view axis. A particle of spectral power β arriving
    /// with BSDF value f and cosine |cos θ_x| adds β·f·|cos θ_x|·weight / N_paths to the pixel's
    /// radiance (pbrt-v4 §5.1.4, W_e = 1/(A cos⁴θ) with the solid-angle pdf d²/cos θ).
    pub weight: f32,
}

/// Pinhole perspective camera.
#[derive(Clone, Debug, PartialEq)]
pub struct Perspective {
    to_world: Transform,
    film: Film,
}

/// Thin-lens camera: a perspective camera with a lens of radius `lens_radius` (m) focused at
/// the plane z = `focus_distance` (m) in camera space.
#[derive(Clone, Debug, PartialEq)]
pub struct ThinLens {
    to_world: Transform,
    film: Film,
    lens_radius: f32,
    focus_distance: f32,
}

/// Orthographic camera: parallel rays along +z from the plane z = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Orthographic {
    to_world: Transform,
    film: Film,
}

/// The closed set of cameras.
#[derive(Clone, Debug, PartialEq)]
pub enum Camera {
    Perspective(Perspective),
    ThinLens(ThinLens),
    Orthographic(Orthographic),
}

impl Camera {
    /// A pinhole camera with full field of view `fov_rad` ∈ (0, π) on `fov_axis`. Errors for an
    /// invalid field of view or resolution (see [`GeometryError::Resolution`]).
    pub fn perspective(
        camera_to_world: Transform,
        fov_rad: f32,
        fov_axis: FovAxis,
        width: u32,
        height: u32,
    ) -> Result<Camera, GeometryError> {
        let film = Film::new(width, height)?.with_fov(fov_rad, fov_axis)?;
        Ok(Camera::Perspective(Perspective {
            to_world: camera_to_world,
            film,
        }))
    }

    /// A pinhole camera from a lens focal length and sensor width (both m; a full-frame sensor
    /// is 0.036 m wide). Horizontal field of view = 2·atan(sensor_width / (2·focal_length)).
    pub fn perspective_focal(
        camera_to_world: Transform,
        focal_length_m: f32,
        sensor_width_m: f32,
        width: u32,
        height: u32,
    ) -> Result<Camera, GeometryError> {
        check_positive("focal length (m)", focal_length_m)?;
        check_positive("sensor width (m)", sensor_width_m)?;
        let fov = 2.0 * (sensor_width_m / (2.0 * focal_length_m)).atan();
        Camera::perspective(camera_to_world, fov, FovAxis::X, width, height)
    }

    /// A thin-lens camera: field of view as for [`Camera::perspective`], aperture radius
    /// `focal_length / (2·f_number)` (m), sharp at `focus_distance_m` along the view axis.
    /// Errors for f-number, focal length or focus distance ≤ 0 or not finite.
    #[allow(clippy::too_many_arguments)]
    pub fn thin_lens(
        camera_to_world: Transform,
        fov_rad: f32,
        fov_axis: FovAxis,
        f_number: f32,
        focal_length_m: f32,
        focus_distance_m: f32,
        width: u32,
        height: u32,
    ) -> Result<Camera, GeometryError> {
        let film = Film::new(width, height)?.with_fov(fov_rad, fov_axis)?;
        check_positive("f-number", f_number)?;
        check_positive("focal length (m)", focal_length_m)?;
        check_positive("focus distance (m)", focus_distance_m)?;
        Ok(Camera::ThinLens(ThinLens {
            to_world: camera_to_world,
            film,
            lens_radius: focal_length_m / (2.0 * f_number),
            focus_distance: focus_distance_m,
        }))
    }

    /// An orthographic camera whose view is `view_width_m` wide (m); the height follows the
    /// image aspect ratio.
    pub fn orthographic(
        camera_to_world: Transform,
        view_width_m: f32,
        width: u32,
        height: u32,
    ) -> Result<Camera, GeometryError> {
        check_positive("orthographic view width (m)", view_width_m)?;
        let mut film = Film::new(width, height)?;
        let half_w = view_width_m / 2.0;
        film.half = Vec2::new(half_w, half_w * height as f32 / width as f32);
        Ok(Camera::Orthographic(Orthographic {
            to_world: camera_to_world,
            film,
        }))
    }

    /// The world-space ray (unit direction, `t_max` = ∞) through raster position `raster`
    /// (pixels, (0, 0) = top-left corner of the image, x right, y down; pixel (i, j) covers
    /// [i, i+1) × [j, j+1)) from lens position `lens` ∈ [0, 1)² (ignored by the pinhole and
    /// orthographic cameras).
    #[inline]
    pub fn generate_ray(&self, raster: Vec2, lens: Vec2) -> Ray {
        match self {
            Camera::Perspective(c) => {
                let xy = c.film.plane(raster);
                Ray::new(
                    c.to_world.point(Vec3::ZERO),
                    c.to_world.vector(xy.extend(1.0)),
                )
            }
            Camera::ThinLens(c) => {
                let focus = c.film.plane(raster).extend(1.0) * c.focus_distance;
                let on_lens = (concentric_disk(lens) * c.lens_radius).extend(0.0);
                Ray::new(
                    c.to_world.point(on_lens),
                    c.to_world.vector(focus - on_lens),
                )
            }
            Camera::Orthographic(c) => {
                let xy = c.film.plane(raster);
                Ray::new(c.to_world.point(xy.extend(0.0)), c.to_world.vector(Vec3::Z))
            }
        }
    }

    /// Where the world point `p` appears on a pinhole perspective camera, or None if it is
    /// behind the camera, more than `margin` pixels outside the image (a reconstruction filter
    /// of that radius still carries such a point into the image), or the camera is not a
    /// pinhole.
    pub fn connect(&self, p: Vec3, margin: f32) -> Option<CameraConnection> {
        let Camera::Perspective(c) = self else {
            return None;
        };
        let pc = c.to_world.inverse().point(p);
        if !(pc.z > 0.0) {
            return None;
        }
        let d = pc.length();
        let cos = pc.z / d;
        let xy = pc.truncate() / pc.z;
        let ndc = -xy / c.film.half;
        let size = Vec2::new(c.film.width as f32, c.film.height as f32);
        let raster = (ndc + Vec2::ONE) * 0.5 * size;
        if !(raster.x >= -margin
            && raster.y >= -margin
            && raster.x < size.x + margin
            && raster.y < size.y + margin)
        {
            return None;
        }
        let area = 4.0 * c.film.half.x * c.film.half.y;
        let weight = size.x * size.y / (area * cos * cos * cos * d * d);
        let eye = c.to_world.point(Vec3::ZERO);
        Some(CameraConnection {
            raster,
            wi: (eye - p) / d,
            distance: d,
            weight,
        })
    }

    fn parts(&self) -> (&Transform, &Film) {
        match self {
            Camera::Perspective(c) => (&c.to_world, &c.film),
            Camera::ThinLens(c) => (&c.to_world, &c.film),
            Camera::Orthographic(c) => (&c.to_world, &c.film),
        }
    }

    /// World position of the pinhole / lens centre / centre of the orthographic view plane, m.
    pub fn position(&self) -> Vec3 {
        self.parts().0.point(Vec3::ZERO)
    }

    /// Unit world-space view direction (camera +z).
    pub fn forward(&self) -> Vec3 {
        self.parts().0.vector(Vec3::Z).normalize_or_zero()
    }

    /// Image size in pixels (width, height).
    pub fn resolution(&self) -> (u32, u32) {
        let film = self.parts().1;
        (film.width, film.height)
    }
}
