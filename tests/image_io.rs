//! Image files: spectral and plain EXR round trips, atomic replacement, sRGB PNG encoding.

use std::fs;
use std::path::{Path, PathBuf};

use spectrace::image_io::{
    AttrValue, Channel, DataWindow, Extras, ImageError, read_exr, spectral_channels,
    write_atomically, write_exr, write_exr_words, write_png_linear, write_png_srgb8,
    write_spectral_exr,
};

/// A fresh, empty scratch folder for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("image_io")
        .join(test);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// Names of the files in `dir`.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Awkward floats that a lossy or converting writer would change: signed zero, subnormals,
/// extremes; every third value is one of them, the others are random finite bit patterns.
fn values(n: usize, seed: u32) -> Vec<f32> {
    let special = [
        -0.0,
        f32::MIN_POSITIVE / 3.0,
        f32::MAX,
        -f32::MAX,
        1.0 + f32::EPSILON,
        3.0e-40,
        0.1,
    ];
    let mut state = seed.wrapping_mul(2_654_435_761).wrapping_add(1);
    (0..n)
        .map(|i| {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            if i % 3 == 0 {
                special[(i / 3 + seed as usize) % special.len()]
            } else {
                f32::from_bits(state & 0xFF7F_FFFF) // any sign, never NaN or ∞
            }
        })
        .collect()
}

fn ch<'a>(name: &'a str, data: &'a [f32]) -> Channel<'a> {
    Channel { name, data }
}

/// A one-channel (`Y`) EXR without extra attributes.
fn write_y(path: &Path, width: usize, height: usize, data: &[f32]) -> Result<(), ImageError> {
    write_exr(path, width, height, &[ch("Y", data)], &[])
}

fn assert_bits_eq(name: &str, got: &[f32], want: &[f32]) {
    assert_eq!(got.len(), want.len(), "{name}");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.to_bits(), w.to_bits(), "{name}[{i}]: {g} vs {w}");
    }
}

#[test]
fn spectral_exr_round_trips_bit_for_bit() {
    let dir = scratch("spectral");
    let path = dir.join("render.exr");
    let (w, h) = (7, 3);
    let wavelengths = [400.0f32, 450.0, 552.5, 600.25, 700.0, 780.125];
    let bins: Vec<Vec<f32>> = (0..wavelengths.len())
        .map(|i| values(w * h, i as u32))
        .collect();
    let bin_refs: Vec<&[f32]> = bins.iter().map(Vec::as_slice).collect();
    let rgb: Vec<Vec<f32>> = (0..3).map(|i| values(w * h, 100 + i)).collect();
    let extra = [ch("R", &rgb[0]), ch("G", &rgb[1]), ch("B", &rgb[2])];
    let attrs = [
        ("software", AttrValue::Text("spectrace".into())),
        ("spp", AttrValue::Int(64)),
    ];
    write_spectral_exr(&path, w, h, &wavelengths, &bin_refs, &extra, &attrs).unwrap();

    let img = read_exr(&path).unwrap();
    assert_eq!((img.width, img.height), (w, h));
    assert_eq!(img.channels.len(), wavelengths.len() + 3);
    let spectral = spectral_channels(&img);
    assert_eq!(spectral.len(), wavelengths.len());
    for (k, &(wl, index)) in spectral.iter().enumerate() {
        assert_eq!(wl, wavelengths[k]);
        assert_bits_eq(&img.channels[index].0, &img.channels[index].1, &bins[k]);
    }
    let names: Vec<&str> = img.channels.iter().map(|(n, _)| n.as_str()).collect();
    for name in [
        "S0.400,000000nm",
        "S0.552,500000nm",
        "S0.600,250000nm",
        "S0.780,125000nm",
    ] {
        assert!(names.contains(&name), "{name} missing from {names:?}");
    }
    for (name, data) in ["R", "G", "B"].iter().zip(&rgb) {
        assert_bits_eq(name, img.channel(name).expect("preview channel"), data);
    }
    let text = |s: &str| Some(AttrValue::Text(s.to_string()));
    assert_eq!(img.attribute("spectralLayoutVersion").cloned(), text("1.0"));
    assert_eq!(
        img.attribute("emissiveUnits").cloned(),
        text("W.m^-2.sr^-1")
    );
    assert_eq!(img.attribute("software").cloned(), text("spectrace"));
    assert_eq!(img.attribute("spp"), Some(&AttrValue::Int(64)));
    assert_eq!(listing(&dir), ["render.exr"]);
}

