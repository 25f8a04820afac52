//! `[materials.NAME]`, with the energy check on reflectances.

use super::*;

/// Checks 0 ≤ S(λ) ≤ 1 over the simulated range and the CIE range at 1 nm.
pub(super) fn check_reflectance(
    cx: &Cx<'_>,
    s: &Spectrum,
    span: &Range<usize>,
    field: &str,
    range: &[Length; 2],
) -> R<()> {
    let lo = range[0].get::<length::nanometer>().min(360.0) as i64;
    let hi = range[1].get::<length::nanometer>().max(830.0) as i64;
    for l in lo..=hi {
        let v = s.eval(l as f32);
        if !(0.0..=1.0 + 1e-6).contains(&v) {
            return Err(cx.err(
                span,
                field,
                match field.rsplit('.').next() {
                    Some(what @ ("opacity" | "weight")) => {
                        format!("{what} is {v} at {l} nm; it must lie in [0, 1]")
                    }
                    _ => format!("reflectance is {v} at {l} nm; it must lie in [0, 1], or the surface would create energy"),
                },
            ));
        }
    }
    Ok(())
}

/// A reflectance that may vary over the surface: a spectrum (checked to lie in [0, 1]), or a
/// table with `checkerboard = [a, b]` (two reflectance spectra; `a` on the checks containing
/// uv = (¼, ¼), checks of ½ in uv as Mitsuba's checkerboard) or `image = "file.png"` (PNG, EXR
/// or HDR; `filter` = "bilinear" (default) or "nearest", `wrap` = "repeat" (default), "mirror"
/// or "clamp"), each with an optional `scale = [su, sv]` applied to uv before the lookup.
pub(super) fn reflectance_texture(
    cx: &Cx<'_>,
    r: &S<Value>,
    field: &str,
    range: &[Length; 2],
) -> R<TextureDesc> {
    let span = r.span();
    // entries of an inline table carry the table's span
    let at = |v: &Value| S::new(span.clone(), v.clone());
    let Value::Table(t) = r.get_ref() else {
        let s = cx.spectrum(r, field, SpectrumUse::Reflectance)?;
        check_reflectance(cx, &s, &span, field, range)?;
        return Ok(s.into());
    };
    if !t.contains_key("checkerboard") && !t.contains_key("image") {
        let s = cx.spectrum(r, field, SpectrumUse::Reflectance)?;
        check_reflectance(cx, &s, &span, field, range)?;
        return Ok(s.into());
    }
    let allowed: &[&str] = if t.contains_key("checkerboard") {
        &["checkerboard", "scale"]
    } else {
        &["image", "filter", "wrap", "scale"]
    };
    if let Some(k) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(cx.err(
            &span,
            format!("{field}.{k}"),
            format!("unknown key; a texture here takes {}", allowed.join(", ")),
        ));
    }
    let to_uv = match t.get("scale") {
        None => Vec::new(),
        Some(v) => {
            let sub = format!("{field}.scale");
            let k = match v {
                Value::Array(a) if a.len() == 2 => {
                    [cx.number(&at(&a[0]), &sub)?, cx.number(&at(&a[1]), &sub)?]
                }
                _ => [cx.number(&at(v), &sub)?; 2],
            };
            if !(k[0].is_finite() && k[1].is_finite() && k[0] != 0.0 && k[1] != 0.0) {
                return Err(cx.err(
                    &span,
                    format!("{field}.scale"),
                    "expected a non-zero number or [su, sv]",
                ));
            }
            vec![TransformStep::Scale([k[0], k[1], 1.0])]
        }
    };
    if let Some(c) = t.get("checkerboard") {
        let Value::Array(ab) = c else {
            return Err(cx.err(
                &span,
                format!("{field}.checkerboard"),
                "expected [a, b], two reflectance spectra",
            ));
        };
        if ab.len() != 2 {
            return Err(cx.err(
                &span,
                format!("{field}.checkerboard"),
                format!(
                    "expected [a, b], two reflectance spectra, found {}",
                    ab.len()
                ),
            ));
        }
        let mut ends = Vec::new();
        for (i, v) in ab.iter().enumerate() {
            let sub = format!("{field}.checkerboard[{i}]");
            let s = cx.spectrum(&at(v), &sub, SpectrumUse::Reflectance)?;
            check_reflectance(cx, &s, &span, &sub, range)?;
            ends.push(s);
        }
        let b = ends.pop().unwrap_or(Spectrum::Constant(0.0));
        let a = ends.pop().unwrap_or(Spectrum::Constant(0.0));
        return Ok(TextureDesc::Checkerboard { a, b, to_uv });
    }
    let word = |key: &str, options: &[&str]| -> R<Option<String>> {
        match t.get(key) {
            None => Ok(None),
            Some(v) => match v {
                Value::String(s) if options.contains(&s.as_str()) => Ok(Some(s.clone())),
                _ => Err(cx.err(
                    &span,
                    format!("{field}.{key}"),
                    format!("expected one of {}", options.join(", ")),
                )),
            },
        }
    };
    let img = &t["image"];
    let Value::String(file) = img else {
        return Err(cx.err(&span, format!("{field}.image"), "expected a file name"));
    };
    let path = cx.path(file);
    if !path.is_file() {
        return Err(cx.err(
            &span,
            format!("{field}.image"),
            format!("image file not found: {}", path.display()),
        ));
    }
    let filter = match word("filter", &["bilinear", "nearest"])?.as_deref() {
        Some("nearest") => TexFilter::Nearest,
        _ => TexFilter::Bilinear,
    };
    let wrap = match word("wrap", &["repeat", "mirror", "clamp"])?.as_deref() {
        Some("mirror") => Wrap::Mirror,
        Some("clamp") => Wrap::Clamp,
        _ => Wrap::Repeat,
    };
    Ok(TextureDesc::Bitmap {
        path,
        filter,
        wrap,
        raw: false,
        to_uv,
        loc: cx.src.span(&span),
    })
}

