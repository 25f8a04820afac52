//! Textures: a description's texture becomes a render-ready [`Texture`]; image files are read
//! here (through `image_io`) and every colour texel is turned into a spectrum once.

use std::sync::Arc;

use glam::Vec3;

use crate::image_io::{Encoding, read_rgb};
use crate::loader::desc::{TextureDesc, TransformStep};
use crate::texture::{Bitmap, Checkerboard, TexFilter, Texture, UvTransform, Wrap};

/// The 2D affine part of `to_uv` (Mitsuba keeps the x, y rows and the translation column).
fn uv_transform(list: &[TransformStep]) -> Result<UvTransform, String> {
    let t = super::shapes::steps(list, 1.0, false)?;
    let m = t.matrix();
    let (o, x, y) = (
        t.point(Vec3::ZERO),
        m.transform_vector3(Vec3::X),
        m.transform_vector3(Vec3::Y),
    );
    Ok(UvTransform {
        rows: [[x.x, y.x, o.x], [x.y, y.y, o.y]],
    })
}

/// The sRGB transfer function inverted (IEC 61966-2-1), as Mitsuba decodes 8- and 16-bit
/// images when it loads them.
pub(super) fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

pub(super) fn texture(t: &TextureDesc) -> Result<Texture, String> {
    Ok(match t {
        TextureDesc::Uniform(s) => Texture::Uniform(s.clone()),
        TextureDesc::Raw([a, b, c]) if a == b && b == c => {
            Texture::Uniform(crate::spectrum::Spectrum::Constant(*a))
        }
        TextureDesc::Raw(v) => {
            return Err(format!(
                "a raw constant of three different numbers {v:?} is not a spectrum (it can only be a normal map)"
            ));
        }
        TextureDesc::Checkerboard { a, b, to_uv } => {
            Texture::Checkerboard(Arc::new(Checkerboard {
                a: a.clone(),
                b: b.clone(),
                to_uv: uv_transform(to_uv)?,
            }))
        }
        TextureDesc::Bitmap {
            path,
            filter,
            wrap,
            raw,
            to_uv,
            ..
        } => {
            let img = read_rgb(path).map_err(|e| e.to_string())?;
            let decode = img.encoding == Encoding::Srgb && !raw;
            let lin = |v: f32| if decode { srgb_to_linear(v) } else { v };
            let to_uv = uv_transform(to_uv)?;
            let b = if img.grey {
                let v = img.rgb.iter().map(|p| lin(p[0])).collect();
                Bitmap::from_grey(img.width, img.height, v, *filter, *wrap, to_uv)
            } else if *raw {
                return Err(format!(
                    "{}: a colour image with raw = true has no spectrum (raw colour values are not reflectances); use a grey image or raw = false",
                    path.display()
                ));
            } else {
                let rgb: Vec<[f32; 3]> = img.rgb.iter().map(|p| p.map(lin)).collect();
                Bitmap::from_rgb(img.width, img.height, &rgb, *filter, *wrap, to_uv)
            };
            Texture::Bitmap(Arc::new(b.map_err(|e| format!("{}: {e}", path.display()))?))
        }
    })
}

/// A normal map: an image of triples used as numbers (decoded from sRGB only when the file is
/// sRGB-encoded and `raw` is false, as Mitsuba reads it), never spectra.
pub(super) fn vector_texture(t: &TextureDesc) -> Result<Texture, String> {
    if let TextureDesc::Raw(v) = t {
        let b = Bitmap::from_vectors(
            1,
            1,
            vec![*v],
            TexFilter::Nearest,
            Wrap::Repeat,
            uv_transform(&[])?,
        )
        .map_err(|e| e.to_string())?;
        return Ok(Texture::Bitmap(Arc::new(b)));
    }
    let TextureDesc::Bitmap {
        path,
        filter,
        wrap,
        raw,
        to_uv,
        ..
    } = t
    else {
        return Err("a normal map must be an image".into());
    };
    let img = read_rgb(path).map_err(|e| e.to_string())?;
    let decode = img.encoding == Encoding::Srgb && !raw;
    let lin = |v: f32| if decode { srgb_to_linear(v) } else { v };
    let v = img.rgb.iter().map(|p| p.map(lin)).collect();
    let b = Bitmap::from_vectors(
        img.width,
        img.height,
        v,
        *filter,
        *wrap,
        uv_transform(to_uv)?,
    );
    Ok(Texture::Bitmap(Arc::new(
        b.map_err(|e| format!("{}: {e}", path.display()))?,
    )))
}

/// A texture read as one number per texel, as Mitsuba's `eval_1` reads it (bump heights): a
/// raw colour image becomes its luminance (Rec. 709 weights, Mitsuba's `luminance`); other
/// textures as [`texture`] reads them.
pub(super) fn scalar_texture(t: &TextureDesc) -> Result<Texture, String> {
    let TextureDesc::Bitmap {
        path,
        filter,
        wrap,
        raw: true,
        to_uv,
        ..
    } = t
    else {
        return texture(t);
    };
    let img = read_rgb(path).map_err(|e| e.to_string())?;
    let v = img
        .rgb
        .iter()
        .map(|p| 0.212671 * p[0] + 0.715160 * p[1] + 0.072169 * p[2])
        .collect();
    let b = Bitmap::from_grey(
        img.width,
        img.height,
        v,
        *filter,
        *wrap,
        uv_transform(to_uv)?,
    );
    Ok(Texture::Bitmap(Arc::new(
        b.map_err(|e| format!("{}: {e}", path.display()))?,
    )))
}

/// Whether the texture is the same at every wavelength: a constant, a checkerboard of two
/// constants, or a grey image.
pub(super) fn is_grey(t: &Texture) -> bool {
    let constant =
        |s: &crate::spectrum::Spectrum| matches!(s, crate::spectrum::Spectrum::Constant(_));
    match t {
        Texture::Uniform(s) => constant(s),
        Texture::Checkerboard(c) => constant(&c.a) && constant(&c.b),
        Texture::Bitmap(b) => b.is_grey(),
    }
}
