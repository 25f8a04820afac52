//! `[media.NAME]`: participating media, which shapes name as their `interior` or `exterior`
//! and the camera as its `medium`.
//!
//! ```toml
//! [media.wine]
//! type = "homogeneous"                 # the default
//! sigma_a = { spectrum = "data/wine_absorbance.csv", scale = "2.3 1/mm" }
//! sigma_s = "0 1/m"
//! phase = "isotropic"                  # or "rayleigh", or { type = "hg", g = 0.3 }
//! ```
//!
//! Coefficients are attenuation coefficients (natural logarithm) per length: a quantity string
//! (`"0.5 1/m"`, `"2 1/mm"`, `"0.1 cm^-1"`), the same at every wavelength, or a table
//! `{ spectrum = <spectrum>, scale = <quantity> }`, the spectrum's shape times the scale. A
//! medium is given by absorption and scattering (`sigma_a`, `sigma_s`, either defaulting to 0),
//! by extinction and single-scattering albedo (`sigma_t`, `albedo` in [0, 1]), or, as filter
//! glass catalogues publish it, by its internal transmittance through a thickness
//! (`internal_transmittance = { spectrum = <τ(λ) in (0, 1]>, thickness = "3 mm" }`, so that
//! σa(λ) = −ln τ(λ) / thickness), with an optional `sigma_s`.

use std::collections::BTreeMap;

use super::*;
use crate::loader::convert::kind;
use crate::medium::PhaseFunction;
use crate::units::{Attenuation, attenuation};

/// The keys of a homogeneous medium.
const KEYS: &[&str] = &[
    "type",
    "emission",
    "sigma_a",
    "sigma_s",
    "sigma_t",
    "albedo",
    "internal_transmittance",
    "phase",
];

/// One `[media.NAME]` table.
pub(super) fn medium(
    cx: &Cx<'_>,
    name: &S<String>,
    m: &S<RawMaterial>,
    range: &[Length; 2],
) -> R<MediumDesc> {
    let sp = m.span();
    let f = format!("media.{}", name.get_ref());
    let keys = &m.get_ref().0;
    if let Some(t) = keys.get("type") {
        let ty = cx.string(t, &format!("{f}.type"), "a medium type")?;
        cx.kind_index(
            ty,
            &t.span(),
            &format!("{f}.type"),
            "medium",
            &["homogeneous"],
        )?;
    }
    for (key, v) in keys {
        if !KEYS.contains(&key.as_str()) {
            let near = crate::params::did_you_mean(key, KEYS.iter().copied());
            return Err(cx.err(
                &v.span(),
                format!("{f}.{key}"),
                format!(
                    "`{key}` does not apply to a medium{near}; it takes {}",
                    KEYS.join(", ")
                ),
            ));
        }
    }
    let coefficient = |key: &str| -> R<Option<Spectrum>> {
        keys.get(key)
            .map(|v| coefficient(cx, v, &format!("{f}.{key}")))
            .transpose()
    };
    let has = |k: &str| keys.contains_key(k);
    let coefficients = if has("sigma_t") {
        for other in ["sigma_a", "internal_transmittance"] {
            if let Some(v) = keys.get(other) {
                return Err(cx.err(
                    &v.span(),
                    format!("{f}.{other}"),
                    "give sigma_t with albedo, or sigma_a (or internal_transmittance) with sigma_s, not both",
                ));
            }
        }
        let sigma_t = coefficient("sigma_t")?.unwrap_or(Spectrum::Constant(0.0));
        let Some(a) = keys.get("albedo") else {
            return Err(cx.err(
                &sp,
                format!("{f}.albedo"),
                "missing; sigma_t needs an albedo (σs/σt, in [0, 1])",
            ));
        };
        let albedo = cx.spectrum(a, &format!("{f}.albedo"), SpectrumUse::Reflectance)?;
        at_most_one(cx, &albedo, a, &format!("{f}.albedo"), range)?;
        Coefficients::Extinction {
            sigma_t,
            albedo: VolumeDesc::Constant {
                value: albedo,
                to_world: Vec::new(),
            },
        }
    } else {
        if let Some(v) = keys.get("albedo") {
            return Err(cx.err(&v.span(), format!("{f}.albedo"), "albedo goes with sigma_t"));
        }
        let sigma_a = match (keys.get("sigma_a"), keys.get("internal_transmittance")) {
            (Some(_), Some(v)) => {
                return Err(cx.err(
                    &v.span(),
                    format!("{f}.internal_transmittance"),
                    "give sigma_a or internal_transmittance, not both",
                ));
            }
            (Some(_), None) => coefficient("sigma_a")?,
            (None, Some(v)) => Some(internal_transmittance(
                cx,
                v,
                &format!("{f}.internal_transmittance"),
                range,
            )?),
            (None, None) => None,
        };
        let sigma_s = coefficient("sigma_s")?;
        if sigma_a.is_none() && sigma_s.is_none() {
            return Err(cx.err(
                &sp,
                &f,
                "a medium needs sigma_a, sigma_s, sigma_t with albedo, or internal_transmittance",
            ));
        }
        Coefficients::AbsorptionScattering {
            sigma_a: sigma_a.unwrap_or(Spectrum::Constant(0.0)),
            sigma_s: sigma_s.unwrap_or(Spectrum::Constant(0.0)),
        }
    };
    let phase = match keys.get("phase") {
        None => PhaseFunction::Isotropic,
        Some(v) => phase(cx, v, &format!("{f}.phase"))?,
    };
    Ok(MediumDesc {
        name: name.get_ref().clone(),
        kind: MediumKind::Homogeneous {
            coefficients,
            phase,
            emission: keys
                .get("emission")
                .map(|v| emission(cx, v, &format!("{f}.emission")))
                .transpose()?,
        },
        loc: cx.src.span(&sp),
    })
}

