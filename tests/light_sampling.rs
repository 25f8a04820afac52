//! Next-event sampling of shapes by solid angle ([`Shape::sample_solid_angle`]): χ² of the
//! sampled directions against the density, the density integrating to 1 over the directions
//! that reach the shape, and every sample being the point a ray from the shading point toward
//! it hits first.
//!
//! Truth: the support and the density come from the ray–shape intersection (a direction has
//! density only if a ray along it hits the shape), and the χ² test integrates the density
//! numerically over each cell; the sampler's own arithmetic is not used to build expectations.

#[path = "support/chi2.rs"]
mod chi2;
mod support;

use chi2::{Grid, chi2_test, sidak};
use glam::{Vec2, Vec3};
use spectrace::geometry::{Cylinder, Frame, Ray, Shape, Sphere};
use support::Rng;

const SAMPLES: usize = 400_000;

/// Distance along `d` from `p` to the first hit of `shape`, if any.
fn first_hit(shape: &Shape, p: Vec3, d: Vec3) -> Option<f32> {
    let n = shape.primitive_count();
    (0..n)
        .filter_map(|i| shape.intersect_primitive(i, &Ray::new(p, d)))
        .map(|(t, _)| t)
        .min_by(f32::total_cmp)
}

/// The density, sr⁻¹, of direction `d` from `p`: the shape's solid-angle density at the
/// point the ray hits first, and 0 where the ray misses (for a one-sided emitter, also where
/// the point hit faces away from `p`: nothing reaches `p` from there).
fn density(shape: &Shape, p: Vec3, d: Vec3, one_sided: bool) -> f64 {
    let ray = Ray::new(p, d);
    let hit = (0..shape.primitive_count())
        .filter_map(|i| shape.intersect_primitive(i, &ray).map(|h| (i, h)))
        .min_by(|a, b| a.1.0.total_cmp(&b.1.0));
    let Some((prim, (t, h))) = hit else {
        return 0.0;
    };
    let it = shape.interaction(0, prim, &ray, t, &h);
    if one_sided && it.n_geom.dot(d) >= 0.0 {
        return 0.0;
    }
    shape.pdf_solid_angle(p, d, it.p, it.n_geom, one_sided) as f64
}

/// Cases: (name, shape, shading point, one-sided). Spheres seen from far (a narrow cone), from
/// near (a wide one), from just outside the surface (a cone of almost a hemisphere), from a
/// point computed on the surface (by area: it may be the inside of a closed emitter) and from
/// inside (by area). Open cylinders (one-sided: the arc of the wall facing the point) seen from
/// beside the wall, from near it, and from beyond an open end, where the wall's far side shows
/// its inside through the opening (which faces away, so has no density); two-sided, by area.
fn cases() -> Vec<(&'static str, Shape, Vec3, bool)> {
    let c = Vec3::new(0.3, -0.2, 1.1);
    let s = |r: f32| Shape::Sphere(Sphere::new(c, r).unwrap());
    let dir = Vec3::new(0.48, 0.6, -0.64);
    let axis = Vec3::new(0.0, 0.6, 0.8);
    let tube = || Shape::Cylinder(Cylinder::new(c, c + axis * 1.5, 0.2, false).unwrap());
    let across = Vec3::new(1.0, 0.0, 0.0); // ⟂ axis
    vec![
        ("far, sin θmax = 0.2", s(0.5), c + dir * 2.5, true),
        ("near, sin θmax = 0.8", s(0.5), c + dir * 0.625, true),
        ("at 1.00005 r", s(0.5), c + dir * 0.500025, true),
        (
            "on the surface (area sampling)",
            s(0.5),
            c + dir * 0.5,
            false,
        ),
        (
            "inside at 0.5 r (area sampling)",
            s(0.5),
            c + dir * 0.25,
            false,
        ),
        (
            "cylinder from beside, ρ = 3 r",
            tube(),
            c + axis * 0.7 + across * 0.6,
            true,
        ),
        (
            "cylinder from near, ρ = 1.1 r",
            tube(),
            c + axis * 0.4 + across * 0.22,
            true,
        ),
        (
            "cylinder from beyond its end",
            tube(),
            c + axis * 2.0 + across * 0.5,
            true,
        ),
        (
            "two-sided cylinder, by area",
            tube(),
            c + axis * 0.7 + across * 0.6,
            false,
        ),
    ]
}

