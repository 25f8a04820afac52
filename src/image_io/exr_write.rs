//! Writing float32 scanline OpenEXR files, plain and spectral.

use std::collections::HashSet;
use std::path::Path;

use exr::prelude::{
    AnyChannel, AnyChannels, Blocks, Compression, Encoding, FlatSamples, Image, IntegerBounds,
    Layer, LineOrder, SmallVec, Vec2, WritableImage,
};

use super::exr_attrs::{check_name, layer_attributes, to_text};
use super::spectral_names::{self, EMISSIVE_UNITS, SPECTRAL_LAYOUT_VERSION};
use super::{AttrValue, Channel, ImageError, WordChannel, invalid, pixel_count, write_atomically};

/// Lossless for float32 (unlike PXR24 or B44), widely supported, and compact.
const ENCODING: Encoding = Encoding {
    compression: Compression::ZIP16,
    blocks: Blocks::ScanLines,
    line_order: LineOrder::Increasing,
};

/// Writes a single-layer, scanline, float32 EXR (ZIP-compressed, lossless) with `channels` and
/// the extra header `attributes`, atomically (see [`write_atomically`]).
///
/// Fails before touching the disk if the image is empty, a channel does not hold exactly
/// `width * height` values, two channels share a name, a value is NaN or infinite (the error
/// names the channel and the pixel), or an attribute is invalid: given twice, a reserved
/// OpenEXR name such as `channels`, or a standard one with the wrong type (`owner`, `software`,
/// `comments`, … are text; `expTime`, `aperture`, `whiteLuminance`, … are floats).
/// EXR stores channels sorted by name; [`super::read_exr`] returns them by name.
pub fn write_exr(
    path: &Path,
    width: usize,
    height: usize,
    channels: &[Channel],
    attributes: &[(&str, AttrValue)],
) -> Result<(), ImageError> {
    write_exr_words(
        path,
        width,
        height,
        channels,
        &Extras::default(),
        attributes,
    )
}

/// What a render's EXR may hold beside its float channels and attributes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Extras<'a> {
    /// Unsigned 32-bit integer channels (OpenEXR's `UINT` pixel type: exact data such as a
    /// film's sums, which viewers list but do not show as colour). Names must differ from
    /// every float channel's.
    pub words: &'a [WordChannel<'a>],
    /// The image as a window of a larger one (None: the whole image).
    pub window: Option<DataWindow>,
}

/// An image that is the window of `width` × `height` pixels at `at` (its top-left pixel,
/// counted from the top-left of the full image) of a `full`-sized image: written as
/// OpenEXR's data window within a display window of the full image, as pbrt-v4 writes a
/// cropped render, so viewers place it where it belongs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DataWindow {
    pub at: [u32; 2],
    pub full: [u32; 2],
}

/// [`write_exr`] with the [`Extras`]: integer channels, a data window.
///
/// Fails as [`write_exr`] does, and also if the window does not fit in the full image.
pub fn write_exr_words(
    path: &Path,
    width: usize,
    height: usize,
    channels: &[Channel],
    extras: &Extras,
    attributes: &[(&str, AttrValue)],
) -> Result<(), ImageError> {
    let words = extras.words;
    let pixels = pixel_count(path, width, height)?;
    if i32::try_from(width).is_err() || i32::try_from(height).is_err() {
        return Err(invalid(
            path,
            format!("image size {width}×{height} is too large for EXR"),
        ));
    }
    if channels.is_empty() {
        return Err(invalid(path, "an EXR file needs at least one channel"));
    }
    let mut names = HashSet::new();
    let all = channels.iter().map(|c| (c.name, c.data.len()));
    for (name, len) in all.chain(words.iter().map(|c| (c.name, c.data.len()))) {
        check_name(path, "channel", name)?;
        if !names.insert(name) {
            return Err(invalid(path, format!("channel `{name}` is given twice")));
        }
        if len != pixels {
            return Err(invalid(
                path,
                format!("channel `{name}` holds {len} values, the image has {pixels} pixels"),
            ));
        }
    }
    for c in channels {
        check_finite(path, width, c)?;
    }
    let layer_attributes = layer_attributes(path, attributes)?;

    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> = channels
        .iter()
        .map(|c| AnyChannel::new(to_text(c.name), FlatSamples::F32(c.data.to_vec())))
        .chain(
            words
                .iter()
                .map(|c| AnyChannel::new(to_text(c.name), FlatSamples::U32(c.data.to_vec()))),
        )
        .collect();
    let mut layer = Layer::new(
        (width, height),
        layer_attributes,
        ENCODING,
        AnyChannels::sort(list),
    );
    let display = match extras.window {
        None => IntegerBounds::from_dimensions((width, height)),
        Some(DataWindow { at, full }) => {
            let fits = |a: u32, n: usize, f: u32| (a as u64 + n as u64) <= f as u64;
            if !fits(at[0], width, full[0]) || !fits(at[1], height, full[1]) {
                return Err(invalid(
                    path,
                    format!(
                        "a data window of {width}×{height} at ({}, {}) does not fit in the {}×{} image",
                        at[0], at[1], full[0], full[1]
                    ),
                ));
            }
            layer.attributes.layer_position = Vec2(at[0] as i32, at[1] as i32);
            IntegerBounds::from_dimensions((full[0] as usize, full[1] as usize))
        }
    };
    let mut image = Image::from_layer(layer);
    image.attributes.display_window = display;
    write_atomically(path, |out| {
        image
            .write()
            .to_buffered(out)
            .map_err(|e| ImageError::Codec {
                path: path.to_path_buf(),
                action: "cannot encode EXR",
                source: Box::new(e),
            })
    })
}

