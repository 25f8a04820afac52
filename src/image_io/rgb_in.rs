//! Reading images as RGB for textures and environment maps: PNG (8 or 16 bit, grey, grey +
//! alpha, RGB, RGBA, palette), JPEG (8-bit grey or RGB, with jpeg-decoder), BMP (with the
//! `image` crate's decoder: 8-bit sRGB values, as Mitsuba reads them), OpenEXR (R, G, B or Y
//! channels) and Radiance HDR (RGBE).

use std::path::Path;

use super::{ImageError, invalid, open_input, pixel_count, read_exr};

/// How an image's stored values relate to linear light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Stored values are linear (EXR, HDR).
    Linear,
    /// Stored values are sRGB-encoded (8- and 16-bit PNG): the reader of the texture decides
    /// whether to linearise them (Mitsuba's `raw = false`, its default) or not.
    Srgb,
}

/// An RGB image, row-major, top row first, values as stored (see `encoding`), in [0, 1] for
/// integer formats and any finite value for float formats.
#[derive(Clone, Debug, PartialEq)]
pub struct RgbImage {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<[f32; 3]>,
    pub encoding: Encoding,
    /// Whether the file had one (grey) channel, copied to R, G and B.
    pub grey: bool,
}

/// Reads `path` by its extension (`.png`, `.jpg`/`.jpeg`, `.bmp`, `.exr`, `.hdr`/`.rgbe`;
/// case-insensitive). Fails with
/// an error naming the file for other extensions, unreadable or corrupt files, EXR files without
/// R, G, B or Y channels, and non-finite values.
pub fn read_rgb(path: &Path) -> Result<RgbImage, ImageError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    let img = match ext.as_str() {
        "png" => read_png(path)?,
        "jpg" | "jpeg" => read_jpeg(path)?,
        "exr" => exr_rgb(path)?,
        "hdr" | "rgbe" | "pic" => super::hdr_in::read_hdr(path)?,
        "bmp" => read_bmp(path)?,
        _ => {
            return Err(invalid(
                path,
                format!("unsupported image type \".{ext}\"; use .png, .jpg, .bmp, .exr or .hdr"),
            ));
        }
    };
    if let Some(i) = img
        .rgb
        .iter()
        .position(|p| p.iter().any(|v| !v.is_finite()))
    {
        return Err(invalid(
            path,
            format!(
                "pixel (x {}, y {}) is not finite: {:?}",
                i % img.width,
                i / img.width,
                img.rgb[i]
            ),
        ));
    }
    Ok(img)
}

fn exr_rgb(path: &Path) -> Result<RgbImage, ImageError> {
    open_input(path, crate::files::MAX_IMAGE_BYTES)?;
    let e = read_exr(path)?;
    let n = pixel_count(path, e.width, e.height)?;
    let rgb = match (
        e.channel("R"),
        e.channel("G"),
        e.channel("B"),
        e.channel("Y"),
    ) {
        (Some(r), Some(g), Some(b), _) => (0..n).map(|i| [r[i], g[i], b[i]]).collect(),
        (None, None, None, Some(y)) => y.iter().map(|&v| [v; 3]).collect(),
        _ => {
            let names: Vec<&str> = e.channels.iter().map(|(n, _)| n.as_str()).collect();
            return Err(invalid(
                path,
                format!(
                    "needs channels R, G and B (or Y alone); the file has {}",
                    names.join(", ")
                ),
            ));
        }
    };
    Ok(RgbImage {
        width: e.width,
        height: e.height,
        rgb,
        encoding: Encoding::Linear,
        grey: e.channel("R").is_none(),
    })
}

fn read_png(path: &Path) -> Result<RgbImage, ImageError> {
    let file = open_input(path, crate::files::MAX_IMAGE_BYTES)?;
    let codec = |e: png::DecodingError| ImageError::Codec {
        path: path.to_path_buf(),
        action: "cannot decode PNG",
        source: Box::new(e),
    };
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    // palettes to RGB(A), fewer than 8 bits to 8; 16 bits stay 16
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(codec)?;
    let mut buf = vec![
        0;
        reader
            .output_buffer_size()
            .ok_or_else(|| invalid(path, "the image is too large"))?
    ];
    let info = reader.next_frame(&mut buf).map_err(codec)?;
    let (w, h) = (info.width as usize, info.height as usize);
    let n = pixel_count(path, w, h)?;
    let channels = info.color_type.samples();
    let wide = info.bit_depth == png::BitDepth::Sixteen;
    let sample = |i: usize| -> f32 {
        if wide {
            u16::from_be_bytes([buf[2 * i], buf[2 * i + 1]]) as f32 / 65535.0
        } else {
            buf[i] as f32 / 255.0
        }
    };
    let row = info.line_size / if wide { 2 } else { 1 };
    let mut rgb = Vec::with_capacity(n);
    for y in 0..h {
        for x in 0..w {
            let i = y * row + x * channels;
            rgb.push(match channels {
                1 | 2 => [sample(i); 3],
                _ => [sample(i), sample(i + 1), sample(i + 2)],
            });
        }
    }
    Ok(RgbImage {
        width: w,
        height: h,
        rgb,
        encoding: Encoding::Srgb,
        grey: channels <= 2,
    })
}

