//! Bidirectional path tracing against closed forms, against itself strategy by strategy, and
//! against the other integrators on scenes they sample well. (The Mitsuba references are in
//! `reference_idiff.rs`; the prism's Fraunhofer lines in `prism.rs`.)

mod support;

use std::f64::consts::PI;

use spectrace::integrator::bdpt::Strategy;
use spectrace::loader::desc::IntegratorKind;
use support::render::{assert_strategies_sum_to_full, mean, render_with, scene_from};

const CIE_Y_INTEGRAL: f64 = 106.856895;
const K_M: f64 = 683.002;

fn furnace_scene(rho: f64) -> spectrace::scene::Scene {
    scene_from(&support::render::furnace_toml("bdpt", rho, 256))
}

/// The white furnace with the tolerance `path` has: a closed sphere of albedo ρ emitting Le
/// everywhere, L = Le/(1 − ρ) within 1 %. Over seeds 0–5 at 256 spp the image mean at ρ = 0.8
/// has σ ≈ 0.1 % (`spectrace render … --integrator bdpt --seed N`), so 1 % is ≥ 4σ.
#[test]
fn furnace() {
    for rho in [0.5, 0.8] {
        let (img, stats) = render_with(&furnace_scene(rho), |_| {});
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        let got = mean(img.band.iter().copied());
        let want = 1.0 / (1.0 - rho);
        assert!(
            (got / want - 1.0).abs() < 0.01,
            "ρ = {rho}: L = {got}, want {want}"
        );
    }
}

/// A 100 W point light 2 m above a ρ = 0.5 Lambertian plane, as `render_physics.rs` checks
/// `path`: L = ρ/π · I cos θ / r². Only s = 1 (light sampling) and t = 1 (light tracing) can
/// sample these paths, and MIS gives t = 1 up to a quarter of the weight under the light, where
/// its splats make single pixels noisy (a few % at 256 spp); so the test compares 8×8-pixel
/// blocks, each within 1 % of the closed form averaged over the block's pixel centres (over
/// seeds 0–5 at 1024 spp the blocks' σ is ≤ 0.05 %, so ≤ 0.1 % at 256).
#[test]
fn point_light_over_plane() {
    let s = scene_from(&support::render::point_over_plane_toml("bdpt"));
    let (img, stats) = render_with(&s, |_| {});
    assert_eq!(stats.nan_samples + stats.inf_samples, 0);
    for by in 0..4 {
        for bx in 0..4 {
            let (mut want_l, mut got_l, mut got_y) = (0.0, 0.0, 0.0);
            for py in by * 8..by * 8 + 8 {
                for px in bx * 8..bx * 8 + 8 {
                    let (r2, cos) = support::render::plane_point(&s, px, py);
                    want_l += 0.5 / PI * (100.0 / (4.0 * PI)) * cos / r2;
                    got_l += img.band[py * 32 + px] as f64;
                    got_y += img.xyz[py * 32 + px][1] as f64;
                }
            }
            let want_y = want_l * K_M * CIE_Y_INTEGRAL / 470.0;
            assert!(
                (got_l / want_l - 1.0).abs() < 0.01,
                "block ({bx},{by}): L = {got_l}, want {want_l}"
            );
            assert!(
                (got_y / want_y - 1.0).abs() < 0.01,
                "block ({bx},{by}): Y = {got_y}, want {want_y}"
            );
        }
    }
}

/// An emitter declared as 100 cd/m² reads 100 cd/m² in Y within 0.5 % (strategy s = 0, t = 2).
#[test]
fn luminance_calibration() {
    let s = scene_from(
        r#"
[camera]
eye = [0, 0, -1]
target = [0, 0, 0]
fov = "20 deg"
[film]
width = 16
height = 16
spp = 64
[integrator]
type = "bdpt"
max_depth = 1
[[shapes]]
type = "rectangle"
transform = [{ scale = 5 }, { rotate = { axis = [0, 1, 0], angle = "180 deg" } }]
emission = { spectrum = "cie-d65", luminance = "100 cd/m^2" }
"#,
    );
    let (img, _) = render_with(&s, |_| {});
    let y = mean(img.xyz.iter().map(|p| p[1]));
    assert!((y / 100.0 - 1.0).abs() < 0.005, "Y = {y} cd/m²");
}

/// A small room: a grey box lit by a ceiling light, with a glossy floor and a diffuse wall, at
/// `max_depth` bounces.
fn room(max_depth: u32, spp: u32) -> spectrace::scene::Scene {
    room_with(ROOM_CAMERA, max_depth, spp)
}

const ROOM_CAMERA: &str = r#"eye = [0, 1.2, 0.95]
target = [0, 0.6, -1]
fov = "75 deg""#;

