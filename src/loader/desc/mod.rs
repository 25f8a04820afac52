//! The scene description: what the file says, validated, with typed quantities (uom) and the
//! source location of every item. `build::build` turns it into a render-ready `Scene`.

use std::path::PathBuf;

pub use crate::film::FilterDesc;
pub use crate::light::SpotFalloff;
pub use crate::material::microfacet::{Distribution, Smith};
pub use crate::scene::{IntegratorKind, LightSelection};
use crate::spectrum::Spectrum;
use crate::spectrum::ior::{ComplexIor, Ior};
pub use crate::texture::{TexFilter, Wrap};
use crate::units::{
    Angle, Illuminance, Irradiance, Length, Luminance, LuminousFlux, LuminousIntensity, Power,
    Radiance, RadiantIntensity,
};

use super::error::Loc;

mod lights;
mod materials;
mod media;
mod shapes;
mod textures;

pub use lights::*;
pub use materials::*;
pub use media::*;
pub use shapes::*;
pub use textures::*;

/// A point or vector given in the scene's length unit, converted to lengths.
pub type Point = [Length; 3];

#[derive(Clone, Debug)]
pub struct SceneDesc {
    /// The scene file, as given.
    pub path: PathBuf,
    /// Shortest and longest simulated wavelength.
    pub wavelength_range: [Length; 2],
    pub camera: CameraDesc,
    pub film: FilmDesc,
    pub integrator: IntegratorDesc,
    pub materials: Vec<MaterialDesc>,
    pub shapes: Vec<ShapeDesc>,
    /// Groups of shapes that are drawn only through `instances` (Mitsuba's `shapegroup`).
    pub groups: Vec<GroupDesc>,
    /// Placements of groups (Mitsuba's `instance`).
    pub instances: Vec<InstanceDesc>,
    pub lights: Vec<LightDesc>,
    /// Participating media, which shapes name as their interior or exterior.
    pub media: Vec<MediumDesc>,
    /// Index into `media` of the medium the camera sits in (None: vacuum).
    pub camera_medium: Option<usize>,
    /// Irradiance and illuminance meters (`[[sensors]]`), measured by `spectrace measure`.
    pub sensors: Vec<SensorDesc>,
    /// What the loader wants the user to know without refusing the file ("file:line: message"),
    /// e.g. a Mitsuba sampler replaced by spectrace's own. Printed once by the CLI.
    pub notes: Vec<String>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    X,
    Y,
    Larger,
    Smaller,
}

#[derive(Clone, Debug)]
pub enum Projection {
    /// Field of view along an axis.
    Fov { fov: Angle, axis: FovAxis },
    /// Focal length and sensor width (horizontal field of view 2·atan(w / 2f)).
    Focal {
        focal_length: Length,
        sensor_width: Length,
    },
}

#[derive(Clone, Debug)]
pub enum CameraKind {
    Perspective {
        projection: Projection,
    },
    /// Thin lens: aperture radius = focal length / (2 · f-number). With a field of view, the focal
    /// length is the one that gives that horizontal field of view on a 36 mm wide sensor.
    ThinLens {
        projection: Projection,
        f_number: f64,
        focus_distance: Length,
    },
    Orthographic {
        view_width: Length,
    },
    /// pbrt-v4's `spherical` camera: every direction on one image, by the equal-area
    /// octahedral mapping or the equirectangular one (`geometry/camera/spherical.rs`).
    Spherical {
        equal_area: bool,
    },
    /// A lens system traced in front of a film (`geometry/camera/realistic.rs`).
    Realistic {
        lens: crate::loader::lens::LensDesc,
        /// The film's diagonal (pbrt-v4's `diagonal`; 35 mm by default).
        film_diagonal: Length,
        /// The stop's diameter, if narrower than the lens file's.
        aperture_diameter: Option<Length>,
        /// Where the film sits: as the lens file says, a distance behind the last vertex, or
        /// focused on a distance from the film.
        focus: LensFocus,
        /// The pixel is the film irradiance per unit radiance (pbrt-v4's realistic camera)
        /// rather than spectrace's radiance-like pixel (`geometry/camera/realistic.rs`).
        irradiance_pixels: bool,
    },
}

/// How a realistic camera is focused.
#[derive(Clone, Debug, PartialEq)]
pub enum LensFocus {
    /// The last thickness of the lens file.
    AsWritten,
    /// The film this far behind the last vertex.
    FilmDistance(Length),
    /// The film moved so a point this far in front of the film is in paraxial focus at the
    /// d line (587.56 nm), as pbrt-v4's `focusdistance` (measured from the film).
    Distance(Length),
}

#[derive(Clone, Debug)]
pub struct CameraDesc {
    pub kind: CameraKind,
    pub eye: Point,
    pub target: Point,
    /// Dimensionless direction.
    pub up: [f64; 3],
    /// The image mirrored left to right: the camera's +x (up × view direction) on the image's
    /// right, as in pbrt's left-handed cameras, where spectrace's (and Mitsuba's) have it on the
    /// left.
    pub mirror: bool,
    /// `[camera.sensor]`.
    pub sensor: Option<CameraSensorDesc>,
    pub loc: Loc,
}

