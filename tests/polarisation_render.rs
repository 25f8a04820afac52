//! Polarised rendering (issue 28) against closed forms: Malus's law through two polarisers,
//! the Fresnel equations' s/p split of light reflected by glass (Brewster's angle included), a
//! quarter-wave plate turning linear light circular, and a scene without polarising materials,
//! whose polarised render must be its unpolarised render with S1 = S2 = S3 = 0.

mod support;

use support::render::{mean, render_with, scene_from};

/// A uniform environment of 1 W·m⁻²·sr⁻¹ (flat spectrum) seen by an orthographic camera along
/// +z through `shapes` (TOML), 4 × 4 pixels.
fn through(materials: &str, shapes: &str, spp: u32) -> spectrace::film::Image {
    let text = format!(
        r#"
[camera]
type = "orthographic"
eye = [0, 0, 0]
target = [0, 0, 1]
view_width = 0.5
[film]
width = 4
height = 4
spp = {spp}
[integrator]
max_depth = 8
{materials}
{shapes}
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#
    );
    let scene = scene_from(&text);
    assert!(
        scene.integrator.polarised,
        "a scene with polarisers renders polarised"
    );
    render_with(&scene, |_| {}).0
}

/// Band radiance (W·m⁻²·sr⁻¹) and the ratios S1/S0, S2/S0, S3/S0 of Y, image means.
fn stokes_ratios(img: &spectrace::film::Image) -> (f64, [f64; 3]) {
    let y = mean(img.xyz.iter().map(|p| p[1]));
    let s = |k: usize| mean(img.stokes.iter().map(|p| p[k][1])) / y;
    (mean(img.band.iter().copied()), [s(0), s(1), s(2)])
}

/// Unpolarised light through polarisers at 0 and θ: L·½cos²θ (Malus), the light leaving
/// polarised along the last one.
#[test]
fn malus_law_through_two_polarisers() {
    for deg in [0.0f64, 30.0, 60.0, 90.0] {
        let img = through(
            &format!(
                "[materials.p0]\ntype = \"polariser\"\n[materials.p1]\ntype = \"polariser\"\nangle = \"{deg} deg\""
            ),
            r#"
[[shapes]]
type = "rectangle"
material = "p0"
transform = [{ translate = [0, 0, 1] }]
[[shapes]]
type = "rectangle"
material = "p1"
transform = [{ translate = [0, 0, 2] }]
"#,
            4096,
        );
        let (l, s) = stokes_ratios(&img);
        let want = 0.5 * deg.to_radians().cos().powi(2);

        println!("θ = {deg}°: L {l:.6} (Malus {want:.6}), S1/S0 {:.6}", s[0]);
        assert!(
            (l - want).abs() <= 1e-3 * 0.5 + 1e-7,
            "θ = {deg}°: {l} vs {want}"
        );
        if deg < 90.0 {
            // polarised along the camera-side polariser, the same line for every θ
            assert!(
                (s[0].hypot(s[1]) - 1.0).abs() < 1e-4,
                "fully polarised: {s:?}"
            );
            assert!(s[2].abs() < 1e-5, "no circular part: {s:?}");
        }
    }
}

/// A polariser at 0° then a quarter-wave retarder at 45°: circular light, |S3| = S0, at the
/// polariser's ½L.
#[test]
fn quarter_wave_plate_turns_linear_light_circular() {
    let img = through(
        r#"
[materials.p]
type = "polariser"
[materials.q]
type = "retarder"
angle = "45 deg"
retardance = "90 deg"
"#,
        r#"
[[shapes]]
type = "rectangle"
material = "q"
transform = [{ translate = [0, 0, 1] }]
[[shapes]]
type = "rectangle"
material = "p"
transform = [{ translate = [0, 0, 2] }]
"#,
        1024,
    );
    let (l, s) = stokes_ratios(&img);
    println!("L {l:.6}, S/S0 {s:?}");
    assert!((l - 0.5).abs() < 1e-3 * 0.5);
    assert!((s[2].abs() - 1.0).abs() < 1e-4, "{s:?}");
    assert!(s[0].abs() < 1e-4 && s[1].abs() < 1e-4, "{s:?}");
}

/// Reflectances of s and p light at a dielectric of index `n` (from vacuum) at incidence
/// angle `theta`: Fresnel's equations.
fn fresnel_sp(n: f64, theta: f64) -> (f64, f64) {
    let ci = theta.cos();
    let ct = (1.0 - (theta.sin() / n).powi(2)).sqrt();
    let rs = (ci - n * ct) / (ci + n * ct);
    let rp = (n * ci - ct) / (n * ci + ct);
    (rs * rs, rp * rp)
}