/// [`room`] seen by the camera whose TOML keys are `camera`.
fn room_with(camera: &str, max_depth: u32, spp: u32) -> spectrace::scene::Scene {
    scene_from(&format!(
        r#"
[camera]
{camera}
[film]
width = 24
height = 24
spp = {spp}
filter = "box"
[integrator]
type = "bdpt"
max_depth = {max_depth}
[materials.grey]
type = "diffuse"
reflectance = 0.6
[materials.glossy]
type = "conductor"
metal = "Au"
roughness = 0.3
[[shapes]]
type = "box"
material = "grey"
two_sided = true
transform = [{{ scale = [2, 2, 2] }}, {{ translate = [0, 1, 0] }}]
[[shapes]]
type = "rectangle"
material = "glossy"
transform = [{{ scale = 0.6 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}, {{ translate = [0, 0.01, 0] }}]
[[shapes]]
type = "rectangle"
transform = [{{ scale = 0.5 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "90 deg" }} }}, {{ translate = [0, 1.99, 0] }}]
emission = {{ radiance = "10 W/m^2/sr" }}
"#
    ))
}

/// The MIS-weighted images of every strategy (s, t) with s + t − 2 ≤ max_depth sum to the full
/// render: the same random numbers feed each, so they agree to rounding (1e-4 relative).
#[test]
fn weighted_strategies_sum_to_the_full_render() {
    let max_depth = 3;
    let s = room(max_depth, 4);
    assert_strategies_sum_to_full(&s, max_depth);
}

/// Each strategy alone, unweighted, is an unbiased estimator of the paths it can sample:
/// direct light on the room's diffuse walls (one bounce) rendered by the camera hitting the
/// light (s = 0, t = 3), by light sampling (s = 1, t = 2) and by light tracing (s = 2, t = 1)
/// converges to the same image, and to `path`. Image means agree within 2 %: over seeds 0–3 at
/// 1024 spp their σ is 0.76 % for s = 0, 0.03 % for s = 1 and 0.16 % for s = 2
/// (`spectrace render room.toml --bdpt-strategy S,T --bdpt-unweighted --seed N`), so s = 0 runs
/// 8192 spp (σ ≈ 0.27 %) and 2 % is ≥ 7σ for each.
#[test]
fn unweighted_strategies_agree_on_direct_light() {
    let s = room(1, 1024);
    let means: Vec<((u32, u32), f64)> = [(0, 3, 8192), (1, 2, 1024), (2, 1, 1024)]
        .into_iter()
        .map(|(sv, t, spp)| {
            let (img, stats) = render_with(&s, |o| {
                o.spp = spp;
                o.strategy = Some(Strategy {
                    s: sv,
                    t,
                    weighted: false,
                });
            });
            assert_eq!(stats.nan_samples + stats.inf_samples, 0);
            ((sv, t), mean(img.band.iter().copied()))
        })
        .collect();
    let (path, _) = render_with(&s, |o| o.integrator = IntegratorKind::Path);
    // `path` at max_depth 1 also sees the light directly (s = 0, t = 2), which these omit
    let (direct, _) = render_with(&s, |o| {
        o.strategy = Some(Strategy {
            s: 0,
            t: 2,
            weighted: false,
        });
    });
    let want = mean(path.band.iter().copied()) - mean(direct.band.iter().copied());
    assert!(want > 0.0);
    for ((sv, t), m) in &means {
        assert!(
            (m / want - 1.0).abs() < 0.02,
            "strategy ({sv}, {t}): image mean {m}, path's one-bounce light {want}"
        );
    }
}

/// The same seed gives the same image with 1 thread and with 2, splats included.
#[test]
fn deterministic_across_thread_counts() {
    let s = room(4, 4);
    let (a, _) = render_with(&s, |o| o.threads = Some(1));
    let (b, _) = render_with(&s, |o| o.threads = Some(2));
    assert_eq!(a.xyz, b.xyz);
    assert_eq!(a.band, b.band);
}

/// `bdpt` and `path` agree on the room with indirect light and a glossy floor: image mean within
/// 1 %, each block of 6×6 pixels within 5 % (over seeds 0–2 the means differed by ≤ 0.15 % and
/// the blocks by ≤ 1.7 %).
#[test]
fn agrees_with_path_on_a_room() {
    let s = room(6, 256);
    let (b, stats) = render_with(&s, |_| {});
    assert_eq!(stats.nan_samples + stats.inf_samples, 0);
    let (p, _) = render_with(&s, |o| {
        o.integrator = IntegratorKind::Path;
        o.spp = 1024;
    });
    let (mb, mp) = (mean(b.band.iter().copied()), mean(p.band.iter().copied()));
    assert!((mb / mp - 1.0).abs() < 0.01, "bdpt {mb}, path {mp}");
    let block = |img: &spectrace::film::Image, bx: usize, by: usize| {
        let mut s = 0.0;
        for y in by * 6..by * 6 + 6 {
            for x in bx * 6..bx * 6 + 6 {
                s += img.band[y * 24 + x] as f64;
            }
        }
        s
    };
    for by in 0..4 {
        for bx in 0..4 {
            let (vb, vp) = (block(&b, bx, by), block(&p, bx, by));
            assert!(
                (vb / vp - 1.0).abs() < 0.05,
                "block ({bx}, {by}): bdpt {vb}, path {vp}"
            );
        }
    }
}

