//! The scene description: what the file says, validated, with typed quantities (uom) and the
//! source location of every item. `build::build` turns it into a render-ready `Scene`.

use std::path::PathBuf;

pub use crate::film::FilterDesc;
pub use crate::light::SpotFalloff;
pub use crate::material::microfacet::Distribution;
pub use crate::scene::{IntegratorKind, LightSelection};
use crate::spectrum::Spectrum;
use crate::spectrum::ior::{ComplexIor, Ior};
pub use crate::texture::{TexFilter, Wrap};
use crate::units::{
    Angle, Illuminance, Irradiance, Length, Luminance, LuminousFlux, LuminousIntensity, Power,
    Radiance, RadiantIntensity,
};

use super::error::Loc;

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
}

#[derive(Clone, Debug)]
pub struct CameraDesc {
    pub kind: CameraKind,
    pub eye: Point,
    pub target: Point,
    /// Dimensionless direction.
    pub up: [f64; 3],
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
    pub loc: Loc,
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
}

/// Default `rr_depth`, Mitsuba 3's: paths keep their first five surface hits.
pub const DEFAULT_RR_DEPTH: u32 = 5;

#[derive(Clone, Debug)]
pub enum MaterialKind {
    Diffuse {
        reflectance: TextureDesc,
    },
    Phong {
        kd: Spectrum,
        ks: Spectrum,
        exponent: f64,
    },
    /// Smooth when `roughness` is None, else microfacets of `distribution` with roughness
    /// [α_u, α_v]: α_u along the surface's ∂p/∂u, α_v across it (equal when isotropic).
    Dielectric {
        ior: Ior,
        exterior_ior: f64,
        roughness: Option<[f64; 2]>,
        distribution: Distribution,
    },
    /// As a dielectric's: smooth, or roughness [α_u, α_v].
    Conductor {
        ior: ComplexIor,
        exterior_ior: f64,
        roughness: Option<[f64; 2]>,
        distribution: Distribution,
    },
    /// No surface: light passes straight through (Mitsuba's `null`).
    Null,
    /// A partly transparent surface (Mitsuba's `mask`): `opacity` (a number or a grey image)
    /// of the nested material, the rest straight through.
    Mask {
        opacity: TextureDesc,
        inner: Box<MaterialKind>,
    },
    /// A blend (Mitsuba's `blendbsdf`): (1 − weight)·f_a + weight·f_b, weight a number or a
    /// grey image in [0, 1].
    Blend {
        weight: TextureDesc,
        a: Box<MaterialKind>,
        b: Box<MaterialKind>,
    },
    /// Mitsuba's `normalmap`: `map` an image of raw triples, each a local normal encoded as
    /// (n + 1)/2, around the nested material.
    NormalMap {
        map: TextureDesc,
        inner: Box<MaterialKind>,
    },
    /// Mitsuba's `bumpmap`: a grey `height` image times `scale` displacing the shading normal
    /// of the nested material.
    BumpMap {
        height: TextureDesc,
        scale: f64,
        inner: Box<MaterialKind>,
    },
    /// A conductor or dielectric (`inner`) with textured parameters: roughness [α_u, α_v] as
    /// grey textures (rough materials), and factors on the reflected and transmitted lobes
    /// (Mitsuba's `specular_reflectance`, `specular_transmittance`).
    Textured {
        alpha: Option<Box<[TextureDesc; 2]>>,
        reflectance: TextureDesc,
        transmittance: TextureDesc,
        inner: Box<MaterialKind>,
    },
    /// A sheet of negligible thickness (Mitsuba's `thindielectric`), indices as a dielectric's.
    ThinDielectric {
        int_ior: f64,
        exterior_ior: f64,
    },
    /// A diffuse base under a dielectric coating (Mitsuba's `plastic`, and `roughplastic` when
    /// `roughness` is given; see `crate::material::Plastic`).
    Plastic {
        diffuse: TextureDesc,
        /// A factor on the coating's reflection (Mitsuba's `specular_reflectance`), 1 by default.
        specular: f64,
        int_ior: f64,
        exterior_ior: f64,
        nonlinear: bool,
        roughness: Option<f64>,
        distribution: Distribution,
    },
}

