//! A scene in code: the builder collects the tables of the scene format (README, "Scene
//! format") and loads them as a file is loaded, so a scene built here and the same scene
//! written as TOML are one scene, checked by one loader.

use std::path::{Path, PathBuf};

use toml::{Table, Value};

use super::items::Material;
use super::placed::{Camera, Light, Meter, Shape};
use super::quantity::{Radiometric, text};
use super::{Error, Scene};
use crate::units::Length;

/// Builds a [`Scene`] from typed items; see [`Scene::builder`].
///
/// ```
/// use spectrace::api::{Camera, Light, Material, Scene, Shape, degrees, metres};
/// use spectrace::units::{Power, power::watt};
/// let scene = Scene::builder()
///     .camera(Camera::perspective(metres([0.0, 1.0, -3.0]), metres([0.0; 3]), degrees(40.0)))
///     .film(32, 24)
///     .material("white", Material::diffuse(0.8))
///     .shape(Shape::sphere(metres([0.0; 3]), metres([0.5; 3])[0]).material("white"))
///     .light(Light::point(metres([0.0, 3.0, 0.0]), Power::new::<watt>(100.0)))
///     .build()?;
/// assert_eq!(scene.inner().film.width, 32);
/// # Ok::<(), spectrace::api::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    root: Table,
    folder: PathBuf,
}

impl Default for SceneBuilder {
    fn default() -> Self {
        let mut scene = Table::new();
        scene.insert("length_unit".into(), text("m"));
        let mut root = Table::new();
        root.insert("scene".into(), Value::Table(scene));
        SceneBuilder {
            root,
            folder: PathBuf::from("."),
        }
    }
}

impl SceneBuilder {
    fn table(&mut self, key: &str) -> &mut Table {
        let v = self
            .root
            .entry(key)
            .or_insert_with(|| Value::Table(Table::new()));
        match v {
            Value::Table(t) => t,
            _ => unreachable!("the builder keeps `{key}` a table"),
        }
    }

    fn push(mut self, key: &str, item: Table) -> Self {
        let v = self
            .root
            .entry(key)
            .or_insert_with(|| Value::Array(Vec::new()));
        if let Value::Array(a) = v {
            a.push(Value::Table(item));
        }
        self
    }

    /// The folder relative file names (meshes, spectra, luminaires) resolve against (default
    /// the current one).
    ///
    /// ```
    /// let b = spectrace::api::Scene::builder().folder(std::path::Path::new("scenes"));
    /// ```
    pub fn folder(mut self, folder: &Path) -> Self {
        self.folder = folder.to_path_buf();
        self
    }

    /// The camera (required).
    ///
    /// ```
    /// use spectrace::api::{Camera, degrees, metres};
    /// let b = spectrace::api::Scene::builder()
    ///     .camera(Camera::perspective(metres([0.0, 0.0, -2.0]), metres([0.0; 3]), degrees(30.0)));
    /// ```
    pub fn camera(mut self, camera: Camera) -> Self {
        self.root.insert("camera".into(), Value::Table(camera.0));
        self
    }

    /// The image's size in pixels (default 512 × 512).
    ///
    /// ```
    /// let b = spectrace::api::Scene::builder().film(64, 48);
    /// ```
    pub fn film(mut self, width: u32, height: u32) -> Self {
        let f = self.table("film");
        f.insert("width".into(), Value::Integer(width as i64));
        f.insert("height".into(), Value::Integer(height as i64));
        self
    }

    /// Samples per pixel when the render's options do not say (default 16).
    ///
    /// ```
    /// let b = spectrace::api::Scene::builder().spp(64);
    /// ```
    pub fn spp(mut self, spp: u32) -> Self {
        self.table("film")
            .insert("spp".into(), Value::Integer(spp as i64));
        self
    }

    /// The most bounces of a path (default 16; `[integrator] max_depth`).
    ///
    /// ```
    /// let b = spectrace::api::Scene::builder().max_depth(1000);
    /// ```
    pub fn max_depth(mut self, bounces: u32) -> Self {
        self.table("integrator")
            .insert("max_depth".into(), Value::Integer(bounces as i64));
        self
    }

    /// The simulated wavelengths (default 360–830 nm); watts count this range only.
    ///
    /// ```
    /// use spectrace::units::{Length, length::nanometer};
    /// let b = spectrace::api::Scene::builder()
    ///     .wavelength_range(Length::new::<nanometer>(380.0), Length::new::<nanometer>(780.0));
    /// ```
    pub fn wavelength_range(mut self, min: Length, max: Length) -> Self {
        self.table("scene").insert(
            "wavelength_range".into(),
            Value::Array(vec![text(min.quantity()), text(max.quantity())]),
        );
        self
    }

    /// A material, named for shapes to use.
    ///
    /// ```
    /// let b = spectrace::api::Scene::builder().material("grey", spectrace::api::Material::diffuse(0.18));
    /// ```
    pub fn material(mut self, name: &str, material: Material) -> Self {
        self.table("materials")
            .insert(name.into(), Value::Table(material.0));
        self
    }

    /// A shape.
    ///
    /// ```
    /// let b = spectrace::api::Scene::builder().shape(spectrace::api::Shape::rectangle());
    /// ```
    pub fn shape(self, shape: Shape) -> Self {
        self.push("shapes", shape.0)
    }

    /// A light.
    ///
    /// ```
    /// use spectrace::units::{Luminance, luminance::candela_per_square_meter};
    /// let b = spectrace::api::Scene::builder()
    ///     .light(spectrace::api::Light::environment(Luminance::new::<candela_per_square_meter>(100.0)));
    /// ```
    pub fn light(self, light: Light) -> Self {
        self.push("lights", light.0)
    }

    /// An illuminance meter, read by [`measure`](super::measure).
    ///
    /// ```
    /// let b = spectrace::api::Scene::builder()
    ///     .meter(spectrace::api::Meter::point("desk", spectrace::api::metres([0.0; 3]), [0.0, 1.0, 0.0]));
    /// ```
    pub fn meter(self, meter: Meter) -> Self {
        self.push("sensors", meter.0)
    }

    /// The scene as the TOML the scene format reads: what [`build`](Self::build) loads, and
    /// the text its error locations refer to.
    ///
    /// ```
    /// let t = spectrace::api::Scene::builder().film(8, 8).to_toml();
    /// assert!(t.contains("width = 8"));
    /// ```
    pub fn to_toml(&self) -> String {
        toml::to_string(&self.root).expect("a table of TOML values always serialises")
    }

    /// Loads and builds the scene. Errors name the field (`lights[0].power`) and its line in
    /// [`to_toml`](Self::to_toml)'s text, called `scene builder` in the message.
    ///
    /// ```
    /// use spectrace::api::{Material, Scene, Shape};
    /// use spectrace::api::{Camera, degrees, metres};
    /// let e = Scene::builder()
    ///     .camera(Camera::perspective(metres([0.0, 0.0, -1.0]), metres([0.0; 3]), degrees(30.0)))
    ///     .material("grey", Material::diffuse(1.5))
    ///     .build()
    ///     .unwrap_err();
    /// assert!(e.to_string().contains("materials.grey.reflectance"), "{e}");
    /// ```
    pub fn build(&self) -> Result<Scene, Error> {
        let text = self.to_toml();
        // named as the builder in errors; relative file names resolve against the folder
        let name = if self.folder == Path::new(".") {
            PathBuf::from("scene builder")
        } else {
            self.folder.join("scene builder")
        };
        let desc = crate::loader::load_str(&text, &name)?;
        Scene::from_desc(desc, "scene builder".into())
    }
}