/// A coefficient in m⁻¹: a quantity string, or `{ spectrum, scale }`.
fn coefficient(cx: &Cx<'_>, v: &S<Value>, field: &str) -> R<Spectrum> {
    let per_m = |q: Attenuation| q.get::<attenuation::per_meter>() as f32;
    match v.get_ref() {
        Value::String(_) => {
            let q = per_m(cx.quantity::<Attenuation>(v, field)?);
            if q < 0.0 {
                return Err(cx.err(&v.span(), field, "must not be negative: a coefficient is at least 0"));
            }
            Ok(Spectrum::Constant(q))
        }
        Value::Table(t) => {
            let get = |k: &str| -> R<S<Value>> {
                t.get(k).map(|x| S::new(v.span(), x.clone())).ok_or_else(|| {
                    cx.err(&v.span(), format!("{field}.{k}"), "missing; expected { spectrum = …, scale = \"1 1/m\" }")
                })
            };
            if let Some(k) = t.keys().find(|k| *k != "spectrum" && *k != "scale") {
                return Err(cx.err(&v.span(), format!("{field}.{k}"), "a coefficient table takes spectrum and scale"));
            }
            let shape = cx.spectrum(&get("spectrum")?, &format!("{field}.spectrum"), SpectrumUse::Reflectance)?;
            let scale = cx.quantity::<Attenuation>(&get("scale")?, &format!("{field}.scale"))?;
            if scale.get::<attenuation::per_meter>() < 0.0 {
                return Err(cx.err(
                    &v.span(),
                    format!("{field}.scale"),
                    "must not be negative: a coefficient is at least 0",
                ));
            }
            Ok(shape.scaled(per_m(scale)))
        }
        other => Err(cx.err(
            &v.span(),
            field,
            format!(
                "expected an attenuation coefficient (e.g. \"0.5 1/m\") or {{ spectrum = …, scale = \"1 1/mm\" }}, found {}",
                kind(other)
            ),
        )),
    }
}

/// The emitted radiance Le in W·m⁻²·sr⁻¹·nm⁻¹: a spectral radiance (`"0.01 W/m^2/sr/nm"`),
/// the same at every wavelength, or `{ spectrum = <spectrum>, scale = <spectral radiance> }`.
fn emission(cx: &Cx<'_>, v: &S<Value>, field: &str) -> R<Spectrum> {
    use crate::units::SpectralRadiance;
    use crate::units::spectral_radiance::watt_per_square_meter_steradian_nanometer as per_nm;
    let value = |q: SpectralRadiance, f: &str| -> R<f32> {
        let x = q.get::<per_nm>() as f32;
        if x < 0.0 {
            return Err(cx.err(&v.span(), f, "an emission cannot be negative"));
        }
        Ok(x)
    };
    match v.get_ref() {
        Value::String(_) => Ok(Spectrum::Constant(value(cx.quantity(v, field)?, field)?)),
        Value::Table(t) => {
            if let Some(k) = t.keys().find(|k| *k != "spectrum" && *k != "scale") {
                return Err(cx.err(&v.span(), format!("{field}.{k}"), "an emission table takes spectrum and scale"));
            }
            let get = |k: &str| -> R<S<Value>> {
                t.get(k)
                    .map(|x| S::new(v.span(), x.clone()))
                    .ok_or_else(|| cx.err(&v.span(), format!("{field}.{k}"), "missing"))
            };
            let shape = cx.spectrum(&get("spectrum")?, &format!("{field}.spectrum"), SpectrumUse::Emission)?;
            let f = format!("{field}.scale");
            Ok(shape.scaled(value(cx.quantity(&get("scale")?, &f)?, &f)?))
        }
        other => Err(cx.err(
            &v.span(),
            field,
            format!("expected a spectral radiance (e.g. \"0.01 W/m^2/sr/nm\") or {{ spectrum = …, scale = … }}, found {}", kind(other)),
        )),
    }
}