/// Unpolarised light reflected by glass (n = 1.5) at incidence θ: S0 = ½(R_s + R_p)·L (within
/// 4 standard errors of the reflection's random choice) and S1/S0 = (R_s − R_p)/(R_s + R_p)
/// (to 10⁻³) with the s direction horizontal in the image; at Brewster's angle atan(n) the
/// reflection is purely s-polarised.
#[test]
fn glass_reflects_s_light_and_only_s_light_at_brewster() {
    let n = 1.5f64;
    for theta in [30.0f64.to_radians(), n.atan(), 70.0f64.to_radians()] {
        let (sin, cos) = theta.sin_cos();
        let text = format!(
            r#"
[camera]
type = "orthographic"
eye = [{ex}, 0, {ez}]
target = [0, 0, 0]
up = [0, 0, 1]
view_width = 0.2
[film]
width = 4
height = 4
spp = 4096
[integrator]
max_depth = 8
polarised = true
[materials.glass]
type = "dielectric"
ior = {n}
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "rectangle"
material = "glass"
transform = [{{ scale = 100 }}]
[[shapes]]
type = "rectangle"
material = "black"
transform = [{{ scale = 100 }}, {{ translate = [0, 0, -1] }}]
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#,
            ex = -5.0 * sin,
            ez = 5.0 * cos,
        );
        let scene = scene_from(&text);
        let img = render_with(&scene, |_| {}).0;
        let (l, s) = stokes_ratios(&img);
        let (rs, rp) = fresnel_sp(n, theta);
        let want = 0.5 * (rs + rp);
        let dolp = (rs - rp) / (rs + rp);
        println!(
            "θ {:.3}°: S0 {l:.6} (Fresnel {want:.6}), S1/S0 {:.6} (Fresnel {dolp:.6})",
            theta.to_degrees(),
            s[0]
        );
        // the reflection is chosen with probability F = want per sample: binomial noise
        let samples = (img.width * img.height) as f64 * 4096.0;
        let se = want * ((1.0 - want) / (want * samples)).sqrt();
        assert!((l - want).abs() < 4.0 * se, "S0 {l} vs {want} ± {se}");
        assert!((s[0] - dolp).abs() < 1e-3, "S1/S0 {} vs {dolp}", s[0]);
        assert!(s[1].abs() < 1e-4 && s[2].abs() < 1e-4, "{s:?}");
    }
}

/// The Cornell box (diffuse only) rendered polarised: S0 is the unpolarised render (the same
/// samples and weights; every bounce depolarises) and S1 = S2 = S3 = 0.
#[test]
fn a_scene_without_polarising_materials_renders_the_same_s0() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.toml"),
    )
    .expect("cornell.toml");
    let unpolarised = scene_from(&text);
    let polarised = scene_from(&text.replace("max_depth = 16", "max_depth = 16\npolarised = true"));
    assert!(polarised.integrator.polarised && !unpolarised.integrator.polarised);
    let small = |o: &mut spectrace::render::RenderOptions| {
        o.spp = 8;
        o.seed = 5;
    };
    let (a, _) = render_with(&unpolarised, small);
    let (b, _) = render_with(&polarised, small);
    assert!(a.stokes.is_empty());
    let mut worst = 0.0f64;
    for (i, (p, q)) in a.xyz.iter().zip(&b.xyz).enumerate() {
        for c in 0..3 {
            let d = (p[c] - q[c]).abs() as f64 / (p[c].abs() as f64).max(1e-3);
            worst = worst.max(d);
        }
        assert!(b.stokes[i].iter().flatten().all(|&v| v == 0.0), "pixel {i}");
    }
    println!("worst relative difference {worst:.2e}");
    assert!(worst < 1e-4, "{worst}");
}

