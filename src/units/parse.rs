//! Quantity strings such as `"100 W"`, `"0.55 um"` or `"800 cd/m^2"`.
//!
//! A quantity string is a finite decimal number, optional white space, and a unit symbol from
//! [`UNITS`]. The parser first recognises the unit's [`Dimension`], then the caller states which
//! dimension it expects ([`parse`]), so that `"100 nm"` given for a power is an error that says
//! what was expected and what was found.

use std::fmt;

use super::quantities::{
    angle, area, attenuation, illuminance, irradiance, length, luminance, luminous_flux,
    luminous_intensity, power, radiance, radiant_intensity, solid_angle, spectral_radiance,
    thermodynamic_temperature,
};
use super::{
    Angle, Area, Attenuation, Illuminance, Irradiance, Length, Luminance, LuminousFlux,
    LuminousIntensity, Power, Radiance, RadiantIntensity, SolidAngle, SpectralRadiance,
    ThermodynamicTemperature,
};

/// The physical dimension (and kind) of a quantity string.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    Length,
    Area,
    Angle,
    SolidAngle,
    Temperature,
    Power,
    RadiantIntensity,
    Irradiance,
    Radiance,
    SpectralRadiance,
    Attenuation,
    LuminousFlux,
    LuminousIntensity,
    Illuminance,
    Luminance,
}

impl Dimension {
    /// A human description with an example unit, used in error messages.
    pub fn describe(self) -> &'static str {
        match self {
            Dimension::Length => "a length (e.g. \"550 nm\", \"2.5 mm\", \"1 m\")",
            Dimension::Area => "an area (e.g. \"1 m^2\")",
            Dimension::Angle => "an angle (e.g. \"45 deg\", \"0.1 rad\")",
            Dimension::SolidAngle => "a solid angle (e.g. \"1 sr\")",
            Dimension::Temperature => "a temperature (e.g. \"6500 K\")",
            Dimension::Power => "a radiant power (e.g. \"100 W\")",
            Dimension::RadiantIntensity => "a radiant intensity (e.g. \"3 W/sr\")",
            Dimension::Irradiance => "an irradiance (e.g. \"1000 W/m^2\")",
            Dimension::Radiance => "a radiance (e.g. \"10 W/m^2/sr\")",
            Dimension::SpectralRadiance => "a spectral radiance (e.g. \"0.01 W/m^2/sr/nm\")",
            Dimension::Attenuation => {
                "an attenuation coefficient (e.g. \"0.5 1/m\", \"2 1/mm\", \"0.1 cm^-1\")"
            }
            Dimension::LuminousFlux => "a luminous flux (e.g. \"1200 lm\")",
            Dimension::LuminousIntensity => "a luminous intensity (e.g. \"100 cd\")",
            Dimension::Illuminance => "an illuminance (e.g. \"10 lx\")",
            Dimension::Luminance => "a luminance (e.g. \"800 cd/m^2\")",
        }
    }
}

/// One accepted unit symbol: its dimension and its factor to the SI base unit of that dimension
/// (metre, m², radian, steradian, kelvin, W, W/sr, W/m², W·m⁻²·sr⁻¹, W·m⁻²·sr⁻¹·m⁻¹, lm, cd, lx,
/// cd/m²).
pub struct UnitSymbol {
    pub symbol: &'static str,
    pub dimension: Dimension,
    pub to_si: f64,
}

const fn u(symbol: &'static str, dimension: Dimension, to_si: f64) -> UnitSymbol {
    UnitSymbol {
        symbol,
        dimension,
        to_si,
    }
}

use Dimension as D;
const DEG: f64 = std::f64::consts::PI / 180.0;