/// Writes a spectral EXR in the layout of Fichet, Pacanowski and Wilkie, "An OpenEXR Layout for
/// Spectral Images" (JCGT 10(3), 2021): one emissive channel per bin, named `S0.<λ>nm` with a
/// comma as decimal separator and six decimals (`S0.552,500000nm`), the attributes
/// `spectralLayoutVersion` = `"1.0"` and `emissiveUnits` = `"W.m^-2.sr^-1"`, and the channels in
/// `extra` beside them (typically an `R`, `G`, `B` preview that ordinary viewers show).
///
/// **Units.** `wavelengths_nm[i]` is the centre of bin `i`, and `bins[i]` holds the *spectral*
/// radiance in W·m⁻²·sr⁻¹·nm⁻¹ averaged over that bin — a density, not the bin's integral.
/// The band radiance in W·m⁻²·sr⁻¹ is Σᵢ `bins[i]` · Δλᵢ. This is the layout's convention: the
/// `emissiveUnits` string names the radiometric quantity (radiance, W.m^-2.sr^-1) and each
/// channel holds its density per unit of the channel name's wavelength unit (here nm), as the
/// layout's reference implementation and pbrt-v4's spectral film write it. The same convention
/// applies to the `S0.` channels this module reads back.
///
/// Fails like [`write_exr`], and also if `wavelengths_nm` and `bins` differ in length or are
/// empty, if the wavelengths are not finite, positive and strictly increasing, if a wavelength
/// does not survive six decimals unchanged, if an `extra` channel's name is itself a spectral
/// channel name, or if `attributes` repeats `spectralLayoutVersion` or `emissiveUnits`.
pub fn write_spectral_exr(
    path: &Path,
    width: usize,
    height: usize,
    wavelengths_nm: &[f32],
    bins: &[&[f32]],
    extra: &[Channel],
    attributes: &[(&str, AttrValue)],
) -> Result<(), ImageError> {
    let spectral = Spectral {
        wavelengths_nm,
        bins,
    };
    write_spectral_exr_words(
        path,
        width,
        height,
        &spectral,
        extra,
        &Extras::default(),
        attributes,
    )
}

/// The spectral channels of [`write_spectral_exr_words`]: bin centres (nm) and the mean
/// spectral radiance of each bin (W·m⁻²·sr⁻¹·nm⁻¹).
pub struct Spectral<'a> {
    pub wavelengths_nm: &'a [f32],
    pub bins: &'a [&'a [f32]],
}

/// [`write_spectral_exr`] with the [`Extras`], as [`write_exr_words`].
pub fn write_spectral_exr_words(
    path: &Path,
    width: usize,
    height: usize,
    spectral: &Spectral,
    extra: &[Channel],
    extras: &Extras,
    attributes: &[(&str, AttrValue)],
) -> Result<(), ImageError> {
    let (wavelengths_nm, bins) = (spectral.wavelengths_nm, spectral.bins);
    if wavelengths_nm.len() != bins.len() {
        return Err(invalid(
            path,
            format!(
                "{} wavelengths for {} spectral bins",
                wavelengths_nm.len(),
                bins.len()
            ),
        ));
    }
    if bins.is_empty() {
        return Err(invalid(
            path,
            "a spectral EXR needs at least one spectral bin",
        ));
    }
    for (i, wl) in wavelengths_nm.iter().enumerate() {
        if !(wl.is_finite() && *wl > 0.0) {
            return Err(invalid(
                path,
                format!("wavelength {i} is {wl} nm, not positive"),
            ));
        }
        if i > 0 && *wl <= wavelengths_nm[i - 1] {
            return Err(invalid(
                path,
                format!(
                    "wavelengths must increase strictly: {} nm then {wl} nm",
                    wavelengths_nm[i - 1]
                ),
            ));
        }
    }
    for c in extra {
        if spectral_names::parse_channel_name(c.name).is_some() {
            return Err(invalid(
                path,
                format!(
                    "extra channel `{}` would read as a spectral channel",
                    c.name
                ),
            ));
        }
    }
    let names = wavelengths_nm
        .iter()
        .map(|&wl| spectral_names::channel_name(path, wl))
        .collect::<Result<Vec<_>, _>>()?;
    let mut channels: Vec<Channel> = names
        .iter()
        .zip(bins)
        .map(|(name, data)| Channel { name, data })
        .collect();
    channels.extend_from_slice(extra);

    let mut all_attributes = vec![
        (
            "spectralLayoutVersion",
            AttrValue::Text(SPECTRAL_LAYOUT_VERSION.into()),
        ),
        ("emissiveUnits", AttrValue::Text(EMISSIVE_UNITS.into())),
    ];
    all_attributes.extend(attributes.iter().cloned());
    write_exr_words(path, width, height, &channels, extras, &all_attributes)
}

/// Checks that every value of a channel is finite.
fn check_finite(path: &Path, width: usize, c: &Channel) -> Result<(), ImageError> {
    match c.data.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(ImageError::NonFinite {
            path: path.to_path_buf(),
            channel: c.name.to_string(),
            x: i % width,
            y: i / width,
            value: c.data[i],
        }),
    }
}
