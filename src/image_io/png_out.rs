//! 8-bit sRGB PNG output, for quick looks at a render.

use std::path::Path;

use crate::colour::spaces::srgb_encode;

use super::{ImageError, invalid, pixel_count, write_atomically};

/// Writes an 8-bit RGB PNG tagged sRGB from *linear* values already scaled to the display
/// range: each value is clamped to [0, 1] (so +∞ gives 255 and negative values give 0), encoded
/// with the sRGB transfer function (IEC 61966-2-1) and rounded to the nearest of 0…255.
/// Written atomically (see [`write_atomically`]).
///
/// Fails if the image is empty or larger than PNG allows, if `rgb_linear` does not hold
/// `width * height` pixels, or if a value is NaN (the error names the channel and pixel).
pub fn write_png_linear(
    path: &Path,
    width: usize,
    height: usize,
    rgb_linear: &[[f32; 3]],
) -> Result<(), ImageError> {
    let pixels = pixel_count(path, width, height)?;
    check_len(path, pixels, rgb_linear.len())?;
    if let Some(i) = rgb_linear.iter().position(|p| p.iter().any(|v| v.is_nan())) {
        let c = rgb_linear[i].iter().position(|v| v.is_nan()).unwrap_or(0);
        return Err(ImageError::NonFinite {
            path: path.to_path_buf(),
            channel: ["R", "G", "B"][c].to_string(),
            x: i % width,
            y: i / width,
            value: f32::NAN,
        });
    }
    let rgb8: Vec<[u8; 3]> = rgb_linear.iter().map(|p| p.map(encode_8bit)).collect();
    write_png_srgb8(path, width, height, &rgb8)
}

/// Writes an 8-bit RGB PNG tagged sRGB from values that are already sRGB-encoded, row-major,
/// top row first. Written atomically (see [`write_atomically`]).
///
/// Fails if the image is empty or larger than PNG allows, or if `rgb8` does not hold
/// `width * height` pixels.
pub fn write_png_srgb8(
    path: &Path,
    width: usize,
    height: usize,
    rgb8: &[[u8; 3]],
) -> Result<(), ImageError> {
    let pixels = pixel_count(path, width, height)?;
    check_len(path, pixels, rgb8.len())?;
    let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
        return Err(invalid(
            path,
            format!("image size {width}×{height} is too large for PNG"),
        ));
    };
    let codec = |e: png::EncodingError| ImageError::Codec {
        path: path.to_path_buf(),
        action: "cannot encode PNG",
        source: Box::new(e),
    };
    write_atomically(path, |out| {
        let mut encoder = png::Encoder::new(out, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = encoder.write_header().map_err(codec)?;
        writer
            .write_image_data(rgb8.as_flattened())
            .map_err(codec)?;
        writer.finish().map_err(codec)
    })
}

/// Linear [0, 1] (clamped) → sRGB-encoded 8 bits, rounded to nearest.
fn encode_8bit(linear: f32) -> u8 {
    let v = f64::from(linear.clamp(0.0, 1.0));
    (srgb_encode(v) * 255.0).round() as u8
}

fn check_len(path: &Path, pixels: usize, len: usize) -> Result<(), ImageError> {
    if len == pixels {
        Ok(())
    } else {
        Err(invalid(
            path,
            format!("{len} pixels given, the image has {pixels}"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoding_ends_and_middle() {
        assert_eq!(encode_8bit(0.0), 0);
        assert_eq!(encode_8bit(-1.0), 0);
        assert_eq!(encode_8bit(1.0), 255);
        assert_eq!(encode_8bit(f32::INFINITY), 255);
        assert_eq!(encode_8bit(0.5), 188); // 255 · (1.055 · 0.5^(1/2.4) − 0.055) = 187.52
        assert_eq!(encode_8bit(0.001), 3); // linear segment: 255 · 12.92 · 0.001 = 3.29
    }
}
