//! pbrt-v4's textures (`src/pbrt/textures.cpp`): a `Texture` directive's spectrum texture, kept
//! by name for the materials that name it (`"texture reflectance" "name"`).
//!
//! `imagemap` is read as pbrt-v4 defines it: (s, t) = (uscale·u + udelta, vscale·v + vdelta),
//! looked up at (s, 1 − t) with t = 0 at the image's last row, bilinear (pbrt-v4's default
//! `filter`) or nearest (`point`), `repeat` or `clamp` wrapping, 8-bit files decoded from sRGB.
//! One difference: a lookup blends the four texels' spectra (spectrace's image textures),
//! pbrt-v4 their RGB before turning it into a spectrum.

use std::path::Path;

use super::Reader;
use super::lexer::Token;
use super::params::{Params, R};
use super::spectra;
use crate::loader::Loc;
use crate::loader::desc::{TextureDesc, TransformStep};
use crate::texture::{TexFilter, Wrap};

/// A `Texture "name" "<ty>" "<class>"` of spectra.
pub(super) fn texture(ty: &str, class: &str, p: &Params, loc: Loc, r: &Reader) -> R<TextureDesc> {
    if ty != "spectrum" {
        return Err(p.err(
            loc,
            format!("a \"{ty}\" texture is not read yet (spectrace reads spectrum textures)"),
        ));
    }
    match class {
        "constant" => Ok(spectra::reflectance(p, "value", 1.0)?.into()),
        "imagemap" => imagemap(p, loc, r),
        other => Err(p.err(
            loc,
            format!(
                "the texture \"{other}\" is not read yet (spectrace reads imagemap and constant)"
            ),
        )),
    }
}

fn imagemap(p: &Params, loc: Loc, r: &Reader) -> R<TextureDesc> {
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
    if let Some(e) = p.string("encoding")?
        && e != "sRGB"
    {
        return Err(p.err(
            p.loc_of("encoding"),
            format!(
                "the encoding \"{e}\" is not read yet (spectrace decodes 8-bit files from sRGB)"
            ),
        ));
    }
    if p.float("scale", 1.0)? != 1.0 || p.bool("invert", false)? {
        return Err(p.err(
            loc,
            "an imagemap's \"scale\" and \"invert\" are not read yet",
        ));
    }
    if let Some(m) = p.string("mapping")?
        && m != "uv"
    {
        return Err(p.err(
            p.loc_of("mapping"),
            format!("the mapping \"{m}\" is not read yet (spectrace reads uv)"),
        ));
    }
    // EWA's anisotropy: no mipmaps here
    let _ = p.float("maxanisotropy", 8.0)?;
    let (su, sv) = (p.float("uscale", 1.0)?, p.float("vscale", 1.0)?);
    let (du, dv) = (p.float("udelta", 0.0)?, p.float("vdelta", 0.0)?);
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
    Ok(TextureDesc::Bitmap {
        path,
        filter,
        wrap,
        raw: false,
        to_uv,
        loc,
    })
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
        self.textures.insert(name, t);
        Ok(())
    }
}
