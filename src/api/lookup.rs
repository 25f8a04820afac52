//! Values that are not images: the readings of a scene's illuminance meters and the named
//! spectra (illuminants, reflectances, glasses, metals) at given wavelengths.

use std::sync::atomic::AtomicBool;

use super::{Error, Estimate, Scene};
use crate::units::{Illuminance, Irradiance, Length, illuminance, irradiance, length};

/// How to measure; see [`measure`].
///
/// ```
/// let o = spectrace::api::MeasureOptions { samples: 1024, ..Default::default() };
/// ```
#[derive(Clone, Debug)]
pub struct MeasureOptions {
    /// Samples per point, 1 to 2²⁴ (rounded up to a multiple of 16 replicas).
    pub samples: u32,
    /// Sampler seed.
    pub seed: u32,
    /// Worker threads (None: every core; at least 1); readings do not depend on it.
    pub threads: Option<usize>,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        MeasureOptions {
            samples: 4096,
            seed: 0,
            threads: None,
        }
    }
}

/// One meter point's reading.
///
/// ```
/// # let readings: Vec<spectrace::MeterReading> = Vec::new();
/// use spectrace::units::illuminance::lux;
/// for r in &readings { println!("{} {:?}: {} lx", r.meter, r.cell, r.illuminance.value.get::<lux>()); }
/// ```
#[derive(Clone, Debug)]
pub struct MeterReading {
    /// The meter's name (`[[sensors]]` `name`, or its index).
    pub meter: String,
    /// The point's cell in a grid (0, 0 for a point meter).
    pub cell: [u32; 2],
    /// Where it is, metres.
    pub position: [Length; 3],
    /// Illuminance E_v = K_m ∫ E(λ) ȳ(λ) dλ and its standard error (16 replicas' spread / 4).
    pub illuminance: Estimate<Illuminance>,
    /// Irradiance ∫ E(λ) dλ over the scene's wavelength range and its standard error.
    pub irradiance: Estimate<Irradiance>,
}

/// Measures every meter point of `scene` (`[[sensors]]`, [`Meter`](super::Meter)) by
/// hemispherical integration, indirect light included (as `spectrace measure`).
///
/// ```
/// use spectrace::api::{Light, Meter, MeasureOptions, Scene, measure, metres};
/// use spectrace::units::{Illuminance, Luminance, illuminance::lux, luminance::candela_per_square_meter};
/// // 1000 lx from above plus a uniform 100 cd/m² sky over the upper hemisphere: π·100 lx
/// let scene = Scene::builder()
///     .camera(spectrace::api::Camera::perspective(metres([0.0, 1.0, -1.0]), metres([0.0; 3]), spectrace::api::degrees(30.0)))
///     .light(Light::directional([0.0, -1.0, 0.0], Illuminance::new::<lux>(1000.0)))
///     .light(Light::environment(Luminance::new::<candela_per_square_meter>(100.0)))
///     .meter(Meter::point("up", metres([0.0; 3]), [0.0, 1.0, 0.0]))
///     .build()?;
/// let r = &measure(&scene, &MeasureOptions { samples: 256, ..Default::default() })?[0];
/// let (e, se) = (r.illuminance.value.get::<lux>(), r.illuminance.standard_error.get::<lux>());
/// assert!((e - (1000.0 + 100.0 * std::f64::consts::PI)).abs() < 4.0 * se + 0.5, "{e} ± {se}");
/// # Ok::<(), spectrace::api::Error>(())
/// ```
pub fn measure(scene: &Scene, options: &MeasureOptions) -> Result<Vec<MeterReading>, Error> {
    measure_with(scene, options, &AtomicBool::new(false))
}

