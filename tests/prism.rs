//! Dispersion through the N-BK7 prism of the default scene: narrow-line beams at the F, d and C
//! lines land on a screen where Snell's law, the Sellmeier formula and the geometry put them,
//! within 0.05°, measured from rendered images, for light tracing and for bidirectional path
//! tracing, which also agree on each line's power on the screen.

mod support;

use glam::{DVec2, Vec2};
use support::prism::{A, C, MESH, through};
use support::render::{render_with, scene_from};

// The beam's axis meets the left face AC at its midpoint at 19.32° above horizontal (minimum
// deviation for the d line), and a screen stands 0.5 m beyond the exit point, perpendicular to
// the d-line exit ray.

/// Exit point and direction of the beam's central ray at wavelength `l`.
fn trace(l: f64) -> (DVec2, DVec2) {
    let d = DVec2::new(19.32f64.to_radians().cos(), 19.32f64.to_radians().sin());
    let (_, exit, out) = through((A + C) * 0.5, d, l);
    (exit, out)
}

/// (wavelength nm, where its spot lands on the screen plane (m), the spot's summed band
/// radiance) for the F, d and C lines rendered by `integrator` with sampler seed `seed`.
fn spots(integrator: &str, seed: u32) -> Vec<(f64, DVec2, f64)> {
    let (e_d, out_d) = trace(587.56);
    let s_centre = e_d + out_d * 0.5;
    let n_s = -out_d; // the screen faces the prism
    let eye = s_centre + n_s * 0.25;
    let mut measured = Vec::new();
    for l in [486.13, 587.56, 656.27] {
        let scene = scene_from(&format!(
            r#"
[camera]
eye = [{ex}, {ey}, 0]
target = [{sx}, {sy}, 0]
up = [0, 0, 1]
fov = "8 deg"
[film]
width = 160
height = 160
spp = 64
filter = "box"
[integrator]
type = "{integrator}"
max_depth = 8
[materials.bk7]
type = "dielectric"
ior = "N-BK7"
[materials.screen]
type = "diffuse"
reflectance = 0.8
[[shapes]]
type = "mesh"
material = "bk7"
{MESH}[[shapes]]
type = "rectangle"
material = "screen"
transform = [{{ scale = 0.1 }}, {{ look_at = {{ eye = [{sx}, {sy}, 0], target = [{tx}, {ty}, 0], up = [0, 0, 1] }} }}]
[[lights]]
type = "beam"
position = [{bx}, {by}, 0]
target = [-0.025, 0.04330125, 0]
radius = "0.5 mm"
spectrum = {{ samples = [[{l0}, 0], [{l}, 1], [{l1}, 0]] }}
power = "1 W"
"#,
            ex = eye.x,
            ey = eye.y,
            sx = s_centre.x,
            sy = s_centre.y,
            tx = s_centre.x + n_s.x,
            ty = s_centre.y + n_s.y,
            bx = -0.025 - 0.3 * 19.32f64.to_radians().cos(),
            by = 0.04330125 - 0.3 * 19.32f64.to_radians().sin(),
            l0 = l - 0.5,
            l1 = l + 0.5,
        ));
        let (img, stats) = render_with(&scene, |o| o.seed = seed);
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        // centroid of the spot, weighted by band radiance
        let (mut sw, mut sx, mut sy) = (0.0f64, 0.0f64, 0.0f64);
        for (i, v) in img.band.iter().enumerate() {
            let v = *v as f64;
            sw += v;
            sx += v * ((i % img.width) as f64 + 0.5);
            sy += v * ((i / img.width) as f64 + 0.5);
        }
        assert!(sw > 0.0, "no light reached the screen at {l} nm");
        let raster = Vec2::new((sx / sw) as f32, (sy / sw) as f32);
        // back-project onto the screen plane
        let ray = scene.camera.generate_ray(raster, Vec2::splat(0.5));
        let (o, d) = (ray.o.as_dvec3(), ray.d.as_dvec3());
        let plane_n = n_s.extend(0.0);
        let t = (s_centre.extend(0.0) - o).dot(plane_n) / d.dot(plane_n);
        let p = o + d * t;
        measured.push((l, DVec2::new(p.x, p.y), sw));
    }
    measured
}

/// Seeds rendered per integrator: the spot powers' spread over them is the noise the power
/// comparison is judged against.
const SEEDS: u32 = 8;

#[test]
fn fraunhofer_lines_land_where_snell_and_sellmeier_say() {
    let light: Vec<_> = (1..=SEEDS).map(|k| spots("light", k)).collect();
    let bdpt: Vec<_> = (1..=SEEDS).map(|k| spots("bdpt", k)).collect();
    for (name, measured) in [("light", &light[0]), ("bdpt", &bdpt[0])] {
        check_lines(name, measured);
    }
    // the two integrators see the same caustic: each line's spot in the same place (within
    // 0.01° seen from the exit point) with the same power. A line of 1 nm is found by few
    // wavelength samples, so one render's power is noisy to a few per cent (as much as 4 %
    // between the two at one seed): the means over the seeds must agree within four standard
    // errors of their difference, and that standard error must be below 1 %, so that a bias
    // of a few per cent cannot hide in it.
    for (i, (l, pl, _)) in light[0].iter().enumerate() {
        let (_, pb, _) = bdpt[0][i];
        let e = trace(*l).0;
        let angle = (*pl - e).angle_to(pb - e).to_degrees().abs();
        assert!(angle < 0.01, "{l} nm: light and bdpt spots {angle}° apart");
        let stats = |runs: &[Vec<(f64, DVec2, f64)>]| {
            let w: Vec<f64> = runs.iter().map(|r| r[i].2).collect();
            let n = w.len() as f64;
            let mean = w.iter().sum::<f64>() / n;
            let var = w.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, var / n)
        };
        let ((ml, vl), (mb, vb)) = (stats(&light), stats(&bdpt));
        let se = (vl + vb).sqrt() / ml;
        let rel = mb / ml - 1.0;
        println!("{l} nm: spot power bdpt ÷ light − 1 = {rel:+.4} (standard error {se:.4})");
        assert!(
            se < 0.01,
            "{l} nm: spot powers too noisy to compare (se {se})"
        );
        assert!(
            rel.abs() < 4.0 * se,
            "{l} nm: spot power bdpt {mb}, light {ml}: {rel:+.4}, {:.1} standard errors",
            rel.abs() / se
        );
    }
}

fn check_lines(integrator: &str, measured: &[(f64, DVec2, f64)]) {
    for (l, p, _) in measured {
        let (e, out) = trace(*l);
        let got = (*p - e).normalize();
        let angle = got.angle_to(out).to_degrees().abs();
        println!("{integrator}, {l} nm: exit direction off by {angle:.4}°");
        assert!(
            angle < 0.05,
            "{integrator}, {l} nm: measured direction differs from Snell + Sellmeier by {angle}°"
        );
    }
    // the spread between F and C, a pure dispersion measure
    let dir = |i: usize| (measured[i].1 - trace(measured[i].0).0).normalize();
    let spread = dir(0).angle_to(dir(2)).to_degrees().abs();
    let want = trace(486.13).1.angle_to(trace(656.27).1).to_degrees().abs();
    println!("{integrator}: F–C spread {spread:.4}°, predicted {want:.4}°");
    assert!(
        (spread - want).abs() < 0.1 * want.max(0.1),
        "{integrator}: F–C spread {spread}°, predicted {want}°"
    );
}
