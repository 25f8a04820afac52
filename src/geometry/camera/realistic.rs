//! The realistic camera: a lens system ([`crate::optics`]) traced exactly, per wavelength, in
//! front of a film (pbrt-v4 §5.3, with every element's glass dispersing).
//!
//! Camera space is the lens space of [`crate::optics`] in metres: the camera's position is the
//! centre of the film and the lens lies along +z. The lens inverts the image; the film is read
//! turned back upright, so raster positions map to the same directions a pinhole camera's do.
//!
//! **What a pixel means**: the film irradiance divided by the projected solid angle of the
//! on-axis exit pupil ([`crate::optics::ExitPupil`]). Looking at a uniform radiance L, the
//! centre of the image reads L (in W·m⁻²·sr⁻¹·nm⁻¹, as a pinhole camera's pixel) and the
//! corners L times the lens's relative illumination. Fresnel losses at the lens surfaces are not
//! modelled (as in pbrt-v4): the lens is an ideally coated one.
//!
//! **pbrt-v4's pixel** ([`Camera::with_irradiance_pixels`]): the film irradiance itself per
//! unit radiance, the same weight times that solid angle, so a uniform radiance L reads L·G₀
//! at the image centre (pbrt-v4's `RealisticCamera::GenerateRay`: cos⁴θ / (pdf · z_rear²)).
//!
//! A ray through dispersive glass serves its own wavelength only, so [`Camera::disperses`]
//! tells the renderer to keep the hero wavelength alone.

use glam::{DVec2, Vec2, Vec3};

use super::{Camera, Film};
use crate::geometry::error::{GeometryError, check_positive};
use crate::geometry::ray::Ray;
use crate::geometry::transform::Transform;
use crate::optics::{ExitPupil, LensError, LensSystem};

/// A lens system in front of a film.
#[derive(Clone, Debug, PartialEq)]
pub struct Realistic {
    pub(super) to_world: Transform,
    /// Half extents of the film, m.
    pub(super) film: Film,
    lens: LensSystem,
    pupil: ExitPupil,
    dispersive: bool,
    /// Factor on every ray's weight: 1 (spectrace's pixel) or G₀, sr (pbrt-v4's irradiance).
    weight_scale: f64,
}

/// Why a realistic camera cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum RealisticError {
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    #[error(transparent)]
    Lens(#[from] LensError),
}

impl Camera {
    /// A realistic camera: `lens` in front of a film `film_diagonal_m` across its diagonal
    /// (pbrt-v4's `diagonal`, 35 mm by default there), of `width` × `height` pixels. Errors for
    /// a bad size or a lens that lets no ray from the film's centre through.
    pub fn realistic(
        camera_to_world: Transform,
        lens: LensSystem,
        film_diagonal_m: f32,
        width: u32,
        height: u32,
    ) -> Result<Camera, RealisticError> {
        check_positive("film diagonal (m)", film_diagonal_m)?;
        let mut film = Film::new(width, height)?;
        let (w, h) = (width as f32, height as f32);
        let half_diag = film_diagonal_m / 2.0;
        let scale = half_diag / (w * w + h * h).sqrt();
        film.half = Vec2::new(w * scale, h * scale);
        let pupil = ExitPupil::new(&lens, half_diag as f64 * 1e3)?;
        Ok(Camera::Realistic(Box::new(Realistic {
            to_world: camera_to_world,
            film,
            dispersive: lens.is_dispersive(),
            lens,
            pupil,
            weight_scale: 1.0,
        })))
    }

    /// This camera with pbrt-v4's pixel for a realistic camera: the film irradiance per unit
    /// radiance (W·m⁻²·nm⁻¹ where the scene has W·m⁻²·sr⁻¹·nm⁻¹), which is spectrace's pixel
    /// times the on-axis exit pupil's projected solid angle G₀ (module docs). Other cameras are
    /// returned unchanged.
    pub fn with_irradiance_pixels(mut self) -> Camera {
        if let Camera::Realistic(c) = &mut self {
            c.weight_scale = c.pupil.normalisation_sr();
        }
        self
    }
}

impl Camera {
    /// The world ray through `raster` from lens sample `lens` at wavelength `lambda_nm`, with
    /// its weight (dimensionless): the ray of [`Camera::generate_ray`] with weight 1 for every
    /// camera but the realistic one, whose rays depend on the wavelength and carry the weight
    /// of its pupil sampling (`camera/realistic.rs`). None if the lens blocks the ray.
    #[inline]
    pub fn generate_ray_at(&self, raster: Vec2, lens: Vec2, lambda_nm: f32) -> Option<(Ray, f32)> {
        match self {
            Camera::Realistic(c) => c.ray(raster, lens, lambda_nm),
            _ => Some((self.generate_ray(raster, lens), 1.0)),
        }
    }

    /// Whether a camera ray serves its hero wavelength only (a realistic camera with dispersive
    /// glass); the renderer then terminates the secondary wavelengths.
    pub fn disperses(&self) -> bool {
        match self {
            Camera::Realistic(c) => c.dispersive(),
            Camera::Perspective(_)
            | Camera::ThinLens(_)
            | Camera::Orthographic(_)
            | Camera::Spherical(_) => false,
        }
    }
}

impl Realistic {
    /// The world ray through raster position `raster` from the pupil sample `u` ∈ [0, 1)² at
    /// `lambda_nm`, and its weight (dimensionless, see the module docs); None if the lens
    /// blocks it.
    #[inline(never)]
    pub(super) fn ray(&self, raster: Vec2, u: Vec2, lambda_nm: f32) -> Option<(Ray, f32)> {
        // the pinhole-equivalent plane point, turned over: the lens inverts the image
        let xy = -self.film.plane(raster);
        let film = DVec2::new(xy.x as f64, xy.y as f64) * 1e3;
        let (r, w) = self.pupil.camera_ray(
            &self.lens,
            film,
            DVec2::new(u.x as f64, u.y as f64),
            lambda_nm as f64,
        )?;
        let w = w * self.weight_scale;
        let o = Vec3::new(r.o.x as f32, r.o.y as f32, r.o.z as f32) * 1e-3;
        let d = Vec3::new(r.d.x as f32, r.d.y as f32, r.d.z as f32);
        let ray = Ray::new(self.to_world.point(o), self.to_world.vector(d));
        (w.is_finite() && w > 0.0).then_some((ray, w as f32))
    }

    /// The ray through `raster` at the d line; where the lens blocks it, the ray from the film
    /// point through the lens's axial point (for probes and previews, never for rendering).
    /// Kept out of line so the other cameras' ray generation stays small.
    #[cold]
    #[inline(never)]
    pub(super) fn preview_ray(&self, raster: Vec2, u: Vec2) -> Ray {
        self.ray(raster, u, crate::spectrum::ior::FRAUNHOFER_D_NM)
            .map(|(r, _)| r)
            .unwrap_or_else(|| {
                let xy = self.film.plane(raster);
                Ray::new(
                    self.to_world.point(Vec3::ZERO),
                    self.to_world.vector(xy.extend(1.0)),
                )
            })
    }

    /// Whether a ray through the lens serves one wavelength only.
    pub(super) fn dispersive(&self) -> bool {
        self.dispersive
    }

    /// The lens system.
    pub fn lens(&self) -> &LensSystem {
        &self.lens
    }
}
