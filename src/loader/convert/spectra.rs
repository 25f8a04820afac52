//! Spectra and indices of refraction in scene files.
//!
//! A spectrum is one of: a number (constant); a name (`"cie-d65"`, `"colorchecker:red"`,
//! `"blackbody:3200K"`); a CSV path (`"data/led.csv"`, relative to the scene file); or a table:
//! `{ samples = [[λ_nm, v], …] }`, `{ file = "…" }`, `{ name = "…" }`, `{ blackbody = "6500 K" }`
//! (absolute Planck radiance, W·m⁻²·sr⁻¹·nm⁻¹), `{ rgb = [r, g, b] }` (linear sRGB, upsampled).

use std::ops::Range;
use std::sync::Arc;

use toml::Value;

use super::{Cx, R, kind};
use crate::loader::raw::S;
use crate::spectrum::blackbody::Blackbody;
use crate::spectrum::data::load_spectrum_file;
use crate::spectrum::ior::{Cauchy, ComplexIor, Ior, Sellmeier};
use crate::spectrum::named::{Named, lookup};
use crate::spectrum::{PiecewiseLinear, Spectrum, rgb2spec};
use crate::units::{ThermodynamicTemperature, plain};

/// What a spectrum is for; sets how an RGB is upsampled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SpectrumUse {
    /// A reflectance: RGB in [0, 1], bounded upsampling.
    Reflectance,
    /// An emission shape: RGB ≥ 0, illuminant upsampling (D65 white).
    Emission,
}

fn looks_like_path(s: &str) -> bool {
    s.ends_with(".csv") || s.contains('/') || s.contains('\\')
}

