//! Image files: float32 OpenEXR (plain and spectral) and 8-bit sRGB PNG out; PNG, EXR and
//! Radiance HDR in as RGB, for textures and environment maps.
//!
//! Plain data in, plain data out: channels are `&[f32]` slices, row-major, top row first, with
//! `width * height` values each. No renderer type appears here, so the film can change without
//! touching the file formats. This is the only module that names the `exr` and `png` crates.
//!
//! Every writer validates everything first (sizes, names, finite values) and then writes
//! through [`write_atomically`]: a temporary file `<path>.tmp-<pid>-<n>` in the same folder, fsync,
//! rename. A failed write never leaves a partial file and never clobbers an existing one.
//!
//! | file | what it holds |
//! | --- | --- |
//! | `atomic.rs` | [`write_atomically`] |
//! | `exr_write.rs` | [`write_exr`], [`write_spectral_exr`], pixel validation |
//! | `exr_read.rs` | [`read_exr`] |
//! | `exr_attrs.rs` | names, text encoding and header attributes ↔ `exr` |
//! | `spectral_names.rs` | `S0.<λ>nm` channel names (Fichet et al. 2021; `S1`–`S3` for a polarised image), [`spectral_channels`] |
//! | `png_out.rs` | [`write_png_linear`], [`write_png_srgb8`] |
//! | `rgb_in.rs` | [`read_rgb`]: PNG, EXR, HDR as RGB with their [`Encoding`] |
//! | `hdr_in.rs` | Radiance RGBE files |

mod atomic;
mod exr_attrs;
mod exr_read;
mod exr_write;
mod hdr_in;
mod png_out;
mod rgb_in;
mod spectral_names;

use std::path::{Path, PathBuf};

pub use atomic::write_atomically;
pub use exr_read::read_exr;
pub use exr_write::{
    DataWindow, Extras, Spectral, write_exr, write_exr_words, write_spectral_exr,
    write_spectral_exr_words,
};
pub use png_out::{write_png_linear, write_png_srgb8};
pub use rgb_in::{Encoding, RgbImage, read_rgb};
pub use spectral_names::{
    EMISSIVE_UNITS, SPECTRAL_LAYOUT_VERSION, spectral_channels, stokes_channel_name,
};

/// One float32 channel, row-major, top row first, `width * height` values.
#[derive(Debug, Clone, Copy)]
pub struct Channel<'a> {
    pub name: &'a str,
    pub data: &'a [f32],
}

/// One unsigned 32-bit integer channel, row-major, top row first, `width * height` values.
#[derive(Debug, Clone, Copy)]
pub struct WordChannel<'a> {
    pub name: &'a str,
    pub data: &'a [u32],
}

/// The value of an extra header attribute.
///
/// Text is stored as its UTF-8 bytes (OpenEXR strings are plain bytes; OpenImageIO reads them as
/// UTF-8). On reading, bytes that are not UTF-8 are taken as Latin-1.
#[derive(Debug, Clone, PartialEq)]
pub enum AttrValue {
    Text(String),
    Float(f32),
    Double(f64),
    Int(i32),
}

/// An EXR file read back by [`read_exr`].
#[derive(Debug, Clone, PartialEq)]
pub struct ExrImage {
    pub width: usize,
    pub height: usize,
    /// All channels as stored in the file (EXR sorts them by name), each `width * height`
    /// values, row-major, top row first.
    pub channels: Vec<(String, Vec<f32>)>,
    /// Unsigned 32-bit integer channels, by name, as stored.
    pub words: Vec<(String, Vec<u32>)>,
    /// Text, float, double and int header attributes, sorted by name. Structural attributes
    /// (`channels`, `dataWindow`, `compression`, …) are not listed.
    pub attributes: Vec<(String, AttrValue)>,
    /// Where the pixels lie in the display window, if it is not their own (a cropped render):
    /// the data window's offset from the display window's top-left and the display window's
    /// size. None when the data window is the display window.
    pub window: Option<DataWindow>,
}

impl ExrImage {
    /// The values of the channel with this exact name.
    pub fn channel(&self, name: &str) -> Option<&[f32]> {
        self.channels
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, d)| d.as_slice())
    }

    /// The attribute with this exact name.
    pub fn attribute(&self, name: &str) -> Option<&AttrValue> {
        self.attributes
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v)
    }
}

/// Why an image could not be written or read. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The file system refused (missing folder, permissions, disk full, …).
    #[error("{}: {action}: {source}", path.display())]
    Io {
        path: PathBuf,
        action: String,
        #[source]
        source: std::io::Error,
    },
    /// The EXR or PNG library could not encode or decode the file.
    #[error("{}: {action}: {source}", path.display())]
    Codec {
        path: PathBuf,
        action: &'static str,
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The arguments or the file's contents break a rule of this module.
    #[error("{}: {reason}", path.display())]
    Invalid { path: PathBuf, reason: String },
    /// A pixel is NaN or infinite: the renderer promised it would never write one.
    #[error(
        "{}: channel `{channel}` holds {value} at pixel (x {x}, y {y}); only finite values are written",
        path.display()
    )]
    NonFinite {
        path: PathBuf,
        channel: String,
        x: usize,
        y: usize,
        value: f32,
    },
}

impl ImageError {
    /// The file the error is about.
    pub fn path(&self) -> &Path {
        match self {
            Self::Io { path, .. }
            | Self::Codec { path, .. }
            | Self::Invalid { path, .. }
            | Self::NonFinite { path, .. } => path,
        }
    }
}

/// Opens an input image through [`crate::files::open_regular`] (a regular file of at most
/// `cap` bytes), its failure as an [`ImageError`] naming the file.
pub(crate) fn open_input(path: &Path, cap: u64) -> Result<std::fs::File, ImageError> {
    crate::files::open_regular(path, cap)
        .map(|(file, _)| file)
        .map_err(|source| ImageError::Io {
            path: path.to_path_buf(),
            action: "cannot read".to_string(),
            source,
        })
}

pub(crate) fn invalid(path: &Path, reason: impl Into<String>) -> ImageError {
    ImageError::Invalid {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

/// Checks that the image is not empty and that `width * height` fits; returns the pixel count.
pub(crate) fn pixel_count(path: &Path, width: usize, height: usize) -> Result<usize, ImageError> {
    if width == 0 || height == 0 {
        return Err(invalid(
            path,
            format!("image size {width}×{height} is empty"),
        ));
    }
    width
        .checked_mul(height)
        .ok_or_else(|| invalid(path, format!("image size {width}×{height} is too large")))
}
