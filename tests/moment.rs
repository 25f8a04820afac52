//! Mitsuba's `moment` integrator: the inner integrator's image plus, per pixel, the second
//! moment of the samples (the mean of their squares). Checked against its definition: the
//! per-pixel variance of a one-sample estimate, m2 − mean², equals the variance measured
//! directly across many one-sample renders with different seeds.

mod support;

use std::path::Path;

use support::render::render_with;

const SCENE: &str = r#"<scene version="3.0.0">
  <integrator type="moment"><integrator type="path"><integer name="max_depth" value="3"/></integrator></integrator>
  <sensor type="perspective">
    <float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0, 2, 3" target="0, 0, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="256"/></sampler>
    <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="12"/>
      <rfilter type="box"/></film>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="diffuse"><spectrum name="reflectance" value="0.6"/></bsdf>
  </shape>
  <shape type="sphere"><point name="center" x="0" y="0.5" z="0"/><float name="radius" value="0.5"/></shape>
  <shape type="disk">
    <transform name="to_world"><scale value="0.4"/><rotate x="1" angle="90"/><translate y="2"/></transform>
    <emitter type="area"><spectrum name="radiance" value="5"/></emitter>
  </shape>
  <emitter type="constant"><spectrum name="radiance" value="0.3"/></emitter>
</scene>"#;

#[test]
fn second_moment_matches_the_variance_across_seeds() {
    let desc = spectrace::loader::mitsuba::load_str(SCENE, Path::new("moment.xml"), &[]).unwrap();
    assert!(desc.integrator.moment);
    let scene = spectrace::build::build(&desc).unwrap();
    assert!(scene.integrator.moment);
    let (img, _) = render_with(&scene, |o| o.threads = Some(2));
    let n_pix = img.xyz.len();

    // variance of a one-sample Y estimate per pixel, from the second moment
    let var_m2: Vec<f64> = (0..n_pix)
        .map(|i| img.xyz_m2[i][1] as f64 - (img.xyz[i][1] as f64).powi(2))
        .collect();
    // the same from 256 one-sample renders with different seeds
    let runs = 256;
    let (mut s1, mut s2) = (vec![0.0f64; n_pix], vec![0.0f64; n_pix]);
    for seed in 0..runs {
        let (one, _) = render_with(&scene, |o| {
            o.spp = 1;
            o.seed = 1000 + seed;
            o.threads = Some(2);
        });
        for i in 0..n_pix {
            let y = one.xyz[i][1] as f64;
            s1[i] += y;
            s2[i] += y * y;
        }
    }
    let var_seeds: Vec<f64> = (0..n_pix)
        .map(|i| (s2[i] - s1[i] * s1[i] / runs as f64) / (runs - 1) as f64)
        .collect();
    let (a, b): (f64, f64) = (var_m2.iter().sum(), var_seeds.iter().sum());
    println!("mean per-pixel variance: from m2 {a:.4e}, across seeds {b:.4e}");
    assert!(a > 0.0 && (a / b - 1.0).abs() < 0.1, "m2 {a} vs seeds {b}");
    // and m2 is never below the squared mean
    assert!(var_m2.iter().all(|&v| v > -1e-3 * a / n_pix as f64));
}