/// Every unit symbol the parser accepts. `^2` and `²` are both accepted, as are `um` and `µm`.
pub const UNITS: &[UnitSymbol] = &[
    u("m", D::Length, 1.0),
    u("km", D::Length, 1e3),
    u("cm", D::Length, 1e-2),
    u("mm", D::Length, 1e-3),
    u("um", D::Length, 1e-6),
    u("µm", D::Length, 1e-6),
    u("nm", D::Length, 1e-9),
    u("m^2", D::Area, 1.0),
    u("m²", D::Area, 1.0),
    u("cm^2", D::Area, 1e-4),
    u("mm^2", D::Area, 1e-6),
    u("rad", D::Angle, 1.0),
    u("mrad", D::Angle, 1e-3),
    u("deg", D::Angle, DEG),
    u("°", D::Angle, DEG),
    u("arcmin", D::Angle, DEG / 60.0),
    u("sr", D::SolidAngle, 1.0),
    u("K", D::Temperature, 1.0),
    u("W", D::Power, 1.0),
    u("mW", D::Power, 1e-3),
    u("kW", D::Power, 1e3),
    u("W/sr", D::RadiantIntensity, 1.0),
    u("mW/sr", D::RadiantIntensity, 1e-3),
    u("W/m^2", D::Irradiance, 1.0),
    u("W/m²", D::Irradiance, 1.0),
    u("mW/m^2", D::Irradiance, 1e-3),
    u("W/m^2/sr", D::Radiance, 1.0),
    u("W/m²/sr", D::Radiance, 1.0),
    u("W/(m^2 sr)", D::Radiance, 1.0),
    u("W/m^2/sr/nm", D::SpectralRadiance, 1e9),
    u("W/m²/sr/nm", D::SpectralRadiance, 1e9),
    u("W/(m^2 sr nm)", D::SpectralRadiance, 1e9),
    u("1/m", D::Attenuation, 1.0),
    u("m^-1", D::Attenuation, 1.0),
    u("m⁻¹", D::Attenuation, 1.0),
    u("1/cm", D::Attenuation, 1e2),
    u("cm^-1", D::Attenuation, 1e2),
    u("cm⁻¹", D::Attenuation, 1e2),
    u("1/mm", D::Attenuation, 1e3),
    u("mm^-1", D::Attenuation, 1e3),
    u("mm⁻¹", D::Attenuation, 1e3),
    u("lm", D::LuminousFlux, 1.0),
    u("klm", D::LuminousFlux, 1e3),
    u("cd", D::LuminousIntensity, 1.0),
    u("mcd", D::LuminousIntensity, 1e-3),
    u("lx", D::Illuminance, 1.0),
    u("klx", D::Illuminance, 1e3),
    u("cd/m^2", D::Luminance, 1.0),
    u("cd/m²", D::Luminance, 1.0),
    u("nit", D::Luminance, 1.0),
    u("nits", D::Luminance, 1.0),
    u("kcd/m^2", D::Luminance, 1e3),
];

/// Why a quantity string was rejected. Each message quotes the input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuantityError {
    #[error("\"{input}\" is empty; expected {}", expected.describe())]
    Empty { input: String, expected: Dimension },
    #[error("\"{input}\" has no number; expected {}", expected.describe())]
    NoNumber { input: String, expected: Dimension },
    #[error("\"{input}\" is not a finite number; expected {}", expected.describe())]
    NonFinite { input: String, expected: Dimension },
    #[error("\"{input}\" has no unit; expected {}", expected.describe())]
    MissingUnit { input: String, expected: Dimension },
    #[error("\"{input}\": unknown unit \"{unit}\"; expected {}", expected.describe())]
    UnknownUnit {
        input: String,
        unit: String,
        expected: Dimension,
    },
    #[error("\"{input}\" is {}, but {} was expected", found.describe(), expected.describe())]
    WrongDimension {
        input: String,
        expected: Dimension,
        found: Dimension,
    },
}

/// A parsed quantity string: its dimension and its value in the SI base unit of that dimension.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnyQuantity {
    pub dimension: Dimension,
    /// Value in the SI base unit of `dimension` (see [`UnitSymbol::to_si`]).
    pub si: f64,
}

/// Splits `"550nm"` or `"550 nm"` into number and unit text.
fn split(s: &str) -> (&str, &str) {
    if let Some(i) = s.find(char::is_whitespace) {
        return (&s[..i], s[i..].trim());
    }
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let exp = (c == b'e' || c == b'E')
            && i > 0
            && b.get(i + 1)
                .is_some_and(|n| n.is_ascii_digit() || *n == b'+' || *n == b'-');
        if c.is_ascii_digit() || c == b'.' || c == b'+' || c == b'-' || exp {
            i += 1;
            if exp {
                i += 1; // the sign or digit after the exponent marker
            }
        } else {
            break;
        }
    }
    (&s[..i], &s[i..])
}

