//! Bidirectional path tracing through participating media, against the other estimators
//! (`path`, whose volumetric walk `tests/media.rs` holds to closed forms and
//! `tests/media_reference.rs` to Mitsuba 3, and `light`) on a medium inside glass, and against
//! Snell, Fresnel and Beer–Lambert on the rainbow of a prism of absorbing glass.

mod support;

use glam::DVec2;
use spectrace::film::Image;
use spectrace::scene::{IntegratorKind, Scene};
use support::prism::{A, C, MESH, through};
use support::render::{render_with, scene_from};

/// A glass ball (index 1.5, not dispersive) holding a spectrally scattering and absorbing fog
/// (σs 3 → 0.5 m⁻¹ across the spectrum, σa 0.3 m⁻¹, Henyey–Greenstein g = 0.4) on a diffuse
/// floor, lit by an area lamp to one side and behind, so that the ball's shadow and caustic
/// fall on floor the camera sees directly. Ball centre (0, 0.6, 0), radius 0.6.
fn glass_fog() -> String {
    support::media::fog_ball(
        "type = \"dielectric\"\nior = 1.5",
        2.4,
        [1.6, 2.2, 1.6],
        4.0,
        512,
    )
}

fn render(scene: &mut Scene, kind: IntegratorKind, seed: u32, spp: u32) -> Image {
    scene.integrator.kind = kind;
    let (img, stats) = render_with(scene, |o| {
        o.seed = seed;
        o.spp = spp;
    });
    assert_eq!(stats.nan_samples + stats.inf_samples, 0, "{kind:?}");
    img
}

/// Whether pixel (x, y) of the 48 × 48 image may see the glass ball: a camera ray through a
/// point within 2 pixels of its centre (the filter's reach) meets the sphere.
fn near_ball(scene: &Scene, x: usize, y: usize) -> bool {
    (-4..=4).any(|i| {
        (-4..=4).any(|j| {
            let raster = glam::Vec2::new(
                x as f32 + 0.5 + i as f32 * 0.5,
                y as f32 + 0.5 + j as f32 * 0.5,
            );
            let ray = scene.camera.generate_ray(raster, glam::Vec2::splat(0.5));
            let oc = ray.o - glam::Vec3::new(0.0, 0.6, 0.0);
            let b = oc.dot(ray.d);
            b * b - (oc.length_squared() - 0.36) >= 0.0
        })
    })
}

/// Y summed over the `size` × `size` tile (tx, ty), over the pixels `keep` accepts, and their
/// count.
fn tile(
    img: &Image,
    (tx, ty, size): (usize, usize, usize),
    keep: &dyn Fn(usize, usize) -> bool,
) -> (f64, usize) {
    let (mut sum, mut n) = (0.0, 0);
    for y in ty * size..(ty + 1) * size {
        for x in tx * size..(tx + 1) * size {
            if keep(x, y) {
                sum += img.xyz[y * 48 + x][1] as f64;
                n += 1;
            }
        }
    }
    (sum, n)
}

