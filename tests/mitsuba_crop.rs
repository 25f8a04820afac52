//! Mitsuba's film crop (`crop_offset_x`, `crop_offset_y`, `crop_width`, `crop_height` on an
//! `hdrfilm`): only the window is rendered and written, every pixel as in the whole image. The
//! Cornell box reference scene with a 48 × 32 window at (24, 40) of its 96 × 96 film must match
//! that window of Mitsuba 3.9.1's own full renders (`tests/reference/cornell/ref_a.exr`,
//! `ref_b.exr`) block by block.

mod support;

use std::path::Path;

/// Each 8 × 8 block of the window: the mean Y of spectrace's two seeds and of Mitsuba's two
/// references at the same place of the full image, within 5 standard errors of the
/// difference (each renderer's from its two renders).
#[test]
fn a_cropped_film_renders_the_window_of_mitsubas_image() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/cornell");
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("mitsuba_crop");
    std::fs::create_dir_all(&out).expect("output folder");
    let xml = std::fs::read_to_string(dir.join("scene.xml")).expect("scene.xml");
    let crop = r#"<rfilter type="box"/>
            <integer name="crop_offset_x" value="24"/>
            <integer name="crop_offset_y" value="40"/>
            <integer name="crop_width" value="48"/>
            <integer name="crop_height" value="32"/>"#;
    assert_eq!(xml.matches(r#"<rfilter type="box"/>"#).count(), 1);
    // beside the original, so that its meshes' relative paths resolve
    let scene = dir.join(format!("crop_{}.xml", std::process::id()));
    std::fs::write(&scene, xml.replace(r#"<rfilter type="box"/>"#, crop)).expect("written");
    let mut ours = Vec::new();
    for seed in ["7", "8"] {
        let exr = out.join(format!("seed{seed}.exr"));
        support::cli::render_mitsuba_units(&scene, &exr, seed);
        // Mitsuba 3.9.1 writes a cropped film as an image of its own, without a data window
        // offset (its `film().write` of a 10 × 8 crop at (5, 7): origin (0, 0), display 10 × 8)
        let read = spectrace::image_io::read_exr(&exr).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(read.window, None);
        ours.push(support::cli::y_channel(&exr));
    }
    std::fs::remove_file(&scene).ok();
    let (w, _, ref_a) = support::cli::y_channel(&dir.join("ref_a.exr"));
    let (_, _, ref_b) = support::cli::y_channel(&dir.join("ref_b.exr"));
    assert_eq!((ours[0].0, ours[0].1), (48, 32));
    let mut worst = 0.0f64;
    for by in 0..4 {
        for bx in 0..6 {
            let (mut sums, mut sq) = ([0.0f64; 4], [0.0f64; 2]);
            for y in by * 8..by * 8 + 8 {
                for x in bx * 8..bx * 8 + 8 {
                    let (i, j) = (y * 48 + x, (y + 40) * w + x + 24);
                    let v = [ours[0].2[i], ours[1].2[i], ref_a[j], ref_b[j]];
                    for k in 0..4 {
                        sums[k] += v[k];
                    }
                    sq[0] += (v[0] - v[1]).powi(2);
                    sq[1] += (v[2] - v[3]).powi(2);
                }
            }
            let n = 64.0;
            let (m_st, m_ref) = (
                (sums[0] + sums[1]) / (2.0 * n),
                (sums[2] + sums[3]) / (2.0 * n),
            );
            let se2 = (sq[0] + sq[1]) / (4.0 * n * n);
            let z = (m_st - m_ref) / se2.sqrt();
            println!("block ({bx}, {by}): spectrace {m_st:.5}, Mitsuba {m_ref:.5}, z {z:+.2}");
            worst = if z.abs() > worst.abs() { z } else { worst };
        }
    }
    println!("worst z {worst:+.2}");
    assert!(worst.abs() < 5.0, "worst block z {worst:.2}");
}