pub(super) fn material(
    cx: &Cx<'_>,
    name: &S<String>,
    m: &S<RawMaterial>,
    range: &[Length; 2],
    all_raw: &std::collections::BTreeMap<S<String>, S<RawMaterial>>,
) -> R<MaterialDesc> {
    let sp = m.span();
    let f = format!("materials.{}", name.get_ref());
    let m = m.get_ref();
    let all = present!(m; kind, reflectance, kd, ks, exponent, ior, exterior_ior, metal, eta, k, roughness, nonlinear, opacity, material, weight, materials, map, height, scale, specular_reflectance, specular_transmittance);
    let ty = cx.required(
        &m.kind,
        &sp,
        &format!("{f}.type"),
        "diffuse, phong, dielectric, conductor, plastic, thin_dielectric, null, mask, blend, normal_map or bump_map",
    )?;
    // `roughness`: a GGX α in [0, 1] (0: smooth), or [α_u, α_v] for an anisotropic lobe
    // (α_u along the surface's ∂p/∂u), where `anisotropic` allows it
    let roughness2 = |cx: &Cx<'_>, anisotropic: bool| -> R<Option<[f64; 2]>> {
        let Some(r) = &m.roughness else {
            return Ok(None);
        };
        if anisotropic && matches!(r.get_ref(), Value::Table(_)) {
            // a texture, read by `lobes` below and looked up at each hit
            return Ok(Some([0.1, 0.1]));
        }
        let field = format!("{f}.roughness");
        let check = |a: f64| -> R<f64> {
            if (0.0..=1.0).contains(&a) {
                Ok(a)
            } else {
                Err(cx.err(
                    &r.span(),
                    &field,
                    format!("expected a GGX α in [0, 1], found {a}"),
                ))
            }
        };
        let a = match r.get_ref() {
            Value::Array(v) if anisotropic => {
                let num = |x: &Value| match x {
                    Value::Integer(i) => Some(*i as f64),
                    Value::Float(f) => Some(*f),
                    _ => None,
                };
                match v.as_slice().iter().map(num).collect::<Vec<_>>()[..] {
                    [Some(u), Some(w)] => [check(u)?, check(w)?],
                    _ => {
                        return Err(cx.err(
                            &r.span(),
                            &field,
                            "expected a number α or two numbers [α_u, α_v]",
                        ));
                    }
                }
            }
            _ => {
                let a = check(cx.number(r, &field)?)?;
                [a, a]
            }
        };
        Ok((a[0] > 0.0 || a[1] > 0.0).then_some(a))
    };
    let roughness = |cx: &Cx<'_>| roughness2(cx, true);
    let exterior = |cx: &Cx<'_>| -> R<f64> {
        match &m.exterior_ior {
            None => Ok(1.0),
            Some(e) => {
                let n = cx.number(e, &format!("{f}.exterior_ior"))?;
                if n < 1.0 {
                    return Err(cx.err(
                        &e.span(),
                        format!("{f}.exterior_ior"),
                        format!("expected an index ≥ 1, found {n}"),
                    ));
                }
                Ok(n)
            }
        }
    };
    let kind = match ty.get_ref().as_str() {
        "diffuse" => {
            cx.only("a diffuse material", &f, &all, &["kind", "reflectance"])?;
            let r = cx.required(
                &m.reflectance,
                &sp,
                &format!("{f}.reflectance"),
                "a reflectance spectrum",
            )?;
            MaterialKind::Diffuse {
                reflectance: reflectance_texture(cx, r, &format!("{f}.reflectance"), range)?,
            }
        }
        "phong" => {
            cx.only(
                "a phong material",
                &f,
                &all,
                &["kind", "kd", "ks", "exponent"],
            )?;
            let kd_v = cx.required(
                &m.kd,
                &sp,
                &format!("{f}.kd"),
                "a diffuse reflectance spectrum",
            )?;
            let ks_v = cx.required(
                &m.ks,
                &sp,
                &format!("{f}.ks"),
                "a specular reflectance spectrum",
            )?;
            let kd = cx.spectrum(kd_v, &format!("{f}.kd"), SpectrumUse::Reflectance)?;
            let ks = cx.spectrum(ks_v, &format!("{f}.ks"), SpectrumUse::Reflectance)?;
            let sum = SumCheck(&kd, &ks);
            check_reflectance(
                cx,
                &sum.spectrum(),
                &ks_v.span(),
                &format!("{f}.kd + {f}.ks"),
                range,
            )?;
            let e = cx.required(
                &m.exponent,
                &sp,
                &format!("{f}.exponent"),
                "a shininess exponent ≥ 0",
            )?;
            let exponent = cx.number(e, &format!("{f}.exponent"))?;
            if !(0.0..=1e6).contains(&exponent) {
                return Err(cx.err(
                    &e.span(),
                    format!("{f}.exponent"),
                    format!("expected 0 to 1e6, found {exponent}"),
                ));
            }
            MaterialKind::Phong { kd, ks, exponent }
        }
        "dielectric" => {
            cx.only(
                "a dielectric material",
                &f,
                &all,
                &[
                    "kind",
                    "ior",
                    "exterior_ior",
                    "roughness",
                    "specular_reflectance",
                    "specular_transmittance",
                ],
            )?;
            let i = cx.required(
                &m.ior,
                &sp,
                &format!("{f}.ior"),
                "an index: a number or a glass name like \"N-BK7\"",
            )?;
            MaterialKind::Dielectric {
                ior: cx.ior(i, &format!("{f}.ior"))?,
                exterior_ior: exterior(cx)?,
                roughness: roughness(cx)?,
                distribution: Distribution::Ggx,
            }
        }
        "null" => {
            cx.only("a null material", &f, &all, &["kind"])?;
            MaterialKind::Null
        }
        // Mitsuba's `normalmap` and `bumpmap` around the material named by `material`: `map`
        // an image of normals encoded (n + 1)/2, or `height` a grey image times `scale`; both
        // images read as stored numbers (Mitsuba's raw = true), not decoded from sRGB
        "normal_map" | "bump_map" => {
            let normal = ty.get_ref() == "normal_map";
            let (key, what): (&str, &str) = if normal {
                ("map", "a normal map material")
            } else {
                ("height", "a bump map material")
            };
            let allowed: &[&str] = if normal {
                &["kind", "map", "material"]
            } else {
                &["kind", "height", "scale", "material"]
            };
            cx.only(what, &f, &all, allowed)?;
            let raw_tex = if normal { &m.map } else { &m.height };
            let t = cx.required(
                raw_tex,
                &sp,
                &format!("{f}.{key}"),
                "an image: { image = \"file.png\" } with optional filter, wrap and scale",
            )?;
            let tex = match reflectance_texture(cx, t, &format!("{f}.{key}"), range)?.raw() {
                t @ TextureDesc::Bitmap { .. } => t,
                _ => {
                    return Err(cx.err(
                        &t.span(),
                        format!("{f}.{key}"),
                        "expected an image: { image = \"file.png\" }",
                    ));
                }
            };
            let inner_name = cx.required(
                &m.material,
                &sp,
                &format!("{f}.material"),
                "the name of the material the map perturbs",
            )?;
            let inner = named(
                cx,
                inner_name,
                &format!("{f}.material"),
                what,
                range,
                all_raw,
            )?;
            if matches!(
                inner.kind,
                MaterialKind::NormalMap { .. } | MaterialKind::BumpMap { .. }
            ) {
                return Err(cx.err(
                    &inner_name.span(),
                    format!("{f}.material"),
                    format!("{what} cannot hold another normal or bump map"),
                ));
            }
            let inner = Box::new(inner.kind);
            if normal {
                MaterialKind::NormalMap { map: tex, inner }
            } else {
                let scale = match &m.scale {
                    Some(v) => cx.number(v, &format!("{f}.scale"))?,
                    None => 1.0,
                };
                MaterialKind::BumpMap {
                    height: tex,
                    scale,
                    inner,
                }
            }
        }
        // Mitsuba's `mask`: `opacity` (a number or a grey texture in [0, 1]) of the material
        // named by `material`, the rest straight through
        "mask" => {
            cx.only(
                "a mask material",
                &f,
                &all,
                &["kind", "opacity", "material"],
            )?;
            let inner_name = cx.required(
                &m.material,
                &sp,
                &format!("{f}.material"),
                "the name of the masked material",
            )?;
            let inner = named(
                cx,
                inner_name,
                &format!("{f}.material"),
                "a mask",
                range,
                all_raw,
            )?;
            let opacity = match &m.opacity {
                Some(o) => reflectance_texture(cx, o, &format!("{f}.opacity"), range)?,
                None => Spectrum::Constant(0.5).into(),
            };
            MaterialKind::Mask {
                opacity,
                inner: Box::new(inner.kind),
            }
        }
        // Mitsuba's `blendbsdf`: (1 − weight)·the first of `materials` + weight·the second
        "blend" => {
            cx.only(
                "a blend material",
                &f,
                &all,
                &["kind", "weight", "materials"],
            )?;
            let names = cx.required(
                &m.materials,
                &sp,
                &format!("{f}.materials"),
                "the names of the two blended materials, [\"a\", \"b\"]",
            )?;
            let [a, b] = &names.get_ref()[..] else {
                return Err(cx.err(
                    &names.span(),
                    format!("{f}.materials"),
                    format!(
                        "expected the names of two materials, found {}",
                        names.get_ref().len()
                    ),
                ));
            };
            let field = format!("{f}.materials");
            let a = named(cx, a, &field, "a blend", range, all_raw)?;
            let b = named(cx, b, &field, "a blend", range, all_raw)?;
            let weight = match &m.weight {
                Some(o) => reflectance_texture(cx, o, &format!("{f}.weight"), range)?,
                None => Spectrum::Constant(0.5).into(),
            };
            MaterialKind::Blend {
                weight,
                a: Box::new(a.kind),
                b: Box::new(b.kind),
            }
        }
        "thin_dielectric" => {
            cx.only(
                "a thin dielectric material",
                &f,
                &all,
                &["kind", "ior", "exterior_ior"],
            )?;
            let i = cx.required(&m.ior, &sp, &format!("{f}.ior"), "the sheet's index")?;
            let n = cx.number(i, &format!("{f}.ior"))?;
            if !(n > 0.0 && n.is_finite()) {
                return Err(cx.err(
                    &i.span(),
                    format!("{f}.ior"),
                    format!("expected a positive index, found {n}"),
                ));
            }
            MaterialKind::ThinDielectric {
                int_ior: n,
                exterior_ior: exterior(cx)?,
            }
        }
        "plastic" => {
            cx.only(
                "a plastic material",
                &f,
                &all,
                &[
                    "kind",
                    "reflectance",
                    "ior",
                    "exterior_ior",
                    "roughness",
                    "nonlinear",
                ],
            )?;
            let r = cx.required(
                &m.reflectance,
                &sp,
                &format!("{f}.reflectance"),
                "the diffuse base's reflectance",
            )?;
            let int_ior = match &m.ior {
                None => 1.49,
                Some(i) => {
                    let n = cx.number(i, &format!("{f}.ior"))?;
                    if !(n > 0.0 && n.is_finite()) {
                        return Err(cx.err(
                            &i.span(),
                            format!("{f}.ior"),
                            format!("expected a positive index, found {n}"),
                        ));
                    }
                    n
                }
            };
            MaterialKind::Plastic {
                diffuse: reflectance_texture(cx, r, &format!("{f}.reflectance"), range)?,
                specular: 1.0,
                int_ior,
                exterior_ior: exterior(cx)?,
                nonlinear: m.nonlinear.as_ref().is_some_and(|b| *b.get_ref()),
                roughness: roughness2(cx, false)?.map(|a| a[0]),
                distribution: Distribution::Ggx,
            }
        }
        "conductor" => {
            cx.only(
                "a conductor material",
                &f,
                &all,
                &[
                    "kind",
                    "metal",
                    "eta",
                    "k",
                    "exterior_ior",
                    "roughness",
                    "specular_reflectance",
                ],
            )?;
            let ior = match (&m.metal, &m.eta, &m.k) {
                (Some(mm), None, None) => cx.metal(mm, &format!("{f}.metal"))?,
                (None, Some(e), Some(k)) => cx.eta_k(e, k, &f)?,
                _ => {
                    return Err(cx.err(
                        &sp,
                        &f,
                        "a conductor needs either `metal` (e.g. \"Au\") or both `eta` and `k`",
                    ));
                }
            };
            MaterialKind::Conductor {
                ior,
                exterior_ior: exterior(cx)?,
                roughness: roughness(cx)?,
                distribution: Distribution::Ggx,
            }
        }
        o => {
            return Err(cx.err(&ty.span(), format!("{f}.type"), format!("unknown material type \"{o}\"; expected diffuse, phong, dielectric, conductor, plastic, thin_dielectric, null, mask, blend, normal_map or bump_map")));
        }
    };
    let kind = if matches!(ty.get_ref().as_str(), "dielectric" | "conductor") {
        lobes(cx, m, &f, range, kind)?
    } else {
        kind
    };
    Ok(MaterialDesc {
        name: name.get_ref().clone(),
        kind,
        loc: cx.src.span(&sp),
    })
}

