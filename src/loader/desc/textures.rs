//! Textures: what a material's slot (or a shape's alpha, a light's image) takes.

use super::*;

/// A spectral quantity that may vary over a surface (see `crate::texture`).
#[derive(Clone, Debug)]
pub enum TextureDesc {
    /// The same spectrum everywhere.
    Uniform(Spectrum),
    /// Mitsuba's checkerboard: `a` on the checks where the fractional parts of `to_uv`(uv) are
    /// both ≤ ½ or both > ½, else `b`.
    Checkerboard {
        a: Spectrum,
        b: Spectrum,
        to_uv: Vec<TransformStep>,
    },
    /// Numbers used as given, not a colour (Mitsuba's `rawconstant`): a normal map's triple in
    /// [0, 1]³ (mapped to a normal by 2v − 1), or a grey value when all three are equal.
    Raw([f32; 3]),
    /// A PLY mesh's vertex or face attribute `name` (`vertex_…`, `face_…`) times `scale`
    /// (Mitsuba's `mesh_attribute`), bound to each mesh the material is on when the scene is
    /// built.
    MeshAttribute { name: String, scale: f64 },
    /// An image file (PNG, JPEG, BMP, EXR, HDR), read when the scene is built.
    Bitmap {
        path: PathBuf,
        filter: TexFilter,
        wrap: Wrap,
        /// Use 8- and 16-bit values as stored instead of decoding sRGB; colour images cannot
        /// then be spectra (Mitsuba's `raw`), so only grey images are accepted with it.
        raw: bool,
        to_uv: Vec<TransformStep>,
        loc: Loc,
    },
    /// pbrt-v4's `imagemap` (see [`PbrtImageDesc`]).
    PbrtImage(Box<PbrtImageDesc>),
    /// pbrt-v4's `scale`: `[tex, scale]`, their product.
    Scaled(Box<[TextureDesc; 2]>),
    /// pbrt-v4's `mix`: `[a, b, amount]`, (1 − amount)·a + amount·b.
    Mix(Box<[TextureDesc; 3]>),
    /// `inner` looked up at coordinates given by the hit's position (pbrt-v4's `spherical`,
    /// `cylindrical` and `planar` mappings, [`crate::texture::Mapping`]).
    Mapped {
        mapping: MappingDesc,
        inner: Box<TextureDesc>,
    },
}

/// A map from positions to texture coordinates (see [`crate::texture::Mapping`]);
/// `to_texture` takes world points (in the scene's length unit) to the texture's space, a
/// row-major 4 × 4 matrix.
#[derive(Clone, Debug)]
pub enum MappingDesc {
    Spherical {
        to_texture: [f64; 16],
    },
    Cylindrical {
        to_texture: [f64; 16],
    },
    /// s = `ds` + `vs`·p, t = `dt` + `vt`·p of the texture-space point p.
    Planar {
        to_texture: [f64; 16],
        vs: [f64; 3],
        vt: [f64; 3],
        ds: f64,
        dt: f64,
    },
}

/// An image as pbrt-v4's `imagemap` reads it (`src/pbrt/textures.cpp`), read when the scene is
/// built: 8-bit values decoded from sRGB when `srgb` (pbrt-v4's `encoding`, by default sRGB for
/// PNG files and linear for others), then `scale` × value, then 1 − that when `invert`
/// (clamped at 0). A float texture (`grey`) reads the average of a colour texel's channels.
#[derive(Clone, Debug)]
pub struct PbrtImageDesc {
    pub path: PathBuf,
    pub filter: TexFilter,
    pub wrap: Wrap,
    pub to_uv: Vec<TransformStep>,
    pub srgb: bool,
    pub grey: bool,
    pub scale: f64,
    pub invert: bool,
    /// Colours of any magnitude (an emitter's image, pbrt-v4's `RGBIlluminantSpectrum`
    /// without its illuminant), not reflectances clamped to [0, 1].
    pub unbounded: bool,
    pub loc: Loc,
}

impl TextureDesc {
    /// Whether a lookup reads the hit's position (a [`TextureDesc::Mapped`] in it), which
    /// only materials' reflectances, roughnesses and amounts can give it.
    pub fn reads_position(&self) -> bool {
        match self {
            TextureDesc::Mapped { .. } => true,
            TextureDesc::Scaled(t) => t.iter().any(TextureDesc::reads_position),
            TextureDesc::Mix(t) => t.iter().any(TextureDesc::reads_position),
            _ => false,
        }
    }

    /// The same texture with an image's values read as stored (`raw`), for images of numbers
    /// (normals, heights, roughness) rather than colours; other textures unchanged.
    pub fn raw(self) -> TextureDesc {
        match self {
            TextureDesc::Bitmap {
                path,
                filter,
                wrap,
                to_uv,
                loc,
                ..
            } => TextureDesc::Bitmap {
                path,
                filter,
                wrap,
                raw: true,
                to_uv,
                loc,
            },
            other => other,
        }
    }
}

impl From<Spectrum> for TextureDesc {
    fn from(s: Spectrum) -> Self {
        TextureDesc::Uniform(s)
    }
}
