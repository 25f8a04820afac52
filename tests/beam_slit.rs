//! A slit beam (`slit = [width, height]`): a rectangle of irradiance power/(width·height) on a
//! plane across it, its height along `up`, by light tracing and by bdpt.

mod support;

use support::render::{render_with, scene_from};

/// A 1 W slit beam, 4 cm wide and 12 cm tall along +y, straight down −z onto a diffuse plane
/// (ρ = 0.5) seen by a camera 4 m away whose view is 40 cm across there: radiance ρ·E/π inside the
/// rectangle, E = 1 W / (0.04 m · 0.12 m), and nothing outside.
#[test]
fn a_slit_beam_lights_its_rectangle_with_power_over_area() {
    for integrator in ["light", "bdpt"] {
        let scene = scene_from(&format!(
            r#"
[camera]
eye = [0, 0, 4]
target = [0, 0, 0]
fov = "5.7248 deg"
[film]
width = 80
height = 80
spp = 16
filter = "box"
[integrator]
type = "{integrator}"
max_depth = 2
[materials.grey]
type = "diffuse"
reflectance = 0.5
[[shapes]]
type = "rectangle"
material = "grey"
transform = [{{ scale = 1 }}]
[[lights]]
type = "beam"
position = [0, 0, 0.5]
target = [0, 0, 0]
slit = ["4 cm", "12 cm"]
power = "1 W"
"#
        ));
        let (img, stats) = render_with(&scene, |_| {});
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        let want = 0.5 * (1.0 / (0.04 * 0.12)) / std::f64::consts::PI;
        // pixels are 5 mm on the plane: the slit covers columns 36..44 and rows 28..52, edges excluded
        let (mut inside, mut n, mut outside) = (0.0f64, 0, 0.0f64);
        for y in 0..80 {
            for x in 0..80 {
                let v = img.band[y * 80 + x] as f64;
                let (cx, cy) = (x as f64 + 0.5 - 40.0, y as f64 + 0.5 - 40.0);
                if cx.abs() < 3.0 && cy.abs() < 11.0 {
                    inside += v;
                    n += 1;
                } else if cx.abs() > 5.0 || cy.abs() > 13.0 {
                    outside += v;
                }
            }
        }
        let mean = inside / n as f64;
        eprintln!("{integrator}: inside {mean:.3} W/m²/sr (want {want:.3}), outside sum {outside}");
        assert!(
            (mean / want - 1.0).abs() < 0.01,
            "{integrator}: {mean} against {want}"
        );
        assert_eq!(outside, 0.0, "{integrator}: light outside the slit");
    }
}
