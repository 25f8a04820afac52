//! Channel names of the spectral OpenEXR layout of Fichet, Pacanowski and Wilkie, "An OpenEXR
//! Layout for Spectral Images", JCGT 10(3), 2021.
//!
//! An emissive, unpolarised channel is named `S0.<value><prefix><unit>`: the value uses a comma
//! as decimal separator and may carry an exponent (`E`/`e`), the unit is `m` or `Hz` with an
//! optional SI prefix. spectrace writes `S0.<λ>nm` with six decimals, e.g. `S0.552,500000nm`,
//! and reads any name of that grammar.

use std::path::Path;

use super::{ExrImage, ImageError, invalid};

/// Value of the `spectralLayoutVersion` attribute.
pub const SPECTRAL_LAYOUT_VERSION: &str = "1.0";
/// Value of the `emissiveUnits` attribute: spectral radiance, per nanometre of the channels'
/// wavelength unit (see [`super::write_spectral_exr`]).
pub const EMISSIVE_UNITS: &str = "W.m^-2.sr^-1";

/// Speed of light in vacuum, m/s. A channel named by frequency f is read as the vacuum
/// wavelength c/f.
const C: f64 = 299_792_458.0;

/// The name of the emissive channel at `wavelength_nm`, e.g. `S0.550,000000nm`. Fails if six
/// decimals do not give back the same `f32`, so that names and wavelengths stay one-to-one.
pub(super) fn channel_name(path: &Path, wavelength_nm: f32) -> Result<String, ImageError> {
    let name = format!("S0.{}nm", format!("{wavelength_nm:.6}").replace('.', ","));
    match parse_channel_name(&name) {
        Some(back) if back == wavelength_nm => Ok(name),
        _ => Err(invalid(
            path,
            format!("wavelength {wavelength_nm} nm cannot be written exactly with six decimals"),
        )),
    }
}

/// The name of Stokes component `k` (1–3) at `wavelength_nm` in the layout's polarised form,
/// e.g. `S1.550,000000nm` (the same decimals as the S0 channels).
pub fn stokes_channel_name(k: usize, wavelength_nm: f32) -> String {
    format!("S{k}.{}nm", format!("{wavelength_nm:.6}").replace('.', ","))
}

/// The wavelength in nm of an emissive unpolarised channel (`S0.…`), or `None` if `name` is not
/// one.
pub(super) fn parse_channel_name(name: &str) -> Option<f32> {
    let rest = name.strip_prefix("S0.")?;
    let (rest, frequency) = match rest.strip_suffix("Hz") {
        Some(r) => (r, true),
        None => (rest.strip_suffix('m')?, false),
    };
    let number_len = rest
        .trim_end_matches(|c: char| c.is_ascii_alphabetic())
        .len();
    let number = &rest[..number_len];
    let prefix = prefix_exponent(&rest[number_len..])?;
    if !is_number(number) {
        return None;
    }
    let decimal = number.replace(',', ".");
    let nm = if !frequency && prefix == -9 {
        decimal.parse::<f32>().ok()?
    } else {
        let value = decimal.parse::<f64>().ok()? * 10f64.powi(prefix);
        let metres = if frequency { C / value } else { value };
        (metres * 1e9) as f32
    };
    (nm.is_finite() && nm > 0.0).then_some(nm)
}

/// Power of ten of an SI prefix (`""` → 0).
fn prefix_exponent(prefix: &str) -> Option<i32> {
    Some(match prefix {
        "Y" => 24,
        "Z" => 21,
        "E" => 18,
        "P" => 15,
        "T" => 12,
        "G" => 9,
        "M" => 6,
        "k" => 3,
        "h" => 2,
        "da" => 1,
        "" => 0,
        "d" => -1,
        "c" => -2,
        "m" => -3,
        "u" => -6,
        "n" => -9,
        "p" => -12,
        _ => return None,
    })
}

/// `digits [, digits] [(E|e) [+|-] digits]` with at least one digit before the exponent.
fn is_number(s: &str) -> bool {
    let (mantissa, exponent) = match s.find(['E', 'e']) {
        Some(i) => (&s[..i], Some(&s[i + 1..])),
        None => (s, None),
    };
    let mut parts = mantissa.splitn(2, ',');
    let int = parts.next().unwrap_or("");
    let frac = parts.next().unwrap_or("");
    let digits = |t: &str| t.bytes().all(|b| b.is_ascii_digit());
    let mantissa_ok = digits(int) && digits(frac) && !(int.is_empty() && frac.is_empty());
    let exponent_ok = exponent.is_none_or(|e| {
        let e = e.strip_prefix(['+', '-']).unwrap_or(e);
        !e.is_empty() && digits(e)
    });
    mantissa_ok && exponent_ok
}

/// The emissive spectral channels of `img` (`S0.<λ>nm` and the other units of the layout):
/// `(wavelength_nm, index into img.channels)`, sorted by wavelength. Other channels (RGB
/// previews, polarised `S1`–`S3`, reflective `T`) are left out.
pub fn spectral_channels(img: &ExrImage) -> Vec<(f32, usize)> {
    let mut out: Vec<(f32, usize)> = img
        .channels
        .iter()
        .enumerate()
        .filter_map(|(i, (name, _))| parse_channel_name(name).map(|wl| (wl, i)))
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        let p = Path::new("x.exr");
        assert_eq!(channel_name(p, 550.0).unwrap(), "S0.550,000000nm");
        assert_eq!(channel_name(p, 552.5).unwrap(), "S0.552,500000nm");
        for wl in [360.0f32, 380.123, 550.1, 779.99, 830.0, 1e4, 0.5] {
            let name = channel_name(p, wl).unwrap();
            assert_eq!(parse_channel_name(&name), Some(wl), "{name}");
        }
        assert!(channel_name(p, 1e-7).is_err());
    }

    #[test]
    fn other_units_of_the_layout() {
        assert_eq!(parse_channel_name("S0.550nm"), Some(550.0));
        assert_eq!(parse_channel_name("S0.0,55um"), Some(550.0));
        assert_eq!(parse_channel_name("S0.5,5E2nm"), Some(550.0));
        assert_eq!(parse_channel_name("S0.550e-9m"), Some(550.0));
        // Frequency → vacuum wavelength c/f: 540 THz is 555.171 nm in vacuum (555.016 nm in air).
        let thz = parse_channel_name("S0.540THz").unwrap();
        assert!((thz - 555.1712).abs() < 1e-3, "{thz}");
    }

    #[test]
    fn non_spectral_names() {
        for name in [
            "R",
            "S0.nm",
            "S0.,nm",
            "S1.550nm",
            "T.550nm",
            "S0.550",
            "S0.550xm",
            "S0.5,5,0nm",
            "S0.-550nm",
            "S0.550e+nm",
            "S0.infnm",
            "S0.0nm",
        ] {
            assert_eq!(parse_channel_name(name), None, "{name}");
        }
    }
}
