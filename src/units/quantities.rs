//! spectrace's system of quantities, built with uom's `system!` and `quantity!` macros.
//!
//! uom's own SI system cannot be extended from outside the crate, and it has no radiance, so the
//! project defines the subset of the ISQ it needs here, with the seven SI base dimensions.
//!
//! Radiometric quantities that share a dimension with another quantity carry their own *kind*:
//! radiance (W·m⁻²·sr⁻¹) and irradiance (W·m⁻²) are both M·T⁻³ because the steradian is
//! dimensionless, but their kinds differ, so `radiance + irradiance` does not compile.
//!
//! ```compile_fail
//! use spectrace::units::{Irradiance, Radiance};
//! let l = Radiance::new::<spectrace::units::radiance::watt_per_square_meter_steradian>(1.0);
//! let e = Irradiance::new::<spectrace::units::irradiance::watt_per_square_meter>(1.0);
//! let _ = l + e; // error: mismatched kinds
//! ```
//!
//! ```compile_fail
//! use spectrace::units::{LuminousFlux, LuminousIntensity};
//! let f = LuminousFlux::new::<spectrace::units::luminous_flux::lumen>(1.0);
//! let i = LuminousIntensity::new::<spectrace::units::luminous_intensity::candela>(1.0);
//! let _ = f + i; // error: lumens are not candelas
//! ```

// Conversion factors are written to f64 precision (the degree is π/180 to 17 digits); uom also
// instantiates them for f32, where clippy calls such literals excessively precise.
#![allow(clippy::excessive_precision)]
#![allow(missing_docs)]

/// Kind of plane angles (rad), separate from dimensionless ratios.
pub trait AngleKind: uom::Kind {}
/// Kind of solid angles (sr).
pub trait SolidAngleKind: uom::Kind {}
/// Kind of radiant intensity (W/sr), separate from power (W).
pub trait RadiantIntensityKind: uom::Kind {}
/// Kind of irradiance (W/m²).
pub trait IrradianceKind: uom::Kind {}
/// Kind of radiance (W·m⁻²·sr⁻¹), separate from irradiance.
pub trait RadianceKind: uom::Kind {}
/// Kind of spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹).
pub trait SpectralRadianceKind: uom::Kind {}
/// Kind of luminous flux (lm = cd·sr), separate from luminous intensity (cd).
pub trait LuminousFluxKind: uom::Kind {}
/// Kind of illuminance (lx = lm/m²), separate from luminance (cd/m²).
pub trait IlluminanceKind: uom::Kind {}

macro_rules! q {
    ($modname:ident, $Q:ident, $desc:expr, [$($dim:ident),+], $kind:ty,
     { $($unit:ident: $factor:expr, $abbr:expr, $sing:expr, $plural:expr;)+ }) => {
        #[macro_use]
        pub mod $modname {
            quantity! {
                #[doc = $desc]
                quantity: $Q; $desc;
                #[doc = $desc]
                dimension: RQ<$($dim),+>;
                kind: $kind;
                units {
                    $(@$unit: $factor; $abbr, $sing, $plural;)+
                }
            }
        }
    };
}

