//! The RGL measured BRDF (`measured` in pbrt-v4 and Mitsuba 3; Dupuy & Jakob 2018's `.bsdf`
//! files) read through Mitsuba's XML, against Mitsuba 3.9.1's own `eval` and `pdf`
//! (tests/reference/rgl/vectors.txt, by `scripts/gen_rgl_vectors.py`) on two files: the
//! synthetic isotropic GGX file of the pbrt-v4 reference scene and an anisotropic table with
//! no structure whose `jacobian` flag is 0 (tests/reference/rgl/asym.bsdf).

use std::path::{Path, PathBuf};

use glam::Vec3;
use spectrace::material::TransportMode;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A scene of one sphere of Mitsuba's `measured` reading `file`, built.
fn build(dir: &Path, file: &Path) -> spectrace::scene::Scene {
    let xml = format!(
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="32"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <emitter type="constant"><spectrum name="radiance" value="0.2"/></emitter>
    <shape type="sphere"><bsdf type="measured"><string name="filename" value="{}"/></bsdf></shape>
</scene>"#,
        file.display()
    );
    let p = dir.join("scene.xml");
    std::fs::write(&p, xml).expect("written");
    let desc = spectrace::loader::load_any(&p, &[]).unwrap_or_else(|e| panic!("{e}"));
    spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"))
}

/// Mitsuba 3.9.1's value (f·cos θ of the light direction) and density for every query, at
/// wavelengths inside and beyond each file's range, to 2·10⁻⁴ relative (f32 arithmetic in a
/// different order).
#[test]
fn measured_files_evaluate_as_mitsuba_evaluates_them() {
    let dir = std::env::temp_dir().join(format!("spectrace-rgl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let ggx = build(&dir, &root().join("tests/reference/pbrt/measured/ggx.bsdf"));
    let asym = build(&dir, &root().join("tests/reference/rgl/asym.bsdf"));
    let text = std::fs::read_to_string(root().join("tests/reference/rgl/vectors.txt"))
        .expect("vectors.txt");
    let mut n = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let mut it = line.split_whitespace();
        let scene = match it.next() {
            Some("ggx") => &ggx,
            Some("asym") => &asym,
            other => panic!("{other:?}"),
        };
        let v: Vec<f32> = it.map(|x| x.parse().expect("a number")).collect();
        let (view, light) = (Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5]));
        let (lambda, value, pdf) = (v[6], v[7], v[8]);
        let w = spectrace::spectrum::SampledWavelengths::<4> {
            lambda: [lambda; 4],
            pdf: [1.0; 4],
        };
        let b = scene.materials[0].at(glam::Vec2::ZERO, &w);
        let ours = b.eval(view, light, &w, TransportMode::Radiance)[0] * light.z;
        assert!(
            (ours - value).abs() <= 2e-4 * value.abs(),
            "{line}: value {ours} vs Mitsuba {value}"
        );
        let ours_pdf = b.pdf(view, light, &w, TransportMode::Radiance);
        assert!(
            (ours_pdf - pdf).abs() <= 2e-4 * pdf,
            "{line}: pdf {ours_pdf} vs Mitsuba {pdf}"
        );
        n += 1;
    }
    assert_eq!(n, 80);
    std::fs::remove_dir_all(&dir).ok();
}