#[test]
fn plain_exr_round_trips_channels_and_attributes() {
    let dir = scratch("plain");
    let path = dir.join("xyz.exr");
    let (w, h) = (4, 5);
    // Deliberately not in name order: EXR sorts them, reading must find them by name.
    let names = ["X", "Y", "Z", "R", "G", "B", "L"];
    let data: Vec<Vec<f32>> = (0..names.len())
        .map(|i| values(w * h, 7 * i as u32))
        .collect();
    let channels: Vec<Channel> = names
        .iter()
        .zip(&data)
        .map(|(name, data)| Channel { name, data })
        .collect();
    let attrs = vec![
        ("comments", AttrValue::Text("Cornell box, 1 spp".into())),
        ("expTime", AttrValue::Float(0.125)),
        ("film", AttrValue::Text("W·m⁻²·sr⁻¹ — UTF-8 text".into())),
        ("gain", AttrValue::Float(-1.5e-7)),
        ("pixelSize", AttrValue::Double(1.0 / 3.0)),
        ("samples", AttrValue::Int(-12345)),
        (
            "spectrace.settings.a_name_longer_than_31_bytes",
            AttrValue::Int(7),
        ),
    ];
    write_exr(&path, w, h, &channels, &attrs).unwrap();

    let img = read_exr(&path).unwrap();
    assert_eq!((img.width, img.height), (w, h));
    assert_eq!(img.channels.len(), names.len());
    for (name, want) in names.iter().zip(&data) {
        assert_bits_eq(name, img.channel(name).expect("channel"), want);
    }
    let want: Vec<(String, AttrValue)> =
        attrs.into_iter().map(|(n, v)| (n.to_string(), v)).collect();
    assert_eq!(img.attributes, want);
    assert!(spectral_channels(&img).is_empty());
}

/// A window of a larger image is written as OpenEXR's data window inside the full display
/// window and read back with its place; one that does not fit is refused before the disk is
/// touched; a whole image has no window.
#[test]
fn a_data_window_round_trips() {
    let dir = scratch("window");
    let (w, h) = (3, 2);
    let y = values(w * h, 5);
    let path = dir.join("win.exr");
    let window = DataWindow {
        at: [13, 22],
        full: [64, 48],
    };
    let extras = Extras {
        words: &[],
        window: Some(window),
    };
    write_exr_words(&path, w, h, &[ch("Y", &y)], &extras, &[]).unwrap();
    let img = read_exr(&path).unwrap();
    assert_eq!((img.width, img.height), (w, h));
    assert_eq!(img.window, Some(window));
    assert_bits_eq("Y", img.channel("Y").unwrap(), &y);

    let bad = dir.join("bad.exr");
    let too_far = Extras {
        words: &[],
        window: Some(DataWindow {
            at: [62, 0],
            full: [64, 48],
        }),
    };
    let e = write_exr_words(&bad, w, h, &[ch("Y", &y)], &too_far, &[]).unwrap_err();
    assert!(e.to_string().contains("does not fit"), "{e}");
    assert!(!bad.exists());

    let whole = dir.join("whole.exr");
    write_y(&whole, w, h, &y).unwrap();
    assert_eq!(read_exr(&whole).unwrap().window, None);
}

#[test]
fn writing_into_a_missing_folder_fails_and_leaves_nothing() {
    let dir = scratch("missing");
    let path = dir.join("no/such/folder/out.exr");
    let data = [1.0f32; 4];
    let err = write_y(&path, 2, 2, &data).unwrap_err();
    assert!(matches!(err, ImageError::Io { .. }), "{err:?}");
    assert_eq!(err.path(), path);
    assert!(
        err.to_string().contains(&path.display().to_string()),
        "{err}"
    );
    let err = write_png_srgb8(&path.with_extension("png"), 1, 1, &[[1, 2, 3]]).unwrap_err();
    assert!(err.to_string().contains("out.png"), "{err}");
    assert!(listing(&dir).is_empty());
}

