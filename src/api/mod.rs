//! The library API for radiometric tests in users' own code: build or load a scene, render it,
//! read values with their units and their standard errors. The CLI loads its scenes and
//! resolves its options through this module too, so a test renders what `spectrace render`
//! renders from the same file and settings.
//!
//! A ten-line test: a grey floor under an 800 lm point light, its luminance against the closed
//! form L = ρ·E/π = ρ·Φ/(4π²h²), within 3 standard errors.
//!
//! ```
//! use spectrace::api::*;
//! use spectrace::units::{luminance::candela_per_square_meter as cd_m2, luminous_flux::lumen, LuminousFlux};
//!
//! let scene = Scene::builder()
//!     .camera(Camera::perspective(metres([0.0, 1.0, 0.0]), metres([0.0, 0.0, 0.0]), degrees(2.0)).up([0.0, 0.0, 1.0]))
//!     .film(16, 16)
//!     .material("grey", Material::diffuse(0.18))
//!     .shape(Shape::rectangle().scale(10.0).rotate([1.0, 0.0, 0.0], degrees(-90.0)).material("grey"))
//!     .light(Light::point(metres([0.0, 2.0, 0.0]), LuminousFlux::new::<lumen>(800.0)).spectrum(Spectrum::named("cie-a")?))
//!     .build()?;
//! let image = render(&scene, &Options { spp: Some(64), ..Options::default() })?;
//! let l = image.mean_luminance(Region::all(&image));
//! let expected = 0.18 * 800.0 / (4.0 * std::f64::consts::PI.powi(2) * 4.0);
//! assert!((l.value.get::<cd_m2>() - expected).abs() < 3.0 * l.standard_error.get::<cd_m2>());
//! # Ok::<(), spectrace::api::Error>(())
//! ```
//!
//! The same scene as TOML text ([`Scene::from_toml`]) or a file ([`Scene::load`], TOML or
//! Mitsuba 3 XML) renders the same image: the builder writes the scene format's TOML
//! ([`SceneBuilder::to_toml`]) and loads it as any file is loaded.
#![warn(missing_docs)]

use std::path::Path;
use std::sync::atomic::AtomicBool;

mod builder;
mod image;
mod items;
mod lookup;
mod optics;
mod placed;
mod quantity;

pub use builder::SceneBuilder;
pub use image::{Estimate, Image, Region};
pub use items::{Emission, Ior, Material, Spectrum};
pub use lookup::{MeasureOptions, MeterReading, SpectrumValues, measure, measure_with, spectrum};
pub use optics::{LensFocalLengths, MaterialAlbedo, lens};
pub use placed::{Camera, Light, Meter, Shape};
pub use quantity::{Brightness, Flux, FluxDensity, Intensity, Radiometric, degrees, metres};

/// Everything that can go wrong: a scene that does not load or build (file, line, field and
/// message), options a render cannot take, a render that cannot start, or an unknown spectrum.
///
/// ```
/// let e = spectrace::Scene::from_toml("[camera]\neye = [0, 0]\ntarget = [0, 0, 1]\nfov = \"40 deg\"").unwrap_err();
/// assert!(matches!(e, spectrace::Error::Scene(_)));
/// assert!(e.to_string().contains("camera.eye"), "{e}");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The scene file or text, located.
    #[error(transparent)]
    Scene(#[from] crate::loader::LoadError),
    /// An option out of its range (which one, and why).
    #[error("{0}")]
    Options(String),
    /// The render could not start (threads, camera kind).
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// A spectrum name that is not known, with the closest known names.
    #[error(transparent)]
    Spectrum(#[from] crate::spectrum::named::UnknownSpectrum),
}

/// A render-ready scene.
///
/// ```
/// let s = spectrace::Scene::from_toml("[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"")?;
/// assert!(format!("{s:?}").contains("TOML text"));
/// # Ok::<(), spectrace::Error>(())
/// ```
pub struct Scene {
    inner: crate::scene::Scene,
    notes: Vec<String>,
    /// The materials' names, in `inner.materials`' order.
    material_names: Vec<String>,
    /// Where the scene came from (a file, or how it was given), for the image's metadata.
    source: String,
}

impl std::fmt::Debug for Scene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Scene")
            .field("source", &self.source)
            .field("shapes", &self.inner.shapes.len())
            .field("lights", &self.inner.lights.len())
            .field("notes", &self.notes)
            .finish()
    }
}

