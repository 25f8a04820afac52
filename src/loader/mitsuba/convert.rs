//! Mitsuba elements → scene description.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::bsdf::bsdf;
use super::sensor::sensor;
use super::shapes::{emitter, shape};
use super::xml::Element;
use crate::loader::desc::*;
use crate::loader::error::{LoadError, SourceMap};
use crate::spectrum::blackbody::Blackbody;

use crate::spectrum::named::{Named, lookup};
use crate::spectrum::{PiecewiseLinear, Spectrum, rgb2spec};
use crate::units::{Angle, Length, angle, length};

pub(super) type R<T> = Result<T, LoadError>;

/// The supported plugins by kind (`what` of [`Cx::unsupported`]): an unknown type is only ever
/// compared with plugins of its own kind.
const PLUGINS: &[(&str, &[&str])] = &[
    ("sensor", &["perspective", "thinlens"]),
    ("film", &["hdrfilm"]),
    ("rfilter", &["box", "gaussian"]),
    ("sampler", &["independent"]),
    ("integrator", &["path"]),
    (
        "shape",
        &["obj", "ply", "rectangle", "cube", "sphere", "disk"],
    ),
    (
        "bsdf",
        &[
            "diffuse",
            "twosided",
            "conductor",
            "roughconductor",
            "dielectric",
            "roughdielectric",
        ],
    ),
    (
        "emitter",
        &["area", "point", "spot", "constant", "directional"],
    ),
    ("shape emitter", &["area"]),
    ("spectrum", &["blackbody", "d65"]),
    (
        "transform",
        &["translate", "scale", "rotate", "matrix", "lookat"],
    ),
];

/// Mitsuba 3's `MI_CIE_D65_NORMALIZATION` (`include/mitsuba/core/spectrum.h`, 3.9.1): its
/// `d65` spectrum is the CIE D65 relative SPD (100 at 560 nm) times this, so that
/// ∫ D65 ȳ dλ / ∫ ȳ dλ = 1 on its own 5 nm tables (checked against `mi.load_dict({"type": "d65"})`
/// in tests/mitsuba_import.rs).
pub(super) const MITSUBA_D65_NORMALIZATION: f64 = 1.0 / 98.99741751876255;

/// Mitsuba's `d65` spectrum with `scale`: the CIE D65 table × scale × [`MITSUBA_D65_NORMALIZATION`],
/// in the emitter's own units (W·m⁻²·sr⁻¹·nm⁻¹ for radiance).
pub(super) fn mitsuba_d65(scale: f64) -> Arc<PiecewiseLinear> {
    match lookup("cie-d65") {
        Ok(Named::Curve {
            spectrum: Spectrum::Piecewise(t),
            ..
        }) => Arc::new(t.scaled((scale * MITSUBA_D65_NORMALIZATION) as f32)),
        // the table is embedded in the binary; its presence is tested in spectrum::named
        _ => unreachable!("cie-d65 is missing from the embedded data"), // ok: embedded, tested
    }
}

pub(super) struct Cx<'a> {
    /// (file, text) of the scene and every included file.
    sources: Vec<(PathBuf, String)>,
    defines: &'a HashMap<String, String>,
    params: HashMap<String, String>,
    ids: HashMap<String, Element>,
}

