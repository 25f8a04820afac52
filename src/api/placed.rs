//! What a scene built in code places in space: the camera (`camera.rs`), shapes, lights and
//! meters, each the TOML table of the scene format (README, `[camera]`, `[[shapes]]`, `[[lights]]`,
//! `[[sensors]]`). Positions are in metres; directions are plain vectors.

use std::path::Path;

use toml::{Table, Value};

use super::items::{Emission, Spectrum};
use super::quantity::{Brightness, Flux, FluxDensity, Intensity, Radiometric};
use super::quantity::{point, text, typed, vector};
use crate::units::{Angle, Length};

pub use camera::Camera;

mod camera;

/// A `[[shapes]]` entry.
///
/// ```
/// use spectrace::{Shape, degrees, metres};
/// let wall = Shape::rectangle().scale(2.0).rotate([0.0, 1.0, 0.0], degrees(90.0)).translate(metres([3.0, 1.0, 0.0])).material("white");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Shape(pub(super) Table);

impl Shape {
    /// A sphere.
    ///
    /// ```
    /// use spectrace::units::{Length, length::centimeter};
    /// let s = spectrace::api::Shape::sphere(spectrace::api::metres([0.0; 3]), Length::new::<centimeter>(5.0));
    /// ```
    pub fn sphere(center: [Length; 3], radius: Length) -> Shape {
        let mut t = typed("sphere");
        t.insert("center".into(), point(center));
        t.insert("radius".into(), text(radius.quantity()));
        Shape(t)
    }

    /// The square [-1, 1]² m in the z = 0 plane, normal +z (place it with transforms).
    ///
    /// ```
    /// let floor = spectrace::api::Shape::rectangle().scale(5.0);
    /// ```
    pub fn rectangle() -> Shape {
        Shape(typed("rectangle"))
    }

    /// The unit disk in the z = 0 plane, normal +z.
    ///
    /// ```
    /// let d = spectrace::api::Shape::disk();
    /// ```
    pub fn disk() -> Shape {
        Shape(typed("disk"))
    }

    /// The cube [-1, 1]³ m.
    ///
    /// ```
    /// let b = spectrace::api::Shape::cuboid();
    /// ```
    pub fn cuboid() -> Shape {
        Shape(typed("box"))
    }

    /// A Wavefront OBJ mesh (relative paths resolve against the builder's folder).
    ///
    /// ```
    /// let m = spectrace::api::Shape::obj(std::path::Path::new("meshes/bunny.obj"));
    /// ```
    pub fn obj(file: &Path) -> Shape {
        let mut t = typed("obj");
        t.insert("file".into(), text(file.display().to_string()));
        Shape(t)
    }

    fn transform(mut self, step: &str, v: Value) -> Shape {
        let mut s = Table::new();
        s.insert(step.into(), v);
        let list = self
            .0
            .entry("transform")
            .or_insert_with(|| Value::Array(Vec::new()));
        if let Value::Array(a) = list {
            a.push(Value::Table(s));
        }
        self
    }

    /// Then moves it by `by`.
    ///
    /// ```
    /// let s = spectrace::api::Shape::disk().translate(spectrace::api::metres([0.0, 2.0, 0.0]));
    /// ```
    pub fn translate(self, by: [Length; 3]) -> Shape {
        self.transform("translate", point(by))
    }

    /// Then rotates it by `angle` about `axis` (right-handed).
    ///
    /// ```
    /// let s = spectrace::api::Shape::disk().rotate([1.0, 0.0, 0.0], spectrace::api::degrees(90.0));
    /// ```
    pub fn rotate(self, axis: [f64; 3], angle: Angle) -> Shape {
        let mut r = Table::new();
        r.insert("axis".into(), vector(axis));
        r.insert("angle".into(), text(angle.quantity()));
        self.transform("rotate", Value::Table(r))
    }

    /// Then scales it by `factor` about the origin.
    ///
    /// ```
    /// let s = spectrace::api::Shape::rectangle().scale(10.0);
    /// ```
    pub fn scale(self, factor: f64) -> Shape {
        self.transform("scale", Value::Float(factor))
    }