/// A spectral quantity that may vary over a surface (see `crate::texture`).
#[derive(Clone, Debug)]
pub enum TextureDesc {
    /// The same spectrum everywhere.
    Uniform(Spectrum),
    /// Mitsuba's checkerboard: `a` on the checks where the fractional parts of `to_uv`(uv) are
    /// both ≤ ½ or both > ½, else `b`.
    Checkerboard {
        a: Spectrum,
        b: Spectrum,
        to_uv: Vec<TransformStep>,
    },
    /// An image file (PNG, EXR, HDR), read when the scene is built.
    Bitmap {
        path: PathBuf,
        filter: TexFilter,
        wrap: Wrap,
        /// Use 8- and 16-bit values as stored instead of decoding sRGB; colour images cannot
        /// then be spectra (Mitsuba's `raw`), so only grey images are accepted with it.
        raw: bool,
        to_uv: Vec<TransformStep>,
        loc: Loc,
    },
}

impl TextureDesc {
    /// The same texture with an image's values read as stored (`raw`), for images of numbers
    /// (normals, heights, roughness) rather than colours; other textures unchanged.
    pub fn raw(self) -> TextureDesc {
        match self {
            TextureDesc::Bitmap {
                path,
                filter,
                wrap,
                to_uv,
                loc,
                ..
            } => TextureDesc::Bitmap {
                path,
                filter,
                wrap,
                raw: true,
                to_uv,
                loc,
            },
            other => other,
        }
    }
}

impl From<Spectrum> for TextureDesc {
    fn from(s: Spectrum) -> Self {
        TextureDesc::Uniform(s)
    }
}

#[derive(Clone, Debug)]
pub struct MaterialDesc {
    pub name: String,
    pub kind: MaterialKind,
    pub loc: Loc,
}

#[derive(Clone, Debug)]
pub enum TransformStep {
    Translate(Point),
    Rotate {
        axis: [f64; 3],
        angle: Angle,
    },
    Scale([f64; 3]),
    /// Row-major 4×4; the translation column is in the scene's length unit, converted to metres.
    Matrix([f64; 16]),
    LookAt {
        eye: Point,
        target: Point,
        up: [f64; 3],
    },
}

#[derive(Clone, Debug)]
pub enum ShapeKind {
    Sphere {
        center: Point,
        radius: Length,
    },
    /// The square [-1, 1]² in the object's z = 0 plane, normal +z, scaled by the length unit.
    Rectangle,
    /// The cube [-1, 1]³, scaled by the length unit.
    Box,
    /// The unit disk in the object's z = 0 plane, normal +z, scaled by the length unit.
    Disk,
    /// The open tube of `radius` around the segment `p0`–`p1` (Mitsuba's `cylinder`), normals
    /// away from the axis unless `flipped`.
    Cylinder {
        p0: Point,
        p1: Point,
        radius: Length,
        flipped: bool,
    },
    /// A Wavefront OBJ mesh; coordinates in the scene's length unit.
    Obj {
        path: PathBuf,
        normals: MeshNormals,
    },
    /// Mesh `shape_index` of a Mitsuba `.serialized` file; coordinates in the scene's length
    /// unit.
    Serialized {
        path: PathBuf,
        shape_index: usize,
        normals: MeshNormals,
    },
    /// A Stanford PLY mesh; coordinates in the scene's length unit.
    Ply {
        path: PathBuf,
        normals: MeshNormals,
    },
    /// A triangle mesh written in the scene file: vertices in the scene's length unit and
    /// 0-based triangle indices.
    Inline {
        vertices: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
    },
}

/// The vertex normals a mesh file is shaded with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshNormals {
    /// The file's normals; face normals (flat shading) if it has none. spectrace's native
    /// reading.
    FromFile,
    /// The file's normals; if it has none, smooth normals computed from the faces, weighted by
    /// angle (Mitsuba 3's default for `obj` and `ply`).
    FromFileOrSmooth,
    /// Face normals only, whatever the file holds (Mitsuba's `face_normals = true`).
    Flat,
}

