//! pbrt-v4's textures (`src/pbrt/textures.cpp`): a `Texture` directive's spectrum or float
//! texture, kept by name for the materials and shapes that name it (`"texture reflectance"
//! "name"`, `"texture displacement"`, `"texture alpha"`, a mix's `amount`).
//!
//! `imagemap` is read as pbrt-v4 defines it: (s, t) = (uscale·u + udelta, vscale·v + vdelta),
//! looked up at (s, 1 − t) with t = 0 at the image's last row, bilinear (pbrt-v4's default
//! `filter`) or nearest (`point`), `repeat` or `clamp` wrapping, 8-bit values decoded from sRGB
//! for PNG files and read linearly from others (pbrt-v4's default `encoding`), then `scale`d
//! and `invert`ed; a float texture reads a colour texel's channel average. `scale` and `mix`
//! combine textures (`crate::texture::{Scaled, Mix}`). One difference: a lookup blends the four
//! texels' spectra (spectrace's image textures), pbrt-v4 their RGB before turning it into a
//! spectrum.

use std::path::Path;

use super::Reader;
use super::lexer::Token;
use super::params::{Params, R};
use crate::loader::Loc;
use crate::loader::desc::{MappingDesc, PbrtImageDesc, TextureDesc, TransformStep};
use crate::spectrum::Spectrum;
use crate::texture::{TexFilter, Wrap};

/// A `Texture "name" "<ty>" "<class>"`: `ty` is `spectrum` (reflectances, as pbrt-v4's
/// albedo textures) or `float` (grey numbers: masks, heights, amounts).
pub(super) fn texture(ty: &str, class: &str, p: &Params, loc: Loc, r: &Reader) -> R<TextureDesc> {
    let float = match ty {
        "float" => true,
        "spectrum" => false,
        other => {
            return Err(p.err(
                loc,
                format!("a texture's type is \"float\" or \"spectrum\", not \"{other}\""),
            ));
        }
    };
    let named = r.named();
    // a float or spectrum parameter of this texture's type, or a texture of it
    let value = |name: &str, default: f64| -> R<TextureDesc> {
        if float {
            Ok(named
                .float(p, name)?
                .unwrap_or_else(|| Spectrum::Constant(default as f32).into()))
        } else {
            named.reflectance(p, name, default)
        }
    };
    let amount = |name: &str, default: f64| -> R<TextureDesc> {
        Ok(named
            .float(p, name)?
            .unwrap_or_else(|| Spectrum::Constant(default as f32).into()))
    };
    match class {
        "constant" => value("value", 1.0),
        "imagemap" => imagemap(p, loc, r, float),
        // pbrt-v4's ScaledTexture: tex × scale, folded when both are numbers
        "scale" => Ok(match (value("tex", 1.0)?, amount("scale", 1.0)?) {
            (TextureDesc::Uniform(t), TextureDesc::Uniform(Spectrum::Constant(k))) => {
                TextureDesc::Uniform(t.scaled(k))
            }
            (t, k) => TextureDesc::Scaled(Box::new([t, k])),
        }),
        "checkerboard" => checkerboard(p, r, value("tex1", 1.0)?, value("tex2", 0.0)?),
        "mix" => Ok(TextureDesc::Mix(Box::new([
            value("tex1", 0.0)?,
            value("tex2", 1.0)?,
            amount("amount", 0.5)?,
        ]))),
        other => Err(p.err(
            loc,
            format!(
                "the texture \"{other}\" is not read yet (spectrace reads imagemap, checkerboard, constant, scale and mix)"
            ),
        )),
    }
}

/// pbrt-v4's 2D `checkerboard`: `tex1` where ⌊s⌋ + ⌊t⌋ is even, else `tex2`, with (s, t) =
/// (uscale·u + udelta, vscale·v + vdelta): Mitsuba's checks (`a` where the fractional parts
/// of the halved coordinates are on the same side of ½) of (s/2, t/2). Point-sampled: pbrt-v4
/// blurs the edges over the ray's footprint (a box-filtered triangle of 1.5 texel widths),
/// which moves no mean. `tex1` and `tex2` must be numbers or spectra.
fn checkerboard(p: &Params, r: &Reader, tex1: TextureDesc, tex2: TextureDesc) -> R<TextureDesc> {
    let dim = p.int("dimension", 2)?;
    if dim != 2 {
        return Err(p.err(
            p.loc_of("dimension"),
            format!("a {dim}-dimensional checkerboard is not read yet (spectrace reads 2)"),
        ));
    }
    let (TextureDesc::Uniform(a), TextureDesc::Uniform(b)) = (tex1, tex2) else {
        let at = if p.get("tex1").is_some_and(|q| q.ty == "texture") {
            "tex1"
        } else {
            "tex2"
        };
        return Err(p.err(
            p.loc_of(at),
            "a checkerboard of textures is not read yet (tex1 and tex2 must be values)",
        ));
    };
    let (mapping, [su, sv, du, dv]) = st_map(p, r)?;
    #[rustfmt::skip]
    let halved = TransformStep::Matrix([
        su / 2.0, 0.0, 0.0, du / 2.0,
        0.0, sv / 2.0, 0.0, dv / 2.0,
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    ]);
    Ok(mapped(
        mapping,
        TextureDesc::Checkerboard {
            a,
            b,
            to_uv: vec![halved],
        },
    ))
}