/// [`measure`] until `cancel` is set (checked between samples): the points not finished are
/// left out.
///
/// ```
/// use std::sync::atomic::AtomicBool;
/// use spectrace::api::{Light, Meter, MeasureOptions, Scene, measure_with, metres};
/// use spectrace::units::{Illuminance, illuminance::lux};
/// let scene = Scene::builder()
///     .camera(spectrace::api::Camera::perspective(metres([0.0, 1.0, -1.0]), metres([0.0; 3]), spectrace::api::degrees(30.0)))
///     .light(Light::directional([0.0, -1.0, 0.0], Illuminance::new::<lux>(1000.0)))
///     .shape(spectrace::Shape::disk().material("m"))
///     .material("m", spectrace::Material::diffuse(0.5))
///     .meter(Meter::point("up", metres([0.0, 1.0, 0.0]), [0.0, 1.0, 0.0]))
///     .build()?;
/// assert!(measure_with(&scene, &MeasureOptions::default(), &AtomicBool::new(true))?.is_empty());
/// # Ok::<(), spectrace::api::Error>(())
/// ```
pub fn measure_with(
    scene: &Scene,
    options: &MeasureOptions,
    cancel: &AtomicBool,
) -> Result<Vec<MeterReading>, Error> {
    let s = &scene.inner;
    if options.samples == 0 || options.samples > 1 << 24 {
        return Err(Error::Options("samples must be from 1 to 16777216".into()));
    }
    if options.threads == Some(0) {
        return Err(Error::Options("threads must be at least 1".into()));
    }
    let opts = crate::render::measure::MeasureOptions {
        samples: options.samples,
        threads: options.threads,
        seed: options.seed,
        max_depth: s.integrator.max_depth,
        spectral_bins: 0,
    };
    let points = s.meter_points();
    let readings = crate::render::measure::measure(s, &points, &opts, cancel, &|_| {})?;
    let mut out = Vec::with_capacity(points.len());
    let mut it = readings.into_iter();
    for m in &s.meters {
        for (k, p) in m.points.iter().enumerate() {
            let Some(r) = it.next().flatten() else {
                continue;
            };
            let lx = Illuminance::new::<illuminance::lux>;
            let wm2 = Irradiance::new::<irradiance::watt_per_square_meter>;
            out.push(MeterReading {
                meter: m.name.clone(),
                cell: m.cell(k),
                position: p
                    .p
                    .to_array()
                    .map(|c| Length::new::<length::meter>(c as f64)),
                illuminance: Estimate {
                    value: lx(r.illuminance_lx),
                    standard_error: lx(r.illuminance_se_lx),
                },
                irradiance: Estimate {
                    value: wm2(r.irradiance_w_m2),
                    standard_error: wm2(r.irradiance_se_w_m2),
                },
            });
        }
    }
    Ok(out)
}

/// A named spectrum's values at given wavelengths; see [`spectrum`].
///
/// ```
/// use spectrace::units::{Length, length::nanometer};
/// let v = spectrace::spectrum("metal:Au", &[Length::new::<nanometer>(550.0)])?;
/// assert!(matches!(v, spectrace::SpectrumValues::Conductor(_)));
/// # Ok::<(), spectrace::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum SpectrumValues {
    /// A curve's values as its source tabulates them: relative spectral power (CIE
    /// illuminants: 100 at 560 nm), reflectance factor, colour-matching value, or a
    /// peak-normalised Planck curve (`kind` says which).
    Curve {
        /// What the values are.
        kind: &'static str,
        /// One per wavelength.
        values: Vec<f64>,
    },
    /// A dielectric's refractive index n.
    Dielectric(Vec<f64>),
    /// A conductor's complex index n + ik, as (n, k).
    Conductor(Vec<(f64, f64)>),
}

/// Looks up a named spectrum (`"cie-d65"`, `"glass:N-BK7"`, `"metal:Au"`,
/// `"colorchecker:red"`, `"blackbody:3200K"`; `spectrace spectrum --list`) at `wavelengths`.
///
/// ```
/// use spectrace::api::{SpectrumValues, spectrum};
/// use spectrace::units::{Length, length::nanometer};
/// let SpectrumValues::Dielectric(n) = spectrum("glass:N-BK7", &[Length::new::<nanometer>(587.56)])?
///     else { unreachable!() };
/// assert!((n[0] - 1.5168).abs() < 1e-4);
/// # Ok::<(), spectrace::api::Error>(())
/// ```
pub fn spectrum(name: &str, wavelengths: &[Length]) -> Result<SpectrumValues, Error> {
    use crate::spectrum::named::{Named, lookup};
    let nm: Vec<f32> = wavelengths
        .iter()
        .map(|l| l.get::<length::nanometer>() as f32)
        .collect();
    if let Some(bad) = nm.iter().find(|l| !(**l > 0.0 && l.is_finite())) {
        return Err(Error::Options(format!(
            "wavelength {bad} nm must be a positive number"
        )));
    }
    Ok(match lookup(name)? {
        Named::Curve { spectrum, kind, .. } => SpectrumValues::Curve {
            kind: kind.quantity(),
            values: nm.iter().map(|&l| spectrum.eval(l) as f64).collect(),
        },
        Named::Dielectric(g) => {
            SpectrumValues::Dielectric(nm.iter().map(|&l| g.ior.eval(l) as f64).collect())
        }
        Named::Conductor(m) => SpectrumValues::Conductor(
            nm.iter()
                .map(|&l| {
                    let (n, k) = m.ior.eval(l);
                    (n as f64, k as f64)
                })
                .collect(),
        ),
    })
}
