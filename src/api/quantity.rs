//! How a scene built in code writes its values: positions are `[Length; 3]` written in metres
//! (the builder's `length_unit`); directions and scale factors are plain numbers; every other
//! dimensional value is a `uom` quantity written as a quantity string in its SI or photometric
//! unit ([`Radiometric`]), so the loader checks it exactly as it checks a file. Marker traits
//! say which quantities an amount may be (a light's flux: W or lm), so a wrong unit does not
//! compile.

use toml::{Table, Value};

use crate::units::{
    Angle, Illuminance, Irradiance, Length, Luminance, LuminousFlux, LuminousIntensity, Power,
    Radiance, RadiantIntensity, ThermodynamicTemperature,
};
use crate::units::{
    angle, illuminance, irradiance, length, luminance, luminous_flux, luminous_intensity, power,
    radiance, radiant_intensity, thermodynamic_temperature,
};

/// Three lengths from numbers of metres.
///
/// ```
/// use spectrace::units::length::centimeter;
/// let p = spectrace::api::metres([0.0, 2.0, 0.5]);
/// assert_eq!(p[2].get::<centimeter>(), 50.0);
/// ```
pub fn metres(xyz: [f64; 3]) -> [Length; 3] {
    xyz.map(Length::new::<length::meter>)
}

/// An angle from a number of degrees.
///
/// ```
/// use spectrace::units::angle::radian;
/// assert!((spectrace::api::degrees(180.0).get::<radian>() - std::f64::consts::PI).abs() < 1e-12);
/// ```
pub fn degrees(d: f64) -> Angle {
    Angle::new::<angle::degree>(d)
}

/// A quantity written as the scene format's quantity string (`"800e0 lm"`), exactly.
///
/// ```
/// use spectrace::Radiometric;
/// use spectrace::units::{LuminousFlux, luminous_flux::lumen};
/// assert_eq!(LuminousFlux::new::<lumen>(800.0).quantity(), "8e2 lm");
/// ```
pub trait Radiometric: Copy {
    /// The quantity string.
    fn quantity(self) -> String;
}

macro_rules! radiometric {
    ($($t:ty => $m:ident :: $u:ident, $sym:literal;)*) => {$(
        impl Radiometric for $t {
            fn quantity(self) -> String {
                // `{:e}` prints the shortest exact decimal, which the parser reads back exactly
                format!(concat!("{:e} ", $sym), self.get::<$m::$u>())
            }
        }
    )*};
}

// each quantity in the unit of the scene format's table that it is written in
radiometric! {
    Length => length::meter, "m";
    Angle => angle::radian, "rad";
    ThermodynamicTemperature => thermodynamic_temperature::kelvin, "K";
    Power => power::watt, "W";
    LuminousFlux => luminous_flux::lumen, "lm";
    RadiantIntensity => radiant_intensity::watt_per_steradian, "W/sr";
    LuminousIntensity => luminous_intensity::candela, "cd";
    Irradiance => irradiance::watt_per_square_meter, "W/m^2";
    Illuminance => illuminance::lux, "lx";
    Radiance => radiance::watt_per_square_meter_steradian, "W/m^2/sr";
    Luminance => luminance::candela_per_square_meter, "cd/m^2";
}

/// A light's total output: a radiant power (W) or a luminous flux (lm).
///
/// ```
/// use spectrace::units::{Power, power::watt};
/// let lamp = spectrace::Light::point(spectrace::metres([0.0; 3]), Power::new::<watt>(60.0));
/// ```
pub trait Flux: Radiometric {}
impl Flux for Power {}
impl Flux for LuminousFlux {}

/// A point or spot light's intensity: W/sr or cd.
///
/// ```
/// use spectrace::units::{RadiantIntensity, radiant_intensity::watt_per_steradian};
/// let l = spectrace::Light::point_intensity(spectrace::metres([0.0; 3]), RadiantIntensity::new::<watt_per_steradian>(3.0));
/// ```
pub trait Intensity: Radiometric {}
impl Intensity for RadiantIntensity {}
impl Intensity for LuminousIntensity {}

/// Light arriving on a plane: an irradiance (W/m²) or an illuminance (lx).
///
/// ```
/// use spectrace::units::{Irradiance, irradiance::watt_per_square_meter};
/// let sun = spectrace::Light::directional([0.0, -1.0, 0.0], Irradiance::new::<watt_per_square_meter>(1000.0));
/// ```
pub trait FluxDensity: Radiometric {}
impl FluxDensity for Irradiance {}
impl FluxDensity for Illuminance {}

/// An emitter's radiance (W·m⁻²·sr⁻¹) or luminance (cd/m²).
///
/// ```
/// use spectrace::units::{Radiance, radiance::watt_per_square_meter_steradian};
/// let sky = spectrace::Light::environment(Radiance::new::<watt_per_square_meter_steradian>(1.0));
/// ```
pub trait Brightness: Radiometric {
    /// The scene format's key for it.
    const KEY: &'static str;
}
impl Brightness for Radiance {
    const KEY: &'static str = "radiance";
}
impl Brightness for Luminance {
    const KEY: &'static str = "luminance";
}

pub(super) fn point(p: [Length; 3]) -> Value {
    Value::Array(
        p.iter()
            .map(|l| Value::Float(l.get::<length::meter>()))
            .collect(),
    )
}

pub(super) fn vector(v: [f64; 3]) -> Value {
    Value::Array(v.iter().map(|&x| Value::Float(x)).collect())
}

pub(super) fn text(s: impl Into<String>) -> Value {
    Value::String(s.into())
}

pub(super) fn typed(kind: &str) -> Table {
    let mut t = Table::new();
    t.insert("type".into(), text(kind));
    t
}