/// The texture's `mapping` when it is not pbrt-v4's default, `uv` (pbrt-v4's
/// `TextureMapping2D::Create`): `spherical` and `cylindrical` about the texture space's origin
/// and z axis, `planar` with `v1` ((1, 0, 0)), `v2` ((0, 1, 0)), `udelta`, `vdelta` (0); the
/// texture space is the one in force at the `Texture` directive. None: `uv`, whose `uscale`,
/// `vscale`, `udelta` and `vdelta` the caller reads.
fn position_mapping(p: &Params, r: &Reader) -> R<Option<MappingDesc>> {
    // row-major: the transpose's columns
    let to_texture = || r.state.ctm.inverse().transpose().to_cols_array();
    Ok(Some(match p.string("mapping")?.as_deref() {
        None | Some("uv") => return Ok(None),
        Some("spherical") => MappingDesc::Spherical {
            to_texture: to_texture(),
        },
        Some("cylindrical") => MappingDesc::Cylindrical {
            to_texture: to_texture(),
        },
        Some("planar") => MappingDesc::Planar {
            to_texture: to_texture(),
            vs: p.vec3("v1", [1.0, 0.0, 0.0])?,
            vt: p.vec3("v2", [0.0, 1.0, 0.0])?,
            ds: p.float("udelta", 0.0)?,
            dt: p.float("vdelta", 0.0)?,
        },
        Some(m) => {
            return Err(p.err(
                p.loc_of("mapping"),
                format!(
                    "the mapping \"{m}\" is not one of pbrt-v4's (uv, spherical, cylindrical, planar)"
                ),
            ));
        }
    }))
}

/// The coordinates `(s, t)` of pbrt-v4's texture lookups: a uv mapping's affine map of (u, v)
/// (from `uscale`, `vscale`, `udelta`, `vdelta`) in a row-major 4 × 4 matrix, or a position
/// mapping with the identity (the texture then wraps itself in [`TextureDesc::Mapped`]).
fn st_map(p: &Params, r: &Reader) -> R<(Option<MappingDesc>, [f64; 4])> {
    Ok(match position_mapping(p, r)? {
        Some(m) => (Some(m), [1.0, 1.0, 0.0, 0.0]),
        None => (
            None,
            [
                p.float("uscale", 1.0)?,
                p.float("vscale", 1.0)?,
                p.float("udelta", 0.0)?,
                p.float("vdelta", 0.0)?,
            ],
        ),
    })
}

/// `t` looked up through `mapping` if it is a position mapping.
fn mapped(mapping: Option<MappingDesc>, t: TextureDesc) -> TextureDesc {
    match mapping {
        Some(mapping) => TextureDesc::Mapped {
            mapping,
            inner: Box::new(t),
        },
        None => t,
    }
}

fn imagemap(p: &Params, loc: Loc, r: &Reader, grey: bool) -> R<TextureDesc> {
    let name = p
        .string("filename")?
        .ok_or_else(|| p.err(loc, "an imagemap needs a \"string filename\""))?;
    let path = r.resolve(&r.root, &name);
    if !path.is_file() {
        return Err(p.err(
            p.loc_of("filename"),
            format!("no image \"{}\"", path.display()),
        ));
    }
    let filter = match p.string("filter")?.as_deref().unwrap_or("bilinear") {
        "bilinear" => TexFilter::Bilinear,
        "point" => TexFilter::Nearest,
        other => {
            return Err(p.err(
                p.loc_of("filter"),
                format!(
                    "the filter \"{other}\" is not read yet (spectrace reads bilinear and point)"
                ),
            ));
        }
    };
    let wrap = match p.string("wrap")?.as_deref().unwrap_or("repeat") {
        "repeat" => Wrap::Repeat,
        "clamp" => Wrap::Clamp,
        other => {
            return Err(p.err(
                p.loc_of("wrap"),
                format!(
                    "the wrap mode \"{other}\" is not read yet (spectrace reads repeat and clamp)"
                ),
            ));
        }
    };
    // pbrt-v4: sRGB for PNG files, linear for others, unless `encoding` says
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let srgb = match p.string("encoding")?.as_deref() {
        None => png,
        Some("sRGB") => true,
        Some("linear") => false,
        Some(e) => {
            return Err(p.err(
                p.loc_of("encoding"),
                format!("the encoding \"{e}\" is not read yet (spectrace reads sRGB and linear)"),
            ));
        }
    };
    // EWA's anisotropy: no mipmaps here
    let _ = p.float("maxanisotropy", 8.0)?;
    let (mapping, [su, sv, du, dv]) = st_map(p, r)?;
    // (u, v) → (s, 1 − t): spectrace's images have v = 0 at the first row
    let to_uv = vec![TransformStep::Matrix([
        su,
        0.0,
        0.0,
        du, //
        0.0,
        -sv,
        0.0,
        1.0 - dv, //
        0.0,
        0.0,
        1.0,
        0.0, //
        0.0,
        0.0,
        0.0,
        1.0,
    ])];
    let image = TextureDesc::PbrtImage(Box::new(PbrtImageDesc {
        path,
        filter,
        wrap,
        to_uv,
        srgb,
        grey,
        scale: p.float("scale", 1.0)?,
        invert: p.bool("invert", false)?,
        unbounded: false,
        loc,
    }));
    Ok(mapped(mapping, image))
}

impl Reader {
    /// `Texture "name" "type" "class" …`: kept by name.
    pub(super) fn texture_directive(
        &mut self,
        d: &str,
        toks: &[Token],
        i: &mut usize,
        file: &Path,
        loc: Loc,
    ) -> R<()> {
        let name = Self::string_arg(toks, i, file, d, loc)?;
        let ty = Self::string_arg(toks, i, file, d, loc)?;
        let class = Self::string_arg(toks, i, file, d, loc)?;
        let p = Params::parse(toks, i, file)?.with_defaults(&self.state.attributes.texture);
        let t = texture(&ty, &class, &p, loc, self)?;
        p.check_unused(&format!("texture \"{class}\""))?;
        if ty == "float" {
            self.float_textures.insert(name, t);
        } else {
            self.textures.insert(name, t);
        }
        Ok(())
    }
}
