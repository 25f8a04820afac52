//! A camera rendering a window of its image (pbrt-v4's `cropwindow` and `pixelbounds`): the
//! film keeps the full image's size, from which every camera maps raster positions to rays,
//! and the window's offset, by which the raster positions it takes and gives are shifted.

use glam::Vec2;

use super::{Camera, Film};

impl Film {
    /// The full image's raster position of the window's `raster`.
    #[inline]
    pub(super) fn full(&self, raster: Vec2) -> Vec2 {
        raster + self.window_at
    }

    /// Whether `raster` lies in the rendered window grown by `margin` pixels on every side.
    #[inline]
    pub(super) fn contains(&self, raster: Vec2, margin: f32) -> bool {
        raster.x >= -margin
            && raster.y >= -margin
            && raster.x < self.window.0 as f32 + margin
            && raster.y < self.window.1 as f32 + margin
    }
}

impl Camera {
    /// The camera rendering only the window of `size` pixels at `at` (its top-left pixel) of
    /// its full image (pbrt-v4's `cropwindow` and `pixelbounds`): every pixel as in the full
    /// image. Errors for an empty window or one not inside the image.
    pub fn with_window(mut self, at: (u32, u32), size: (u32, u32)) -> Result<Camera, String> {
        let film = match &mut self {
            Camera::Perspective(c) => &mut c.film,
            Camera::ThinLens(c) => &mut c.film,
            Camera::Orthographic(c) => &mut c.film,
            Camera::Spherical(c) => &mut c.film,
            // its film's raster positions are mapped to the film plane through `Film::plane`,
            // which takes the window's offset as every camera's does
            Camera::Realistic(c) => &mut c.film,
        };
        let inside = at.0.checked_add(size.0).is_some_and(|x| x <= film.width)
            && at.1.checked_add(size.1).is_some_and(|y| y <= film.height);
        if size.0 == 0 || size.1 == 0 || !inside {
            return Err(format!(
                "the crop window of {} × {} pixels at ({}, {}) is not inside the {} × {} image",
                size.0, size.1, at.0, at.1, film.width, film.height
            ));
        }
        film.window_at = Vec2::new(at.0 as f32, at.1 as f32);
        film.window = size;
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Transform;
    use crate::geometry::camera::FovAxis;

    /// A window's pixel sees what the full image's pixel at the same place sees, connections
    /// land at the window's raster positions, and a window outside the image is refused.
    #[test]
    fn a_window_is_the_full_image_s_pixels() {
        let full = Camera::perspective(Transform::identity(), 1.0, FovAxis::X, 64, 48).unwrap();
        let win = full.clone().with_window((10, 20), (16, 8)).unwrap();
        assert_eq!(win.resolution(), (16, 8));
        let (a, b) = (
            full.generate_ray(Vec2::new(13.5, 22.5), Vec2::ZERO),
            win.generate_ray(Vec2::new(3.5, 2.5), Vec2::ZERO),
        );
        assert!((a.d - b.d).length() < 1e-6);
        let p = a.o + a.d * 5.0;
        let c = win.connect(p, Vec2::ZERO, 0.0).expect("inside the window");
        assert!(
            (c.raster - Vec2::new(3.5, 2.5)).length() < 1e-3,
            "{}",
            c.raster
        );
        assert!(
            win.connect(
                full.generate_ray(Vec2::new(40.5, 5.5), Vec2::ZERO).at(5.0),
                Vec2::ZERO,
                0.0
            )
            .is_none()
        );
        assert!(full.clone().with_window((60, 0), (8, 8)).is_err());
        assert!(full.with_window((0, 0), (0, 8)).is_err());
    }
}