/// A thin-lens camera sees the same defocused image through `path`, `bdpt` (whose t = 1
/// strategies sample the lens from each light vertex) and light tracing (likewise): a spot light
/// draws a sharp disk of 9 cm radius on a wall 2 m away, and the camera (f/1.4 at the 67 mm
/// focal length of a 30° view on a 36 mm sensor, focused at 0.5 m) blurs it by a circle of
/// 7 cm radius there, about 2 pixels. Every 2×2-pixel block holding more than 1 % of the light
/// agrees with `path` within 10 %, and the image means within 1 % (at 256 spp against `path`
/// at 1024, seeds 1–3, the blocks differed by at most 4.6 %; these counts halve that). Mapping
/// lens connections to raster positions as a pinhole does sharpens the disk: its edge blocks
/// then differ by 30–90 % (measured).
#[test]
fn thin_lens_agrees_across_integrators() {
    let s = scene_from(
        r#"
[camera]
type = "thinlens"
eye = [0, 0, 0]
target = [0, 0, 1]
fov = "30 deg"
f_number = 1.4
focus_distance = "0.5 m"
[film]
width = 32
height = 32
spp = 256
filter = "box"
[integrator]
type = "path"
max_depth = 1
[materials.wall]
type = "diffuse"
reflectance = 0.8
[[shapes]]
type = "rectangle"
material = "wall"
transform = [{ rotate = { axis = [0, 1, 0], angle = "180 deg" } }, { translate = [0, 0, 2] }]
[[lights]]
type = "spot"
position = [0.3, 0, 1]
target = [0, 0, 2]
cone_angle = "5 deg"
falloff_start = "4.9 deg"
spectrum = "cie-e"
intensity = "10 W/sr"
"#,
    );
    let (p, _) = render_with(&s, |o| o.spp = 4096);
    let block = |img: &spectrace::film::Image, bx: usize, by: usize| {
        let mut s = 0.0;
        for y in by * 2..by * 2 + 2 {
            for x in bx * 2..bx * 2 + 2 {
                s += img.band[y * 32 + x] as f64;
            }
        }
        s
    };
    let total: f64 = p.band.iter().map(|&v| v as f64).sum();
    for (kind, spp) in [(IntegratorKind::Bdpt, 1024), (IntegratorKind::Light, 1024)] {
        let (img, stats) = render_with(&s, |o| {
            o.integrator = kind;
            o.spp = spp;
        });
        assert_eq!(stats.nan_samples + stats.inf_samples, 0);
        let (mi, mp) = (mean(img.band.iter().copied()), mean(p.band.iter().copied()));
        assert!((mi / mp - 1.0).abs() < 0.01, "{kind:?} {mi}, path {mp}");
        for by in 0..16 {
            for bx in 0..16 {
                let (vi, vp) = (block(&img, bx, by), block(&p, bx, by));
                if vp > 0.01 * total {
                    assert!(
                        (vi / vp - 1.0).abs() < 0.1,
                        "{kind:?} block ({bx}, {by}): {vi}, path {vp}"
                    );
                }
            }
        }
    }
}

/// Ctrl-C (the cancel flag) keeps the passes every pixel completed: the image then equals a full
/// render at that sample count (the splats' weights assume every pixel took each pass's samples).
/// Spectral bins carry the same estimate as the band radiance: Σ bins × width = L per pixel.
#[test]
fn cancelled_render_keeps_whole_passes_and_spectral_bins_add_up() {
    use std::sync::atomic::{AtomicBool, Ordering};
    let s = room(4, 64);
    let mut o = spectrace::render::RenderOptions::from_scene(&s);
    o.spectral_bins = 47;
    let cancel = AtomicBool::new(false);
    let (film, stats) = spectrace::render::render(&s, &o, &cancel, &|done, total| {
        if done > total / 4 {
            cancel.store(true, Ordering::Relaxed);
        }
    })
    .expect("renders");
    assert!(
        stats.partial && stats.spp_done > 0 && stats.spp_done < 64,
        "{stats:?}"
    );
    for y in 0..24 {
        for x in 0..24 {
            assert_eq!(film.samples_at(x, y), stats.spp_done as u64);
        }
    }
    let img = film.image();
    let (full, _) = render_with(&s, |o| o.spp = stats.spp_done);
    assert_eq!(img.xyz, full.xyz);
    let width = 470.0 / 47.0;
    for (i, l) in img.band.iter().enumerate() {
        let sum: f32 = img.spectral.iter().map(|b| b[i] * width).sum();
        assert!(
            (sum - l).abs() <= 1e-4 * l.abs() + 1e-7,
            "pixel {i}: Σ bins {sum}, L {l}"
        );
    }
}
