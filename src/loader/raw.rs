//! The scene file as TOML, before validation: every section is a flat struct with spans, and
//! unknown keys are errors (`deny_unknown_fields`). `convert.rs` checks which keys apply to
//! which `type` and turns values into typed quantities.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::{Spanned, Value};

pub type S<T> = Spanned<T>;

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub scene: Option<S<RawSettings>>,
    pub camera: Option<S<RawCamera>>,
    pub film: Option<S<RawFilm>>,
    pub integrator: Option<S<RawIntegrator>>,
    #[serde(default)]
    pub materials: BTreeMap<S<String>, S<RawMaterial>>,
    /// Participating media (`[media.NAME]`), read by `convert/items/media.rs` from their keys.
    #[serde(default)]
    pub media: BTreeMap<S<String>, S<RawMaterial>>,
    #[serde(default)]
    pub shapes: Vec<S<RawShape>>,
    #[serde(default)]
    pub lights: Vec<S<RawLight>>,
    /// Groups of shapes drawn only through `instances` (`[[groups.NAME.shapes]]`).
    #[serde(default)]
    pub groups: BTreeMap<S<String>, S<RawGroup>>,
    #[serde(default)]
    pub instances: Vec<S<RawInstance>>,
    /// Irradiance and illuminance meters (`spectrace measure`).
    #[serde(default)]
    pub sensors: Vec<S<RawSensor>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawSensor {
    #[serde(rename = "type")]
    pub kind: Option<S<String>>,
    pub name: Option<S<String>>,
    pub position: Option<S<Value>>,
    pub normal: Option<S<Value>>,
    pub corner: Option<S<Value>>,
    pub edge_u: Option<S<Value>>,
    pub edge_v: Option<S<Value>>,
    pub count: Option<S<Value>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawGroup {
    #[serde(default)]
    pub shapes: Vec<S<RawShape>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawInstance {
    pub group: Option<S<String>>,
    pub transform: Option<S<Vec<S<Value>>>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawSettings {
    pub length_unit: Option<S<String>>,
    pub wavelength_range: Option<S<Vec<S<Value>>>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawCamera {
    #[serde(rename = "type")]
    pub kind: Option<S<String>>,
    pub eye: Option<S<Value>>,
    pub target: Option<S<Value>>,
    pub up: Option<S<Value>>,
    pub fov: Option<S<Value>>,
    pub fov_axis: Option<S<String>>,
    pub focal_length: Option<S<Value>>,
    pub sensor_width: Option<S<Value>>,
    pub f_number: Option<S<Value>>,
    pub focus_distance: Option<S<Value>>,
    pub view_width: Option<S<Value>>,
    /// A realistic camera's lens file (pbrt-v4's format, `loader/lens.rs`).
    pub lens_file: Option<S<String>>,
    pub film_diagonal: Option<S<Value>>,
    pub aperture_diameter: Option<S<Value>>,
    pub film_distance: Option<S<Value>>,
    /// The name of the medium the camera sits in (`[media.NAME]`).
    pub medium: Option<S<String>>,
    /// `[camera.sensor]`: spectral sensitivities, exposure and white balance.
    pub sensor: Option<S<RawCameraSensor>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawCameraSensor {
    pub curves: Option<S<String>>,
    pub file: Option<S<String>>,
    pub iso: Option<S<Value>>,
    pub shutter: Option<S<Value>>,
    pub f_number: Option<S<Value>>,
    pub white_balance: Option<S<String>>,
    pub adaptation: Option<S<String>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawFilm {
    pub width: Option<S<Value>>,
    pub height: Option<S<Value>>,
    pub spp: Option<S<Value>>,
    pub filter: Option<S<Value>>,
    pub filter_radius: Option<S<Value>>,
    pub spectral_bins: Option<S<Value>>,
    pub exposure: Option<S<Value>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawIntegrator {
    #[serde(rename = "type")]
    pub kind: Option<S<String>>,
    pub max_depth: Option<S<Value>>,
    pub rr_depth: Option<S<Value>>,
    pub light_selection: Option<S<String>>,
    /// `split` (default) or `hero`: what a camera path does at its first dispersive hit.
    pub dispersion: Option<S<String>>,
    /// `direct`: light and BSDF samples per camera hit.
    pub emitter_samples: Option<S<Value>>,
    pub bsdf_samples: Option<S<Value>>,
    /// Also write second moments (`m2.X`, `m2.Y`, `m2.Z`), as Mitsuba's `moment`.
    pub second_moment: Option<S<bool>>,
    /// Render polarised: every path carries Stokes vectors, the image gains S1–S3 channels.
    pub polarised: Option<S<bool>>,
}

/// A material's keys, `type` and the kind's own, read by the kind's reader
/// (`convert/items/materials/`), which rejects the keys it does not take.
#[derive(Deserialize, Debug)]
#[serde(transparent)]
pub struct RawMaterial(pub BTreeMap<String, S<Value>>);

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawShape {
    #[serde(rename = "type")]
    pub kind: Option<S<String>>,
    pub material: Option<S<String>>,
    pub file: Option<S<String>>,
    pub center: Option<S<Value>>,
    pub radius: Option<S<Value>>,
    pub transform: Option<S<Vec<S<Value>>>>,
    pub two_sided: Option<S<bool>>,
    pub emission: Option<S<RawEmission>>,
    pub vertices: Option<S<Vec<S<Value>>>>,
    pub faces: Option<S<Vec<S<Value>>>>,
    /// Names of the media inside and outside the shape (`[media.NAME]`).
    pub interior: Option<S<String>>,
    pub exterior: Option<S<String>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawEmission {
    pub spectrum: Option<S<Value>>,
    pub radiance: Option<S<Value>>,
    pub luminance: Option<S<Value>>,
    pub power: Option<S<Value>>,
    pub scale: Option<S<Value>>,
    pub two_sided: Option<S<bool>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawLight {
    #[serde(rename = "type")]
    pub kind: Option<S<String>>,
    pub spectrum: Option<S<Value>>,
    pub position: Option<S<Value>>,
    pub target: Option<S<Value>>,
    pub direction: Option<S<Value>>,
    pub power: Option<S<Value>>,
    pub intensity: Option<S<Value>>,
    pub radiance: Option<S<Value>>,
    pub luminance: Option<S<Value>>,
    pub irradiance: Option<S<Value>>,
    pub scale: Option<S<Value>>,
    pub cone_angle: Option<S<Value>>,
    pub falloff_start: Option<S<Value>>,
    pub falloff: Option<S<Value>>,
    pub angular_diameter: Option<S<Value>>,
    pub radius: Option<S<Value>>,
    /// A beam's slit, [width, height].
    pub slit: Option<S<Value>>,
    /// An environment map's image file.
    pub image: Option<S<String>>,
    /// A luminaire's photometric file (.ies or .ldt).
    pub file: Option<S<String>>,
    /// A luminaire's C = 0° direction.
    pub c0: Option<S<Value>>,
    /// The tilt a luminaire's tilt table is read at.
    pub tilt: Option<S<Value>>,
    /// A sky's model ("cie-overcast", "cie-1" … "cie-15").
    pub model: Option<S<String>>,
    /// The sun by angles: elevation above the horizon and azimuth clockwise from north.
    pub sun_elevation: Option<S<Value>>,
    pub sun_azimuth: Option<S<Value>>,
    /// The sun by place and time (deg, east positive; ISO 8601 with a zone).
    pub latitude: Option<S<Value>>,
    pub longitude: Option<S<Value>>,
    pub time: Option<S<String>>,
    /// The scene's up and north directions for the sky and the sun.
    pub up: Option<S<Value>>,
    pub north: Option<S<Value>>,
    /// An environment map's rotation (transform steps, as shapes have).
    pub transform: Option<S<Vec<S<Value>>>>,
}
