//! Radiance HDR (RGBE) files: the text header (`FORMAT=32-bit_rle_rgbe`, a `-Y h +X w`
//! resolution line), then scanlines flat or with the adaptive run-length encoding of Greg
//! Ward's `ray/src/common/color.c` (each of the four components in turn, runs marked by a count
//! above 128). A value is m·2^(e − 136) for a mantissa m and a shared exponent e > 0, and 0 for
//! e = 0: Greg Ward's and Bruce Walter's `rgbe2float`, which Mitsuba 3.9.1 (checked with
//! `mi.Bitmap`), stb_image and OpenImageIO follow. (Radiance's own `colr_color` adds ½ to m,
//! which would make a channel stored as 0 non-zero.)

use std::path::Path;

use super::rgb_in::{Encoding, RgbImage};
use super::{ImageError, invalid, pixel_count};

pub(crate) fn read_hdr(path: &Path) -> Result<RgbImage, ImageError> {
    let bytes =
        crate::files::read_bytes(path, crate::files::MAX_IMAGE_BYTES).map_err(|source| {
            ImageError::Io {
                path: path.to_path_buf(),
                action: "cannot read".to_string(),
                source,
            }
        })?;
    let bad = |why: &str| invalid(path, format!("not a readable Radiance HDR file: {why}"));
    let (w, h, pos) = header(&bytes, &bad)?;
    let n = pixel_count(path, w, h)?;
    let data = &bytes[pos..];
    // every scanline takes at least 4 bytes and every run at most 127 pixels of one component:
    // a header promising more pixels than the data can hold is refused before allocating
    if h.saturating_mul(4) > data.len() || n / 127 > data.len() {
        return Err(bad(&format!(
            "{w} × {h} pixels promised by the header, {} bytes of pixel data",
            data.len()
        )));
    }
    let mut rgbe = vec![[0u8; 4]; n];
    let mut p = 0;
    let mut take = |k: usize| -> Result<&[u8], ImageError> {
        let s = data
            .get(p..p + k)
            .ok_or_else(|| bad("the pixel data ends early"))?;
        p += k;
        Ok(s)
    };
    for y in 0..h {
        let row = &mut rgbe[y * w..(y + 1) * w];
        let head = take(4)?;
        let rle = (8..0x8000).contains(&w)
            && head[0] == 2
            && head[1] == 2
            && ((head[2] as usize) << 8 | head[3] as usize) == w;
        if !rle {
            row[0].copy_from_slice(head);
            for px in row.iter_mut().skip(1) {
                px.copy_from_slice(take(4)?);
            }
            continue;
        }
        for c in 0..4 {
            let mut x = 0;
            while x < w {
                let count = take(1)?[0] as usize;
                if count > 128 {
                    let run = count - 128;
                    let v = take(1)?[0];
                    if x + run > w {
                        return Err(bad("a run overflows its scanline"));
                    }
                    row[x..x + run].iter_mut().for_each(|px| px[c] = v);
                    x += run;
                } else {
                    if count == 0 || x + count > w {
                        return Err(bad("a literal overflows its scanline"));
                    }
                    for (px, &v) in row[x..x + count].iter_mut().zip(take(count)?) {
                        px[c] = v;
                    }
                    x += count;
                }
            }
        }
    }
    let rgb = rgbe
        .iter()
        .map(|&[r, g, b, e]| {
            if e == 0 {
                [0.0; 3]
            } else {
                let f = (e as f32 - 136.0).exp2();
                [r, g, b].map(|m| m as f32 * f)
            }
        })
        .collect();
    Ok(RgbImage {
        width: w,
        height: h,
        rgb,
        encoding: Encoding::Linear,
        grey: false,
    })
}

/// The header (`#?RADIANCE`, `FORMAT=32-bit_rle_rgbe`, then an empty line) and the resolution
/// line `-Y h +X w`: the width, the height and where the pixel data starts.
fn header(
    bytes: &[u8],
    bad: &dyn Fn(&str) -> ImageError,
) -> Result<(usize, usize, usize), ImageError> {
    // header lines up to an empty line, then the resolution line
    let mut pos = 0;
    let line = |pos: &mut usize| -> Option<String> {
        let start = *pos;
        let end = start + bytes.get(start..)?.iter().position(|&b| b == b'\n')?;
        *pos = end + 1;
        Some(
            String::from_utf8_lossy(&bytes[start..end])
                .trim()
                .to_string(),
        )
    };
    let first = line(&mut pos).ok_or_else(|| bad("empty"))?;
    if !first.starts_with("#?") {
        return Err(bad("it does not start with #?RADIANCE"));
    }
    loop {
        let l = line(&mut pos).ok_or_else(|| bad("the header does not end"))?;
        if l.is_empty() {
            break;
        }
        if let Some(f) = l.strip_prefix("FORMAT=")
            && f != "32-bit_rle_rgbe"
        {
            return Err(bad(&format!("format {f} (only 32-bit_rle_rgbe is read)")));
        }
    }
    let res = line(&mut pos).ok_or_else(|| bad("no resolution line"))?;
    let parts: Vec<&str> = res.split_whitespace().collect();
    let (h, w) = match parts.as_slice() {
        ["-Y", h, "+X", w] => (h.parse::<usize>().ok(), w.parse::<usize>().ok()),
        _ => (None, None),
    };
    let (Some(h), Some(w)) = (h, w) else {
        return Err(bad(&format!(
            "resolution \"{res}\" (only the standard -Y h +X w orientation is read)"
        )));
    };
    Ok((w, h, pos))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 9 × 2 file, both scanlines run-length encoded; pixel values m·2^(e − 136) (Mitsuba
    /// 3.9.1's `mi.Bitmap` reads [128, 64, 200, 129] as [1, 0.5, 1.5625]); a header promising
    /// more pixels than the file holds is an error, not an allocation.
    #[test]
    fn reads_rle_scanlines() {
        let w = 9usize;
        let mut f = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 9\n".to_vec();
        for y in 0..2u8 {
            f.extend([2, 2, 0, w as u8]);
            // r: a run of 9 of (100 + y); g: 9 literals 0..9; b: run 9 of 0; e: run 9 of 129
            f.extend([128 + 9, 100 + y]);
            f.push(9);
            f.extend(0..9u8);
            f.extend([128 + 9, 0]);
            f.extend([128 + 9, 129]);
        }
        let p = std::env::temp_dir().join(format!("spectrace-hdr-{}.hdr", std::process::id()));
        std::fs::write(&p, &f).unwrap();
        let img = read_hdr(&p).unwrap();
        assert_eq!((img.width, img.height), (9, 2));
        std::fs::write(
            &p,
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n\x02\x02",
        )
        .unwrap();
        let e = read_hdr(&p).unwrap_err().to_string();
        assert!(e.contains("100000 × 100000"), "{e}");
        std::fs::write(
            &p,
            [
                b"#?RADIANCE\n\n-Y 1 +X 2\n".as_slice(),
                &[128, 64, 200, 129, 0, 0, 0, 0],
            ]
            .concat(),
        )
        .unwrap();
        assert_eq!(read_hdr(&p).unwrap().rgb[0], [1.0, 0.5, 1.5625]);
        std::fs::remove_file(&p).ok();
        let s = (129.0f32 - 136.0).exp2();
        assert_eq!(img.rgb[3], [100.0 * s, 3.0 * s, 0.0]);
        assert_eq!(img.rgb[9 + 8], [101.0 * s, 8.0 * s, 0.0]);
    }
}