/// Per spectral bin: N-BK7 (dispersive) reflecting unpolarised light at Brewster's angle for
/// 587.6 nm. In every 10 nm bin S1/S0 is Fresnel's (R_s − R_p)/(R_s + R_p) at the bin's centre
/// with n from SCHOTT's Sellmeier formula (evaluated here), to 2·10⁻³: 1 at 587.6 nm and less
/// away from it, where R_p no longer vanishes.
#[test]
fn brewster_reflection_per_spectral_bin_follows_the_glass_dispersion() {
    let theta = support::prism::n_bk7(587.6).atan();
    let (sin, cos) = theta.sin_cos();
    let text = format!(
        r#"
[camera]
type = "orthographic"
eye = [{ex}, 0, {ez}]
target = [0, 0, 0]
up = [0, 0, 1]
view_width = 0.2
[film]
width = 4
height = 4
spp = 2048
spectral_bins = 47
[integrator]
max_depth = 8
polarised = true
[materials.glass]
type = "dielectric"
ior = "N-BK7"
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "rectangle"
material = "glass"
transform = [{{ scale = 100 }}]
[[shapes]]
type = "rectangle"
material = "black"
transform = [{{ scale = 100 }}, {{ translate = [0, 0, -1] }}]
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#,
        ex = -5.0 * sin,
        ez = 5.0 * cos,
    );
    let scene = scene_from(&text);
    let img = render_with(&scene, |o| o.spectral_bins = 47).0;
    let bins = img.bins.clone().expect("bins");
    assert_eq!(img.stokes_spectral.len(), 3 * bins.count);
    let mut checked = 0;
    for b in 0..bins.count {
        let s0 = mean(img.spectral[b].iter().copied());
        let s1 = mean(img.stokes_spectral[b].iter().copied());
        let s2 = mean(img.stokes_spectral[bins.count + b].iter().copied());
        if s0 <= 0.0 {
            continue;
        }
        let (rs, rp) = fresnel_sp(support::prism::n_bk7(bins.centre(b) as f64), theta);
        let want = (rs - rp) / (rs + rp);
        assert!(
            (s1 / s0 - want).abs() < 2e-3 && (s2 / s0).abs() < 1e-4,
            "bin at {} nm: S1/S0 {} vs {want}, S2/S0 {}",
            bins.centre(b),
            s1 / s0,
            s2 / s0
        );
        checked += 1;
    }
    assert!(checked >= 40, "{checked} bins");
}

/// The library API's typed Stokes accessor: behind one polariser unpolarised light of
/// L = 1 W·m⁻²·sr⁻¹ leaves with half its luminance, fully linearly polarised (DoLP 1); an
/// unpolarised render has no Stokes vector.
#[test]
fn the_api_reads_stokes_vectors() {
    let text = r#"
[camera]
type = "orthographic"
eye = [0, 0, 0]
target = [0, 0, 1]
view_width = 0.5
[film]
width = 2
height = 2
spp = 256
[materials.p]
type = "polariser"
[[shapes]]
type = "rectangle"
material = "p"
transform = [{ translate = [0, 0, 1] }]
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#;
    let opts = spectrace::Options::default();
    let scene = spectrace::Scene::from_toml(text).expect("the scene");
    let img = spectrace::render(&scene, &opts).expect("a render");
    let (s, dolp) = img.stokes(1, 0).expect("a polarised image");
    assert!((dolp - 1.0).abs() < 1e-4, "DoLP {dolp}");
    assert!((s[0].value - img.luminance(1, 0).value).abs() < 1e-9);
    let clear =
        spectrace::Scene::from_toml(&text.replace("type = \"polariser\"", "type = \"null\""))
            .expect("the scene");
    let bright = spectrace::render(&clear, &opts).expect("a render");
    assert!(bright.stokes(1, 0).is_none());
    let ratio = s[0].value / bright.luminance(1, 0).value;
    assert!((ratio - 0.5).abs() < 2e-3, "{ratio}");
}

