//! Environment maps: their sampling against their own density (χ²), and a render against a
//! closed form: a diffuse plane facing the zenith under a map that varies only with θ reflects
//! L = ρ/π · E with E = ∫ L_env(ω) cos θ dω over the upper hemisphere, computed here from the
//! pixels by quadrature of Mitsuba's lookup (rows at v = j/(H − 1), linear in between). The same
//! map is compared with Mitsuba 3.9.1 in `tests/reference/envmap` (run by `reference_idiff.rs`).

#[path = "support/chi2.rs"]
mod chi2;
mod support;

use glam::{Mat3, Vec2, Vec3};

use chi2::{Grid, chi2_test};
use spectrace::light::EnvMapLight;
use spectrace::spectrum::{SampledWavelengths, Spectrum};
use support::Rng;
use support::render::{render_with, scene_from};

/// An 16 × 9 map: a sky getting brighter toward the zenith, a dim ground, and a bright patch.
fn pixels() -> (usize, usize, Vec<[f32; 3]>) {
    let (w, h) = (16, 9);
    let mut rgb = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let sky = if j < h / 2 {
                [0.3, 0.5, 1.0].map(|c| c * (1.0 - j as f32 / h as f32))
            } else {
                [0.05, 0.04, 0.03]
            };
            rgb.push(if (i, j) == (5, 2) {
                [40.0, 35.0, 30.0]
            } else {
                sky
            });
        }
    }
    (w, h, rgb)
}

#[test]
fn chi2_sampling_matches_pdf() {
    let (w, h, rgb) = pixels();
    // rotated, so the frame change is exercised too
    let rot = Mat3::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.7);
    let m = EnvMapLight::new(w, h, &rgb, Spectrum::Constant(1.0), rot).unwrap();
    let wl = SampledWavelengths::<4> {
        lambda: [450.0, 520.0, 600.0, 680.0],
        pdf: [1.0; 4],
    };
    let mut rng = Rng::new(11);
    let grid = Grid {
        n_cos: 20,
        n_phi: 40,
        both_hemispheres: true,
    };
    let r = chi2_test(
        grid,
        400_000,
        || {
            let u = Vec2::new(rng.uniform(), rng.uniform());
            m.sample_li(&wl, u).map(|s| s.wi)
        },
        |d| m.pdf_li(d) as f64,
    );
    assert!(r.p_value > 0.001, "{r:?}");
    assert!((r.integral - 1.0).abs() < 0.01, "{r:?}");
}

/// E over the upper hemisphere of a map whose rows are constant: 2π ∫ L(θ) cos θ sin θ dθ,
/// L piecewise linear between rows j at θ = π j/(H − 1); Simpson with 20 000 steps.
fn horizontal_irradiance(rows: &[f64]) -> f64 {
    let h = rows.len();
    let l = |theta: f64| {
        let y = theta / std::f64::consts::PI * (h - 1) as f64;
        let j = (y as usize).min(h - 2);
        let t = y - j as f64;
        rows[j] * (1.0 - t) + rows[j + 1] * t
    };
    let n = 20_000;
    let b = std::f64::consts::FRAC_PI_2;
    let f = |th: f64| l(th) * th.cos() * th.sin();
    let step = b / n as f64;
    let mut s = f(0.0) + f(b);
    for k in 1..n {
        s += f(k as f64 * step) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    2.0 * std::f64::consts::PI * s * step / 3.0
}

#[test]
fn plane_under_a_sky_gradient_matches_the_closed_form() {
    let (w, h) = (8usize, 9usize);
    let rows: Vec<f64> = (0..h)
        .map(|j| if j <= 4 { 1.0 - 0.2 * j as f64 } else { 0.1 })
        .collect();
    // a grey EXR: Y = the row's value, so pixel luminance is scale × value cd/m²
    let dir = std::env::temp_dir().join(format!("spectrace-envmap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let exr = dir.join("sky.exr");
    let y: Vec<f32> = (0..w * h).map(|k| rows[k / w] as f32).collect();
    spectrace::image_io::write_exr(
        &exr,
        w,
        h,
        &[spectrace::image_io::Channel {
            name: "Y",
            data: &y,
        }],
        &[],
    )
    .unwrap();
    let rho = 0.6;
    let scale = 1000.0;
    let scene = scene_from(&format!(
        r#"
[camera]
type = "orthographic"
eye = [0, 1, 0]
target = [0, 0, 0]
up = [0, 0, -1]
view_width = "1 m"

[film]
width = 8
height = 8
spp = 256

[integrator]
max_depth = 1

[materials.plane]
type = "diffuse"
reflectance = {rho}

[[shapes]]
type = "rectangle"
material = "plane"
transform = [{{ scale = 1000 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}]

[[lights]]
type = "environment"
image = {:?}
scale = {scale}
"#,
        exr.display().to_string()
    ));
    let (img, stats) = render_with(&scene, |_| {});
    assert_eq!(stats.nan_samples + stats.inf_samples, 0);
    let mean_y: f64 = img.xyz.iter().map(|p| p[1] as f64).sum::<f64>() / img.xyz.len() as f64;
    let want = rho / std::f64::consts::PI * horizontal_irradiance(&rows) * scale;
    println!("Y = {mean_y:.4} cd/m², closed form {want:.4}");
    assert!(
        (mean_y / want - 1.0).abs() < 0.005,
        "Y = {mean_y:.4} cd/m², closed form {want:.4}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