impl Cx<'_> {
    pub fn spectrum(&self, v: &S<Value>, field: &str, usage: SpectrumUse) -> R<Spectrum> {
        let span = v.span();
        match v.get_ref() {
            Value::Integer(_) | Value::Float(_) => {
                let x = self.number(v, field)?;
                if x < 0.0 {
                    return Err(self.err(
                        &span,
                        field,
                        format!("a spectrum cannot be negative, found {x}"),
                    ));
                }
                Ok(Spectrum::Constant(x as f32))
            }
            Value::String(s) if looks_like_path(s) => self.spectrum_file(s, &span, field),
            Value::String(s) => self.named_spectrum(s, &span, field),
            Value::Table(t) => {
                let keys: Vec<&str> = t.keys().map(String::as_str).collect();
                if keys.len() != 1 {
                    return Err(self.err(
                        &span,
                        field,
                        format!(
                            "a spectrum table has exactly one of samples, file, name, blackbody, rgb; found {{{}}}",
                            keys.join(", ")
                        ),
                    ));
                }
                let val = &t[keys[0]];
                let sub = format!("{field}.{}", keys[0]);
                match (keys[0], val) {
                    ("samples", Value::Array(a)) => self.samples(a, &span, &sub),
                    ("file", Value::String(s)) => self.spectrum_file(s, &span, &sub),
                    ("name", Value::String(s)) => self.named_spectrum(s, &span, &sub),
                    ("blackbody", Value::String(s)) => {
                        let t: ThermodynamicTemperature = crate::units::parse::parse(s)
                            .map_err(|e| self.err(&span, &sub, e.to_string()))?;
                        let k = plain::kelvin_f32(t);
                        if k <= 0.0 {
                            return Err(self.err(&span, &sub, format!("temperature must be positive, found {s}")));
                        }
                        Ok(Spectrum::Blackbody(Blackbody::absolute(k)))
                    }
                    ("rgb", Value::Array(_)) => {
                        let sv = S::new(span.clone(), val.clone());
                        let rgb = self.vec3(&sv, &sub)?.map(|x| x as f32);
                        let r = match usage {
                            SpectrumUse::Reflectance => rgb2spec::albedo(rgb),
                            SpectrumUse::Emission => rgb2spec::illuminant(rgb),
                        };
                        r.map_err(|e| self.err(&span, &sub, e.to_string()))
                    }
                    (k @ ("samples" | "file" | "name" | "blackbody" | "rgb"), other) => Err(self.err(
                        &span,
                        &sub,
                        format!("`{k}` has the wrong type ({}); see the scene format in the README", kind(other)),
                    )),
                    (k, _) => Err(self.err(
                        &span,
                        &sub,
                        format!("unknown spectrum form `{k}`; expected samples, file, name, blackbody or rgb"),
                    )),
                }
            }
            other => Err(self.err(
                &span,
                field,
                format!(
                    "expected a spectrum (number, name, file or table), found {}",
                    kind(other)
                ),
            )),
        }
    }

    fn named_spectrum(&self, s: &str, span: &std::ops::Range<usize>, field: &str) -> R<Spectrum> {
        match lookup(s) {
            Ok(Named::Curve { spectrum, .. }) => Ok(spectrum),
            Ok(_) => Err(self.err(
                span,
                field,
                format!("\"{s}\" is an index of refraction, not a spectrum"),
            )),
            Err(e) => Err(self.err(span, field, e.to_string())),
        }
    }

    fn spectrum_file(&self, s: &str, span: &std::ops::Range<usize>, field: &str) -> R<Spectrum> {
        let path = self.path(s);
        if !path.exists() {
            return Err(self.err(
                span,
                field,
                format!("spectrum file not found: {}", path.display()),
            ));
        }
        let t = load_spectrum_file(&path).map_err(|e| self.err(span, field, e.to_string()))?;
        if t.values().iter().any(|v| *v < 0.0) {
            return Err(self.err(
                span,
                field,
                format!("{} has negative values", path.display()),
            ));
        }
        Ok(Spectrum::Piecewise(Arc::new(t)))
    }

    fn samples(&self, a: &[Value], span: &std::ops::Range<usize>, field: &str) -> R<Spectrum> {
        let (lambda, value) = self.pairs(a, span, field)?;
        if value.iter().any(|v| *v < 0.0) {
            return Err(self.err(span, field, "a spectrum cannot be negative"));
        }
        PiecewiseLinear::new(lambda, value)
            .map(|t| Spectrum::Piecewise(Arc::new(t)))
            .map_err(|e| self.err(span, field, e.to_string()))
    }

    /// `[[λ_nm, v], …]` as two columns.
    fn pairs(
        &self,
        a: &[Value],
        span: &std::ops::Range<usize>,
        field: &str,
    ) -> R<(Vec<f32>, Vec<f32>)> {
        let mut lambda = Vec::with_capacity(a.len());
        let mut value = Vec::with_capacity(a.len());
        for (i, p) in a.iter().enumerate() {
            let pair = match p {
                Value::Array(x) if x.len() == 2 => x,
                _ => {
                    return Err(self.err(
                        span,
                        format!("{field}[{i}]"),
                        "expected [wavelength_nm, value]",
                    ));
                }
            };
            let num = |x: &Value| match x {
                Value::Integer(n) => Some(*n as f32),
                Value::Float(f) if f.is_finite() => Some(*f as f32),
                _ => None,
            };
            match (num(&pair[0]), num(&pair[1])) {
                (Some(l), Some(v)) if l > 0.0 => {
                    lambda.push(l);
                    value.push(v);
                }
                _ => {
                    return Err(self.err(
                        span,
                        format!("{field}[{i}]"),
                        "expected [wavelength_nm > 0, finite value]",
                    ));
                }
            }
        }
        Ok((lambda, value))
    }

    /// A dielectric index: a number, a glass name (`"glass:N-BK7"` or `"N-BK7"`), or
    /// `{ sellmeier = { B = […], C = […] } }` (λ in µm, C in µm²), `{ cauchy = { A, B, C } }`,
    /// `{ model = { nd, vd } }` (a model glass from its catalogue n_d and Abbe number,
    /// [`Ior::model`]), `{ samples = [[λ_nm, n], …] }`.
    pub fn ior(&self, v: &S<Value>, field: &str) -> R<Ior> {
        let span = v.span();
        match v.get_ref() {
            Value::Integer(_) | Value::Float(_) => {
                let n = self.number(v, field)?;
                if n < 1.0 {
                    return Err(self.err(
                        &span,
                        field,
                        format!("an index of refraction below 1 ({n}) is not supported"),
                    ));
                }
                Ok(Ior::Constant(n as f32))
            }
            Value::String(s) => {
                let name = if s.contains(':') {
                    s.clone()
                } else {
                    format!("glass:{s}")
                };
                match lookup(&name) {
                    Ok(Named::Dielectric(g)) => Ok(g.ior),
                    Ok(_) => Err(self.err(&span, field, format!("\"{s}\" is not a dielectric"))),
                    Err(e) => Err(self.err(&span, field, e.to_string())),
                }
            }
            Value::Table(t) if t.len() == 1 => {
                let (key, val) = t
                    .iter()
                    .next()
                    .map(|(k, v)| (k.as_str(), v))
                    .unwrap_or(("", v.get_ref()));
                self.ior_formula(key, val, &span, &format!("{field}.{key}"))
            }
            other => Err(self.err(
                &span,
                field,
                format!(
                    "expected an index of refraction (number, glass name or table), found {}",
                    kind(other)
                ),
            )),
        }
    }

    /// An index given by a formula or samples: `sellmeier = { A, B, C }`, `cauchy = { A, B,
    /// C }` or `samples = [[λ_nm, n], …]` (the table's one key, `key`, at the field `sub`).
    fn ior_formula(&self, key: &str, val: &Value, span: &Range<usize>, sub: &str) -> R<Ior> {
        match (key, val) {
            ("sellmeier", Value::Table(tt)) => {
                if let Some(k) = tt.keys().find(|k| !["A", "B", "C"].contains(&k.as_str())) {
                    return Err(self.err(
                        span,
                        format!("{sub}.{k}"),
                        "unknown key; expected A, B, C",
                    ));
                }
                let a = if tt.contains_key("A") {
                    self.coeffs(tt, span, sub, "A")?[0]
                } else {
                    0.0
                };
                let (b, c) = (
                    self.coeffs(tt, span, sub, "B")?,
                    self.coeffs(tt, span, sub, "C")?,
                );
                if b.len() != c.len() || b.is_empty() || b.len() > 4 {
                    return Err(self.err(span, sub, "B and C need the same length, 1 to 4 terms"));
                }
                let mut s = Sellmeier {
                    a,
                    b: [0.0; 4],
                    c: [0.0; 4],
                };
                s.b[..b.len()].copy_from_slice(&b);
                s.c[..c.len()].copy_from_slice(&c);
                Ok(Ior::Sellmeier(s))
            }
            ("cauchy", Value::Table(tt)) => {
                if let Some(k) = tt.keys().find(|k| !["A", "B", "C"].contains(&k.as_str())) {
                    return Err(self.err(
                        span,
                        format!("{sub}.{k}"),
                        "unknown key; expected A, B, C",
                    ));
                }
                let a = self.coeffs(tt, span, sub, "A")?[0];
                let b = self.coeffs(tt, span, sub, "B")?[0];
                let c = if tt.contains_key("C") {
                    self.coeffs(tt, span, sub, "C")?[0]
                } else {
                    0.0
                };
                Ok(Ior::Cauchy(Cauchy {
                    a: a as f32,
                    b: b as f32,
                    c: c as f32,
                }))
            }
            ("samples", Value::Array(a)) => {
                let (l, n) = self.pairs(a, span, sub)?;
                if n.iter().any(|n| *n < 1.0) {
                    return Err(self.err(
                        span,
                        sub,
                        "an index of refraction below 1 is not supported",
                    ));
                }
                PiecewiseLinear::new(l, n)
                    .map(|t| Ior::Table(Arc::new(t)))
                    .map_err(|e| self.err(span, sub, e.to_string()))
            }
            ("model", Value::Table(tt)) => {
                if let Some(k) = tt.keys().find(|k| !["nd", "vd"].contains(&k.as_str())) {
                    return Err(self.err(span, format!("{sub}.{k}"), "unknown key; expected nd, vd"));
                }
                let nd = self.coeffs(tt, span, sub, "nd")?[0];
                let vd = self.coeffs(tt, span, sub, "vd")?[0];
                Ior::model(nd, vd).ok_or_else(|| {
                    self.err(span, sub, "a model glass needs nd ≥ 1 and an Abbe number vd > 0")
                })
            }
            _ => Err(self.err(
                span,
                sub,
                "expected sellmeier = {B, C}, cauchy = {A, B, C}, model = {nd, vd} or samples = [[λ, n], …]",
            )),
        }
    }

    /// The numbers of coefficient `name` of a formula table: a number or a list.
    fn coeffs(&self, tt: &toml::Table, span: &Range<usize>, sub: &str, name: &str) -> R<Vec<f64>> {
        match tt.get(name) {
            Some(Value::Array(a)) => a
                .iter()
                .map(|x| match x {
                    Value::Integer(n) => Ok(*n as f64),
                    Value::Float(f) if f.is_finite() => Ok(*f),
                    _ => Err(self.err(span, format!("{sub}.{name}"), "expected finite numbers")),
                })
                .collect(),
            Some(Value::Integer(n)) => Ok(vec![*n as f64]),
            Some(Value::Float(f)) if f.is_finite() => Ok(vec![*f]),
            _ => Err(self.err(
                span,
                format!("{sub}.{name}"),
                "missing or not a number list",
            )),
        }
    }

    /// A conductor's complex index from a metal name (`"metal:Au"` or `"Au"`).
    pub fn metal(&self, v: &S<String>, field: &str) -> R<ComplexIor> {
        let s = v.get_ref();
        let name = if s.contains(':') {
            s.clone()
        } else {
            format!("metal:{s}")
        };
        match lookup(&name) {
            Ok(Named::Conductor(m)) => Ok(m.ior),
            Ok(_) => Err(self.err(&v.span(), field, format!("\"{s}\" is not a metal"))),
            Err(e) => Err(self.err(&v.span(), field, e.to_string())),
        }
    }

    /// A conductor's complex index from `eta` and `k` spectra.
    pub fn eta_k(&self, eta: &S<Value>, k: &S<Value>, field: &str) -> R<ComplexIor> {
        let table = |v: &S<Value>, name: &str| -> R<Arc<PiecewiseLinear>> {
            let f = format!("{field}.{name}");
            match self.spectrum(v, &f, SpectrumUse::Emission)? {
                Spectrum::Piecewise(t) => Ok(t),
                Spectrum::Constant(c) => Ok(Arc::new(
                    PiecewiseLinear::new(vec![1.0, 1e5], vec![c, c])
                        .map_err(|e| self.err(&v.span(), &f, e.to_string()))?,
                )),
                _ => Err(self.err(
                    &v.span(),
                    &f,
                    "expected a number, a table of samples or a file",
                )),
            }
        };
        Ok(ComplexIor {
            n: table(eta, "eta")?,
            k: table(k, "k")?,
        })
    }
}