impl Scene {
    /// A scene in code, mirroring the TOML format (see [`SceneBuilder`]).
    ///
    /// ```
    /// use spectrace::api::{Scene, Material};
    /// let b = Scene::builder().material("grey", Material::diffuse(0.18));
    /// assert!(b.to_toml().contains("[materials.grey]"));
    /// ```
    pub fn builder() -> SceneBuilder {
        SceneBuilder::default()
    }

    /// A scene from TOML text; relative file names resolve against the current folder.
    ///
    /// ```
    /// let e = spectrace::api::Scene::from_toml("[camera]\nfov = 3").err().unwrap();
    /// assert!(e.to_string().contains("camera"));
    /// ```
    pub fn from_toml(text: &str) -> Result<Scene, Error> {
        Self::from_toml_in(text, Path::new("."))
    }

    /// A scene from TOML text whose relative file names resolve against `folder`.
    ///
    /// ```no_run
    /// let s = spectrace::api::Scene::from_toml_in("…", std::path::Path::new("scenes"));
    /// ```
    pub fn from_toml_in(text: &str, folder: &Path) -> Result<Scene, Error> {
        // errors call it "TOML text" (there is no file); relative names resolve in `folder`
        let name = if folder == Path::new(".") {
            std::path::PathBuf::from("TOML text")
        } else {
            folder.join("TOML text")
        };
        let desc = crate::loader::load_str(text, &name)?;
        Self::from_desc(desc, "TOML text".into())
    }

    /// A scene from TOML text that errors call `name`; relative file names resolve against
    /// `name`'s folder (for text that stands for a file, or is made by a tool).
    ///
    /// ```
    /// let e = spectrace::Scene::from_toml_as("[camera]\nfov = 3", std::path::Path::new("gen/room.toml"))
    ///     .unwrap_err();
    /// assert!(e.to_string().starts_with("gen/room.toml:"), "{e}");
    /// ```
    pub fn from_toml_as(text: &str, name: &Path) -> Result<Scene, Error> {
        let desc = crate::loader::load_str(text, name)?;
        Self::from_desc(desc, name.display().to_string())
    }

    /// A scene file: spectrace TOML, or Mitsuba 3 XML (`.xml`).
    ///
    /// ```no_run
    /// let s = spectrace::api::Scene::load(std::path::Path::new("scenes/cornell.toml"))?;
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn load(path: &Path) -> Result<Scene, Error> {
        Self::load_with(path, &[])
    }

    /// A scene file with values for a Mitsuba scene's `$name` parameters (as `-D name=value`
    /// on the command line; TOML scenes have none).
    ///
    /// ```no_run
    /// let defines = [("spp".to_string(), "64".to_string())];
    /// let s = spectrace::api::Scene::load_with(std::path::Path::new("cbox.xml"), &defines)?;
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn load_with(path: &Path, defines: &[(String, String)]) -> Result<Scene, Error> {
        let desc = crate::loader::load_any(path, defines)?;
        Self::from_desc(desc, path.display().to_string())
    }

    fn from_desc(desc: crate::loader::SceneDesc, source: String) -> Result<Scene, Error> {
        // a scene that does not build keeps the loader's notes, which may explain why
        let inner = crate::build::build(&desc).map_err(|mut e| {
            for n in &desc.notes {
                e.message.push_str(&format!("\nnote: {n}"));
            }
            e
        })?;
        Ok(Scene {
            inner,
            material_names: desc.materials.iter().map(|m| m.name.clone()).collect(),
            notes: desc.notes,
            source,
        })
    }

    /// What the loader noted about the scene without refusing it (how a Mitsuba scene's
    /// features were read).
    ///
    /// ```
    /// let s = spectrace::api::Scene::from_toml("[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"\n[film]\nwidth = 4\nheight = 4")?;
    /// assert!(s.notes().is_empty());
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The scene as the renderer sees it (for what this API does not cover yet).
    ///
    /// ```no_run
    /// # let s = spectrace::api::Scene::load(std::path::Path::new("x.toml"))?;
    /// let lights = s.inner().lights.len();
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn inner(&self) -> &crate::scene::Scene {
        &self.inner
    }
}

/// The most samples per pixel a render takes (2²⁴), and what a time limit or a target error
/// without a sample count renders toward.
pub const MAX_SPP: u32 = 1 << 24;

/// Which estimator renders: the scene's own [`crate::scene::IntegratorKind`].
pub use crate::scene::IntegratorKind as Integrator;