    /// Then scales it by a factor per axis.
    ///
    /// ```
    /// let s = spectrace::api::Shape::cuboid().scale_xyz([1.0, 0.1, 1.0]);
    /// ```
    pub fn scale_xyz(self, factors: [f64; 3]) -> Shape {
        self.transform("scale", vector(factors))
    }

    /// Its material, a name given to [`SceneBuilder::material`](super::SceneBuilder::material).
    ///
    /// ```
    /// let s = spectrace::api::Shape::rectangle().material("grey");
    /// ```
    pub fn material(mut self, name: &str) -> Shape {
        self.0.insert("material".into(), text(name));
        self
    }

    /// The material on both faces.
    ///
    /// ```
    /// let s = spectrace::api::Shape::rectangle().two_sided();
    /// ```
    pub fn two_sided(mut self) -> Shape {
        self.0.insert("two_sided".into(), Value::Boolean(true));
        self
    }

    /// Makes it an area light.
    ///
    /// ```
    /// use spectrace::units::{Luminance, luminance::candela_per_square_meter};
    /// let panel = spectrace::api::Shape::rectangle()
    ///     .emission(spectrace::api::Emission::uniform(Luminance::new::<candela_per_square_meter>(1000.0)));
    /// ```
    pub fn emission(mut self, e: Emission) -> Shape {
        self.0.insert("emission".into(), Value::Table(e.0));
        self
    }
}

/// A `[[lights]]` entry.
///
/// ```
/// use spectrace::units::{LuminousFlux, luminous_flux::lumen};
/// let bulb = spectrace::Light::point(spectrace::metres([0.0, 2.5, 0.0]), LuminousFlux::new::<lumen>(800.0))
///     .spectrum(spectrace::Spectrum::named("cie-led-b3")?);
/// # Ok::<(), spectrace::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Light(pub(super) Table);

impl Light {
    /// An isotropic point light of total flux `amount` (I = Φ/4π).
    ///
    /// ```
    /// use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    /// let l = spectrace::api::Light::point(spectrace::api::metres([0.0, 2.0, 0.0]), LuminousFlux::new::<lumen>(800.0));
    /// ```
    pub fn point(position: [Length; 3], amount: impl Flux) -> Light {
        let mut t = typed("point");
        t.insert("position".into(), point(position));
        t.insert("power".into(), text(amount.quantity()));
        Light(t)
    }

    /// An isotropic point light of intensity `amount` (W/sr or cd).
    ///
    /// ```
    /// use spectrace::units::{LuminousIntensity, luminous_intensity::candela};
    /// let l = spectrace::api::Light::point_intensity(spectrace::api::metres([0.0, 2.0, 0.0]), LuminousIntensity::new::<candela>(100.0));
    /// ```
    pub fn point_intensity(position: [Length; 3], amount: impl Intensity) -> Light {
        let mut t = typed("point");
        t.insert("position".into(), point(position));
        t.insert("intensity".into(), text(amount.quantity()));
        Light(t)
    }

    /// A spot at `position` aimed at `target`, `cone_angle` its half-angle, `amount` its
    /// flux over the cone (the smoothstep falloff integrated).
    ///
    /// ```
    /// use spectrace::api::{Light, degrees, metres};
    /// use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    /// let l = Light::spot(metres([0.0, 3.0, 0.0]), metres([0.0; 3]), degrees(30.0), LuminousFlux::new::<lumen>(1000.0))
    ///     .falloff_start(degrees(25.0));
    /// ```
    pub fn spot(
        position: [Length; 3],
        target: [Length; 3],
        cone_angle: Angle,
        amount: impl Flux,
    ) -> Light {
        let mut t = typed("spot");
        t.insert("position".into(), point(position));
        t.insert("target".into(), point(target));
        t.insert("cone_angle".into(), text(cone_angle.quantity()));
        t.insert("power".into(), text(amount.quantity()));
        Light(t)
    }

    /// A spot's full-intensity half-angle.
    ///
    /// ```
    /// # use spectrace::api::{Light, degrees, metres};
    /// # use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    /// # let l = Light::spot(metres([0.0, 3.0, 0.0]), metres([0.0; 3]), degrees(30.0), LuminousFlux::new::<lumen>(1000.0));
    /// let l = l.falloff_start(degrees(20.0));
    /// ```
    pub fn falloff_start(mut self, angle: Angle) -> Light {
        self.0
            .insert("falloff_start".into(), text(angle.quantity()));
        self
    }

