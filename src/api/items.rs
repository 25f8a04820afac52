//! The items of a scene built in code that are not placed in space: spectra, indices of
//! refraction, materials and emission. Each is the TOML value or table the scene format reads
//! (README, "Spectra", `[materials.NAME]`, `emission`).

use std::path::Path;

use toml::{Table, Value};

use super::Error;
use super::quantity::{Brightness, Flux, Radiometric, text, typed, vector};
use crate::units::{Length, ThermodynamicTemperature, length};

/// A spectrum as the scene format reads it (README, "Spectra"): a reflectance, the shape of
/// a light's emission, or an index of refraction's table.
///
/// ```
/// let d65 = spectrace::Spectrum::named("cie-d65")?;
/// let grey: spectrace::Spectrum = 0.18.into();
/// # Ok::<(), spectrace::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum(pub(super) Value);

impl Spectrum {
    /// The same value at every wavelength.
    ///
    /// ```
    /// let s = spectrace::api::Spectrum::constant(0.5);
    /// ```
    pub fn constant(v: f64) -> Spectrum {
        Spectrum(Value::Float(v))
    }

    /// A named spectrum (`"cie-d65"`, `"cie-a"`, `"colorchecker:red"`, `"blackbody:3000K"`,
    /// `spectrace spectrum --list`); an unknown name is an error suggesting the closest.
    ///
    /// ```
    /// assert!(spectrace::api::Spectrum::named("cie-a").is_ok());
    /// let e = spectrace::api::Spectrum::named("cie-d56").unwrap_err();
    /// assert!(e.to_string().contains("cie-d65"));
    /// ```
    pub fn named(name: &str) -> Result<Spectrum, Error> {
        crate::spectrum::named::lookup(name)?;
        Ok(Spectrum(text(name)))
    }

    /// A CSV file of `wavelength_nm,value` (relative paths resolve against the builder's
    /// folder).
    ///
    /// ```
    /// let s = spectrace::api::Spectrum::file(std::path::Path::new("led.csv"));
    /// ```
    pub fn file(path: &Path) -> Spectrum {
        // `{ file = … }`: a bare string without `.csv` or a folder would be read as a name
        let mut f = Table::new();
        f.insert("file".into(), text(path.display().to_string()));
        Spectrum(Value::Table(f))
    }

    /// Planck's law at `t`, absolute: W·m⁻²·sr⁻¹·nm⁻¹.
    ///
    /// ```
    /// use spectrace::units::{ThermodynamicTemperature, thermodynamic_temperature::kelvin};
    /// let s = spectrace::api::Spectrum::blackbody(ThermodynamicTemperature::new::<kelvin>(6500.0));
    /// ```
    pub fn blackbody(t: ThermodynamicTemperature) -> Spectrum {
        let mut b = Table::new();
        b.insert("blackbody".into(), text(t.quantity()));
        Spectrum(Value::Table(b))
    }

    /// Piecewise linear through (wavelength, value) points.
    ///
    /// ```
    /// use spectrace::units::{Length, length::nanometer};
    /// let nm = Length::new::<nanometer>;
    /// let s = spectrace::api::Spectrum::samples(&[(nm(400.0), 0.1), (nm(700.0), 0.9)]);
    /// ```
    pub fn samples(points: &[(Length, f64)]) -> Spectrum {
        let pts = points
            .iter()
            .map(|(l, v)| {
                Value::Array(vec![
                    Value::Float(l.get::<length::nanometer>()),
                    Value::Float(*v),
                ])
            })
            .collect();
        let mut b = Table::new();
        b.insert("samples".into(), Value::Array(pts));
        Spectrum(Value::Table(b))
    }

    /// Linear sRGB, upsampled (Jakob–Hanika).
    ///
    /// ```
    /// let s = spectrace::api::Spectrum::rgb([0.8, 0.2, 0.1]);
    /// ```
    pub fn rgb(rgb: [f64; 3]) -> Spectrum {
        let mut b = Table::new();
        b.insert("rgb".into(), vector(rgb));
        Spectrum(Value::Table(b))
    }
}

impl From<f64> for Spectrum {
    fn from(v: f64) -> Spectrum {
        Spectrum::constant(v)
    }
}

/// An index of refraction: a constant, a named glass, Sellmeier or Cauchy coefficients.
///
/// ```
/// let bk7 = spectrace::Ior::glass("N-BK7")?;
/// # Ok::<(), spectrace::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Ior(Value);

impl Ior {
    /// The same index at every wavelength.
    ///
    /// ```
    /// let n = spectrace::api::Ior::constant(1.5);
    /// ```
    pub fn constant(n: f64) -> Ior {
        Ior(Value::Float(n))
    }

    /// A glass of the catalogue (`"N-BK7"`, `"glass:diamond"`); an unknown name is an error.
    ///
    /// ```
    /// assert!(spectrace::api::Ior::glass("glass:N-BK7").is_ok());
    /// ```
    pub fn glass(name: &str) -> Result<Ior, Error> {
        let full = if name.contains(':') {
            name.to_string()
        } else {
            format!("glass:{name}")
        };
        crate::spectrum::named::lookup(&full)?;
        Ok(Ior(text(full)))
    }

    /// n²(λ) = 1 + Σ Bᵢλ²/(λ² − Cᵢ), λ in µm, C in µm².
    ///
    /// ```
    /// let bk7 = spectrace::api::Ior::sellmeier(
    ///     [1.03961212, 0.231792344, 1.01046945], [0.00600069867, 0.0200179144, 103.560653]);
    /// ```
    pub fn sellmeier(b: [f64; 3], c_um2: [f64; 3]) -> Ior {
        let mut s = Table::new();
        s.insert("B".into(), vector(b));
        s.insert("C".into(), vector(c_um2));
        let mut t = Table::new();
        t.insert("sellmeier".into(), Value::Table(s));
        Ior(Value::Table(t))
    }