/// How to render; `None` fields take the scene's settings.
///
/// ```
/// let o = spectrace::api::Options { spp: Some(16), seed: 3, ..Default::default() };
/// assert_eq!(o.threads, None);
/// ```
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Samples per pixel, 1 to [`MAX_SPP`] (None: the scene's, or [`MAX_SPP`] when a time limit
    /// or a target error is given, which then ends the render).
    pub spp: Option<u32>,
    /// Sampler seed: the image is a function of the scene, the options and this.
    pub seed: u32,
    /// The estimator.
    pub integrator: Option<Integrator>,
    /// Worker threads (None: every core; at least 1); the image does not depend on it.
    pub threads: Option<usize>,
    /// Spectral bins over the scene's wavelength range (None: the scene's; at most 1000), for
    /// [`Image::spectral_radiance`].
    pub spectral_bins: Option<u32>,
    /// Stop at the end of the pass after which the next would end past this render time (more
    /// than 0 s, less than 10⁹ s).
    pub time_limit: Option<std::time::Duration>,
    /// Stop at the end of the first pass whose estimated relative error of the image's Y is
    /// below this (a fraction between 0 and 1, e.g. 0.01).
    pub target_error: Option<f64>,
}

impl Options {
    /// The renderer's options for `scene`: the scene's settings overridden by these. An option
    /// out of range is an [`Error::Options`] naming it.
    ///
    /// ```
    /// use spectrace::api::{Options, Scene};
    /// let s = Scene::from_toml("[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"\n[film]\nwidth = 4\nheight = 4\nspp = 7")?;
    /// assert_eq!(Options::default().render_options(&s)?.spp, 7);
    /// assert!(Options { spp: Some(0), ..Default::default() }.render_options(&s).is_err());
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn render_options(&self, scene: &Scene) -> Result<crate::render::RenderOptions, Error> {
        let mut o = crate::render::RenderOptions::from_scene(&scene.inner);
        if let Some(spp) = self.spp {
            if spp == 0 {
                return Err(Error::Options("spp must be at least 1".into()));
            }
            if spp > MAX_SPP {
                return Err(Error::Options(format!("spp must be at most {MAX_SPP}")));
            }
            o.spp = spp;
        } else if self.time_limit.is_some() || self.target_error.is_some() {
            // a budget without a sample count: samples until the budget ends the render
            o.spp = MAX_SPP;
        }
        if self.threads == Some(0) {
            return Err(Error::Options("threads must be at least 1".into()));
        }
        o.threads = self.threads;
        o.seed = self.seed;
        if let Some(b) = self.spectral_bins {
            if b > 1000 {
                return Err(Error::Options("spectral_bins must be at most 1000".into()));
            }
            o.spectral_bins = b;
        }
        if let Some(i) = self.integrator {
            o.integrator = i;
        }
        if let Some(t) = self.time_limit
            && (t.is_zero() || t.as_secs_f64() >= 1e9)
        {
            return Err(Error::Options(format!(
                "time_limit {t:?}: expected more than 0 s and less than 10⁹ s"
            )));
        }
        if let Some(e) = self.target_error
            && !(e > 0.0 && e < 1.0)
        {
            return Err(Error::Options(format!(
                "target_error {e}: expected a fraction between 0 and 1, such as 0.01"
            )));
        }
        o.time_limit = self.time_limit;
        o.target_error = self.target_error;
        Ok(o)
    }
}

/// Renders `scene` to the end.
///
/// ```no_run
/// # let scene = spectrace::api::Scene::load(std::path::Path::new("x.toml"))?;
/// let image = spectrace::api::render(&scene, &Default::default())?;
/// # Ok::<(), spectrace::api::Error>(())
/// ```
pub fn render(scene: &Scene, options: &Options) -> Result<Image, Error> {
    render_with(scene, options, &AtomicBool::new(false), &|_, _| {})
}

/// Renders `scene` until it ends or `cancel` is set (checked between tiles); `progress(done,
/// total)` receives sample counts as tiles finish. A cancelled render returns what it has
/// ([`Image::complete`] is false).
///
/// ```
/// use std::sync::atomic::AtomicBool;
/// let s = spectrace::api::Scene::from_toml("[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"\n[film]\nwidth = 4\nheight = 4")?;
/// let image = spectrace::api::render_with(&s, &Default::default(), &AtomicBool::new(true), &|_, _| {})?;
/// assert!(!image.complete());
/// # Ok::<(), spectrace::api::Error>(())
/// ```
pub fn render_with(
    scene: &Scene,
    options: &Options,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Image, Error> {
    let o = options.render_options(scene)?;
    let (film, stats) = crate::render::render(&scene.inner, &o, cancel, progress)?;
    Ok(Image::new(
        film.image(),
        &o,
        &stats,
        &scene.inner,
        &scene.source,
    ))
}
