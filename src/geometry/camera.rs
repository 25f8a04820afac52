//! Cameras: pinhole perspective, thin lens, orthographic, realistic (a traced lens system,
//! `camera/realistic.rs`) and pbrt-v4's spherical (`camera/spherical.rs`).
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

mod realistic;
mod spherical;
mod window;
pub use realistic::{Realistic, RealisticError};
pub use spherical::Spherical;

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
    /// The full image the camera frames, pixels.
    width: u32,
    height: u32,
    /// Half extents of the image on the camera plane: at z = 1 for perspective cameras
    /// (tangents of the half angles), at z = 0 in metres for the orthographic camera.
    half: Vec2,
    /// The part of the full image rendered (pbrt-v4's `cropwindow`, `pixelbounds`): its
    /// top-left pixel and size. Raster positions the camera takes and gives are the window's
    /// (its pixel (0, 0) is the full image's `window_at`).
    window_at: Vec2,
    window: (u32, u32),
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
            window_at: Vec2::ZERO,
            window: (width, height),
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

    /// Raster position (pixels) of the camera-plane point (x, y): the inverse of
    /// [`Film::plane`].
    #[inline]
    fn raster(&self, xy: Vec2) -> Vec2 {
        let ndc = -xy / self.half;
        (ndc + Vec2::ONE) * 0.5 * Vec2::new(self.width as f32, self.height as f32) - self.window_at
    }

    /// Where a ray from the lens point `pl` (camera space, on z = 0) along `v` (camera space,
    /// v.z > 0) appears on the image, pixels: the point where it meets the plane of focus at
    /// z = `focus` (None: a pinhole, the ray's own direction), projected through the lens centre
    /// onto z = 1.
    #[inline]
    fn raster_of_ray(&self, pl: Vec2, v: Vec3, focus: Option<f32>) -> Vec2 {
        self.raster(match focus {
            None => v.truncate() / v.z,
            Some(f) => (pl + v.truncate() * (f / v.z)) / f,
        })
    }

    /// Area of the image on the plane z = 1 (perspective cameras), m² per m² of distance.
    #[inline]
    fn plane_area(&self) -> f32 {
        4.0 * self.half.x * self.half.y
    }

    /// Camera-plane (x, y) of a raster position.
    #[inline]
    fn plane(&self, raster: Vec2) -> Vec2 {
        let full = self.full(raster);
        let ndc = full / Vec2::new(self.width as f32, self.height as f32) * 2.0 - Vec2::ONE;
        -ndc * self.half
    }
}