/// kd + ks as one spectrum, for the energy check.
struct SumCheck<'a>(&'a Spectrum, &'a Spectrum);
impl SumCheck<'_> {
    fn spectrum(&self) -> Spectrum {
        // tabulate at 1 nm over a wide range; only used for the check
        let l: Vec<f32> = (200..=2000).map(|x| x as f32).collect();
        let v: Vec<f32> = l.iter().map(|&x| self.0.eval(x) + self.1.eval(x)).collect();
        match crate::spectrum::PiecewiseLinear::new(l, v) {
            Ok(t) => Spectrum::Piecewise(std::sync::Arc::new(t)),
            Err(_) => Spectrum::Constant(f32::NAN),
        }
    }
}

/// The material called `name` (a mask's `material`, a blend's `materials`), which may not be a
/// mask or a blend itself; errors are located at the name.
fn named(
    cx: &Cx<'_>,
    name: &S<String>,
    field: &str,
    holder: &str,
    range: &[Length; 2],
    all_raw: &std::collections::BTreeMap<S<String>, S<RawMaterial>>,
) -> R<MaterialDesc> {
    let Some((key, raw)) = all_raw.iter().find(|(k, _)| k.get_ref() == name.get_ref()) else {
        return Err(cx.err(
            &name.span(),
            field,
            format!("no material named \"{}\"", name.get_ref()),
        ));
    };
    let kind = raw.get_ref().kind.as_ref().map(|k| k.get_ref().as_str());
    if matches!(kind, Some("mask" | "blend")) {
        return Err(cx.err(
            &name.span(),
            field,
            format!("{holder} cannot hold another mask or blend"),
        ));
    }
    material(cx, key, raw, range, all_raw)
}