#[test]
fn directions_match_their_density_and_it_integrates_to_one() {
    // spheres: a cylinder's density grows as 1/cos θ_light toward its silhouette, which the
    // cells' numerical integration cannot follow; its samples are checked point by point in
    // the next test and its images against Mitsuba's (`tests/reference/cylinders`)
    let cases: Vec<_> = cases()
        .into_iter()
        .filter(|c| matches!(c.1, Shape::Sphere(_)))
        .collect();
    let level = sidak(0.01, cases.len());
    for (k, (name, shape, p, one_sided)) in cases.iter().enumerate() {
        // the grid's pole toward the centre, so the cone's cells are in the first cos θ bins
        let (lo, hi) = shape.primitive_aabb(0);
        let frame = Frame::from_normal((0.5 * (lo + hi) - *p).normalize());
        let mut rng = Rng::new(0xC0DE_0000 + k as u64);
        let inside = name.contains("area");
        let grid = Grid {
            n_cos: if inside { 20 } else { 200 },
            n_phi: 40,
            both_hemispheres: true,
        };
        let r = chi2_test(
            grid,
            SAMPLES,
            || {
                let u = Vec2::new(rng.uniform(), rng.uniform());
                let x = shape.sample_solid_angle(*p, u, *one_sided)?;
                Some(frame.to_local((x.s.p - *p).normalize()))
            },
            |local| density(shape, *p, frame.to_world(local), *one_sided),
        );
        assert!(
            r.p_value > level && r.in_empty_cells == 0,
            "{name}: χ² {:.1} on {} dof, p = {:.2e} (level {level:.1e}), {} samples where the \
             density is 0",
            r.chi2,
            r.dof,
            r.p_value,
            r.in_empty_cells
        );
        assert!(
            (r.integral - 1.0).abs() < 2e-3,
            "{name}: ∫ pdf dω = {}",
            r.integral
        );
        assert_eq!(r.rejected, 0, "{name}: rejected samples");
    }
}

#[test]
fn samples_are_the_first_hit_toward_them_and_report_their_density() {
    for (name, shape, p, one_sided) in cases() {
        let mut rng = Rng::new(7);
        let inside = name.contains("area") || !one_sided;
        for _ in 0..20_000 {
            let u = Vec2::new(rng.uniform(), rng.uniform());
            let Some(x) = shape.sample_solid_angle(p, u, one_sided) else {
                continue;
            };
            let (s, pdf) = (x.s, x.pdf);
            assert!(
                (x.wi - (s.p - p).normalize()).length() < 1e-5
                    && (x.distance - (s.p - p).length()).abs() <= 1e-6 * x.distance,
                "{name}: the direction and distance are the point's"
            );
            let r = (s.p - p).length();
            let d = (s.p - p) / r;
            assert!(pdf > 0.0 && pdf.is_finite(), "{name}: pdf {pdf}");
            let pdf_again = shape.pdf_solid_angle(p, d, s.p, s.n, one_sided);
            assert!(
                (pdf_again - pdf).abs() <= 1e-4 * pdf,
                "{name}: sampled pdf {pdf}, pdf_solid_angle {pdf_again}"
            );
            if !inside {
                // outside, the point must be on the side facing p: the first hit along d
                let cos_l = s.n.dot(-d).abs().max(1e-3);
                let Some(t) = first_hit(&shape, p, d) else {
                    // a ray that grazes the silhouette may miss by rounding
                    assert!(
                        cos_l < 2e-3,
                        "{name}: the ray toward a sample at {:?} misses",
                        s.p
                    );
                    continue;
                };
                // within the rounding of the points' coordinates (~10⁻⁷ m here), which moves
                // the hit along a grazing ray by that over |cos θ_light|
                assert!(
                    (t - r).abs() <= 1e-4 * r + 4.0 * s.p_error.length() / cos_l,
                    "{name}: the sample is at {r} m, the first hit toward it at {t} m"
                );
            }
        }
    }
}