/// A camera's sensor (see `crate::sensor`).
#[derive(Clone, Debug)]
pub struct CameraSensorDesc {
    /// "cie-1931", a camera's name or a file's.
    pub name: String,
    /// r, g, b sensitivities; None for the CIE 1931 observer.
    pub curves: Option<[Spectrum; 3]>,
    pub iso: f64,
    pub shutter: crate::units::Time,
    pub f_number: f64,
    /// The illuminant to balance to (name, spectrum) and how.
    pub white_balance: Option<(String, Spectrum, crate::sensor::Adaptation)>,
    /// What a raw value means (ISO 12232's exposure, or pbrt-v4's sensor).
    pub calibration: crate::sensor::Calibration,
}

#[derive(Clone, Debug)]
pub struct FilmDesc {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    pub filter: FilterDesc,
    /// Number of bins of the spectral EXR output (0: none).
    pub spectral_bins: u32,
    /// Exposure for the PNG preview in EV (None: automatic).
    pub exposure_ev: Option<f64>,
    /// pbrt-v4's firefly clamp (`maxcomponentvalue`): the largest X, Y or Z (cd/m²) one
    /// camera sample's estimate may have; a larger sample is scaled down to it, whole. A
    /// biased estimator, used to reproduce pbrt-v4's images; None: no clamp.
    pub max_component: Option<f64>,
    /// pbrt-v4's `cropwindow` / `pixelbounds`: the film (`width` × `height`) is the window at
    /// pixel `at` of a `full`-sized image, which the camera frames; None: the whole image.
    pub crop: Option<CropDesc>,
    pub loc: Loc,
}

/// A rendered window of a larger image (see [`FilmDesc::crop`]), pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CropDesc {
    pub at: [u32; 2],
    pub full: [u32; 2],
    /// Written as OpenEXR's data window at `at` inside a display window of the full image, as
    /// pbrt-v4 writes a cropped render; false: an image of its own, as Mitsuba 3 writes one.
    pub data_window: bool,
}

#[derive(Clone, Debug)]
pub struct IntegratorDesc {
    pub kind: IntegratorKind,
    pub max_depth: u32,
    /// Russian roulette may end a camera path at surface hit k only when k > `rr_depth` (hits
    /// counted from 1 at the first surface the camera ray meets): Mitsuba 3's `rr_depth`.
    pub rr_depth: u32,
    /// How next-event estimation chooses among the lights.
    pub light_selection: LightSelection,
    /// Also write each pixel's second moment (the mean of the squared sample values), as
    /// Mitsuba's `moment` integrator does around another one.
    pub moment: bool,
    /// Render polarised (Stokes vectors along paths, S0–S3 written), as Mitsuba's `stokes`
    /// integrator in a polarised variant asks; a scene holding a polarising element renders
    /// polarised whatever this says.
    pub polarised: bool,
    /// TOML `dispersion = "split"` (the default) or `"hero"`. A camera path that meets a
    /// dispersive interface keeps only its hero wavelength (Wilkie et al. 2014 §4); with
    /// `split`, the sample is traced again with each of its other wavelengths as the hero and
    /// each wavelength keeps its own path's estimate (`integrator::split`), so a sample through
    /// glass carries every wavelength. Unbiased either way; `split` costs a path per
    /// wavelength where the camera sees through dispersive glass and lowers the colour noise
    /// there.
    pub split_dispersion: bool,
    /// First-hit quantities written beside the image (Mitsuba's `aov`).
    pub aovs: Vec<crate::scene::Aov>,
    /// A `null` surface is a medium boundary that the path, light and bidirectional tracers
    /// pass without a bounce, as pbrt-v4's `interface` (its `SkipIntersection` in `path`,
    /// `lightpath` and BDPT's random walks; BDPT's connections pass it too, pbrt-v4's `Tr`).
    /// False: a delta transmission counted toward `max_depth`, as Mitsuba 3's `null`.
    /// (`volpath` passes them either way.)
    pub skip_null: bool,
}

/// Default `rr_depth`, Mitsuba 3's: paths keep their first five surface hits.
pub const DEFAULT_RR_DEPTH: u32 = 5;

/// Where a meter measures.
#[derive(Clone, Debug)]
pub enum SensorKind {
    /// One point; `normal` (dimensionless, non-zero) is the side measured.
    Point { position: Point, normal: [f64; 3] },
    /// `count[0] × count[1]` points at the centres of the cells of the parallelogram
    /// `corner + s·edge_u + t·edge_v` (s, t in [0, 1]), measuring the side of `normal`.
    Grid {
        corner: Point,
        edge_u: Point,
        edge_v: Point,
        count: [u32; 2],
        normal: [f64; 3],
    },
}

/// A meter (`[[sensors]]`).
#[derive(Clone, Debug)]
pub struct SensorDesc {
    pub name: String,
    pub kind: SensorKind,
    pub loc: Loc,
}
