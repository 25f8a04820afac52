//! The camera of a scene built in code: the `[camera]` table.

use toml::{Table, Value};

use super::super::quantity::{Radiometric, point, text, typed, vector};
use crate::units::{Angle, Length};

/// The `[camera]` table.
///
/// ```
/// use spectrace::{Camera, degrees, metres};
/// let c = Camera::perspective(metres([0.0, 1.6, -3.0]), metres([0.0, 1.0, 0.0]), degrees(50.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Camera(pub(in crate::api) Table);

impl Camera {
    /// A pinhole at `eye` looking at `target`, `fov` across the image's width.
    ///
    /// ```
    /// use spectrace::api::{Camera, degrees, metres};
    /// let c = Camera::perspective(metres([0.0, 1.0, -3.0]), metres([0.0; 3]), degrees(40.0));
    /// ```
    pub fn perspective(eye: [Length; 3], target: [Length; 3], fov: Angle) -> Camera {
        let mut t = typed("perspective");
        t.insert("eye".into(), point(eye));
        t.insert("target".into(), point(target));
        t.insert("fov".into(), text(fov.quantity()));
        Camera(t)
    }

    /// A parallel projection `view_width` wide.
    ///
    /// ```
    /// use spectrace::api::{Camera, metres};
    /// use spectrace::units::{Length, length::meter};
    /// let c = Camera::orthographic(metres([0.0, 5.0, 0.0]), metres([0.0; 3]), Length::new::<meter>(2.0));
    /// ```
    pub fn orthographic(eye: [Length; 3], target: [Length; 3], view_width: Length) -> Camera {
        let mut t = typed("orthographic");
        t.insert("eye".into(), point(eye));
        t.insert("target".into(), point(target));
        t.insert("view_width".into(), text(view_width.quantity()));
        Camera(t)
    }

    /// The image's up direction (default +y).
    ///
    /// ```
    /// # use spectrace::api::{Camera, degrees, metres};
    /// let c = Camera::perspective(metres([0.0, 3.0, 0.0]), metres([0.0; 3]), degrees(40.0)).up([0.0, 0.0, 1.0]);
    /// ```
    pub fn up(mut self, up: [f64; 3]) -> Camera {
        self.0.insert("up".into(), vector(up));
        self
    }

    /// A thin lens of this f-number focused at `focus_distance` (the focal length is the one
    /// giving the field of view on a 36 mm sensor).
    ///
    /// ```
    /// # use spectrace::api::{Camera, degrees, metres};
    /// let c = Camera::perspective(metres([0.0, 0.0, -3.0]), metres([0.0; 3]), degrees(40.0))
    ///     .thin_lens(2.8, metres([0.0, 0.0, 3.0])[2]);
    /// ```
    pub fn thin_lens(mut self, f_number: f64, focus_distance: Length) -> Camera {
        self.0.insert("type".into(), text("thinlens"));
        self.0.insert("f_number".into(), Value::Float(f_number));
        self.0
            .insert("focus_distance".into(), text(focus_distance.quantity()));
        self
    }
}
