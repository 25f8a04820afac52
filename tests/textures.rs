//! Textures against closed forms: a plane under a uniform environment of band radiance L
//! reflects ρ(uv)·L, so with an orthographic camera whose view is exactly the rectangle, every
//! pixel shows the texture's value at a known uv. The checks and texels below fall on pixel
//! edges, so each pixel lies on one of them: the pattern's orientation (Mitsuba's: rectangle uv
//! (0, 0) at its local corner (−1, −1), image row 0 at v = 0), its scale and the sRGB decoding
//! of 8-bit PNG values (IEC 61966-2-1) are all visible. The same textures are compared with
//! Mitsuba 3.9.1 in `tests/reference/textures` (run by `reference_idiff.rs`).

mod support;

use std::path::PathBuf;

use support::render::{render_with, scene_from};

const N: usize = 32;

/// A plane scene whose `[materials.plane]` reflectance is `reflectance` (TOML), under a uniform
/// environment of 1 W·m⁻²·sr⁻¹, seen by an orthographic camera covering the rectangle [−1, 1]²
/// with N × N pixels, top row at y = +1.
fn plane(reflectance: &str) -> String {
    format!(
        r#"
[camera]
type = "orthographic"
eye = [0, 0, 1]
target = [0, 0, 0]
up = [0, 1, 0]
view_width = "2 m"

[film]
width = {N}
height = {N}
spp = 64
filter = "box"

[integrator]
max_depth = 1

[materials.plane]
type = "diffuse"
reflectance = {reflectance}

[[shapes]]
type = "rectangle"
material = "plane"

[[lights]]
type = "environment"
spectrum = 1
radiance = "1 W/m^2/sr"
"#
    )
}

/// Mean band radiance over pixel rows r0..r1 and columns c0..c1.
fn block(band: &[f32], r: std::ops::Range<usize>, c: std::ops::Range<usize>) -> f64 {
    let mut s = 0.0;
    let mut n = 0.0;
    for y in r {
        for x in c.clone() {
            s += band[y * N + x] as f64;
            n += 1.0;
        }
    }
    s / n
}

/// Mitsuba's checkerboard: `a` where the fractional parts of to_uv(uv) are both ≤ ½ or both
/// > ½. With scale 2, the checks are 8 × 8 pixels; the bottom-left one (uv near (0, 0)) is `a`.
#[test]
fn checkerboard_checks_fall_where_mitsuba_puts_them() {
    let scene = scene_from(&plane("{ checkerboard = [0.8, 0.2], scale = [2, 2] }"));
    let (img, _) = render_with(&scene, |_| {});
    let mut worst: f64 = 0.0;
    for by in 0..4 {
        for bx in 0..4 {
            // block (bx, by) counted from the bottom-left: u ∈ [bx/4, (bx+1)/4), v likewise
            let a = (bx % 2) == (by % 2);
            let want = if a { 0.8 } else { 0.2 };
            let rows = (N - 8 * (by + 1))..(N - 8 * by);
            // the edge pixels of each check too: every pixel lies on one check
            let got = block(&img.band, rows, 8 * bx..8 * (bx + 1));
            worst = worst.max((got / want - 1.0).abs());
            assert!(
                (got / want - 1.0).abs() < 0.01,
                "check ({bx}, {by}) from the bottom left: {got:.4}, expected {want}"
            );
        }
    }
    println!("worst relative error over the 16 checks: {worst:.2e}");
}

/// sRGB decoding per IEC 61966-2-1, written out independently of the renderer's.
fn srgb_decode(byte: u8) -> f64 {
    let c = byte as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// A 2 × 2 grey PNG, nearest filtering: row 0 of the file (values 0 and 64) at v ∈ [0, ½),
/// i.e. the bottom half of the rectangle as the camera sees it; values decoded from sRGB.
#[test]
fn png_texels_are_decoded_and_oriented_as_mitsuba() {
    let dir = std::env::temp_dir().join(format!("spectrace-tex-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png: PathBuf = dir.join("grey.png");
    let bytes = [[0u8, 64], [128, 255]];
    {
        let f = std::fs::File::create(&png).unwrap();
        let mut e = png::Encoder::new(f, 2, 2);
        e.set_color(png::ColorType::Grayscale);
        e.set_depth(png::BitDepth::Eight);
        let mut w = e.write_header().unwrap();
        w.write_image_data(&[0, 64, 128, 255]).unwrap();
    }
    let scene = scene_from(&plane(&format!(
        "{{ image = {:?}, filter = \"nearest\" }}",
        png.display().to_string()
    )));
    let (img, _) = render_with(&scene, |_| {});
    let h = N / 2;
    for (row, col, rows, cols) in [
        (0, 0, h..N, 0..h),
        (0, 1, h..N, h..N),
        (1, 0, 0..h, 0..h),
        (1, 1, 0..h, h..N),
    ] {
        let want = srgb_decode(bytes[row][col]);
        let got = block(&img.band, rows, cols);
        assert!(
            (got - want).abs() < 0.01 * want.max(0.05),
            "texel (x {col}, row {row}): {got:.5}, expected {want:.5}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
