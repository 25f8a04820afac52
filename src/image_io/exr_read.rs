//! Reading float OpenEXR files back.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use exr::prelude::{FlatSamples, ReadChannels, ReadLayers, read};

use super::exr_attrs::{from_text, read_attributes};
use super::{DataWindow, ExrImage, ImageError, invalid};

/// Reads a single-layer float EXR (any file [`super::write_exr`] or
/// [`super::write_spectral_exr`] writes, and most scanline or tiled single-part files): all
/// channels by name, converted to `f32` (half floats are exact in `f32`), and the text, float,
/// double and int header attributes.
///
/// Unsigned-integer channels are returned apart, in [`ExrImage::words`]. The data window's size
/// is the image size; where it is not the display window, [`ExrImage::window`] says where in
/// it the image lies (a data window reaching outside the display window reads as None). Fails with an error naming the file if it cannot
/// be opened or decoded, holds several layers (parts) or deep data, or a subsampled channel. A panic inside the decoder on a corrupt file
/// is caught and reported as an error too.
pub fn read_exr(path: &Path) -> Result<ExrImage, ImageError> {
    // a device or FIFO is refused before the decoder opens it
    super::open_input(path, u64::MAX)?;
    let decoded = catch_unwind(AssertUnwindSafe(|| {
        read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .all_layers()
            .all_attributes()
            .from_file(path)
    }));
    let image = match decoded {
        Ok(Ok(image)) => image,
        Ok(Err(exr::error::Error::Io(source))) => {
            return Err(ImageError::Io {
                path: path.to_path_buf(),
                action: "cannot read".to_string(),
                source,
            });
        }
        Ok(Err(e)) => {
            return Err(ImageError::Codec {
                path: path.to_path_buf(),
                action: "cannot decode EXR",
                source: Box::new(e),
            });
        }
        Err(_) => {
            return Err(invalid(
                path,
                "the EXR decoder failed on this file (corrupt?)",
            ));
        }
    };

    let [layer] = image.layer_data.as_slice() else {
        return Err(invalid(
            path,
            format!(
                "the file has {} layers; only single-layer files are read",
                image.layer_data.len()
            ),
        ));
    };
    let (width, height) = (layer.size.0, layer.size.1);
    let pixels = width * height;
    let mut channels = Vec::with_capacity(layer.channel_data.list.len());
    let mut words = Vec::new();
    for channel in &layer.channel_data.list {
        let name = from_text(&channel.name);
        if channel.sampling.0 != 1 || channel.sampling.1 != 1 {
            return Err(invalid(path, format!("channel `{name}` is subsampled")));
        }
        let values: Vec<f32> = match &channel.sample_data {
            FlatSamples::F32(v) => v.clone(),
            FlatSamples::F16(v) => v.iter().map(|h| h.to_f32()).collect(),
            FlatSamples::U32(v) => {
                if v.len() != pixels {
                    return Err(invalid(
                        path,
                        format!(
                            "channel `{name}` holds {} values for {pixels} pixels",
                            v.len()
                        ),
                    ));
                }
                words.push((name, v.clone()));
                continue;
            }
        };
        if values.len() != pixels {
            return Err(invalid(
                path,
                format!(
                    "channel `{name}` holds {} values for {pixels} pixels",
                    values.len()
                ),
            ));
        }
        channels.push((name, values));
    }
    let attributes = read_attributes(&layer.attributes, image.attributes.other.iter());
    let display = image.attributes.display_window;
    let at = layer.attributes.layer_position - display.position;
    let inside = at.0 >= 0
        && at.1 >= 0
        && at.0 as usize + width <= display.size.0
        && at.1 as usize + height <= display.size.1;
    let own = at.0 == 0 && at.1 == 0 && (width, height) == (display.size.0, display.size.1);
    let window = (inside && !own).then_some(DataWindow {
        at: [at.0 as u32, at.1 as u32],
        full: [display.size.0 as u32, display.size.1 as u32],
    });
    Ok(ExrImage {
        width,
        height,
        channels,
        words,
        attributes,
        window,
    })
}
