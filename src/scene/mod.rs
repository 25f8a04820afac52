//! The immutable, render-ready scene: plain `f32` values in fixed units (nm, m, rad,
//! W·m⁻²·sr⁻¹·nm⁻¹), closed enums, no strings or parameter maps. [`crate::build::build`] makes it from a
//! [`crate::loader::SceneDesc`] in one place.

mod settings;

pub use settings::{Aov, AovKind, IntegratorKind, LightSelection};

use glam::Vec3;

use crate::film::Filter;
use crate::geometry::accel::Accel;
use crate::geometry::camera::Camera;
use crate::geometry::shape::Shape;
use crate::light::Light;
use crate::material::Material;
use crate::spectrum::WavelengthRange;

/// What a shape is made of: its material, whether both faces use it, and its emitter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Surface {
    /// Index into [`Scene::materials`]; None for a black, purely emitting shape.
    pub material: Option<u32>,
    /// Whether the back face uses the material too (the integrator flips the shading frame).
    pub two_sided: bool,
    /// Index into [`Scene::lights`] of the shape's area light.
    pub light: Option<u32>,
    /// Whether the material reads the mesh's attributes (the integrator then finds the hit's
    /// barycentric weights); only for meshes of the scene's own list, not of groups.
    pub attributes: bool,
}

/// Film settings in plain units.
#[derive(Clone, Debug)]
pub struct FilmSettings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// The pixel filter, tabulated for sampling by the build step.
    pub filter: Filter,
    /// Bins of the spectral EXR output (0: none).
    pub spectral_bins: u32,
    /// PNG exposure in EV (None: automatic).
    pub exposure_ev: Option<f32>,
    /// The largest X, Y or Z (cd/m²) of one camera sample's estimate (pbrt-v4's
    /// `maxcomponentvalue`, see [`crate::film::clamp_max_component`]); None: no clamp.
    pub max_component: Option<f32>,
    /// The image is the window at pixel `.0` of a `.1`-sized image (pixels), to be written as
    /// the EXR's data window inside that display window (pbrt-v4's cropped renders); None: an
    /// image of its own.
    pub data_window: Option<([u32; 2], [u32; 2])>,
}

/// Integrator settings.
#[derive(Clone, Debug, PartialEq)]
pub struct IntegratorSettings {
    pub kind: IntegratorKind,
    pub max_depth: u32,
    /// Surface hits a camera path keeps before Russian roulette may end it (see
    /// [`crate::loader::desc::IntegratorDesc::rr_depth`]).
    pub rr_depth: u32,
    /// How next-event estimation chooses among the lights.
    pub light_selection: LightSelection,
    /// Write second moments (see [`crate::loader::desc::IntegratorDesc::moment`]).
    pub moment: bool,
    /// Render polarised: paths carry a Stokes vector per wavelength
    /// (`integrator::stokes`) and the film sums S1–S3 beside S0. Set by the scene's integrator
    /// or by any polarising element among its materials.
    pub polarised: bool,
    /// At a camera path's first dispersive hit, estimate every wavelength by a path of its
    /// own instead of keeping the hero alone (see
    /// [`crate::loader::desc::IntegratorDesc::split_dispersion`]).
    pub split_dispersion: bool,
    /// First-hit quantities to write beside the image (see [`crate::render::aov`]).
    pub aovs: Vec<Aov>,
    /// `null` surfaces passed without a bounce (see
    /// [`crate::loader::desc::IntegratorDesc::skip_null`]).
    pub skip_null: bool,
}

/// A render-ready scene. Shapes are in world space, metres.
pub struct Scene {
    pub shapes: Vec<Shape>,
    /// One entry per shape.
    pub surfaces: Vec<Surface>,
    pub accel: Accel,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    /// Indices into `lights` of the lights at infinity, which rays that escape can see (so an
    /// escaped ray does not visit every light).
    pub infinite_lights: Vec<u32>,
    /// Emitted power of each light over the wavelength range, W (lights at infinity: through a
    /// disk of the scene's radius), for light selection proportional to power.
    pub light_power: Vec<f64>,
    /// The light tree over the lights (next-event estimation's default selection, see
    /// [`crate::light::LightTree`]).
    pub light_tree: crate::light::LightTree,
    /// Relative weight of each light under uniform light selection (Mitsuba's
    /// `sampling_weight`, 1 unless the scene sets it).
    pub light_sampling_weights: Vec<f64>,
    pub camera: Camera,
    pub film: FilmSettings,
    pub integrator: IntegratorSettings,
    pub wavelengths: WavelengthRange,
    /// Axis-aligned bounds of all shapes, m.
    pub bounds: (Vec3, Vec3),
    /// Irradiance meters, measured by `spectrace measure` (not by rendering).
    pub meters: Vec<Meter>,
    /// The camera's sensor (`[camera.sensor]`): raw values and exposure in the EXR.
    pub camera_sensor: Option<crate::sensor::CameraSensor>,
    /// Participating media; empty in a scene without any, which renders with the surface
    /// estimators alone.
    pub media: Vec<crate::medium::Medium>,
    /// The media on either side of each shape (indexed as `surfaces`); empty when `media` is.
    pub medium_interfaces: Vec<crate::medium::MediumInterface>,
    /// Index into `media` of the medium the camera sits in (None: vacuum).
    pub camera_medium: Option<u32>,
}

/// A point where irradiance is measured: position (m) and unit normal of the measured side.
#[derive(Clone, Copy, Debug)]
pub struct MeterPoint {
    pub p: Vec3,
    pub n: Vec3,
}

/// A named meter: one point, or a grid of `grid[0] × grid[1]` points, row `j` of `grid[1]`
/// holding points `j·grid[0] .. (j + 1)·grid[0]` along the first edge.
#[derive(Clone, Debug)]
pub struct Meter {
    pub name: String,
    pub grid: [u32; 2],
    pub points: Vec<MeterPoint>,
}

impl Meter {
    /// The grid cell (i along the first edge, j along the second) of point `k`.
    pub fn cell(&self, k: usize) -> [u32; 2] {
        let nu = self.grid[0].max(1) as usize;
        [(k % nu) as u32, (k / nu) as u32]
    }
}

impl Scene {
    /// Barycentric weights of a hit on a mesh of the scene's own list (for mesh attributes);
    /// (1, 0, 0) for other shapes.
    pub fn barycentrics(&self, hit: &crate::geometry::shape::Intersection) -> [f32; 3] {
        match self.shapes.get(hit.shape as usize) {
            Some(crate::geometry::shape::Shape::Mesh(m)) => {
                m.barycentrics(hit.prim as usize, hit.p)
            }
            _ => [1.0, 0.0, 0.0],
        }
    }

    /// Every meter's points, meter after meter (a grid's row by row), as `measure` reads them.
    pub fn meter_points(&self) -> Vec<MeterPoint> {
        self.meters
            .iter()
            .flat_map(|m| m.points.iter().copied())
            .collect()
    }

    /// Centre and radius (m) of a sphere bounding every shape.
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        let (lo, hi) = self.bounds;
        if lo.x > hi.x {
            return (Vec3::ZERO, 1.0);
        }
        ((lo + hi) * 0.5, ((hi - lo) * 0.5).length().max(1e-3))
    }
}
