//! Textures: a description's texture becomes a render-ready [`Texture`]; image files are read
//! here (through `image_io`) and every colour texel is turned into a spectrum once.

use std::sync::Arc;

use glam::{Mat4, Vec3};

use crate::image_io::{Encoding, read_rgb};
use crate::loader::desc::{MappingDesc, PbrtImageDesc, TextureDesc, TransformStep};
use crate::texture::{
    AttributeTexture, Bitmap, Checkerboard, Mapped, Mapping, Mix, Scaled, TexFilter, Texture,
    UvTransform, Wrap,
};

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
        TextureDesc::MeshAttribute { name, scale } => bound_attribute(name, *scale)?,
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
        TextureDesc::PbrtImage(d) => pbrt_image(d)?,
        TextureDesc::Scaled(t) => Texture::Scaled(Arc::new(Scaled {
            tex: texture(&t[0])?,
            scale: texture(&t[1])?,
        })),
        TextureDesc::Mix(t) => Texture::Mix(Arc::new(Mix {
            a: texture(&t[0])?,
            b: texture(&t[1])?,
            amount: texture(&t[2])?,
        })),
        TextureDesc::Mapped { mapping, inner } => Texture::Mapped(Arc::new(Mapped {
            mapping: self::mapping(mapping),
            inner: texture(inner)?,
        })),
    })
}

/// A position mapping in plain `f32` (world metres to texture space).
fn mapping(m: &MappingDesc) -> Mapping {
    // row-major in the description, column-major in glam
    let mat = |a: &[f64; 16]| Mat4::from_cols_array(&a.map(|x| x as f32)).transpose();
    let v = |a: &[f64; 3]| Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32);
    match m {
        MappingDesc::Spherical { to_texture } => Mapping::Spherical {
            to_texture: mat(to_texture),
        },
        MappingDesc::Cylindrical { to_texture } => Mapping::Cylindrical {
            to_texture: mat(to_texture),
        },
        MappingDesc::Planar {
            to_texture,
            vs,
            vt,
            ds,
            dt,
        } => Mapping::Planar {
            to_texture: mat(to_texture),
            vs: v(vs),
            vt: v(vt),
            ds: *ds as f32,
            dt: *dt as f32,
        },
    }
}

/// pbrt-v4's `imagemap` ([`PbrtImageDesc`]): decoded, scaled, inverted and, for a float
/// texture, averaged over the channels, texel by texel.
fn pbrt_image(d: &PbrtImageDesc) -> Result<Texture, String> {
    let img = read_rgb(&d.path).map_err(|e| e.to_string())?;
    let decode = d.srgb && img.encoding == Encoding::Srgb;
    let (scale, invert) = (d.scale as f32, d.invert);
    let value = |v: f32| {
        let v = scale * if decode { srgb_to_linear(v) } else { v };
        if invert { (1.0 - v).max(0.0) } else { v }
    };
    let to_uv = uv_transform(&d.to_uv)?;
    let b = if img.grey || d.grey {
        // pbrt-v4's float lookup of a colour image: the channels' average
        let v = img
            .rgb
            .iter()
            .map(|p| {
                if img.grey {
                    value(p[0])
                } else {
                    p.map(value).iter().sum::<f32>() / 3.0
                }
            })
            .collect();
        Bitmap::from_grey(img.width, img.height, v, d.filter, d.wrap, to_uv)
    } else {
        let rgb: Vec<[f32; 3]> = img.rgb.iter().map(|p| p.map(value)).collect();
        if d.unbounded {
            Bitmap::from_rgb_unbounded(img.width, img.height, &rgb, d.filter, d.wrap, to_uv)
        } else {
            Bitmap::from_rgb(img.width, img.height, &rgb, d.filter, d.wrap, to_uv)
        }
    };
    Ok(Texture::Bitmap(Arc::new(
        b.map_err(|e| format!("{}: {e}", d.path.display()))?,
    )))
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
        Texture::Attribute(a) => !a.is_colour(),
        Texture::Scaled(s) => is_grey(&s.tex) && is_grey(&s.scale),
        Texture::Mix(m) => is_grey(&m.a) && is_grey(&m.b),
        Texture::Mapped(m) => is_grey(&m.inner),
    }
}

/// A mesh's attributes by name, as [`with_mesh`] binds them.
type Bound = Vec<(String, Arc<AttributeTexture>)>;

thread_local! {
    /// The attributes of the mesh a material is being built for ([`with_mesh`]); None while a
    /// material is first built, unbound.
    static BOUND: std::cell::RefCell<Option<Bound>> =
        const { std::cell::RefCell::new(None) };
    /// Whether an unbound build met a mesh attribute ([`take_wanted`]).
    static WANTED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// A `mesh_attribute` texture. Unbound (a material's first build), a placeholder that marks
/// the material as wanting a mesh: the build step then builds it again for each mesh it is on,
/// inside [`with_mesh`]. A thread-local rather than a context argument through every material
/// constructor: only this texture reads it, and only while the scene is built on one thread.
fn bound_attribute(name: &str, scale: f64) -> Result<Texture, String> {
    BOUND.with(|b| match &*b.borrow() {
        None => {
            WANTED.set(true);
            Ok(Texture::Uniform(crate::spectrum::Spectrum::Constant(0.0)))
        }
        Some(list) => {
            let Some((_, t)) = list.iter().find(|(n, _)| n == name) else {
                let have: Vec<&str> = list.iter().map(|(n, _)| n.as_str()).collect();
                return Err(format!(
                    "the mesh has no attribute \"{name}\" (it has: {})",
                    if have.is_empty() {
                        "none".to_string()
                    } else {
                        have.join(", ")
                    }
                ));
            };
            Ok(Texture::Attribute(if scale == 1.0 {
                t.clone()
            } else {
                Arc::new(t.scaled(scale as f32))
            }))
        }
    })
}

/// Whether the material built since the last call read a mesh attribute unbound.
pub(super) fn take_wanted() -> bool {
    WANTED.replace(false)
}

/// Runs `f` (a material's build) with `mesh`'s attributes bound.
pub(super) fn with_mesh<R>(
    mesh: &crate::geometry::shape::Mesh,
    attributes: &[crate::geometry::shape::MeshAttribute],
    f: impl FnOnce() -> R,
) -> Result<R, String> {
    let list = attributes
        .iter()
        .map(|a| {
            Ok((
                a.name.clone(),
                Arc::new(AttributeTexture::new(a, mesh, 1.0)?),
            ))
        })
        .collect::<Result<Vec<_>, String>>()?;
    BOUND.with(|b| *b.borrow_mut() = Some(list));
    let r = f();
    BOUND.with(|b| *b.borrow_mut() = None);
    Ok(r)
}
