//! `[materials.NAME]`: dispatch by `type` through [`KINDS`], one reader per kind in its own file.
//!
//! A kind's file holds `KIND`: its `type` name, the keys it takes and a reader from a
//! [`Mat`] (the material's keys, with located errors and the shared readers for reflectances,
//! roughness and the materials it names). Keys the kind does not take are errors naming them
//! and the keys it does take, so a misspelt key never passes silently.

mod blend;
mod coating;
mod conductor;
mod dielectric;
mod diffuse;
mod element;
mod mask;
mod measured;
mod null;
mod perturb;
mod phong;
mod plastic;
mod pplastic;
mod texture;
mod thin_dielectric;

use std::collections::BTreeMap;

use super::*;
use crate::loader::LoadError;
use crate::loader::convert::kind;
use crate::params::did_you_mean;
use texture::{check_reflectance, reflectance_texture};

/// A material kind's TOML reader.
pub(super) struct Kind {
    /// The `type` name.
    name: &'static str,
    /// The keys it takes besides `type`.
    keys: &'static [&'static str],
    /// Reads the material; the keys were checked against `keys` before.
    read: fn(&Mat<'_>) -> R<MaterialKind>,
}

/// Every material kind of the TOML format, in the order "expected …" lists them.
const KINDS: &[Kind] = &[
    diffuse::KIND,
    phong::KIND,
    dielectric::KIND,
    conductor::KIND,
    plastic::KIND,
    pplastic::KIND,
    measured::KIND,
    thin_dielectric::KIND,
    coating::THIN_FILM,
    null::KIND,
    element::POLARISER,
    element::RETARDER,
    mask::KIND,
    blend::KIND,
    perturb::NORMAL_MAP,
    perturb::BUMP_MAP,
];

/// The materials of the file by name, for the materials that name others.
type AllRaw = BTreeMap<S<String>, S<RawMaterial>>;

/// One material being read: its keys, where it stands, and the scene's wavelength range.
pub(super) struct Mat<'a> {
    cx: &'a Cx<'a>,
    /// `materials.NAME`, the prefix of every field in errors.
    f: String,
    /// The material's table.
    sp: Range<usize>,
    keys: &'a BTreeMap<String, S<Value>>,
    /// The simulated wavelength range, over which reflectances must lie in [0, 1].
    range: &'a [Length; 2],
    all: &'a AllRaw,
}