/// How much light an area emitter gives; its spectrum gives the shape.
/// How bright an environment map is (see `build/lights.rs`).
#[derive(Clone, Debug)]
pub enum EnvMapAmount {
    /// A factor on the illuminant of an RGB (1, 1, 1) pixel.
    Scale(f64),
    /// Mean band radiance over the sphere.
    Radiance(Radiance),
    /// Mean luminance over the sphere.
    Luminance(Luminance),
    /// Irradiance on a plane facing the map's zenith (+y of its frame, after its transform).
    Irradiance(Irradiance),
    /// Illuminance on a plane facing the map's zenith.
    Illuminance(Illuminance),
}

#[derive(Clone, Debug)]
pub enum EmitAmount {
    Radiance(Radiance),
    Luminance(Luminance),
    Power(Power),
    LuminousFlux(LuminousFlux),
    /// The spectrum is already spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹; multiply by this.
    Scale(f64),
}

#[derive(Clone, Debug)]
pub struct EmissionDesc {
    pub spectrum: Spectrum,
    /// A radiance that varies over the surface (Mitsuba's textured `radiance`), in place of
    /// `spectrum`, read as given (W·m⁻²·sr⁻¹·nm⁻¹ per texel value).
    pub texture: Option<TextureDesc>,
    pub amount: EmitAmount,
    pub two_sided: bool,
    /// As [`LightDesc::sampling_weight`].
    pub sampling_weight: f64,
    pub loc: Loc,
}

#[derive(Clone, Debug)]
pub struct ShapeDesc {
    pub kind: ShapeKind,
    /// Applied in order, first to last, after converting the object to metres.
    pub transform: Vec<TransformStep>,
    /// Index into `SceneDesc::materials`; None for a pure emitter (black).
    pub material: Option<usize>,
    pub two_sided: bool,
    pub emission: Option<EmissionDesc>,
    /// Metres per scene length unit (for OBJ coordinates and unit shapes).
    pub unit_m: f64,
    pub loc: Loc,
}

/// Shapes in their own object space, drawn once per instance: one BVH per group, so that a
/// thousand instances cost one group's memory (Mitsuba's `shapegroup`). No emitters.
#[derive(Clone, Debug)]
pub struct GroupDesc {
    pub id: String,
    pub shapes: Vec<ShapeDesc>,
    pub loc: Loc,
}

/// A group placed by a transform (Mitsuba's `instance`).
#[derive(Clone, Debug)]
pub struct InstanceDesc {
    /// Index into `SceneDesc::groups`.
    pub group: usize,
    /// Applied in order, first to last (metres; a matrix's translation in `unit_m` metres).
    pub transform: Vec<TransformStep>,
    /// Metres per scene length unit.
    pub unit_m: f64,
    pub loc: Loc,
}

/// How strong a point or spot light is.
#[derive(Clone, Debug)]
pub enum PointAmount {
    Power(Power),
    LuminousFlux(LuminousFlux),
    Intensity(RadiantIntensity),
    LuminousIntensity(LuminousIntensity),
    /// The spectrum is already spectral intensity in W·sr⁻¹·nm⁻¹; multiply by this.
    Scale(f64),
}

/// How strong a directional light is, measured on a plane perpendicular to it.
#[derive(Clone, Debug)]
pub enum DirectionalAmount {
    Irradiance(Irradiance),
    Illuminance(Illuminance),
    /// The spectrum is already spectral irradiance in W·m⁻²·nm⁻¹; multiply by this.
    Scale(f64),
}

