//! Mitsuba spectrum properties: a float, `<spectrum>` (λ:value lists, `filename`, `blackbody`,
//! `d65`) and `<rgb>`, read as Mitsuba reads them (emitters shaped by its normalised D65).

use std::sync::Arc;

use super::cx::{Cx, R, mitsuba_d65};
use super::xml::Element;
use crate::spectrum::blackbody::Blackbody;
use crate::spectrum::{PiecewiseLinear, Spectrum, rgb2spec};

impl Cx<'_> {
    /// A spectrum property: float, `spectrum` (value list, filename, type blackbody/d65), `rgb`.
    pub(super) fn spectrum(&self, e: &Element, emission: bool) -> R<Spectrum> {
        let e = self.resolve(e)?;
        match e.tag.as_str() {
            // Mitsuba gives an emitter's bare float the shape of its D65 illuminant
            "float" if emission => Ok(Spectrum::Piecewise(mitsuba_d65(self.float(e)?))),
            "float" => Ok(Spectrum::Constant(self.float(e)? as f32)),
            "rgb" => self.rgb_spectrum(e, emission),
            "spectrum" => {
                if let Some(t) = e.attr("type") {
                    return self.typed_spectrum(e, t);
                }
                if let Some(f) = e.attr("filename") {
                    let path = self.resolve_file(f);
                    let text = crate::files::read_text(&path, crate::files::MAX_TEXT_BYTES).map_err(|er| {
                        self.err(
                            e,
                            format!("cannot read spectrum file {}: {er}", path.display()),
                        )
                    })?;
                    let mut l = Vec::new();
                    let mut v = Vec::new();
                    for line in text
                        .lines()
                        .map(str::trim)
                        .filter(|s| !s.is_empty() && !s.starts_with('#'))
                    {
                        let x = self.floats(e, line)?;
                        if x.len() != 2 {
                            return Err(self.err(
                                e,
                                format!("{}: expected \"wavelength value\" lines", path.display()),
                            ));
                        }
                        l.push(x[0] as f32);
                        v.push(x[1] as f32);
                    }
                    return PiecewiseLinear::new(l, v)
                        .map(|t| Spectrum::Piecewise(Arc::new(t)))
                        .map_err(|er| self.err(e, er.to_string()));
                }
                let v = e
                    .attr("value")
                    .ok_or_else(|| self.err(e, "missing value"))?;
                if !v.contains(':') {
                    return Ok(Spectrum::Constant(
                        self.floats(e, v)?.first().copied().unwrap_or(0.0) as f32,
                    ));
                }
                let mut l = Vec::new();
                let mut y = Vec::new();
                for pair in v.split(',') {
                    let (a, b) = pair
                        .split_once(':')
                        .ok_or_else(|| self.err(e, format!("\"{pair}\" is not λ:value")))?;
                    let a: f32 = a
                        .trim()
                        .parse()
                        .map_err(|_| self.err(e, format!("\"{a}\" is not a wavelength")))?;
                    let b: f32 = b
                        .trim()
                        .parse()
                        .map_err(|_| self.err(e, format!("\"{b}\" is not a number")))?;
                    l.push(a);
                    y.push(b);
                }
                PiecewiseLinear::new(l, y)
                    .map(|t| Spectrum::Piecewise(Arc::new(t)))
                    .map_err(|er| self.err(e, er.to_string()))
            }
            "texture" => Err(self.err(
                e,
                "a texture is not supported here: spectrace reads textures for reflectances, a mask's opacity, a blend's weight, roughness (alpha), specular factors and normal and bump maps, not yet for an emitter's radiance; give a <spectrum>, <rgb> or <float>",
            )),
            other => Err(self.err(
                e,
                format!("<{other}> cannot give a spectrum; use <float>, <spectrum> or <rgb>"),
            )),
        }
    }

    /// An `<rgb>`: an albedo's bounded upsampling, or for an emitter Mitsuba's `d65` with a
    /// colour.
    fn rgb_spectrum(&self, e: &Element, emission: bool) -> R<Spectrum> {
        let v = e
            .attr("value")
            .ok_or_else(|| self.err(e, "missing value"))?;
        let f = self.floats(e, v)?;
        let rgb = match f.len() {
            1 => [f[0] as f32; 3],
            3 => [f[0] as f32, f[1] as f32, f[2] as f32],
            _ => return Err(self.err(e, "expected 3 numbers")),
        };
        if emission {
            // Mitsuba's `d65` spectrum with a colour: the unbounded sigmoid spectrum
            // (scale 2·max(rgb)) times its normalised D65, so RGB (1, 1, 1) is exactly
            // that D65, ∫S ȳ dλ / ∫ȳ dλ ≈ 1, not spectrace's ∫S ȳ dλ = 1
            return match rgb2spec::unbounded(rgb) {
                Ok(Spectrum::Rgb { poly, scale }) => Ok(Spectrum::RgbIlluminant {
                    poly,
                    scale,
                    illuminant: mitsuba_d65(1.0),
                }),
                Ok(other) => Ok(other),
                Err(er) => Err(self.err(e, er.to_string())),
            };
        }
        // Mitsuba's table lookup, not spectrace's refined fit (see `albedo_table`)
        rgb2spec::albedo_table(rgb).map_err(|er| self.err(e, er.to_string()))
    }

    /// A `<spectrum type="…">`: `blackbody` (absolute Planck radiance) or `d65` (Mitsuba's
    /// normalised D65 times `scale`).
    fn typed_spectrum(&self, e: &Element, t: &str) -> R<Spectrum> {
        match t {
            "blackbody" => {
                let t = self
                    .opt_float(e, "temperature")?
                    .ok_or_else(|| self.err(e, "missing temperature"))?;
                if !(t > 0.0) {
                    let at = self.child(e, "temperature").unwrap_or(e);
                    return Err(self.err(
                        at,
                        format!("a blackbody's temperature must be above 0 K, not {t} K"),
                    ));
                }
                Ok(Spectrum::Blackbody(Blackbody::absolute(t as f32)))
            }
            "d65" => {
                if let Some(c) = e.children.iter().find(|c| c.attr("name") != Some("scale")) {
                    return Err(self.err(
                        c,
                        "a d65 spectrum takes only a scale here (no color or nested texture)",
                    ));
                }
                let scale = self.opt_float(e, "scale")?.unwrap_or(1.0);
                Ok(Spectrum::Piecewise(mitsuba_d65(scale)))
            }
            other => Err(self.unsupported(e, "spectrum", other)),
        }
    }

    pub(super) fn spectrum_prop(
        &self,
        e: &Element,
        name: &str,
        default: f32,
        emission: bool,
    ) -> R<Spectrum> {
        match self.child(e, name) {
            Some(c) => self.spectrum(c, emission),
            // an emitter without its spectrum emits Mitsuba's D65 × default
            None if emission => Ok(Spectrum::Piecewise(mitsuba_d65(default as f64))),
            None => Ok(Spectrum::Constant(default)),
        }
    }
}