impl Mat<'_> {
    /// `materials.NAME.key`.
    fn field(&self, key: &str) -> String {
        format!("{}.{key}", self.f)
    }

    fn get(&self, key: &str) -> Option<&S<Value>> {
        self.keys.get(key)
    }

    /// The value of `key`, or an error saying it is missing and `what` it should be.
    fn required(&self, key: &str, what: &str) -> R<&S<Value>> {
        self.get(key).ok_or_else(|| self.missing(key, what))
    }

    /// The error for `key` missing, saying `what` it should be.
    fn missing(&self, key: &str, what: &str) -> LoadError {
        self.cx.err(
            &self.sp,
            self.field(key),
            format!("missing; expected {what}"),
        )
    }

    fn number(&self, v: &S<Value>, key: &str) -> R<f64> {
        self.cx.number(v, &self.field(key))
    }

    /// A finite index > 0 at `key`.
    fn index(&self, v: &S<Value>, key: &str) -> R<f64> {
        let n = self.number(v, key)?;
        if !(n > 0.0 && n.is_finite()) {
            return Err(self.cx.err(
                &v.span(),
                self.field(key),
                format!("expected a positive index, found {n}"),
            ));
        }
        Ok(n)
    }

    /// A reflectance spectrum or texture at `key` (see [`reflectance_texture`]).
    fn texture(&self, v: &S<Value>, key: &str) -> R<TextureDesc> {
        reflectance_texture(self.cx, v, &self.field(key), self.range)
    }

    /// A reflectance at `key`, or the constant `default` if absent.
    fn texture_or(&self, key: &str, default: f32) -> R<TextureDesc> {
        match self.get(key) {
            Some(v) => self.texture(v, key),
            None => Ok(Spectrum::Constant(default).into()),
        }
    }

    /// `key` as a boolean, `false` if absent.
    fn flag(&self, key: &str) -> R<bool> {
        match self.get(key).map(|v| (v.get_ref(), v.span())) {
            None => Ok(false),
            Some((Value::Boolean(b), _)) => Ok(*b),
            Some((other, span)) => Err(self.cx.err(
                &span,
                self.field(key),
                format!("expected true or false, found {}", kind(other)),
            )),
        }
    }

    /// `key` as a string with its span.
    fn string(&self, key: &str, what: &str) -> R<Option<S<String>>> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => {
                let s = self.cx.string(v, &self.field(key), what)?;
                Ok(Some(S::new(v.span(), s.to_string())))
            }
        }
    }

    /// `exterior_ior`: the index outside, ≥ 1 (default 1).
    fn exterior(&self) -> R<f64> {
        let Some(e) = self.get("exterior_ior") else {
            return Ok(1.0);
        };
        let n = self.number(e, "exterior_ior")?;
        if n < 1.0 {
            return Err(self.cx.err(
                &e.span(),
                self.field("exterior_ior"),
                format!("expected an index ≥ 1, found {n}"),
            ));
        }
        Ok(n)
    }

    /// `roughness`: a GGX α in [0, 1] (0: smooth), or [α_u, α_v] for an anisotropic lobe (α_u
    /// along the surface's ∂p/∂u) where `anisotropic` allows it; `None` when smooth or absent.
    /// A texture (a table) reads as α = 0.1 here and is looked up at each hit ([`lobes`]).
    fn roughness(&self, anisotropic: bool) -> R<Option<[f64; 2]>> {
        let Some(r) = self.get("roughness") else {
            return Ok(None);
        };
        if anisotropic && matches!(r.get_ref(), Value::Table(_)) {
            return Ok(Some([0.1, 0.1]));
        }
        let field = self.field("roughness");
        let check = |a: f64| -> R<f64> {
            if (0.0..=1.0).contains(&a) {
                Ok(a)
            } else {
                Err(self.cx.err(
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
                match v.iter().map(num).collect::<Vec<_>>()[..] {
                    [Some(u), Some(w)] => [check(u)?, check(w)?],
                    _ => {
                        return Err(self.cx.err(
                            &r.span(),
                            &field,
                            "expected a number α or two numbers [α_u, α_v]",
                        ));
                    }
                }
            }
            _ => {
                let a = check(self.cx.number(r, &field)?)?;
                [a, a]
            }
        };
        Ok((a[0] > 0.0 || a[1] > 0.0).then_some(a))
    }

    /// The material named by the string at `key` (required: `what` it names), read as
    /// [`Mat::named`] reads it.
    fn named_at(
        &self,
        key: &str,
        what: &str,
        holder: &str,
        not: &[&str],
        not_what: &str,
    ) -> R<(S<String>, MaterialKind)> {
        let name = self
            .string(key, "a material name")?
            .ok_or_else(|| self.missing(key, what))?;
        let kind = self.named(&name, key, holder, not, not_what)?;
        Ok((name, kind))
    }

    /// The material called `name` (a mask's `material`, a blend's `materials`), which may not
    /// be one of `not` (`type` names) itself; errors are located at the name and say `holder`
    /// cannot hold `not_what`.
    fn named(
        &self,
        name: &S<String>,
        key: &str,
        holder: &str,
        not: &[&str],
        not_what: &str,
    ) -> R<MaterialKind> {
        let field = self.field(key);
        let Some((key, raw)) = self.all.iter().find(|(k, _)| k.get_ref() == name.get_ref()) else {
            return Err(self.cx.err(
                &name.span(),
                field,
                format!("no material named \"{}\"", name.get_ref()),
            ));
        };
        let ty = raw.get_ref().0.get("type").map(|t| t.get_ref());
        if matches!(ty, Some(Value::String(t)) if not.contains(&t.as_str())) {
            return Err(self.cx.err(
                &name.span(),
                field,
                format!("{holder} cannot hold {not_what}"),
            ));
        }
        Ok(material(self.cx, key, raw, self.range, self.all)?.kind)
    }
}

/// A conductor or dielectric with a texture for `roughness` (`{ image = … }`, grey, isotropic)
/// or `specular_reflectance` / `specular_transmittance` (spectra or textures) becomes
/// [`MaterialKind::Textured`] around it; otherwise `kind` is returned unchanged.
fn lobes(m: &Mat<'_>, kind: MaterialKind) -> R<MaterialKind> {
    let alpha = match m.get("roughness") {
        Some(r) if matches!(r.get_ref(), Value::Table(_)) => {
            // roughness images are numbers as stored, not sRGB-decoded colours
            let t = m.texture(r, "roughness")?.raw();
            Some(Box::new([t.clone(), t]))
        }
        _ => None,
    };
    let (sr, st) = ("specular_reflectance", "specular_transmittance");
    if alpha.is_none() && m.get(sr).is_none() && m.get(st).is_none() {
        return Ok(kind);
    }
    Ok(MaterialKind::Textured {
        alpha,
        remap: false,
        reflectance: m.texture_or(sr, 1.0)?,
        transmittance: m.texture_or(st, 1.0)?,
        inner: Box::new(kind),
    })
}

pub(super) fn material(
    cx: &Cx<'_>,
    name: &S<String>,
    m: &S<RawMaterial>,
    range: &[Length; 2],
    all: &AllRaw,
) -> R<MaterialDesc> {
    let sp = m.span();
    let f = format!("materials.{}", name.get_ref());
    let keys = &m.get_ref().0;
    let names: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
    let Some(ty) = keys.get("type") else {
        return Err(cx.err(
            &sp,
            format!("{f}.type"),
            format!("missing; expected {}", names.join(", ")),
        ));
    };
    let ty_name = cx.string(ty, &format!("{f}.type"), "a material type")?;
    let field = format!("{f}.type");
    let kind = &KINDS[cx.kind_index(ty_name, &ty.span(), &field, "material", &names)?];
    for (key, v) in keys {
        if key != "type" && !kind.keys.contains(&key.as_str()) {
            let near = did_you_mean(key, kind.keys.iter().copied());
            return Err(cx.err(
                &v.span(),
                format!("{f}.{key}"),
                format!(
                    "`{key}` does not apply to a {} material{near}; it takes type, {}",
                    kind.name,
                    kind.keys.join(", ")
                ),
            ));
        }
    }
    let m = Mat {
        cx,
        f,
        sp: sp.clone(),
        keys,
        range,
        all,
    };
    Ok(MaterialDesc {
        name: name.get_ref().clone(),
        kind: (kind.read)(&m)?,
        loc: cx.src.span(&sp),
    })
}
