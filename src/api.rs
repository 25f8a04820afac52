//! The library API for radiometric tests in users' own code: load a scene, render it, read
//! values with their units and their standard errors.
//!
//! ```
//! use spectrace::api::{Options, Region, Scene, render};
//! use spectrace::units::luminance::candela_per_square_meter;
//!
//! // a camera inside a closed sphere that emits 100 cd/m² of D65 and reflects nothing
//! let scene = Scene::from_toml(r#"
//!     [camera]
//!     eye = [0, 0, 0]
//!     target = [0, 0, 1]
//!     fov = "40 deg"
//!     [film]
//!     width = 8
//!     height = 8
//!     [materials.black]
//!     type = "diffuse"
//!     reflectance = 0
//!     [[shapes]]
//!     type = "sphere"
//!     radius = 1
//!     material = "black"
//!     two_sided = true
//!     emission = { spectrum = "cie-d65", luminance = "100 cd/m^2", two_sided = true }
//! "#)?;
//! let image = render(&scene, &Options { spp: Some(64), ..Options::default() })?;
//! let l = image.mean_luminance(Region::all(&image));
//! let (v, se) = (l.value.get::<candela_per_square_meter>(), l.standard_error.get::<candela_per_square_meter>());
//! assert!((v - 100.0).abs() < 4.0 * se + 1e-9, "{v} ± {se}");
//! # Ok::<(), spectrace::api::Error>(())
//! ```
#![warn(missing_docs)]

use std::path::Path;
use std::sync::atomic::AtomicBool;

use crate::units::{Length, Luminance, Radiance, SpectralRadiance};
use crate::units::{length, luminance, radiance, spectral_radiance};

/// Everything that can go wrong: a scene that does not load or build (file, line, field and
/// message), or a render that cannot start.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The scene file or text, located.
    #[error(transparent)]
    Scene(#[from] crate::loader::LoadError),
    /// The render could not start (threads, camera kind).
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
}

/// A render-ready scene.
pub struct Scene {
    inner: crate::scene::Scene,
}

impl Scene {
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
        let desc = crate::loader::load_str(text, &folder.join("scene.toml"))?;
        Ok(Scene {
            inner: crate::scene::build(&desc)?,
        })
    }

    /// A scene file: spectrace TOML, or Mitsuba 3 XML (`.xml`).
    ///
    /// ```no_run
    /// let s = spectrace::api::Scene::load(std::path::Path::new("scenes/cornell.toml"))?;
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn load(path: &Path) -> Result<Scene, Error> {
        let desc = crate::loader::load_any(path, &[])?;
        Ok(Scene {
            inner: crate::scene::build(&desc)?,
        })
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

/// Which estimator renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Path tracing with next-event estimation and MIS.
    Path,
    /// Light tracing (particles from the lights).
    Light,
    /// Bidirectional path tracing.
    Bdpt,
}

/// How to render; `None` fields take the scene's settings.
///
/// ```
/// let o = spectrace::api::Options { spp: Some(16), seed: 3, ..Default::default() };
/// assert_eq!(o.threads, None);
/// ```
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// Sampler seed: the image is a function of the scene, the options and this.
    pub seed: u32,
    /// The estimator.
    pub integrator: Option<Integrator>,
    /// Worker threads (None: every core); the image does not depend on it.
    pub threads: Option<usize>,
    /// Spectral bins over the scene's wavelength range (0: none), for
    /// [`Image::spectral_radiance`].
    pub spectral_bins: u32,
}

/// Renders `scene` (Ctrl-C is not watched: the render runs to the end).
///
/// ```no_run
/// # let scene = spectrace::api::Scene::load(std::path::Path::new("x.toml"))?;
/// let image = spectrace::api::render(&scene, &Default::default())?;
/// # Ok::<(), spectrace::api::Error>(())
/// ```
pub fn render(scene: &Scene, options: &Options) -> Result<Image, Error> {
    let s = &scene.inner;
    let mut o = crate::render::RenderOptions::from_scene(s);
    if let Some(spp) = options.spp {
        o.spp = spp.max(1);
    }
    o.seed = options.seed;
    o.threads = options.threads;
    o.spectral_bins = options.spectral_bins;
    if let Some(i) = options.integrator {
        o.integrator = match i {
            Integrator::Path => crate::loader::desc::IntegratorKind::Path,
            Integrator::Light => crate::loader::desc::IntegratorKind::Light,
            Integrator::Bdpt => crate::loader::desc::IntegratorKind::Bdpt,
        };
    }
    let cancel = AtomicBool::new(false);
    let (film, stats) = crate::render::render(s, &o, &cancel, &|_, _| {})?;
    Ok(Image {
        inner: film.image(),
        spp: stats.spp_done,
        camera_samples: !matches!(
            o.integrator,
            crate::loader::desc::IntegratorKind::Light | crate::loader::desc::IntegratorKind::Bdpt
        ),
    })
}

/// A rectangle of pixels: columns `x0 .. x0 + width`, rows `y0 .. y0 + height` (row 0 on top).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// First column.
    pub x0: usize,
    /// First row.
    pub y0: usize,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
}