/// A sphere lamp (radius R = 0.5 m, band radiance L = 1 W·m⁻²·sr⁻¹, black) 2 m above a ρ = 0.5
/// Lambertian plane, direct light only: a sphere wholly above a point's horizon gives it the
/// irradiance of a point source at its centre, E = π·L·(R/d)²·cos β (d the distance to the
/// centre, cos β = h/d), so the plane's radiance is ρ·L·R²·h/d³. Checked for the integrators
/// whose estimators use the sphere's solid-angle density (path and direct with MIS, bdpt in its
/// MIS weights, whitted without); 1 % as the point-light test in `render_physics.rs` (with the
/// cone sampled, the path estimate's noise is only the cosine's spread over the cone).
#[test]
fn sphere_lamp_over_plane_matches_the_closed_form() {
    for integrator in ["path", "direct", "bdpt", "whitted"] {
        let text = support::render::point_over_plane_toml(integrator);
        let light = &text[text.find("[[lights]]").expect("a light")..];
        let text = text.replace(
            light,
            r#"[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "sphere"
radius = 0.5
center = [0, 2, 0]
material = "black"
emission = { radiance = "1 W/m^2/sr" }
"#,
        );
        let s = support::render::scene_from(&text);
        // bdpt at 4096 spp: its border blocks' σ is ≈ 0.4 % at 1024 (seeds 1, 2 with
        // `spectrace render … --spp 1024`), so ≈ 0.2 % here and 1 % is 5σ
        let spp = if integrator == "bdpt" { 4096 } else { 256 };
        let (img, stats) = support::render::render_with(&s, |o| o.spp = spp);
        assert_eq!(stats.nan_samples + stats.inf_samples, 0, "{integrator}");
        // bdpt's light-tracing splats make single pixels noisy (see `bdpt.rs`): it is checked
        // on the 8×8-pixel blocks around the border, which the lamp's image does not reach
        let size = if integrator == "bdpt" { 8 } else { 1 };
        let cells: Vec<(usize, usize)> = if size == 8 {
            (0..4)
                .flat_map(|by| (0..4).map(move |bx| (bx, by)))
                .filter(|&(bx, by)| bx % 3 == 0 || by % 3 == 0)
                .collect()
        } else {
            vec![(4, 16), (20, 27), (30, 2), (9, 9), (27, 24)]
        };
        for (cx, cy) in cells {
            let (mut want, mut got) = (0.0, 0.0);
            for py in cy * size..(cy + 1) * size {
                for px in cx * size..(cx + 1) * size {
                    let (r2, _) = support::render::plane_point(&s, px, py);
                    want += 0.5 * 1.0 * 0.25 * 2.0 / r2.powf(1.5);
                    got += img.band[py * 32 + px] as f64;
                }
            }
            assert!(
                (got / want - 1.0).abs() < 0.01,
                "{integrator} {size}×{size} cell ({cx},{cy}): L = {got}, want {want}"
            );
        }
    }
}

/// A many-light scene for the meters: a black floor under `n`² lamps on a jittered grid over
/// 12 m × 12 m, 0.3–0.8 m high, powers log-uniform over 1–100 W, every fourth a point light and
/// the others black spheres of 5 cm; a grid of 8 × 8 irradiance meters on the floor. Returns
/// the TOML and each lamp as (centre, radius (0: point), band power W).
fn many_lamps(n: usize, selection: &str) -> (String, Vec<(Vec3, f64, f64)>) {
    let mut rng = Rng::new(25);
    let mut toml = support::render::black_floor(&format!(
        r#"[integrator]
type = "path"
max_depth = 2
light_selection = "{selection}"
[[sensors]]
type = "grid"
name = "floor"
corner = [-5, 0, -5]
edge_u = [0, 0, 10]
edge_v = [10, 0, 0]
count = [8, 8]
"#
    ));
    let mut lamps = Vec::new();
    let step = 12.0 / n as f32;
    for i in 0..n {
        for j in 0..n {
            let x = -6.0 + (i as f32 + 0.1 + 0.8 * rng.uniform()) * step;
            let z = -6.0 + (j as f32 + 0.1 + 0.8 * rng.uniform()) * step;
            let y = 0.3 + 0.5 * rng.uniform();
            let power = 10f64.powf(2.0 * rng.uniform() as f64);
            if rng.uniform() < 0.25 {
                toml += &format!(
                    "[[lights]]\ntype = \"point\"\nposition = [{x}, {y}, {z}]\nspectrum = \"cie-e\"\npower = \"{power} W\"\n"
                );
                lamps.push((Vec3::new(x, y, z), 0.0, power));
            } else {
                let r = 0.005f64;
                let radiance = power / (4.0 * std::f64::consts::PI.powi(2) * r * r);
                toml += &format!(
                    "[[shapes]]\ntype = \"sphere\"\nradius = {r}\ncenter = [{x}, {y}, {z}]\nmaterial = \"black\"\nemission = {{ spectrum = \"cie-e\", radiance = \"{radiance} W/m^2/sr\" }}\n"
                );
                lamps.push((Vec3::new(x, y, z), r, power));
            }
        }
    }
    (toml, lamps)
}