/// A Fresnel rhomb of N-BK7, rendered: light from a lamp through a polariser enters an end
/// face at normal incidence, is totally reflected twice at the design angle θ (one reflection
/// retards by 45° at 587.6 nm: θ ≈ 55.2°) in the plane z = 0 and leaves the other end face
/// toward an orthographic camera, whose Stokes basis lies in that plane (the p direction). A
/// retarder with s and p axes keeps S1 and turns (S2, S3) by its retardance Δ(λ) = 2δ(n(λ), θ)
/// (Born and Wolf's δ, SCHOTT's Sellmeier n, evaluated here). The light entering is measured by
/// the same camera looking straight at the polariser (the polariser's own frame is not what
/// is tested); in every 10 nm bin, S1 out = S1 in and |S3| out = |S2 in·sin Δ|, |S2| out =
/// |S2 in·cos Δ|, within 10⁻³ of S0: at 45° to s and p, circular at the design wavelength.
/// Paths are cut after the five scattering events of the direct way through (`max_depth`), so
/// that the end faces' double partial reflections (relative weight R² ≈ 2·10⁻³, four more total
/// reflections, another state) do not blur the comparison with their sampling noise.
#[test]
fn a_rendered_fresnel_rhomb_turns_linear_light_circular() {
    let nd = support::prism::n_bk7(587.6);
    let theta_max = ((2.0 / (1.0 + nd * nd)).sqrt())
        .asin()
        .max((1.0 / nd).asin());
    let (mut lo, mut hi) = (theta_max, 89f64.to_radians());
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if support::prism::tir_retardance(nd, mid) > std::f64::consts::FRAC_PI_4 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta = 0.5 * (lo + hi);
    let (s, c) = theta.sin_cos();
    // the parallelepiped: long faces y = ±h, end faces with normal n_e = (sin θ, −cos θ, 0),
    // long enough that the beam from the entry face's centre leaves the exit face's centre
    let h = 0.1;
    let a = h * (1.0 / c + 3.0 * s * s / c - c) / (2.0 * s);
    let cot = c / s;
    let ne = [s, -c, 0.0];
    let at = |p: [f64; 3], t: f64| [p[0] + ne[0] * t, p[1] + ne[1] * t, p[2]];
    let (entry, exit) = ([-a, 0.0, 0.0], [a, 0.0, 0.0]);
    let eye = at(exit, 1.0);
    let pol = at(entry, -0.3);
    let lamp = at(entry, -0.6);
    let v = |p: [f64; 3]| format!("[{}, {}, {}]", p[0], p[1], p[2]);
    let text = format!(
        r#"
[camera]
type = "orthographic"
eye = {eye}
target = {exit}
up = [0, 0, 1]
view_width = 0.02
[film]
width = 4
height = 4
spp = 1024
spectral_bins = 47
[integrator]
max_depth = 5
[materials.glass]
type = "dielectric"
ior = "N-BK7"
[materials.p]
type = "polariser"
angle = "45 deg"
[[shapes]]
type = "box"
material = "glass"
transform = [{{ matrix = [{a}, {hc}, 0, 0, 0, {h}, 0, 0, 0, 0, 0.1, 0, 0, 0, 0, 1] }}]
[[shapes]]
type = "rectangle"
material = "p"
transform = [{{ scale = 0.2 }}, {{ look_at = {{ eye = {pol}, target = {pol_to}, up = [0, 0, 1] }} }}]
[[shapes]]
type = "rectangle"
transform = [{{ scale = 0.3 }}, {{ look_at = {{ eye = {lamp}, target = {lamp_to}, up = [0, 0, 1] }} }}]
emission = {{ radiance = "1 W/m^2/sr" }}
"#,
        eye = v(eye),
        exit = v(exit),
        pol = v(pol),
        lamp = v(lamp),
        // both face along the beam: the polariser at normal incidence
        pol_to = v(at(pol, 1.0)),
        lamp_to = v(at(lamp, 1.0)),
        hc = h * cot,
    );
    let scene = scene_from(&text);
    assert!(scene.integrator.polarised);
    let per_bin = |scene: &spectrace::scene::Scene| {
        let img = render_with(scene, |o| o.spectral_bins = 47).0;
        let nb = img.bins.as_ref().expect("bins").count;
        let m = |p: &Vec<f32>| mean(p.iter().copied());
        (0..nb)
            .map(|b| {
                let s0 = m(&img.spectral[b]);
                let r = |k: usize| m(&img.stokes_spectral[k * nb + b]) / s0;
                (
                    img.bins.as_ref().unwrap().centre(b) as f64,
                    s0,
                    [r(0), r(1), r(2)],
                )
            })
            .collect::<Vec<_>>()
    };
    let out = per_bin(&scene);
    // the light entering: the same camera, moved between the polariser and the rhomb, looking
    // straight at the polariser
    let cam = at(pol, 0.1);
    let input_text = text
        .replacen(
            &format!("eye = {}", v(eye)),
            &format!("eye = {}", v(cam)),
            1,
        )
        .replacen(
            &format!("target = {}", v(exit)),
            &format!("target = {}", v(pol)),
            1,
        );
    let input = per_bin(&scene_from(&input_text));
    let mut checked = 0;
    for ((l, s0, so), (_, i0, si)) in out.iter().zip(&input) {
        if *s0 <= 0.0 || *i0 <= 0.0 {
            continue;
        }
        let d = 2.0 * support::prism::tir_retardance(support::prism::n_bk7(*l), theta);
        let (want2, want3) = ((si[1] * d.cos()).abs(), (si[1] * d.sin()).abs());
        assert!(
            (so[0] - si[0]).abs() < 1e-3
                && (so[1].abs() - want2).abs() < 1e-3
                && (so[2].abs() - want3).abs() < 1e-3,
            "{l} nm: in {si:?}, out {so:?}, want S1 {}, |S2| {want2}, |S3| {want3}, S0 out/in {}",
            si[0],
            s0 / i0
        );
        checked += 1;
    }
    assert!(checked >= 40, "{checked} bins");
}