/// How a world point connects to a perspective camera (pinhole or thin lens), for light tracing
/// and the t = 1 strategies of `bdpt`: the camera's importance sampled from the point
/// (pbrt-v4 §5.4, `SampleWi`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraConnection {
    /// Raster position where the point appears, pixels.
    pub raster: Vec2,
    /// The point on the lens the connection reaches (the pinhole itself for a pinhole), m.
    pub p_lens: Vec3,
    /// Unit direction from the point toward `p_lens` (world).
    pub wi: Vec3,
    /// Distance to `p_lens`, m.
    pub distance: f32,
    /// Pixel measurement weight W_e·cos θ_lens / (p_lens(x)·d²) times the pixel count:
    /// N_pixels / (A · cos³θ · d²), with A the image area on the plane z = 1, θ the angle of
    /// the connection to the view axis and d its length. A particle of spectral power β arriving
    /// with BSDF value f and cosine |cos θ_x| adds β·f·|cos θ_x|·weight / N_paths to the
    /// pixel's radiance (pbrt-v4 §5.1.4 and §5.2.3: W_e = 1/(A·A_lens·cos⁴θ), the lens point
    /// uniform with density 1/A_lens, A_lens = 1 for a pinhole).
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
    Realistic(Box<Realistic>),
    Spherical(Spherical),
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
    #[inline(always)]
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
            // at the d line; where the lens blocks that ray, the ray from the film point through
            // the lens's axial point (for probes and previews, never for rendering)
            Camera::Realistic(c) => c.preview_ray(raster, lens),
            Camera::Spherical(c) => c.ray(raster),
        }
    }

    /// Where the world point `p` appears on a perspective camera, seen through the lens point
    /// chosen by `u_lens` ∈ [0, 1)² (uniform on a thin lens; ignored by a pinhole), or None if
    /// it is behind the lens, more than `margin` pixels outside the image (a reconstruction
    /// filter of that radius still carries such a point into the image), or the camera is
    /// orthographic (a delta in direction, which no point can connect to) or realistic (its
    /// importance is not sampled: the renderer refuses light tracing and BDPT with it).
    pub fn connect(&self, p: Vec3, u_lens: Vec2, margin: f32) -> Option<CameraConnection> {
        let (to_world, film, lens) = match self {
            Camera::Perspective(c) => (&c.to_world, &c.film, None),
            Camera::ThinLens(c) => (
                &c.to_world,
                &c.film,
                Some((concentric_disk(u_lens) * c.lens_radius, c.focus_distance)),
            ),
            Camera::Orthographic(_) | Camera::Realistic(_) | Camera::Spherical(_) => return None,
        };
        let pc = to_world.inverse().point(p);
        let pl = lens.map_or(Vec2::ZERO, |(l, _)| l).extend(0.0);
        let v = pc - pl;
        if !(v.z > 0.0) {
            return None;
        }
        let d = v.length();
        let cos = v.z / d;
        let raster = film.raster_of_ray(pl.truncate(), v, lens.map(|(_, f)| f));
        if !film.contains(raster, margin) {
            return None;
        }
        let pixels = film.width as f32 * film.height as f32;
        let weight = pixels / (film.plane_area() * cos * cos * cos * d * d);
        let p_lens = to_world.point(pl);
        Some(CameraConnection {
            raster,
            p_lens,
            wi: (p_lens - p) / d,
            distance: d,
            weight,
        })
    }

    /// Density per unit solid angle, sr⁻¹, with which [`Camera::generate_ray`] from the lens
    /// point `o` (world) produces the direction `dir` (unit, world) for a raster position
    /// uniform over the image: 1/(A·cos³θ) inside the image, 0 outside it or behind the camera
    /// (pbrt-v4's `PDF_We`). 0 for the orthographic camera (a delta in direction).
    pub fn pdf_we(&self, o: Vec3, dir: Vec3) -> f32 {
        let (to_world, film, focus) = match self {
            Camera::Perspective(c) => (&c.to_world, &c.film, None),
            Camera::ThinLens(c) => (&c.to_world, &c.film, Some(c.focus_distance)),
            Camera::Orthographic(_) | Camera::Realistic(_) | Camera::Spherical(_) => return 0.0,
        };
        let inv = to_world.inverse();
        let v = inv.vector(dir);
        let v = v / v.length();
        if !(v.z > 0.0) {
            return 0.0;
        }
        let raster = film.raster_of_ray(inv.point(o).truncate(), v, focus);
        if !film.contains(raster, 0.0) {
            return 0.0;
        }
        1.0 / (film.plane_area() * v.z * v.z * v.z)
    }

    fn parts(&self) -> (&Transform, &Film) {
        match self {
            Camera::Perspective(c) => (&c.to_world, &c.film),
            Camera::ThinLens(c) => (&c.to_world, &c.film),
            Camera::Orthographic(c) => (&c.to_world, &c.film),
            Camera::Realistic(c) => (&c.to_world, &c.film),
            Camera::Spherical(c) => (&c.to_world, &c.film),
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

    /// Unit world-space up direction (camera +y): the image's vertical.
    pub fn up(&self) -> Vec3 {
        self.parts().0.vector(Vec3::Y).normalize_or_zero()
    }

    /// Image size in pixels (width, height): the rendered window's.
    pub fn resolution(&self) -> (u32, u32) {
        self.parts().1.window
    }
}