/// Irradiance (W/m²) at floor point `p` (normal +y) from the lamps: a point light gives
/// (Φ/4π)·cos θ/d², and so does a Lambertian sphere wholly above the horizon (π·L·(R/d)²·cos θ
/// with Φ = 4π²R²L). Lamps shadowing each other are ignored: with 5 mm spheres that costs
/// under 10⁻³ of the light (measured: 5 cm spheres lose up to 7 % at points under a lamp).
fn lamps_irradiance(p: Vec3, lamps: &[(Vec3, f64, f64)]) -> f64 {
    lamps
        .iter()
        .map(|&(c, _, power)| {
            let d = (c - p).as_dvec3();
            let d2 = d.length_squared();
            power / (4.0 * std::f64::consts::PI) * (d.y / d2.sqrt()) / d2
        })
        .sum()
}

/// 1024 lamps, irradiance meters on the floor: the light tree and selection by power both
/// give the closed form within their standard errors (unbiased), and the tree's standard
/// errors are at least 3× smaller at the same sample count (10× lower variance measured).
#[test]
fn many_lights_tree_and_power_agree_with_the_closed_form() {
    let mut se_mean = Vec::new();
    for selection in ["tree", "power"] {
        let (toml, lamps) = many_lamps(32, selection);
        let scene = support::render::scene_from(&toml);
        let points = &scene.meters[0].points;
        // power selection's estimates are heavy-tailed (a near, weak lamp is rarely chosen), so
        // its standard errors only hold with many samples
        let r = support::render::measure(&scene, 65536, 1);
        let mut se_sum = 0.0;
        for (pt, x) in points.iter().zip(&r) {
            let truth = lamps_irradiance(pt.p, &lamps);
            let err = x.irradiance_w_m2 - truth;
            // 5 standard errors (64 points × 2 selections; P(|t| > 5) is ~10⁻⁶ each) and
            // the f32 arithmetic of the estimate
            assert!(
                err.abs() < 5.0 * x.irradiance_se_w_m2 + 1e-4 * truth,
                "{selection} at {:?}: {} ± {} W/m², closed form {truth}",
                pt.p,
                x.irradiance_w_m2,
                x.irradiance_se_w_m2
            );
            se_sum += x.irradiance_se_w_m2 / truth;
        }
        se_mean.push(se_sum / points.len() as f64);
    }
    assert!(
        se_mean[1] > 3.0 * se_mean[0],
        "relative standard errors: tree {}, power {}",
        se_mean[0],
        se_mean[1]
    );
}

/// The tree weighs lights of different kinds by what they deliver, not by their power: a point
/// light of 1 W/sr and a one-sided square lamp of 0.2 m × 0.2 m at 25 W·m⁻²·sr⁻¹, both 1 m
/// straight above a floor point and facing it, give it the same irradiance (I/d² = 1 W/m²
/// and L·A/d² = 1 W/m² within 0.4 %, the square's finite size), so the tree must pick them
/// about equally there. Their powers differ fourfold (4π W against π W), and selection in
/// proportion to power (or pbrt-v4's importance, which takes a flat lamp's power) would pick
/// the point light 80 % of the time.
#[test]
fn the_tree_picks_a_point_and_a_flat_lamp_by_their_irradiance() {
    let toml = support::render::black_floor(&format!(
        r#"[integrator]
type = "path"
max_depth = 2
[[lights]]
type = "point"
position = [0, 1, 0]
spectrum = "cie-e"
power = "{p} W"
[[shapes]]
type = "rectangle"
material = "black"
transform = [{{ scale = 0.1 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "90 deg" }} }}, {{ translate = [0, 1, 0] }}]
emission = {{ spectrum = "cie-e", radiance = "25 W/m^2/sr" }}
"#,
        p = 4.0 * std::f64::consts::PI
    ));
    let scene = support::render::scene_from(&toml);
    let (p, n) = (Vec3::new(0.0, 0.0, 0.0), Vec3::Y);
    let point = scene
        .lights
        .iter()
        .position(|l| matches!(l, spectrace::light::Light::Point(_)))
        .expect("a point light");
    let pmf_point = scene.light_tree.pmf(p, n, point);
    let pmf_lamp = scene.light_tree.pmf(p, n, 1 - point);
    assert!((pmf_point + pmf_lamp - 1.0).abs() < 1e-5);
    assert!(
        (pmf_point - 0.5).abs() < 0.02,
        "point light picked with probability {pmf_point}, the lamp {pmf_lamp}"
    );
}