q!(length, Length, "length", [P1, Z0, Z0, Z0, Z0, Z0, Z0], dyn uom::Kind, {
    meter: 1.0, "m", "meter", "meters";
    kilometer: 1.0E3, "km", "kilometer", "kilometers";
    centimeter: 1.0E-2, "cm", "centimeter", "centimeters";
    millimeter: 1.0E-3, "mm", "millimeter", "millimeters";
    micrometer: 1.0E-6, "µm", "micrometer", "micrometers";
    nanometer: 1.0E-9, "nm", "nanometer", "nanometers";
});
q!(mass, Mass, "mass", [Z0, P1, Z0, Z0, Z0, Z0, Z0], dyn uom::Kind, {
    kilogram: 1.0, "kg", "kilogram", "kilograms";
});
q!(time, Time, "time", [Z0, Z0, P1, Z0, Z0, Z0, Z0], dyn uom::Kind, {
    second: 1.0, "s", "second", "seconds";
});
q!(electric_current, ElectricCurrent, "electric current", [Z0, Z0, Z0, P1, Z0, Z0, Z0], dyn uom::Kind, {
    ampere: 1.0, "A", "ampere", "amperes";
});
q!(thermodynamic_temperature, ThermodynamicTemperature, "thermodynamic temperature",
   [Z0, Z0, Z0, Z0, P1, Z0, Z0], dyn uom::Kind, {
    kelvin: 1.0, "K", "kelvin", "kelvins";
});
q!(amount_of_substance, AmountOfSubstance, "amount of substance", [Z0, Z0, Z0, Z0, Z0, P1, Z0], dyn uom::Kind, {
    mole: 1.0, "mol", "mole", "moles";
});
q!(luminous_intensity, LuminousIntensity, "luminous intensity", [Z0, Z0, Z0, Z0, Z0, Z0, P1], dyn uom::Kind, {
    candela: 1.0, "cd", "candela", "candelas";
});
q!(area, Area, "area", [P2, Z0, Z0, Z0, Z0, Z0, Z0], dyn uom::Kind, {
    square_meter: 1.0, "m²", "square meter", "square meters";
    square_millimeter: 1.0E-6, "mm²", "square millimeter", "square millimeters";
});
q!(angle, Angle, "plane angle", [Z0, Z0, Z0, Z0, Z0, Z0, Z0], dyn super::AngleKind, {
    radian: 1.0, "rad", "radian", "radians";
    degree: 1.745_329_251_994_329_5_E-2, "°", "degree", "degrees";
});
q!(solid_angle, SolidAngle, "solid angle", [Z0, Z0, Z0, Z0, Z0, Z0, Z0], dyn super::SolidAngleKind, {
    steradian: 1.0, "sr", "steradian", "steradians";
});
q!(power, Power, "radiant flux (power)", [P2, P1, N3, Z0, Z0, Z0, Z0], dyn uom::Kind, {
    watt: 1.0, "W", "watt", "watts";
    milliwatt: 1.0E-3, "mW", "milliwatt", "milliwatts";
    kilowatt: 1.0E3, "kW", "kilowatt", "kilowatts";
});
q!(radiant_intensity, RadiantIntensity, "radiant intensity", [P2, P1, N3, Z0, Z0, Z0, Z0],
   dyn super::RadiantIntensityKind, {
    watt_per_steradian: 1.0, "W/sr", "watt per steradian", "watts per steradian";
});
q!(irradiance, Irradiance, "irradiance", [Z0, P1, N3, Z0, Z0, Z0, Z0], dyn super::IrradianceKind, {
    watt_per_square_meter: 1.0, "W/m²", "watt per square meter", "watts per square meter";
});
q!(radiance, Radiance, "radiance", [Z0, P1, N3, Z0, Z0, Z0, Z0], dyn super::RadianceKind, {
    watt_per_square_meter_steradian: 1.0, "W·m⁻²·sr⁻¹", "watt per square meter steradian",
        "watts per square meter steradian";
});
q!(spectral_radiance, SpectralRadiance, "spectral radiance", [N1, P1, N3, Z0, Z0, Z0, Z0],
   dyn super::SpectralRadianceKind, {
    watt_per_square_meter_steradian_meter: 1.0, "W·m⁻²·sr⁻¹·m⁻¹",
        "watt per square meter steradian meter", "watts per square meter steradian meter";
    watt_per_square_meter_steradian_nanometer: 1.0E9, "W·m⁻²·sr⁻¹·nm⁻¹",
        "watt per square meter steradian nanometer", "watts per square meter steradian nanometer";
});
q!(attenuation, Attenuation, "attenuation coefficient (absorption, scattering, extinction per length)",
   [N1, Z0, Z0, Z0, Z0, Z0, Z0], dyn uom::Kind, {
    per_meter: 1.0, "m⁻¹", "per meter", "per meter";
    per_centimeter: 1.0E2, "cm⁻¹", "per centimeter", "per centimeter";
    per_millimeter: 1.0E3, "mm⁻¹", "per millimeter", "per millimeter";
});
q!(luminous_flux, LuminousFlux, "luminous flux", [Z0, Z0, Z0, Z0, Z0, Z0, P1], dyn super::LuminousFluxKind, {
    lumen: 1.0, "lm", "lumen", "lumens";
});
q!(illuminance, Illuminance, "illuminance", [N2, Z0, Z0, Z0, Z0, Z0, P1], dyn super::IlluminanceKind, {
    lux: 1.0, "lx", "lux", "lux";
});
q!(luminance, Luminance, "luminance", [N2, Z0, Z0, Z0, Z0, Z0, P1], dyn uom::Kind, {
    candela_per_square_meter: 1.0, "cd/m²", "candela per square meter", "candelas per square meter";
});

system! {
    quantities: RQ {
        length: meter, L;
        mass: kilogram, M;
        time: second, T;
        electric_current: ampere, I;
        thermodynamic_temperature: kelvin, Th;
        amount_of_substance: mole, N;
        luminous_intensity: candela, J;
    }

    units: RU {
        mod length::Length,
        mod mass::Mass,
        mod time::Time,
        mod electric_current::ElectricCurrent,
        mod thermodynamic_temperature::ThermodynamicTemperature,
        mod amount_of_substance::AmountOfSubstance,
        mod luminous_intensity::LuminousIntensity,
        mod area::Area,
        mod angle::Angle,
        mod solid_angle::SolidAngle,
        mod power::Power,
        mod radiant_intensity::RadiantIntensity,
        mod irradiance::Irradiance,
        mod radiance::Radiance,
        mod spectral_radiance::SpectralRadiance,
        mod attenuation::Attenuation,
        mod luminous_flux::LuminousFlux,
        mod illuminance::Illuminance,
        mod luminance::Luminance,
    }
}

/// The quantities with `f64` storage, in SI base units internally.
pub mod f64 {
    mod rq {
        pub use super::super::*;
    }
    RQ!(self::rq, f64);
}