#[test]
fn an_existing_file_is_replaced_only_on_success() {
    let dir = scratch("replace");
    let path = dir.join("film.exr");
    let first = values(6, 1);
    write_y(&path, 3, 2, &first).unwrap();
    let before = fs::read(&path).unwrap();

    let mut bad = values(6, 2);
    bad[4] = f32::NAN;
    let err = write_y(&path, 3, 2, &bad).unwrap_err();
    match &err {
        ImageError::NonFinite { channel, x, y, .. } => {
            assert_eq!((channel.as_str(), *x, *y), ("Y", 1, 1))
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }
    assert!(
        err.to_string().contains("film.exr") && err.to_string().contains("`Y`"),
        "{err}"
    );
    let bins: [&[f32]; 1] = [&bad];
    let err = write_spectral_exr(&path, 3, 2, &[550.0], &bins, &[], &[]).unwrap_err();
    assert!(err.to_string().contains("S0.550,000000nm"), "{err}");
    assert_eq!(fs::read(&path).unwrap(), before);
    assert_eq!(listing(&dir), ["film.exr"]);

    // A failure in the middle of writing: the closure wrote bytes, then failed.
    let err = write_atomically(&path, |out| {
        use std::io::Write;
        out.write_all(b"partial").unwrap();
        Err(ImageError::Invalid {
            path: path.clone(),
            reason: "simulated".into(),
        })
    });
    assert!(err.is_err());
    // A panic in the middle of writing.
    let panicked = std::panic::catch_unwind(|| {
        write_atomically(&path, |_| panic!("simulated panic while writing"))
    });
    assert!(panicked.is_err());
    assert_eq!(fs::read(&path).unwrap(), before);
    assert_eq!(listing(&dir), ["film.exr"]);

    let second = values(6, 3);
    write_y(&path, 3, 2, &second).unwrap();
    assert_ne!(fs::read(&path).unwrap(), before);
    assert_bits_eq("Y", read_exr(&path).unwrap().channel("Y").unwrap(), &second);
    assert_eq!(listing(&dir), ["film.exr"]);
}

#[test]
fn bad_arguments_are_errors_that_name_the_file() {
    let dir = scratch("invalid");
    let path = dir.join("bad.exr");
    let (four, three) = ([0.5f32; 4], [0.5f32; 3]);
    let y = [ch("Y", &four)];
    let text = |s: &str| AttrValue::Text(s.into());
    let exr =
        |channels: &[Channel], attrs: &[(&str, AttrValue)]| write_exr(&path, 2, 2, channels, attrs);
    let spectral = |wavelengths: &[f32], bins: &[&[f32]], extra: &[Channel], attr: &str| {
        write_spectral_exr(&path, 2, 2, wavelengths, bins, extra, &[(attr, text("x"))])
    };
    let cases: Vec<(&str, Result<(), ImageError>)> = vec![
        ("holds 3 values", write_y(&path, 2, 2, &three)),
        ("empty", write_y(&path, 0, 2, &[])),
        ("at least one channel", exr(&[], &[])),
        ("twice", exr(&[ch("Y", &four), ch("Y", &four)], &[])),
        ("name is empty", exr(&[ch("", &four)], &[])),
        ("twice", exr(&y, &[("a", text("x")), ("a", text("y"))])),
        ("reserved", exr(&y, &[("channels", text("x"))])),
        ("must be text", exr(&y, &[("owner", AttrValue::Int(1))])),
        ("must be a float", exr(&y, &[("expTime", text("1/60"))])),
        (
            "strictly",
            spectral(&[500.0, 500.0], &[&four, &four], &[], "a"),
        ),
        (
            "strictly",
            spectral(&[600.0, 500.0], &[&four, &four], &[], "a"),
        ),
        ("not positive", spectral(&[f32::NAN], &[&four], &[], "a")),
        ("not positive", spectral(&[-5.0], &[&four], &[], "a")),
        (
            "2 wavelengths for 1",
            spectral(&[1.0, 2.0], &[&four], &[], "a"),
        ),
        ("at least one spectral", spectral(&[], &[], &[], "a")),
        ("six decimals", spectral(&[1e-7], &[&four], &[], "a")),
        ("holds 3 values", spectral(&[500.0], &[&three], &[], "a")),
        (
            "as a spectral",
            spectral(&[500.0], &[&four], &[ch("S0.6um", &four)], "a"),
        ),
        ("twice", spectral(&[500.0], &[&four], &[], "emissiveUnits")),
        (
            "4 pixels given, the image has 6",
            write_png_srgb8(&path, 3, 2, &[[0; 3]; 4]),
        ),
        (
            "`G`",
            write_png_linear(&path, 1, 1, &[[0.0, f32::NAN, 0.0]]),
        ),
        ("empty", write_png_linear(&path, 1, 0, &[])),
    ];
    for (expected, result) in cases {
        let err = result.expect_err(expected);
        let message = err.to_string();
        assert!(
            message.starts_with(&path.display().to_string()),
            "{message}"
        );
        assert!(
            message.contains(expected),
            "expected {expected:?} in {message}"
        );
    }
    assert!(listing(&dir).is_empty());
}

#[test]
fn reading_a_bad_file_is_an_error() {
    let dir = scratch("read_bad");
    let missing = dir.join("missing.exr");
    let err = read_exr(&missing).unwrap_err();
    assert!(
        matches!(err, ImageError::Io { .. }) && err.path() == missing,
        "{err:?}"
    );

    let garbage = dir.join("garbage.exr");
    fs::write(&garbage, b"this is not an OpenEXR file at all").unwrap();
    assert_eq!(read_exr(&garbage).unwrap_err().path(), garbage);

    // A real file cut short.
    let good = dir.join("good.exr");
    let data = values(64 * 64, 9);
    write_y(&good, 64, 64, &data).unwrap();
    let bytes = fs::read(&good).unwrap();
    let cut = dir.join("cut.exr");
    fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    assert_eq!(read_exr(&cut).unwrap_err().path(), cut);
}

/// Decodes an 8-bit RGB PNG: (width, height, pixels, has sRGB chunk).
fn decode_png(path: &Path) -> (u32, u32, Vec<[u8; 3]>, bool) {
    let file = std::io::BufReader::new(fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(
        (info.color_type, info.bit_depth),
        (png::ColorType::Rgb, png::BitDepth::Eight)
    );
    let pixels = buf[..info.buffer_size()]
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    (
        info.width,
        info.height,
        pixels,
        reader.info().srgb.is_some(),
    )
}

/// IEC 61966-2-1, written out independently of the crate.
fn expected_8bit(linear: f32) -> u8 {
    let x = f64::from(linear).clamp(0.0, 1.0);
    let encoded = if x <= 0.0031308 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (255.0 * encoded + 0.5).floor() as u8
}

#[test]
fn png_from_linear_values_is_srgb_encoded_and_rounded() {
    let dir = scratch("png");
    let path = dir.join("preview.png");
    let (w, h) = (4, 3);
    let linear = [0.001f32, 0.2, 0.0031308, 0.04, 0.9, 1e-9, 0.5, 0.25, 0.75];
    let mut pixels = vec![[0.0f32, 0.5, 1.0], [2.0, -1.0, f32::INFINITY]];
    pixels
        .extend((0..w * h - 2).map(|i| [linear[i % 9], linear[(i + 1) % 9], linear[(i + 5) % 9]]));
    write_png_linear(&path, w, h, &pixels).unwrap();

    let (pw, ph, got, srgb) = decode_png(&path);
    assert_eq!((pw, ph), (w as u32, h as u32));
    assert!(srgb, "the PNG should carry an sRGB chunk");
    for (i, (g, p)) in got.iter().zip(&pixels).enumerate() {
        assert_eq!(*g, p.map(expected_8bit), "pixel {i} from {p:?}");
    }
    // Anchors: 0 → 0, 0.5 → 188 (255 · 0.735357 = 187.52), 1 → 255; 2, +∞ clamp to 255; −1 → 0.
    assert_eq!(got[0], [0, 188, 255]);
    assert_eq!(got[1], [255, 0, 255]);
}

#[test]
fn png_from_encoded_bytes_is_written_verbatim() {
    let dir = scratch("png8");
    let path = dir.join("bytes.png");
    let (w, h) = (3, 2);
    let pixels: Vec<[u8; 3]> = (0..w * h)
        .map(|i| [i as u8 * 40, 255 - i as u8, 7])
        .collect();
    write_png_srgb8(&path, w, h, &pixels).unwrap();
    let (pw, ph, got, _) = decode_png(&path);
    assert_eq!((pw as usize, ph as usize), (w, h));
    assert_eq!(got, pixels);
    assert_eq!(listing(&dir), ["bytes.png"]);
}

/// Texture and environment-map inputs read as RGB: a JPEG of two flat sRGB blocks written by
/// OpenImageIO (`scripts/gen_test_images.py`) decodes to its code values within 2/255, marked
/// sRGB-encoded; a 16-bit grey PNG keeps its 16 bits; an unknown extension names the formats.
#[test]
fn rgb_inputs_decode_to_their_values() {
    use spectrace::image_io::{Encoding, read_rgb};
    let jpg = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/images/blocks.jpg");
    let img = read_rgb(&jpg).unwrap();
    assert_eq!(
        (img.width, img.height, img.encoding),
        (16, 8, Encoding::Srgb)
    );
    for (i, p) in img.rgb.iter().enumerate() {
        let want = if i % 16 < 8 {
            [200.0, 60.0, 30.0]
        } else {
            [20.0, 90.0, 220.0]
        };
        for k in 0..3 {
            assert!(
                (p[k] * 255.0 - want[k]).abs() <= 2.0,
                "pixel {i}: {p:?} vs {want:?}"
            );
        }
    }
    let dir = scratch("rgb_inputs");
    let png = dir.join("grey16.png");
    {
        let f = std::fs::File::create(&png).unwrap();
        let mut e = png::Encoder::new(f, 2, 1);
        e.set_color(png::ColorType::Grayscale);
        e.set_depth(png::BitDepth::Sixteen);
        let mut w = e.write_header().unwrap();
        w.write_image_data(&[0x12, 0x34, 0xFF, 0xFF]).unwrap();
    }
    let img = read_rgb(&png).unwrap();
    assert!(img.grey && img.encoding == Encoding::Srgb);
    assert_eq!(img.rgb[0], [0x1234 as f32 / 65535.0; 3]);
    assert_eq!(img.rgb[1], [1.0; 3]);
    let e = read_rgb(&dir.join("x.tga")).unwrap_err().to_string();
    assert!(e.contains(".tga") && e.contains(".jpg"), "{e}");
}

/// Inputs that cannot be a texture: an EXR without colour channels, a corrupt PNG, a missing
/// file. Each error names the file and what is wrong.
#[test]
fn unusable_images_are_named_errors() {
    use spectrace::image_io::read_rgb;
    let dir = scratch("unusable_images");
    let exr = dir.join("alpha.exr");
    write_exr(&exr, 2, 1, &[ch("A", &[0.5, 1.0])], &[]).unwrap();
    let e = read_rgb(&exr).unwrap_err().to_string();
    assert!(
        e.contains("alpha.exr") && e.contains("R, G and B") && e.contains("A"),
        "{e}"
    );
    let png = dir.join("broken.png");
    fs::write(&png, b"\x89PNG\r\n\x1a\nnot really").unwrap();
    let e = read_rgb(&png).unwrap_err().to_string();
    assert!(e.contains("broken.png") && e.contains("PNG"), "{e}");
    let e = read_rgb(&dir.join("nope.jpg")).unwrap_err().to_string();
    assert!(e.contains("nope.jpg"), "{e}");
}