impl Cx<'_> {
    pub(super) fn err(&self, e: &Element, msg: impl Into<String>) -> LoadError {
        let (file, text) = &self.sources[e.src];
        let field = match e.attr("name") {
            Some(n) => format!("<{} name=\"{n}\">", e.tag),
            None => format!("<{}>", e.tag),
        };
        LoadError::new(file, SourceMap::new(text).loc(e.pos), field, msg)
    }

    pub(super) fn loc(&self, e: &Element) -> crate::loader::Loc {
        SourceMap::new(&self.sources[e.src].1).loc(e.pos)
    }

    pub(super) fn dir(&self, e: &Element) -> PathBuf {
        self.sources[e.src]
            .0
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default()
    }

    pub(super) fn unsupported(&self, e: &Element, what: &str, kind: &str) -> LoadError {
        let same_kind = PLUGINS
            .iter()
            .find(|(k, _)| *k == what)
            .map(|(_, names)| *names)
            .unwrap_or(&[]);
        let near = same_kind
            .iter()
            .max_by(|a, b| strsim::jaro_winkler(kind, a).total_cmp(&strsim::jaro_winkler(kind, b)))
            .copied();
        let msg = match near {
            Some(near) => format!(
                "{what} type \"{kind}\" is not supported; the nearest supported {what} is \"{near}\" (supported: {})",
                same_kind.join(", ")
            ),
            None => format!("{what} type \"{kind}\" is not supported"),
        };
        self.err(e, msg)
    }

    /// `$name` substitution in every attribute value, recursively.
    pub(super) fn substitute(&self, e: &mut Element) -> R<()> {
        for (k, v) in e.attrs.iter_mut() {
            while let Some(i) = v.find('$') {
                let rest = &v[i + 1..];
                let end = rest
                    .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .unwrap_or(rest.len());
                let name = &rest[..end];
                let Some(value) = self.defines.get(name).or_else(|| self.params.get(name)) else {
                    let (file, text) = &self.sources[e.src];
                    return Err(LoadError::new(
                        file,
                        SourceMap::new(text).loc(e.pos),
                        format!("<{}> {k}", e.tag),
                        format!(
                            "${name} is not defined: add <default name=\"{name}\" value=\"…\"/> or -D {name}=…"
                        ),
                    ));
                };
                *v = format!("{}{}{}", &v[..i], value, &rest[end..]);
            }
        }
        for c in &mut e.children {
            self.substitute(c)?;
        }
        Ok(())
    }

    pub(super) fn float(&self, e: &Element) -> R<f64> {
        let v = e
            .attr("value")
            .ok_or_else(|| self.err(e, "missing value"))?;
        let x: f64 = v
            .trim()
            .parse()
            .map_err(|_| self.err(e, format!("\"{v}\" is not a number")))?;
        if !x.is_finite() {
            return Err(self.err(e, format!("\"{v}\" is not finite")));
        }
        Ok(x)
    }

    pub(super) fn floats(&self, e: &Element, s: &str) -> R<Vec<f64>> {
        s.split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .map(|t| {
                t.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| self.err(e, format!("\"{t}\" is not a number")))
            })
            .collect()
    }

    /// A `point`/`vector` from x, y, z or value attributes.
    pub(super) fn vec3(&self, e: &Element) -> R<[f64; 3]> {
        if let Some(v) = e.attr("value") {
            let f = self.floats(e, v)?;
            return match f.len() {
                1 => Ok([f[0]; 3]),
                3 => Ok([f[0], f[1], f[2]]),
                _ => Err(self.err(e, format!("expected 1 or 3 numbers, found {}", f.len()))),
            };
        }
        let mut out = [0.0; 3];
        for (i, k) in ["x", "y", "z"].iter().enumerate() {
            if let Some(v) = e.attr(k) {
                out[i] = self.floats(e, v)?.first().copied().unwrap_or(0.0);
            }
        }
        Ok(out)
    }

    pub(super) fn child<'e>(&self, e: &'e Element, name: &str) -> Option<&'e Element> {
        e.children.iter().find(|c| c.attr("name") == Some(name))
    }

    pub(super) fn opt_float(&self, e: &Element, name: &str) -> R<Option<f64>> {
        self.child(e, name).map(|c| self.float(c)).transpose()
    }

    pub(super) fn string(&self, e: &Element, name: &str) -> Option<String> {
        self.child(e, name)
            .and_then(|c| c.attr("value"))
            .map(str::to_string)
    }

    pub(super) fn resolve<'e>(&'e self, e: &'e Element) -> R<&'e Element> {
        if e.tag == "ref" {
            let id = e.attr("id").ok_or_else(|| self.err(e, "missing id"))?;
            return self.ids.get(id).ok_or_else(|| {
                self.err(e, format!("refers to id \"{id}\", which is not defined"))
            });
        }
        Ok(e)
    }

    /// A spectrum property: float, `spectrum` (value list, filename, type blackbody/d65), `rgb`.
    pub(super) fn spectrum(&self, e: &Element, emission: bool) -> R<Spectrum> {
        let e = self.resolve(e)?;
        match e.tag.as_str() {
            // Mitsuba gives an emitter's bare float the shape of its D65 illuminant
            "float" if emission => Ok(Spectrum::Piecewise(mitsuba_d65(self.float(e)?))),
            "float" => Ok(Spectrum::Constant(self.float(e)? as f32)),
            "rgb" => {
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
                rgb2spec::albedo(rgb).map_err(|er| self.err(e, er.to_string()))
            }
            "spectrum" => {
                if let Some(t) = e.attr("type") {
                    return match t {
                        "blackbody" => {
                            let t = self
                                .opt_float(e, "temperature")?
                                .ok_or_else(|| self.err(e, "missing temperature"))?;
                            Ok(Spectrum::Blackbody(Blackbody::absolute(t as f32)))
                        }
                        "d65" => {
                            if let Some(c) =
                                e.children.iter().find(|c| c.attr("name") != Some("scale"))
                            {
                                return Err(self.err(
                                    c,
                                    "a d65 spectrum takes only a scale here (no color or nested texture)",
                                ));
                            }
                            let scale = self.opt_float(e, "scale")?.unwrap_or(1.0);
                            Ok(Spectrum::Piecewise(mitsuba_d65(scale)))
                        }
                        other => Err(self.unsupported(e, "spectrum", other)),
                    };
                }
                if let Some(f) = e.attr("filename") {
                    let path = self.dir(e).join(f);
                    let text = std::fs::read_to_string(&path).map_err(|er| {
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
            other => Err(self.err(
                e,
                format!("<{other}> cannot give a spectrum; use <float>, <spectrum> or <rgb>"),
            )),
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

    /// `to_world` steps in order.
    pub(super) fn transform(&self, t: &Element) -> R<Vec<TransformStep>> {
        let m = |x: f64| Length::new::<length::meter>(x);
        let mut steps = Vec::new();
        for c in &t.children {
            steps.push(match c.tag.as_str() {
                "translate" => TransformStep::Translate(self.vec3(c)?.map(m)),
                "scale" => TransformStep::Scale({
                    let mut s = self.vec3(c)?;
                    if c.attr("value").is_none() {
                        for (i, k) in ["x", "y", "z"].iter().enumerate() {
                            if c.attr(k).is_none() {
                                s[i] = 1.0;
                            }
                        }
                    }
                    s
                }),
                "rotate" => {
                    let a = c
                        .attr("angle")
                        .ok_or_else(|| self.err(c, "missing angle (degrees)"))?;
                    let deg = self.floats(c, a)?.first().copied().unwrap_or(0.0);
                    let axis = match c.attr("value") {
                        Some(_) => self.vec3(c)?,
                        None => self.vec3(c)?,
                    };
                    if axis == [0.0; 3] {
                        return Err(self.err(c, "the rotation axis is zero"));
                    }
                    TransformStep::Rotate {
                        axis,
                        angle: Angle::new::<angle::degree>(deg),
                    }
                }
                "matrix" => {
                    let v = c
                        .attr("value")
                        .ok_or_else(|| self.err(c, "missing value"))?;
                    let f = self.floats(c, v)?;
                    if f.len() != 16 {
                        return Err(self.err(c, format!("expected 16 numbers, found {}", f.len())));
                    }
                    let mut a = [0.0; 16];
                    a.copy_from_slice(&f);
                    TransformStep::Matrix(a)
                }
                "lookat" => {
                    let g = |k: &str| -> R<[f64; 3]> {
                        let v = c
                            .attr(k)
                            .ok_or_else(|| self.err(c, format!("missing {k}")))?;
                        let f = self.floats(c, v)?;
                        if f.len() != 3 {
                            return Err(self.err(c, format!("{k}: expected 3 numbers")));
                        }
                        Ok([f[0], f[1], f[2]])
                    };
                    TransformStep::LookAt {
                        eye: g("origin")?.map(m),
                        target: g("target")?.map(m),
                        up: if c.attr("up").is_some() {
                            g("up")?
                        } else {
                            [0.0, 1.0, 0.0]
                        },
                    }
                }
                other => return Err(self.unsupported(c, "transform", other)),
            });
        }
        Ok(steps)
    }
}

pub(super) fn scene(
    mut root: Element,
    text: &str,
    path: &Path,
    defines: &HashMap<String, String>,
) -> R<SceneDesc> {
    let mut cx = Cx {
        sources: vec![(path.to_path_buf(), text.to_string())],
        defines,
        params: HashMap::new(),
        ids: HashMap::new(),
    };
    if root.tag != "scene" {
        return Err(cx.err(&root, "the root element must be <scene>"));
    }
    match root.attr("version") {
        Some(v) if v.starts_with("3.") || v.starts_with("2.") => {}
        Some(v) => {
            return Err(cx.err(
                &root,
                format!("scene version {v} is not supported; use 2.x or 3.x"),
            ));
        }
        None => return Err(cx.err(&root, "missing version (e.g. version=\"3.0.0\")")),
    }
    // includes, spliced in place (depth-limited)
    let mut depth = 0;
    while root.children.iter().any(|c| c.tag == "include") {
        depth += 1;
        if depth > 16 {
            return Err(cx.err(&root, "includes nest more than 16 deep"));
        }
        let mut out = Vec::new();
        for c in std::mem::take(&mut root.children) {
            if c.tag != "include" {
                out.push(c);
                continue;
            }
            let f = c
                .attr("filename")
                .ok_or_else(|| cx.err(&c, "missing filename"))?;
            let p = cx.dir(&c).join(f);
            let t = std::fs::read_to_string(&p)
                .map_err(|e| cx.err(&c, format!("cannot read {}: {e}", p.display())))?;
            let mut inc = super::parse_file(&t, &p)?;
            cx.sources.push((p, t));
            inc.set_source(cx.sources.len() - 1);
            out.extend(inc.children);
        }
        root.children = out;
    }
    for c in root.children.iter().filter(|c| c.tag == "default") {
        let (Some(n), Some(v)) = (c.attr("name"), c.attr("value")) else {
            return Err(cx.err(c, "a <default> needs name and value"));
        };
        cx.params.insert(n.to_string(), v.to_string());
    }
    cx.substitute(&mut root)?;
    for c in &root.children {
        if let Some(id) = c.attr("id") {
            cx.ids.insert(id.to_string(), c.clone());
        }
    }

    let mut film = FilmDesc {
        width: 768,
        height: 576,
        spp: 4,
        // Mitsuba's default rfilter
        filter: FilterDesc::MitsubaGaussian { stddev: 0.5 },
        spectral_bins: 0,
        exposure_ev: None,
        loc: Default::default(),
    };
    let mut integrator = IntegratorDesc {
        kind: IntegratorKind::Path,
        max_depth: 1024,
        rr_depth: DEFAULT_RR_DEPTH,
        // Mitsuba chooses emitters in proportion to their sampling_weight, 1 by default
        light_selection: LightSelection::Uniform,
    };
    let mut camera = None;
    let mut materials: Vec<MaterialDesc> = Vec::new();
    let mut material_ids: HashMap<String, (usize, bool)> = HashMap::new();
    let mut shapes = Vec::new();
    let mut lights = Vec::new();

    for c in &root.children {
        match c.tag.as_str() {
            "default" | "include" => {}
            "integrator" => {
                let t = c.attr("type").unwrap_or("");
                if t != "path" {
                    return Err(cx.unsupported(c, "integrator", t));
                }
                if let Some(d) = cx.child(c, "max_depth") {
                    integrator.max_depth = max_depth(&cx, d)?;
                }
                // Mitsuba's rr_depth: roulette may end a path at vertex k > rr_depth (vertex 1
                // is the first surface hit), the same meaning as spectrace's
                if let Some(d) = cx.child(c, "rr_depth") {
                    let v = cx.float(d)?;
                    if v.fract() != 0.0 || v <= 0.0 {
                        return Err(
                            cx.err(d, format!("rr_depth must be a positive integer, not {v}"))
                        );
                    }
                    integrator.rr_depth = v.min(1024.0) as u32;
                }
                if let Some(h) = cx.child(c, "hide_emitters")
                    && h.attr("value") == Some("true")
                {
                    return Err(cx.err(
                        h,
                        "hide_emitters = true is not supported: spectrace always shows emitters seen directly",
                    ));
                }
            }
            "sensor" => camera = Some(sensor(&cx, c, &mut film)?),
            "bsdf" => {
                if let Some(id) = c.attr("id") {
                    let (m, two) = bsdf(&cx, c, id)?;
                    material_ids.insert(id.to_string(), (materials.len(), two));
                    materials.push(m);
                }
            }
            "shape" => shapes.push(shape(&cx, c, &mut materials, &material_ids)?),
            "emitter" => lights.push(emitter(&cx, c)?),
            "spectrum" | "texture" | "rgb" | "float" => {}
            other => {
                return Err(cx.err(
                    c,
                    format!("<{other}> is not supported at the top level of a scene"),
                ));
            }
        }
    }
    let camera = camera.ok_or_else(|| cx.err(&root, "the scene has no <sensor>"))?;
    let nm = |x: f64| Length::new::<length::nanometer>(x);
    Ok(SceneDesc {
        path: path.to_path_buf(),
        wavelength_range: [nm(360.0), nm(830.0)],
        camera,
        film,
        integrator,
        materials,
        shapes,
        lights,
    })
}

/// Mitsuba's `max_depth` (path length: 1 = emitters seen directly, 2 = one bounce, −1 =
/// unlimited) as spectrace's number of bounces (0 = emitters seen directly; 1024 = unlimited).
/// Mitsuba's 0 renders black and anything below −1 is an error in Mitsuba: both are refused.
fn max_depth(cx: &Cx<'_>, d: &Element) -> R<u32> {
    let v = cx.float(d)?;
    if v.fract() != 0.0 {
        return Err(cx.err(d, format!("max_depth must be an integer, not {v}")));
    }
    match v as i64 {
        -1 => Ok(1024),
        0 => Err(cx.err(
            d,
            "max_depth 0 renders a black image in Mitsuba; use 1 for emitters seen directly",
        )),
        n if n < -1 => Err(cx.err(
            d,
            format!("max_depth must be -1 (unlimited) or at least 1, not {n}"),
        )),
        n => Ok((n - 1).min(1024) as u32),
    }
}
