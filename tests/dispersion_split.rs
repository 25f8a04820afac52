//! Splitting camera samples at dispersion (`integrator::split`, issue 30) keeps every
//! estimator unbiased: a dispersive slab's spectral transmittance per bin against Fresnel and
//! Sellmeier at several wavelengths, for `path` and `bdpt`, split and not; and bdpt's weighted
//! strategies still sum to the full render when samples split.

mod support;

use support::render::{assert_strategies_sum_to_full, mean, render_with, scene_from};

/// N-SF11 from SCHOTT's data sheet (2017): Sellmeier B₁…B₃ and C₁…C₃ in µm², typed here.
fn n_sf11(lambda_nm: f64) -> f64 {
    let l2 = (lambda_nm / 1000.0).powi(2);
    let b = [1.737_596_95, 0.313_747_346, 1.898_781_01];
    let c = [0.013_188_707, 0.062_306_814_2, 155.236_29];
    (1.0 + (0..3).map(|i| b[i] * l2 / (l2 - c[i])).sum::<f64>()).sqrt()
}

/// Unpolarised Fresnel reflectance from air at incidence `theta` onto index `n`.
fn fresnel(theta: f64, n: f64) -> f64 {
    let (ci, si) = (theta.cos(), theta.sin());
    let ct = (1.0 - (si / n).powi(2)).sqrt();
    let rs = ((ci - n * ct) / (ci + n * ct)).powi(2);
    let rp = ((n * ci - ct) / (n * ci + ct)).powi(2);
    0.5 * (rs + rp)
}

const BINS: usize = 6;
const TILT_DEG: f64 = 30.0;

/// A camera looking along +z through an N-SF11 slab 0.2 m thick, tilted 30° about x, at a
/// black emitter of 1 W·m⁻²·sr⁻¹ over 400–700 nm (flat: 1/300 W·m⁻²·sr⁻¹·nm⁻¹) that fills the
/// view; nothing else. The rays the slab reflects leave into the void, so each pixel sees
/// the emitter times the slab's transmittance with its internal reflections,
/// (1 − R)²·Σₖ R²ᵏ = (1 − R)/(1 + R), at the angle of incidence (unpolarised R at each face,
/// the renderer's scalar model).
fn slab(integrator: &str, dispersion: &str, with_slab: bool, spp: u32) -> String {
    let glass = if with_slab {
        format!(
            r#"
[[shapes]]
type = "box"
material = "sf11"
transform = [{{ scale = [5, 5, 0.1] }}, {{ rotate = {{ axis = [1, 0, 0], angle = "{TILT_DEG} deg" }} }}, {{ translate = [0, 0, 2] }}]"#
        )
    } else {
        String::new()
    };
    format!(
        r#"
[scene]
wavelength_range = ["400 nm", "700 nm"]
[camera]
eye = [0, 0, 0]
target = [0, 0, 1]
fov = "2 deg"
[film]
width = 8
height = 8
spp = {spp}
filter = "box"
[integrator]
type = "{integrator}"
max_depth = 64
dispersion = "{dispersion}"
[materials.black]
type = "diffuse"
reflectance = 0
[materials.sf11]
type = "dielectric"
ior = "N-SF11"
[[shapes]]
type = "rectangle"
material = "black"
transform = [{{ scale = 20 }}, {{ translate = [0, 0, 6] }}]
emission = {{ radiance = "1 W/m^2/sr", two_sided = true }}
{glass}
"#
    )
}

/// Per bin: the mean over the pixels of the spectral radiance, and its standard error over
/// the 64 pixels (independent samples), W·m⁻²·sr⁻¹·nm⁻¹.
fn bins(text: &str) -> Vec<(f64, f64)> {
    let scene = scene_from(text);
    let (img, stats) = render_with(&scene, |o| o.spectral_bins = BINS as u32);
    assert_eq!(stats.nan_samples + stats.inf_samples, 0);
    img.spectral
        .iter()
        .map(|plane| {
            let m = mean(plane.iter().copied());
            let n = plane.len() as f64;
            let var = plane.iter().map(|v| (*v as f64 - m).powi(2)).sum::<f64>() / (n - 1.0);
            (m, (var / n).sqrt())
        })
        .collect()
}