#[derive(Clone, Debug)]
pub enum LightKind {
    Point {
        position: Point,
        amount: PointAmount,
    },
    /// Full intensity inside `falloff_start`, falling as `falloff` says to zero at
    /// `cone_angle` (half-angles).
    Spot {
        position: Point,
        target: Point,
        cone_angle: Angle,
        falloff_start: Angle,
        falloff: SpotFalloff,
        amount: PointAmount,
        /// Mitsuba's spot `texture`: an image across the cone, in the frame of `transform`
        /// (whose +z is the axis); see `crate::light::SpotLight`.
        texture: Option<Box<(TextureDesc, Vec<TransformStep>)>>,
    },
    /// Light travelling along `direction` (dimensionless); a disk of `angular_diameter` if > 0.
    Directional {
        direction: [f64; 3],
        angular_diameter: Angle,
        amount: DirectionalAmount,
    },
    /// Uniform radiance from every direction.
    Environment { amount: EmitAmount },
    /// Radiance from a latitude–longitude image (see `crate::light::EnvMapLight`): the light's
    /// `spectrum` is the illuminant an RGB (1, 1, 1) pixel has, and `amount` scales it
    /// (`Scale`), or sets the mean radiance or luminance over the sphere.
    EnvMap {
        path: PathBuf,
        /// Rotation from the map's frame (+y up) to the world.
        transform: Vec<TransformStep>,
        amount: EnvMapAmount,
    },
    /// Mitsuba's `projector`: `image` projected from the origin of `transform` (rigid) along
    /// its +z, with the field of view `fov` across the image's x (`fov_axis_y`: across y), the
    /// light's `spectrum` multiplying the image (see `crate::light::ProjectorLight`).
    Projector {
        transform: Vec<TransformStep>,
        fov: Angle,
        fov_axis_y: bool,
        image: TextureDesc,
    },
    /// A measured luminaire (an IES LM-63 or EULUMDAT file, `crate::light::GoniometricLight`):
    /// its photometric nadir (γ = 0°) points from `position` at `target`, its C = 0° plane
    /// toward `c0` (a direction, made perpendicular to the nadir; None: world +x, or +z when
    /// the nadir is within 25° of the x axis), and the file's tilt table is read at `tilt`.
    /// The light's `spectrum` shapes the emission; the file gives the candela.
    Luminaire {
        position: Point,
        target: Point,
        c0: Option<[f64; 3]>,
        tilt: Angle,
        photometry: Box<crate::loader::photometric::Photometry>,
        amount: LuminaireAmount,
    },
    /// A CIE sky (`crate::daylight::sky`) above the plane perpendicular to `up`, its sun toward
    /// `sun` (unit, world; it shapes the sky, it is not itself a light), radiance
    /// L_z·(L/L_z)(direction)·S(λ)/(K_m ∫ S ȳ dλ) with the zenith luminance L_z from `amount`.
    Sky {
        model: crate::daylight::sky::SkyModel,
        sun: [f64; 3],
        up: [f64; 3],
        amount: SkyAmount,
    },
    /// A collimated beam leaving a disk of `radius` at `position` toward `target`; `amount` is
    /// its total power (W or lm) or a scale of a spectrum already in W·nm⁻¹.
    Beam {
        position: Point,
        target: Point,
        radius: Length,
        amount: PointAmount,
    },
}

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

/// How bright a sky is: its zenith luminance, or the illuminance (or band irradiance) it
/// gives an unobstructed horizontal plane.
#[derive(Clone, Debug)]
pub enum SkyAmount {
    ZenithLuminance(Luminance),
    HorizontalIlluminance(Illuminance),
    HorizontalIrradiance(Irradiance),
}

/// How bright a luminaire is: as its file says, scaled, or set to a total flux.
#[derive(Clone, Debug)]
pub enum LuminaireAmount {
    /// The file's absolute candela (times the tilt factor).
    File,
    /// The file's candela (times the tilt factor) times this.
    Scale(f64),
    /// The distribution rescaled to this total luminous flux.
    LuminousFlux(LuminousFlux),
    /// The distribution rescaled to this radiant power over the film's wavelength range.
    Power(Power),
}

#[derive(Clone, Debug)]
pub struct LightDesc {
    pub kind: LightKind,
    pub spectrum: Spectrum,
    /// Relative weight for choosing this light under [`LightSelection::Uniform`] (Mitsuba's
    /// `sampling_weight`, 1 by default).
    pub sampling_weight: f64,
    pub loc: Loc,
}