    /// n(λ) = A + B/λ², λ in µm, B in µm².
    ///
    /// ```
    /// let n = spectrace::api::Ior::cauchy(1.5, 0.004);
    /// ```
    pub fn cauchy(a: f64, b_um2: f64) -> Ior {
        let mut s = Table::new();
        s.insert("A".into(), Value::Float(a));
        s.insert("B".into(), Value::Float(b_um2));
        let mut t = Table::new();
        t.insert("cauchy".into(), Value::Table(s));
        Ior(Value::Table(t))
    }
}

/// A `[materials.NAME]` table.
///
/// ```
/// let m = spectrace::Material::diffuse(spectrace::Spectrum::named("colorchecker:red")?);
/// # Ok::<(), spectrace::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Material(pub(super) Table);

impl Material {
    /// Lambertian: f = ρ/π.
    ///
    /// ```
    /// let m = spectrace::api::Material::diffuse(0.18);
    /// ```
    pub fn diffuse(reflectance: impl Into<Spectrum>) -> Material {
        let mut t = typed("diffuse");
        t.insert("reflectance".into(), reflectance.into().0);
        Material(t)
    }

    /// The notes' normalised Phong: f = k_d/π + k_s (n+2)/(2π) cosⁿα.
    ///
    /// ```
    /// let m = spectrace::api::Material::phong(0.5, 0.3, 20.0);
    /// ```
    pub fn phong(kd: impl Into<Spectrum>, ks: impl Into<Spectrum>, exponent: f64) -> Material {
        let mut t = typed("phong");
        t.insert("kd".into(), kd.into().0);
        t.insert("ks".into(), ks.into().0);
        t.insert("exponent".into(), Value::Float(exponent));
        Material(t)
    }

    /// A smooth dielectric (exact Fresnel and Snell per wavelength).
    ///
    /// ```
    /// let glass = spectrace::api::Material::dielectric(spectrace::api::Ior::glass("N-BK7")?);
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn dielectric(ior: Ior) -> Material {
        let mut t = typed("dielectric");
        t.insert("ior".into(), ior.0);
        Material(t)
    }

    /// A smooth conductor of the catalogue (`"Au"`, `"Ag"`, `"Cu"`, `"Al"`).
    ///
    /// ```
    /// let gold = spectrace::api::Material::conductor("Au").roughness(0.1);
    /// ```
    pub fn conductor(metal: &str) -> Material {
        let mut t = typed("conductor");
        t.insert("metal".into(), text(metal));
        Material(t)
    }

    /// A diffuse base under a smooth dielectric coating of index `ior` (Mitsuba's `plastic`).
    ///
    /// ```
    /// let m = spectrace::api::Material::plastic(0.5, 1.49);
    /// ```
    pub fn plastic(reflectance: impl Into<Spectrum>, ior: f64) -> Material {
        let mut t = typed("plastic");
        t.insert("reflectance".into(), reflectance.into().0);
        t.insert("ior".into(), Value::Float(ior));
        Material(t)
    }

    /// GGX roughness α (dielectrics, conductors, plastics).
    ///
    /// ```
    /// let m = spectrace::api::Material::conductor("Al").roughness(0.2);
    /// ```
    pub fn roughness(mut self, alpha: f64) -> Material {
        self.0.insert("roughness".into(), Value::Float(alpha));
        self
    }
}

/// A shape's `emission`: a Lambertian area light.
///
/// ```
/// use spectrace::units::{Radiance, radiance::watt_per_square_meter_steradian};
/// let e = spectrace::Emission::uniform(Radiance::new::<watt_per_square_meter_steradian>(10.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Emission(pub(super) Table);

impl Emission {
    /// Emitting radiance (W·m⁻²·sr⁻¹) or luminance (cd/m²).
    ///
    /// ```
    /// use spectrace::units::{Luminance, luminance::candela_per_square_meter};
    /// let e = spectrace::api::Emission::uniform(Luminance::new::<candela_per_square_meter>(100.0));
    /// ```
    pub fn uniform<B: Brightness>(amount: B) -> Emission {
        let mut t = Table::new();
        t.insert(B::KEY.into(), text(amount.quantity()));
        Emission(t)
    }

    /// Emitting a total power (W) or flux (lm): Φ = π·L·A (2π·L·A two-sided).
    ///
    /// ```
    /// use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    /// let e = spectrace::api::Emission::power(LuminousFlux::new::<lumen>(800.0));
    /// ```
    pub fn power(amount: impl Flux) -> Emission {
        let mut t = Table::new();
        t.insert("power".into(), text(amount.quantity()));
        Emission(t)
    }

    /// The emission's spectral shape (default constant).
    ///
    /// ```
    /// # use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    /// # let e = spectrace::api::Emission::power(LuminousFlux::new::<lumen>(800.0));
    /// let e = e.spectrum(spectrace::api::Spectrum::named("cie-d65")?);
    /// # Ok::<(), spectrace::api::Error>(())
    /// ```
    pub fn spectrum(mut self, s: Spectrum) -> Emission {
        self.0.insert("spectrum".into(), s.0);
        self
    }

    /// Emits on both sides.
    ///
    /// ```
    /// # use spectrace::units::{LuminousFlux, luminous_flux::lumen};
    /// let e = spectrace::api::Emission::power(LuminousFlux::new::<lumen>(800.0)).two_sided();
    /// ```
    pub fn two_sided(mut self) -> Emission {
        self.0.insert("two_sided".into(), Value::Boolean(true));
        self
    }
}