/// `{ spectrum = τ(λ), thickness = "3 mm" }` as σa(λ) = −ln τ(λ)/d in m⁻¹, tabulated per nm
/// over the range; τ must lie in (0, 1] there.
fn internal_transmittance(
    cx: &Cx<'_>,
    v: &S<Value>,
    field: &str,
    range: &[Length; 2],
) -> R<Spectrum> {
    let Value::Table(t) = v.get_ref() else {
        return Err(cx.err(
            &v.span(),
            field,
            "expected { spectrum = <τ(λ)>, thickness = \"3 mm\" }",
        ));
    };
    if let Some(k) = t.keys().find(|k| *k != "spectrum" && *k != "thickness") {
        return Err(cx.err(
            &v.span(),
            format!("{field}.{k}"),
            "internal_transmittance takes spectrum and thickness",
        ));
    }
    let get = |k: &str| -> R<S<Value>> {
        t.get(k)
            .map(|x| S::new(v.span(), x.clone()))
            .ok_or_else(|| cx.err(&v.span(), format!("{field}.{k}"), "missing"))
    };
    let tau = cx.spectrum(
        &get("spectrum")?,
        &format!("{field}.spectrum"),
        SpectrumUse::Reflectance,
    )?;
    let d = cx.length(&get("thickness")?, &format!("{field}.thickness"))?;
    let d_m = d.get::<length::meter>();
    if !(d_m > 0.0) {
        return Err(cx.err(
            &v.span(),
            format!("{field}.thickness"),
            format!("must be positive, found {d_m} m"),
        ));
    }
    let (lo, hi) = (
        range[0].get::<length::nanometer>(),
        range[1].get::<length::nanometer>(),
    );
    let mut lambda = Vec::new();
    let mut sigma = Vec::new();
    let mut l = lo;
    while l <= hi {
        let tv = tau.eval(l as f32) as f64;
        if !(tv > 0.0 && tv <= 1.0) {
            return Err(cx.err(
                &v.span(),
                format!("{field}.spectrum"),
                format!("is {tv} at {l} nm; an internal transmittance lies in (0, 1]"),
            ));
        }
        lambda.push(l as f32);
        sigma.push((-tv.ln() / d_m) as f32);
        l += 1.0;
    }
    crate::spectrum::PiecewiseLinear::new(lambda, sigma)
        .map(|t| Spectrum::Piecewise(std::sync::Arc::new(t)))
        .map_err(|e| cx.err(&v.span(), field, e.to_string()))
}

/// Checks that the albedo stays within [0, 1] over the range (per nm).
fn at_most_one(cx: &Cx<'_>, s: &Spectrum, v: &S<Value>, field: &str, range: &[Length; 2]) -> R<()> {
    let (lo, hi) = (
        range[0].get::<length::nanometer>(),
        range[1].get::<length::nanometer>(),
    );
    let mut l = lo;
    while l <= hi {
        let x = s.eval(l as f32);
        if x > 1.0 {
            return Err(cx.err(
                &v.span(),
                field,
                format!("is {x} at {l} nm; an albedo above 1 would create energy"),
            ));
        }
        l += 1.0;
    }
    Ok(())
}

/// `"isotropic"`, `"rayleigh"` or `{ type = "hg", g = … }` (|g| < 1).
fn phase(cx: &Cx<'_>, v: &S<Value>, field: &str) -> R<PhaseFunction> {
    let names = ["isotropic", "hg", "rayleigh"];
    let (name, table): (&str, Option<&toml::Table>) = match v.get_ref() {
        Value::String(s) => (s.as_str(), None),
        Value::Table(t) => match t.get("type") {
            Some(Value::String(s)) => (s.as_str(), Some(t)),
            _ => {
                return Err(cx.err(
                    &v.span(),
                    format!("{field}.type"),
                    "missing; expected isotropic, hg or rayleigh",
                ));
            }
        },
        other => {
            return Err(cx.err(
                &v.span(),
                field,
                format!(
                    "expected a phase function name or table, found {}",
                    kind(other)
                ),
            ));
        }
    };
    cx.kind_index(name, &v.span(), field, "phase function", &names)?;
    let extra: BTreeMap<&str, &Value> = table
        .map(|t| {
            t.iter()
                .filter(|(k, _)| *k != "type")
                .map(|(k, v)| (k.as_str(), v))
                .collect()
        })
        .unwrap_or_default();
    match name {
        "hg" => {
            let Some(g) = extra.get("g") else {
                return Err(cx.err(
                    &v.span(),
                    format!("{field}.g"),
                    "missing; Henyey–Greenstein needs its mean cosine g in (−1, 1)",
                ));
            };
            if let Some(k) = extra.keys().find(|k| **k != "g") {
                return Err(cx.err(&v.span(), format!("{field}.{k}"), "hg takes g"));
            }
            let g = cx.number(&S::new(v.span(), (*g).clone()), &format!("{field}.g"))?;
            if !(g.abs() < 1.0) {
                return Err(cx.err(
                    &v.span(),
                    format!("{field}.g"),
                    format!("g must lie strictly between -1 and 1, not {g}"),
                ));
            }
            Ok(PhaseFunction::HenyeyGreenstein { g: g as f32 })
        }
        other => {
            if let Some(k) = extra.keys().next() {
                return Err(cx.err(
                    &v.span(),
                    format!("{field}.{k}"),
                    format!("{other} takes no parameters"),
                ));
            }
            Ok(if other == "rayleigh" {
                PhaseFunction::Rayleigh
            } else {
                PhaseFunction::Isotropic
            })
        }
    }
}