    /// Parallel light travelling along `direction`, `amount` on a plane facing it.
    ///
    /// ```
    /// use spectrace::units::{Illuminance, illuminance::lux};
    /// let sun = spectrace::api::Light::directional([0.0, -1.0, 0.0], Illuminance::new::<lux>(1000.0));
    /// ```
    pub fn directional(direction: [f64; 3], amount: impl FluxDensity) -> Light {
        let mut t = typed("directional");
        t.insert("direction".into(), vector(direction));
        t.insert("irradiance".into(), text(amount.quantity()));
        Light(t)
    }

    /// Uniform light from every direction: radiance or luminance.
    ///
    /// ```
    /// use spectrace::units::{Luminance, luminance::candela_per_square_meter};
    /// let l = spectrace::api::Light::environment(Luminance::new::<candela_per_square_meter>(100.0));
    /// ```
    pub fn environment<B: Brightness>(amount: B) -> Light {
        let mut t = typed("environment");
        t.insert(B::KEY.into(), text(amount.quantity()));
        Light(t)
    }

    /// A measured luminaire (IES LM-63 or EULUMDAT file) with its nadir toward `target`.
    ///
    /// ```
    /// use spectrace::api::{Light, metres};
    /// let l = Light::luminaire(std::path::Path::new("downlight.ies"), metres([0.0, 3.0, 0.0]), metres([0.0; 3]));
    /// ```
    pub fn luminaire(file: &Path, position: [Length; 3], target: [Length; 3]) -> Light {
        let mut t = typed("luminaire");
        t.insert("file".into(), text(file.display().to_string()));
        t.insert("position".into(), point(position));
        t.insert("target".into(), point(target));
        Light(t)
    }

    /// The light's spectral shape (default: equal energy; luminaires: CIE A).
    ///
    /// ```
    /// # use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    /// # let l = spectrace::api::Light::point(spectrace::api::metres([0.0; 3]), LuminousFlux::new::<lumen>(800.0));
    /// let l = l.spectrum(spectrace::api::Spectrum::named("cie-a")?);
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn spectrum(mut self, s: Spectrum) -> Light {
        self.0.insert("spectrum".into(), s.0);
        self
    }
}

/// An illuminance meter (`[[sensors]]`), read by [`measure`](super::measure).
///
/// ```
/// let desk = spectrace::Meter::point("desk", spectrace::metres([1.0, 0.75, 1.0]), [0.0, 1.0, 0.0]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Meter(pub(super) Table);

impl Meter {
    /// One point measuring the side `normal` faces.
    ///
    /// ```
    /// let m = spectrace::api::Meter::point("desk", spectrace::api::metres([0.0, 0.8, 0.0]), [0.0, 1.0, 0.0]);
    /// ```
    pub fn point(name: &str, position: [Length; 3], normal: [f64; 3]) -> Meter {
        let mut t = typed("point");
        t.insert("name".into(), text(name));
        t.insert("position".into(), point(position));
        t.insert("normal".into(), vector(normal));
        Meter(t)
    }

    /// Points at the centres of `count` cells of the parallelogram `corner` + [0, 1]·`edge_u`
    /// + [0, 1]·`edge_v`, measuring the side of edge_u × edge_v.
    ///
    /// ```
    /// use spectrace::api::{Meter, metres};
    /// let m = Meter::grid("workplane", metres([0.0, 0.8, 0.0]), metres([0.0, 0.0, 3.0]), metres([4.0, 0.0, 0.0]), [6, 8]);
    /// ```
    pub fn grid(
        name: &str,
        corner: [Length; 3],
        edge_u: [Length; 3],
        edge_v: [Length; 3],
        count: [u32; 2],
    ) -> Meter {
        let mut t = typed("grid");
        t.insert("name".into(), text(name));
        t.insert("corner".into(), point(corner));
        t.insert("edge_u".into(), point(edge_u));
        t.insert("edge_v".into(), point(edge_v));
        t.insert(
            "count".into(),
            Value::Array(count.iter().map(|&c| Value::Integer(c as i64)).collect()),
        );
        Meter(t)
    }
}