impl Region {
    /// The whole image.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let r = spectrace::api::Region::all(&image);
    /// ```
    pub fn all(image: &Image) -> Region {
        Region {
            x0: 0,
            y0: 0,
            width: image.width(),
            height: image.height(),
        }
    }
}

/// A value and its standard error, in the same unit.
#[derive(Clone, Copy, Debug)]
pub struct Estimate<Q> {
    /// The estimate.
    pub value: Q,
    /// Its standard error (from the per-pixel sample variance; NaN when it cannot be
    /// estimated: light tracing and `bdpt` splat into pixels without per-pixel moments).
    pub standard_error: Q,
}

/// A rendered image with typed accessors.
pub struct Image {
    inner: crate::film::Image,
    /// Samples per pixel taken.
    spp: u32,
    /// Whether every pixel's value is a mean of its own camera samples (so its second moment
    /// is known).
    camera_samples: bool,
}

impl Image {
    /// Width, pixels.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let n = image.width() * image.height();
    /// ```
    pub fn width(&self) -> usize {
        self.inner.width
    }

    /// Height, pixels.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let h = image.height();
    /// ```
    pub fn height(&self) -> usize {
        self.inner.height
    }

    fn at(&self, x: usize, y: usize) -> usize {
        assert!(
            x < self.width() && y < self.height(),
            "pixel ({x}, {y}) outside the image"
        );
        y * self.width() + x
    }

    /// Luminance of pixel (x, y) (CIE 1931 Y). Panics outside the image.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// use spectrace::units::luminance::candela_per_square_meter;
    /// let cd = image.luminance(0, 0).get::<candela_per_square_meter>();
    /// ```
    pub fn luminance(&self, x: usize, y: usize) -> Luminance {
        Luminance::new::<luminance::candela_per_square_meter>(
            self.inner.xyz[self.at(x, y)][1] as f64,
        )
    }

    /// CIE 1931 X, Y, Z of pixel (x, y), on the luminance scale (Y in cd/m²).
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let [x, y, z] = image.xyz(0, 0);
    /// ```
    pub fn xyz(&self, x: usize, y: usize) -> [Luminance; 3] {
        self.inner.xyz[self.at(x, y)]
            .map(|v| Luminance::new::<luminance::candela_per_square_meter>(v as f64))
    }

    /// Radiance of pixel (x, y) over the scene's wavelength range.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// use spectrace::units::radiance::watt_per_square_meter_steradian;
    /// let l = image.radiance(0, 0).get::<watt_per_square_meter_steradian>();
    /// ```
    pub fn radiance(&self, x: usize, y: usize) -> Radiance {
        Radiance::new::<radiance::watt_per_square_meter_steradian>(
            self.inner.band[self.at(x, y)] as f64,
        )
    }

    /// Spectral radiance of pixel (x, y) in the spectral bin holding `wavelength` (its mean
    /// over the bin); None without bins ([`Options::spectral_bins`]) or outside the range.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// use spectrace::units::{Length, length::nanometer};
    /// let l = image.spectral_radiance(0, 0, Length::new::<nanometer>(550.0));
    /// ```
    pub fn spectral_radiance(
        &self,
        x: usize,
        y: usize,
        wavelength: Length,
    ) -> Option<SpectralRadiance> {
        let i = self.at(x, y);
        let bins = self.inner.bins.as_ref()?;
        let b = bins.index(wavelength.get::<length::nanometer>() as f32)?;
        Some(SpectralRadiance::new::<
            spectral_radiance::watt_per_square_meter_steradian_nanometer,
        >(self.inner.spectral[b][i] as f64))
    }

    /// The mean luminance over `region` and its standard error: each pixel's mean of `spp`
    /// samples has variance (m₂ − Ȳ²)/(spp − 1), m₂ its mean squared sample, and pixels are
    /// independent (each has its own scrambled sampler), so the region's mean has the variance
    /// Σ varᵢ / N². Panics if the region leaves the image or is empty.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let est = image.mean_luminance(spectrace::api::Region { x0: 0, y0: 0, width: 4, height: 4 });
    /// ```
    pub fn mean_luminance(&self, r: Region) -> Estimate<Luminance> {
        assert!(r.width > 0 && r.height > 0, "empty region");
        let (mut sum, mut var) = (0.0f64, 0.0f64);
        for y in r.y0..r.y0 + r.height {
            for x in r.x0..r.x0 + r.width {
                let i = self.at(x, y);
                let m = self.inner.xyz[i][1] as f64;
                sum += m;
                let m2 = self.inner.xyz_m2[i][1] as f64;
                var += (m2 - m * m).max(0.0) / (self.spp as f64 - 1.0).max(1.0);
            }
        }
        let n = (r.width * r.height) as f64;
        let se = if self.camera_samples && self.spp > 1 {
            var.sqrt() / n
        } else {
            f64::NAN
        };
        let cd = |v: f64| Luminance::new::<luminance::candela_per_square_meter>(v);
        Estimate {
            value: cd(sum / n),
            standard_error: cd(se),
        }
    }
}