/// The closed form's mean over each 50 nm bin (1 nm midpoint rule), W·m⁻²·sr⁻¹·nm⁻¹.
fn expected() -> Vec<f64> {
    let theta = TILT_DEG.to_radians();
    (0..BINS)
        .map(|b| {
            let lo = 400.0 + 50.0 * b as f64;
            let t: f64 = (0..50)
                .map(|i| {
                    let r = fresnel(theta, n_sf11(lo + i as f64 + 0.5));
                    (1.0 - r) / (1.0 + r)
                })
                .sum::<f64>()
                / 50.0;
            t / 300.0
        })
        .collect()
}

#[test]
fn a_dispersive_slab_transmits_what_fresnel_and_sellmeier_say_in_every_bin() {
    let want = expected();
    // the emitter alone, every bin 1/300
    for (b, (m, se)) in bins(&slab("path", "split", false, 256)).iter().enumerate() {
        let d = m * 300.0 - 1.0;
        assert!(
            se * 300.0 < 2e-3 && d.abs() < 4.0 * se * 300.0,
            "bin {b} without the slab: {m} ± {se}"
        );
    }
    // hero-only samples put one wavelength per sample through the slab: 2.3 times the
    // standard error of split ones at equal spp here, so they take 4 times the samples
    let cases = [
        ("path", "split", 4096),
        ("path", "hero", 16384),
        ("bdpt", "split", 4096),
    ];
    for (integrator, dispersion, spp) in cases {
        let got = bins(&slab(integrator, dispersion, true, spp));
        for (b, ((m, se), w)) in got.iter().zip(&want).enumerate() {
            let rel = m / w - 1.0;
            eprintln!(
                "{integrator} {dispersion}, {}–{} nm: {m:.6e} ± {se:.1e}, Fresnel {w:.6e} ({rel:+.4})",
                400 + 50 * b,
                450 + 50 * b
            );
            assert!(se / w < 2e-3, "too noisy to check 0.5 %: {se} against {w}");
            assert!(
                (m - w).abs() < 4.0 * se + 1e-4 * w,
                "{integrator} {dispersion}, bin {b}: {m} ± {se}, want {w}"
            );
        }
    }
}

/// A room with a rough N-SF11 sphere (every bdpt strategy can sample the paths through it)
/// under a ceiling lamp.
fn glass_room(max_depth: u32, spp: u32) -> spectrace::scene::Scene {
    scene_from(&format!(
        r#"
[camera]
eye = [0, 1.0, 0.95]
target = [0, 0.4, -0.5]
fov = "60 deg"
[film]
width = 24
height = 24
spp = {spp}
filter = "box"
[integrator]
type = "bdpt"
max_depth = {max_depth}
dispersion = "split"
[materials.grey]
type = "diffuse"
reflectance = 0.6
[materials.glass]
type = "dielectric"
ior = "N-SF11"
roughness = 0.3
[[shapes]]
type = "box"
material = "grey"
two_sided = true
transform = [{{ scale = [2, 2, 2] }}, {{ translate = [0, 1, 0] }}]
[[shapes]]
type = "sphere"
center = [0, 0.35, -0.3]
radius = 0.35
material = "glass"
[[shapes]]
type = "rectangle"
transform = [{{ scale = 0.5 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "90 deg" }} }}, {{ translate = [0, 1.99, 0] }}]
emission = {{ radiance = "10 W/m^2/sr" }}
"#
    ))
}

/// The MIS-weighted images of every strategy sum to the full render also when samples split
/// at the glass (the same random numbers feed each: equal to rounding, 1e-4 relative), and
/// the split changes the image only by noise.
#[test]
fn weighted_strategies_sum_to_the_full_render_when_samples_split() {
    let max_depth = 3;
    let s = glass_room(max_depth, 4);
    assert_strategies_sum_to_full(&s, max_depth);
    // split against hero over the image, both at 256 spp: equal within noise
    let big = glass_room(8, 256);
    let y = |split: bool| {
        let (img, _) = render_with(&big, |o| o.split_dispersion = split);
        (
            mean(img.band.iter().copied()),
            mean(img.xyz.iter().map(|p| p[1])),
        )
    };
    let (a, b) = (y(true), y(false));
    eprintln!(
        "split: L {:.5} Y {:.4}; hero: L {:.5} Y {:.4}",
        a.0, a.1, b.0, b.1
    );
    assert!((a.0 / b.0 - 1.0).abs() < 0.01 && (a.1 / b.1 - 1.0).abs() < 0.01);
}