/// A conductor or dielectric with a texture for `roughness` (`{ image = … }`, grey, isotropic)
/// or `specular_reflectance` / `specular_transmittance` (spectra or textures) becomes
/// [`MaterialKind::Textured`] around it; otherwise `kind` is returned unchanged.
fn lobes(
    cx: &Cx<'_>,
    m: &RawMaterial,
    f: &str,
    range: &[Length; 2],
    kind: MaterialKind,
) -> R<MaterialKind> {
    let alpha = match &m.roughness {
        Some(r) if matches!(r.get_ref(), Value::Table(_)) => {
            // roughness images are numbers as stored, not sRGB-decoded colours
            let t = reflectance_texture(cx, r, &format!("{f}.roughness"), range)?.raw();
            Some(Box::new([t.clone(), t]))
        }
        _ => None,
    };
    let factor = |v: &Option<S<Value>>, key: &str| -> R<TextureDesc> {
        match v {
            Some(v) => reflectance_texture(cx, v, &format!("{f}.{key}"), range),
            None => Ok(Spectrum::Constant(1.0).into()),
        }
    };
    if alpha.is_none() && m.specular_reflectance.is_none() && m.specular_transmittance.is_none() {
        return Ok(kind);
    }
    Ok(MaterialKind::Textured {
        alpha,
        reflectance: factor(&m.specular_reflectance, "specular_reflectance")?,
        transmittance: factor(&m.specular_transmittance, "specular_transmittance")?,
        inner: Box::new(kind),
    })
}
