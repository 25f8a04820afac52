//! Lights and the amounts that set their scale.

use super::*;

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
    /// Radiance from a square image in pbrt-v4's equal-area octahedral layout (see
    /// `crate::light::OctahedralMapLight`): the light's `spectrum` is the illuminant of an RGB
    /// (1, 1, 1) pixel, `amount` scales it (irradiance and illuminance on a plane facing the
    /// map's +z, pbrt-v4's "up").
    OctahedralMap {
        path: PathBuf,
        /// Rotation from the map's frame to the world.
        transform: Vec<TransformStep>,
        amount: EnvMapAmount,
    },
    /// Mitsuba's `projector` or pbrt-v4's `projection`: `image` projected from the origin of
    /// `transform` (rigid) along its +z, with the field of view `fov` across the image's
    /// `fov_axis`, the light's `spectrum` multiplying the image (see
    /// `crate::light::ProjectorLight`): Mitsuba's plane irradiance π·spectrum·image, or, with
    /// `constant_intensity`, pbrt-v4's intensity spectrum·image.
    Projector {
        transform: Vec<TransformStep>,
        fov: Angle,
        fov_axis: crate::loader::desc::FovAxis,
        image: TextureDesc,
        constant_intensity: bool,
    },
    /// pbrt-v4's `goniometric` light (`crate::light::GoniometricMapLight`): a point at the
    /// origin of `transform` (rigid) whose intensity is the light's `spectrum` times the grey
    /// of the square image at `path` (the mean of its linear R, G, B; 8- and 16-bit files
    /// decoded from sRGB), laid over the directions of the transform's frame in the
    /// equal-area octahedral layout.
    GoniometricMap {
        path: PathBuf,
        transform: Vec<TransformStep>,
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
        section: BeamSection,
        amount: PointAmount,
    },
}

/// A beam's cross-section.
#[derive(Clone, Debug)]
pub enum BeamSection {
    /// A disk of this radius.
    Disk(Length),
    /// A slit: `width` across, `height` along `up` (a unit vector across the beam).
    Slit {
        width: Length,
        height: Length,
        up: [f64; 3],
    },
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
