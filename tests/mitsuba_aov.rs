//! Mitsuba's `aov` integrator: first-hit channels beside the image, against closed forms. A
//! camera at the origin looks down −z at a 4 × 4 m rectangle 2 m away: a pixel whose centre
//! ray has direction d (unit) sees depth 2/|d_z| m, position 2·d/|d_z|, both normals +z,
//! primitive 0 or 1 and shape 0. Pixel values average the pixel's rays (box filter), so the
//! centre ray's value holds to second order in the pixel's width: 0.2 % here.

mod support;

use support::cli::{spectrace, tmpdir};

const SCENE: &str = r#"<scene version="3.0.0">
  <integrator type="aov">
    <string name="aovs" value="dd:depth, pp:position, nn:sh_normal, gg:geo_normal, ii:shape_index"/>
    <integrator type="path" name="image"/>
  </integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, -1" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/>
      <rfilter type="box"/></film>
  </sensor>
  <emitter type="constant"/>
  <shape type="rectangle">
    <transform name="to_world"><scale value="2"/><translate z="-2"/></transform>
    <bsdf type="diffuse"/>
  </shape>
</scene>"#;

#[test]
fn aov_channels_are_the_first_hits_closed_forms() {
    let dir = tmpdir("mitsuba-aov");
    std::fs::write(dir.join("aov.xml"), SCENE).unwrap();
    let (ok, err) = spectrace(&dir, &["render", "aov.xml", "-q", "-o", "aov.exr"]);
    assert!(ok, "{err}");
    let img = spectrace::image_io::read_exr(&dir.join("aov.exr")).unwrap();
    let ch = |n: &str| {
        img.channel(n)
            .unwrap_or_else(|| panic!("no channel {n}"))
            .to_vec()
    };
    let (w, h) = (16usize, 12usize);
    // the pixel centre's direction: fov 40° across x
    let tan = (20f64).to_radians().tan();
    let mut worst = 0.0f64;
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let sx = ((x as f64 + 0.5) / w as f64 * 2.0 - 1.0) * tan;
            let sy = (1.0 - (y as f64 + 0.5) / h as f64 * 2.0) * tan * h as f64 / w as f64;
            let d = [sx, sy, -1.0];
            let len = (sx * sx + sy * sy + 1.0).sqrt();
            let depth = 2.0 * len;
            let rel = |a: f32, b: f64, scale: f64| (a as f64 - b).abs() / scale;
            worst = worst.max(rel(ch("dd.T")[i], depth, depth));
            for (k, c) in ["pp.X", "pp.Y", "pp.Z"].iter().enumerate() {
                worst = worst.max(rel(ch(c)[i], 2.0 * d[k], 2.0));
            }
            for c in ["nn", "gg"] {
                for (k, v) in [0.0, 0.0, 1.0].iter().enumerate() {
                    let n = ch(&format!("{c}.{}", ["X", "Y", "Z"][k]))[i];
                    assert!((n as f64 - v).abs() < 1e-5, "{c} at ({x}, {y}): {n}");
                }
            }
            assert_eq!(ch("ii.I")[i], 0.0);
        }
    }
    assert!(worst < 2e-3, "worst relative error {worst}");
}

/// Unsupported AOV types and an aov without its image integrator are located errors.
#[test]
fn aov_errors_are_located() {
    let dir = tmpdir("mitsuba-aov-bad");
    for (from, to, expect) in [
        (
            "gg:geo_normal",
            "gg:albedo",
            "AOV type \"albedo\" is not supported",
        ),
        (
            "<integrator type=\"path\" name=\"image\"/>",
            "",
            "needs exactly one nested <integrator>",
        ),
        ("ii:shape_index", "ii", "\"ii\" is not a name:type pair"),
    ] {
        std::fs::write(dir.join("bad.xml"), SCENE.replace(from, to)).unwrap();
        let (ok, err) = spectrace(&dir, &["render", "bad.xml", "-q", "-o", "bad.exr"]);
        assert!(
            !ok && err.contains(expect) && err.contains("bad.xml:"),
            "{err}"
        );
    }
}