/// An 8-bit JPEG (sRGB-encoded, as JPEG files are): grey or RGB; CMYK and 16-bit lossless files
/// are refused.
fn read_jpeg(path: &Path) -> Result<RgbImage, ImageError> {
    let file = open_input(path, crate::files::MAX_IMAGE_BYTES)?;
    let mut decoder = jpeg_decoder::Decoder::new(std::io::BufReader::new(file));
    let pixels = decoder.decode().map_err(|e| ImageError::Codec {
        path: path.to_path_buf(),
        action: "cannot decode JPEG",
        source: Box::new(e),
    })?;
    let info = decoder
        .info()
        .ok_or_else(|| invalid(path, "the JPEG has no image header"))?;
    let (w, h) = (info.width as usize, info.height as usize);
    let n = pixel_count(path, w, h)?;
    let byte = |v: u8| v as f32 / 255.0;
    let (rgb, grey) = match info.pixel_format {
        jpeg_decoder::PixelFormat::L8 if pixels.len() == n => {
            (pixels.iter().map(|&v| [byte(v); 3]).collect(), true)
        }
        jpeg_decoder::PixelFormat::RGB24 if pixels.len() == 3 * n => (
            pixels
                .chunks_exact(3)
                .map(|p| [byte(p[0]), byte(p[1]), byte(p[2])])
                .collect(),
            false,
        ),
        other => {
            return Err(invalid(
                path,
                format!("JPEG pixel format {other:?} is not read (only 8-bit grey or RGB)"),
            ));
        }
    };
    Ok(RgbImage {
        width: w,
        height: h,
        rgb,
        encoding: Encoding::Srgb,
        grey,
    })
}

/// A BMP file (any bit depth and compression the `image` crate decodes) as 8-bit sRGB values;
/// alpha is dropped. A file the decoder reads as luminance counts as grey.
fn read_bmp(path: &Path) -> Result<RgbImage, ImageError> {
    let file = open_input(path, crate::files::MAX_IMAGE_BYTES)?;
    let codec = |e: image::ImageError| ImageError::Codec {
        path: path.to_path_buf(),
        action: "cannot decode BMP",
        source: Box::new(e),
    };
    let decoder =
        image::codecs::bmp::BmpDecoder::new(std::io::BufReader::new(file)).map_err(codec)?;
    let img = image::DynamicImage::from_decoder(decoder).map_err(codec)?;
    let (w, h) = (img.width() as usize, img.height() as usize);
    pixel_count(path, w, h)?;
    let rgb8 = img.to_rgb8();
    let byte = |v: u8| v as f32 / 255.0;
    let rgb: Vec<[f32; 3]> = rgb8
        .pixels()
        .map(|p| [byte(p[0]), byte(p[1]), byte(p[2])])
        .collect();
    let grey = matches!(
        img.color(),
        image::ColorType::L8
            | image::ColorType::La8
            | image::ColorType::L16
            | image::ColorType::La16
    );
    Ok(RgbImage {
        width: w,
        height: h,
        rgb,
        encoding: Encoding::Srgb,
        grey,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 24-bit BMP by the format's definition: 14-byte file header, 40-byte info header,
    /// rows bottom-up, BGR, each row padded to 4 bytes. `height` is the header's (negative:
    /// rows top-down).
    fn bmp(width: i32, height: i32, rows_as_stored: &[Vec<[u8; 3]>]) -> Vec<u8> {
        let mut pixels = Vec::new();
        for row in rows_as_stored {
            for p in row {
                pixels.extend([p[2], p[1], p[0]]);
            }
            while pixels.len() % 4 != 0 {
                pixels.push(0);
            }
        }
        let mut f = b"BM".to_vec();
        f.extend((54 + pixels.len() as u32).to_le_bytes());
        f.extend([0; 4]);
        f.extend(54u32.to_le_bytes());
        f.extend(40u32.to_le_bytes());
        f.extend(width.to_le_bytes());
        f.extend(height.to_le_bytes());
        f.extend(1u16.to_le_bytes());
        f.extend(24u16.to_le_bytes());
        f.extend([0; 4]);
        f.extend((pixels.len() as u32).to_le_bytes());
        f.extend([0; 16]);
        f.extend(pixels);
        f
    }

    fn read(name: &str, bytes: &[u8]) -> Result<RgbImage, ImageError> {
        let dir = std::env::temp_dir().join(format!("spectrace-bmp-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        read_rgb(&path)
    }

    /// Rows stored bottom-up come out top row first, channels in R, G, B order, values /255.
    #[test]
    fn bmp_reads_rows_top_first_in_rgb() {
        let bottom = vec![[10, 20, 30], [40, 50, 60], [70, 80, 90]];
        let top = vec![[255, 0, 0], [0, 255, 0], [0, 0, 255]];
        let img = read("a.bmp", &bmp(3, 2, &[bottom, top])).unwrap();
        assert_eq!((img.width, img.height, img.grey), (3, 2, false));
        assert_eq!(img.encoding, Encoding::Srgb);
        assert_eq!(img.rgb[0], [1.0, 0.0, 0.0]);
        assert_eq!(img.rgb[2], [0.0, 0.0, 1.0]);
        assert_eq!(img.rgb[3], [10.0 / 255.0, 20.0 / 255.0, 30.0 / 255.0]);
        // a negative height stores rows top-down
        let img = read(
            "b.bmp",
            &bmp(1, -2, &[vec![[255, 255, 255]], vec![[0, 0, 0]]]),
        )
        .unwrap();
        assert_eq!(img.rgb, vec![[1.0; 3], [0.0; 3]]);
    }

    /// A truncated file or a header claiming 2³⁰ × 2³⁰ pixels is an error naming the file.
    #[test]
    fn bad_bmp_is_an_error() {
        let mut f = bmp(4, 4, &vec![vec![[1, 2, 3]; 4]; 4]);
        f.truncate(60);
        let e = read("short.bmp", &f).unwrap_err().to_string();
        assert!(e.contains("short.bmp"), "{e}");
        let huge = bmp(1 << 30, 1 << 30, &[vec![[1, 2, 3]]]);
        let e = read("huge.bmp", &huge).unwrap_err().to_string();
        assert!(e.contains("huge.bmp"), "{e}");
    }
}