/// Parses a quantity string of any supported dimension. `expected` is only used to word errors
/// about the number or an unknown unit.
pub fn parse_any(input: &str, expected: Dimension) -> Result<AnyQuantity, QuantityError> {
    let owned = || input.to_string();
    let s = input.trim();
    if s.is_empty() {
        return Err(QuantityError::Empty {
            input: owned(),
            expected,
        });
    }
    let (num, unit) = split(s);
    if num.is_empty() {
        // "NaN W" and "inf K" split at white space, so only unit-first strings get here.
        return Err(QuantityError::NoNumber {
            input: owned(),
            expected,
        });
    }
    let value: f64 = num.parse().map_err(|_| QuantityError::NoNumber {
        input: owned(),
        expected,
    })?;
    if !value.is_finite() {
        return Err(QuantityError::NonFinite {
            input: owned(),
            expected,
        });
    }
    if unit.is_empty() {
        return Err(QuantityError::MissingUnit {
            input: owned(),
            expected,
        });
    }
    let sym =
        UNITS
            .iter()
            .find(|u| u.symbol == unit)
            .ok_or_else(|| QuantityError::UnknownUnit {
                input: owned(),
                unit: unit.to_string(),
                expected,
            })?;
    Ok(AnyQuantity {
        dimension: sym.dimension,
        si: value * sym.to_si,
    })
}

/// A typed quantity that can be read from a quantity string.
pub trait ParseQuantity: Sized {
    const DIMENSION: Dimension;
    /// Builds the quantity from its value in the SI base unit of [`Self::DIMENSION`].
    fn from_si(si: f64) -> Self;
}

/// Parses a quantity string into the typed quantity `Q`, rejecting other dimensions.
///
/// ```
/// use spectrace::units::{parse::parse, Length, Power, length::nanometer};
/// let l: Length = parse("0.55 um").unwrap();
/// assert!((l.get::<nanometer>() - 550.0).abs() < 1e-9);
/// assert!(parse::<Power>("100 nm").is_err());
/// ```
pub fn parse<Q: ParseQuantity>(input: &str) -> Result<Q, QuantityError> {
    let any = parse_any(input, Q::DIMENSION)?;
    if any.dimension != Q::DIMENSION {
        return Err(QuantityError::WrongDimension {
            input: input.to_string(),
            expected: Q::DIMENSION,
            found: any.dimension,
        });
    }
    Ok(Q::from_si(any.si))
}

macro_rules! parse_impl {
    ($($Q:ty, $dim:ident, $module:ident::$base:ident;)+) => {$(
        impl ParseQuantity for $Q {
            const DIMENSION: Dimension = Dimension::$dim;
            fn from_si(si: f64) -> Self {
                <$Q>::new::<$module::$base>(si)
            }
        }
    )+};
}

parse_impl! {
    Length, Length, length::meter;
    Area, Area, area::square_meter;
    Angle, Angle, angle::radian;
    SolidAngle, SolidAngle, solid_angle::steradian;
    ThermodynamicTemperature, Temperature, thermodynamic_temperature::kelvin;
    Power, Power, power::watt;
    RadiantIntensity, RadiantIntensity, radiant_intensity::watt_per_steradian;
    Irradiance, Irradiance, irradiance::watt_per_square_meter;
    Radiance, Radiance, radiance::watt_per_square_meter_steradian;
    SpectralRadiance, SpectralRadiance, spectral_radiance::watt_per_square_meter_steradian_meter;
    Attenuation, Attenuation, attenuation::per_meter;
    LuminousFlux, LuminousFlux, luminous_flux::lumen;
    LuminousIntensity, LuminousIntensity, luminous_intensity::candela;
    Illuminance, Illuminance, illuminance::lux;
    Luminance, Luminance, luminance::candela_per_square_meter;
}

impl fmt::Display for Dimension {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.describe())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_number_and_unit() {
        assert_eq!(split("550nm"), ("550", "nm"));
        assert_eq!(split("1e3W"), ("1e3", "W"));
        assert_eq!(split("2.5e-3 m"), ("2.5e-3", "m"));
        assert_eq!(split("800 cd/m^2"), ("800", "cd/m^2"));
        assert_eq!(split("5em"), ("5", "em"));
    }

    #[test]
    fn every_symbol_is_unique() {
        for (i, a) in UNITS.iter().enumerate() {
            for b in &UNITS[i + 1..] {
                assert_ne!(a.symbol, b.symbol);
            }
        }
    }
}