/// `bdpt` (512 spp) against `path` (2048 spp, as its paths through the glass to the lamp are
/// found by chance) on the whole image of the fogged glass ball, what the camera sees through
/// the glass included: the image means within 1 %, each 24 × 24 quadrant holding a tenth of
/// the light or more within 3 %; `light` (2048 spp) against `bdpt` on the floor seen directly
/// (its shadow and caustic through glass and fog included; light tracing cannot see through
/// the glass, a specular surface), each quadrant's floor pixels within 2 %. Measured over
/// seeds 1–3: means within 0.32 %, quadrants within 1.6 % (bdpt / path) and 0.94 %
/// (light / bdpt); at 8192 spp every 12 × 12 tile of bdpt and path agrees within 0.4 %. (The
/// connections inside the ball are short: ignoring the fog's transmittance on them moves this
/// image by 0.7 %; `tests/media.rs`'s `null`-bounded fog, where connections cross the fog to
/// the lamp and the floor, catches that at +36 %.)
#[test]
fn bdpt_path_and_light_agree_on_a_medium_inside_glass() {
    let seed = 1;
    let mut scene = scene_from(&glass_fog());
    let bdpt = render(&mut scene, IntegratorKind::Bdpt, seed, 512);
    let path = render(&mut scene, IntegratorKind::Path, seed, 2048);
    let light = render(&mut scene, IntegratorKind::Light, seed, 2048);
    let all = |_: usize, _: usize| true;
    let floor = |x: usize, y: usize| !near_ball(&scene, x, y);
    let mut bad = Vec::new();
    let mut check = |what: String, got: f64, want: f64, tol: f64| {
        println!("{what}: {:.4}", got / want);
        if (got / want - 1.0).abs() >= tol {
            bad.push(format!("{what}: {:.4}", got / want));
        }
    };
    let (p, _) = tile(&path, (0, 0, 48), &all);
    let (b, _) = tile(&bdpt, (0, 0, 48), &all);
    check("mean Y, bdpt / path".into(), b, p, 0.01);
    for ty in 0..2 {
        for tx in 0..2 {
            let (qp, _) = tile(&path, (tx, ty, 24), &all);
            let (qb, _) = tile(&bdpt, (tx, ty, 24), &all);
            if qp > 0.1 * p {
                check(format!("quadrant ({tx}, {ty}), bdpt / path"), qb, qp, 0.03);
            }
            let (fb, n) = tile(&bdpt, (tx, ty, 24), &floor);
            let (fl, _) = tile(&light, (tx, ty, 24), &floor);
            if n >= 200 && fb > 0.01 * p {
                check(
                    format!("floor of quadrant ({tx}, {ty}), light / bdpt"),
                    fl,
                    fb,
                    0.02,
                );
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

// The prism of `tests/prism.rs` (`support::prism`): the beam's axis meets the left face AC at
// its midpoint at 19.32° above horizontal (minimum deviation for the d line).
const BEAM_DEG: f64 = 19.32;
/// The beam's radius, m.
const BEAM_R: f64 = 0.5e-3;

/// σa(λ) of the tinting glass, m⁻¹: a filter with a pass band near 500 nm.
const SIGMA_A: [[f64; 2]; 5] = [
    [360.0, 40.0],
    [500.0, 4.0],
    [560.0, 12.0],
    [650.0, 36.0],
    [830.0, 20.0],
];

fn sigma_a(l: f64) -> f64 {
    let i = SIGMA_A.windows(2).position(|w| l <= w[1][0]).unwrap_or(3);
    let ([l0, s0], [l1, s1]) = (SIGMA_A[i], SIGMA_A[i + 1]);
    s0 + (s1 - s0) * (l - l0) / (l1 - l0)
}

/// The path length inside the prism, m, of the ray of the beam offset by `u` metres
/// (in the xy plane, across its axis) at wavelength `l`: Snell at the left face, then to the
/// right face BC.
fn inside(l: f64, u: f64) -> f64 {
    let d = DVec2::new(BEAM_DEG.to_radians().cos(), BEAM_DEG.to_radians().sin());
    let (entry, exit, _) = through((A + C) * 0.5 + d.perp() * u, d, l);
    (exit - entry).length()
}

/// The beam's transmittance through the tinting glass at wavelength `l`: exp(−σa ℓ) averaged
/// over the beam's disk (uniform; the prism is a prism, so each in-plane offset u weighs
/// as its chord, √(r² − u²)).
fn beam_transmittance(l: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for k in 0..400 {
        let u = BEAM_R * ((k as f64 + 0.5) / 200.0 - 1.0);
        let wgt = (BEAM_R * BEAM_R - u * u).sqrt();
        num += wgt * (-sigma_a(l) * inside(l, u)).exp();
        den += wgt;
    }
    num / den
}

/// The prism's rainbow on a white screen 0.5 m beyond it, seen by a camera beside the beam,
/// with the prism clear (`tint` false) or of tinting glass, 48 × 48 pixels at `spp` with seed
/// `seed`; spectral bins of 16 over the film's range.
fn rainbow(integrator: IntegratorKind, tint: bool, spp: u32, seed: u32) -> Image {
    let d = DVec2::new(BEAM_DEG.to_radians().cos(), BEAM_DEG.to_radians().sin());
    let m = (A + C) * 0.5;
    let beam = m - d * 0.3;
    // the screen faces the d line's exit ray, centred on it 0.5 m on
    let (_, e, out) = through(m, d, 587.56);
    let (s, eye) = (e + out * 0.5, e + out * 0.25);
    // the clear prism holds a medium too, of σa = 0, so that both renders take the same
    // random walk and read the same random numbers
    let samples: Vec<String> = SIGMA_A
        .iter()
        .map(|[l, v]| format!("[{l}, {}]", if tint { *v } else { 0.0 }))
        .collect();
    let media = format!(
        "[media.tint]\nsigma_a = {{ spectrum = {{ samples = [{}] }}, scale = \"1 1/m\" }}\n",
        samples.join(", ")
    );
    let mut scene = scene_from(&format!(
        r#"
[camera]
eye = [{ex}, {ey}, 0]
target = [{sx}, {sy}, 0]
up = [0, 0, 1]
fov = "12 deg"
[film]
width = 48
height = 48
spp = 64
[integrator]
max_depth = 8
{media}
[materials.bk7]
type = "dielectric"
ior = "N-BK7"
[materials.screen]
type = "diffuse"
reflectance = 0.8
[[shapes]]
type = "mesh"
material = "bk7"
interior = "tint"
{MESH}[[shapes]]
type = "rectangle"
material = "screen"
transform = [{{ scale = 0.1 }}, {{ look_at = {{ eye = [{sx}, {sy}, 0], target = [{tx}, {ty}, 0], up = [0, 0, 1] }} }}]
[[lights]]
type = "beam"
position = [{bx}, {by}, 0]
target = [{mx}, {my}, 0]
radius = "{r} mm"
spectrum = "cie-e"
power = "1 W"
"#,
        ex = eye.x,
        ey = eye.y,
        sx = s.x,
        sy = s.y,
        tx = s.x - out.x,
        ty = s.y - out.y,
        bx = beam.x,
        by = beam.y,
        mx = m.x,
        my = m.y,
        r = BEAM_R * 1e3,
    ));
    scene.integrator.kind = integrator;
    let (img, stats) = render_with(&scene, |o| {
        o.spectral_bins = 16;
        o.seed = seed;
        o.spp = spp;
    });
    assert_eq!(stats.nan_samples + stats.inf_samples, 0);
    img
}

/// Per spectral bin, the screen's radiance summed over the image with the tinting glass over
/// that with clear glass, and the bins' bounds (nm).
fn tint_ratios(kind: IntegratorKind, spp: u32, seed: u32) -> Vec<(f64, f64, f64)> {
    let (tinted, clear) = (
        rainbow(kind, true, spp, seed),
        rainbow(kind, false, spp, seed),
    );
    let b = tinted.bins.as_ref().expect("spectral bins");
    let sum = |img: &Image, i: usize| img.spectral[i].iter().map(|&v| v as f64).sum::<f64>();
    (0..b.count)
        .map(|i| {
            let (c, w) = (b.centre(i) as f64, b.width() as f64);
            (c - w / 2.0, c + w / 2.0, sum(&tinted, i) / sum(&clear, i))
        })
        .collect()
}

/// The beam's transmittance averaged over the wavelengths from `l0` to `l1` nm.
fn bin_transmittance(l0: f64, l1: f64) -> f64 {
    let n = 60;
    (0..n)
        .map(|k| beam_transmittance(l0 + (k as f64 + 0.5) * (l1 - l0) / n as f64))
        .sum::<f64>()
        / n as f64
}

/// A prism of absorbing glass casts a tinted rainbow: on the screen, each spectral bin's
/// radiance (summed over the image) with the tinting glass over that with clear glass is the
/// beam's Beer–Lambert transmittance exp(−σa(λ) ℓ(λ)) averaged over the bin, ℓ(λ) the path
/// inside the prism by Snell's law with N-BK7's Sellmeier formula (about 5 cm; σa from 4 to
/// 40 m⁻¹, so the transmittance ranges from 0.16 to 0.73 across the bins).
///
/// `light`: within 0.5 % in every bin, at one seed. The two renders trace the same particles
/// (the glass only absorbs, and the clear prism holds a medium of σa = 0), so the ratio has
/// no noise of the rainbow's own (measured: within 0.1 %).
///
/// `bdpt`: its light subpaths play Russian roulette from their second bounce on the
/// throughput, which the tint lowers, so the two renders' particles part there and the ratio
/// is noisy (1.6 % per bin at 64 spp). Over 8 seeds at 256 spp, each bin's mean ratio lies
/// within 4 standard errors of Beer–Lambert, and that standard error is below 0.5 %
/// (measured: about 0.3 %).
#[test]
fn a_prism_of_absorbing_glass_casts_a_tinted_rainbow() {
    let mut bad = Vec::new();
    for (l0, l1, got) in tint_ratios(IntegratorKind::Light, 64, 5) {
        let want = bin_transmittance(l0, l1);
        println!("light, {l0:.0}–{l1:.0} nm: tinted ÷ clear {got:.4}, Beer–Lambert {want:.4}");
        if (got / want - 1.0).abs() >= 0.005 {
            bad.push(format!(
                "light, {l0:.0}–{l1:.0} nm: tinted ÷ clear {got:.4}, Beer–Lambert {want:.4}"
            ));
        }
    }
    let seeds = 8;
    let runs: Vec<_> = (1..=seeds)
        .map(|k| tint_ratios(IntegratorKind::Bdpt, 256, k))
        .collect();
    for (i, &(l0, l1, _)) in runs[0].iter().enumerate() {
        let want = bin_transmittance(l0, l1);
        let r: Vec<f64> = runs.iter().map(|run| run[i].2 / want).collect();
        let n = r.len() as f64;
        let mean = r.iter().sum::<f64>() / n;
        let se = (r.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
        println!(
            "bdpt, {l0:.0}–{l1:.0} nm: tinted ÷ clear ÷ Beer–Lambert {mean:.4} (standard error {se:.4})"
        );
        if se >= 0.005 || (mean - 1.0).abs() >= 4.0 * se {
            bad.push(format!(
                "bdpt, {l0:.0}–{l1:.0} nm: tinted ÷ clear ÷ Beer–Lambert {mean:.4}, standard error {se:.4}"
            ));
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
