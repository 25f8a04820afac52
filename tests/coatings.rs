//! Thin-film coatings in renders: energy through a coated glass in a uniform field, and a
//! coated gold mirror's colour against the Airy formula evaluated here (Born & Wolf's sign
//! conventions, n + ik, independent of the renderer's Macleod form).

mod support;

use spectrace::optics::thin_film::C64;
use spectrace::spectrum::named::{Named, lookup};
use support::render::{mean, render_with, scene_from};

fn furnace_with(material: &str, spp: u32) -> String {
    format!(
        r#"
[scene]
wavelength_range = ["400 nm", "700 nm"]
[camera]
eye = [0, 0, -3]
target = [0, 0, 0]
fov = "2 deg"
[film]
width = 8
height = 8
spp = {spp}
[integrator]
max_depth = 64
[materials.black]
type = "diffuse"
reflectance = 0
{material}
[[shapes]]
type = "sphere"
center = [0, 0, 0]
radius = 0.5
material = "m"
[[shapes]]
type = "sphere"
center = [0, 0, 0]
radius = 20
material = "black"
emission = {{ radiance = "1 W/m^2/sr", two_sided = true }}
"#
    )
}

/// Mean band radiance of the central 4 × 4 pixels and its standard error over the 16.
fn centre(text: &str) -> (f64, f64) {
    let scene = scene_from(text);
    let (img, _) = render_with(&scene, |_| {});
    let v: Vec<f32> = (2..6)
        .flat_map(|y| (2..6).map(move |x| (x, y)))
        .map(|(x, y)| img.band[y * 8 + x])
        .collect();
    let m = mean(v.iter().copied());
    let var = v.iter().map(|x| (*x as f64 - m).powi(2)).sum::<f64>() / 15.0;
    (m, (var / 16.0).sqrt())
}

#[test]
fn a_lossless_coated_glass_in_a_uniform_field_is_invisible_and_a_silvered_one_is_not() {
    let lossless = r#"
[materials.m]
type = "dielectric"
ior = 1.5
coating = [{ thickness = "55 nm", ior = "ZnS" }, { thickness = "95 nm", ior = "MgF2" }]
"#;
    let (m, se) = centre(&furnace_with(lossless, 256));
    println!("lossless coated glass: {m:.5} ± {se:.5}");
    assert!((m - 1.0).abs() < 4.0 * se.max(1e-4), "{m} ± {se}");
    let silvered = r#"
[materials.m]
type = "dielectric"
ior = 1.5
coating = [{ thickness = "20 nm", metal = "Ag" }]
"#;
    let (m, se) = centre(&furnace_with(silvered, 256));
    println!("silvered glass: {m:.5} ± {se:.5}");
    // 20 nm of silver absorbs a few per cent: clearly below 1
    assert!(1.0 - m > 6.0 * se && m > 0.2, "{m} ± {se}");
}

/// |r|² of one layer (index n1, thickness d nm) on a substrate n2 + ik2 at normal incidence
/// from air: r = (r01 + r12 e^{2iβ}) / (1 + r01 r12 e^{2iβ}), β = 2π n1 d / λ (Born & Wolf
/// §1.6.4 and §14.4, with the complex index n + ik).
fn airy_on_metal(n1: f64, d: f64, n2: f64, k2: f64, l: f64) -> f64 {
    let one = C64::real(1.0);
    let n1c = C64::real(n1);
    let n2c = C64::new(n2, k2);
    let r01 = (one - n1c) / (one + n1c);
    let r12 = (n1c - n2c) / (n1c + n2c);
    let b = 4.0 * std::f64::consts::PI * n1 * d / l;
    let e = C64::new(b.cos(), b.sin());
    let r = (r01 + r12 * e) / (one + r01 * r12 * e);
    r.norm2()
}

#[test]
fn a_coated_gold_mirror_reflects_what_the_airy_formula_says() {
    let gold = match lookup("metal:Au") {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    };
    let zns = match lookup("glass:ZnS") {
        Ok(Named::Dielectric(g)) => g.ior,
        other => panic!("{other:?}"),
    };
    let coated = r#"
[materials.m]
type = "conductor"
metal = "Au"
coating = [{ thickness = "THICK nm", ior = "ZnS" }]
"#;
    // the centre pixels see the sphere within 3.5° of normal incidence
    let d = 60.0;
    let coated = coated.replace("THICK", &d.to_string());
    let (m, se) = centre(&furnace_with(&coated, 64));
    let (mb, seb) = centre(&furnace_with(
        "[materials.m]\ntype = \"conductor\"\nmetal = \"Au\"\n",
        64,
    ));
    // the band radiance: the mean of R over 400–700 nm times 1 W·m⁻²·sr⁻¹
    let n = 3000;
    let expect = (0..n)
        .map(|i| {
            let l = 400.0 + 300.0 * (i as f64 + 0.5) / n as f64;
            let (nn, k) = gold.eval(l as f32);
            airy_on_metal(zns.eval_f64(l), d, nn as f64, k as f64, l)
        })
        .sum::<f64>()
        / n as f64;
    let bare = (0..n)
        .map(|i| {
            let l = 400.0 + 300.0 * (i as f64 + 0.5) / n as f64;
            let (nn, k) = gold.eval(l as f32);
            airy_on_metal(1.0, 0.0, nn as f64, k as f64, l)
        })
        .sum::<f64>()
        / n as f64;
    println!(
        "coated gold: {m:.5} ± {se:.5}, Airy {expect:.5}; bare gold {mb:.5} ± {seb:.5}, Fresnel {bare:.5}"
    );
    assert!((mb - bare).abs() < 4.0 * seb + 3e-4, "{mb} vs {bare}");
    assert!((m - expect).abs() < 4.0 * se + 3e-4, "{m} vs {expect}");
    assert!(
        (expect - bare).abs() > 0.02,
        "the coating must matter for this test to bite"
    );
}

#[test]
fn a_soap_film_renders_with_r_plus_t_equal_to_one() {
    let bubble = r#"
[materials.m]
type = "thin_film"
layers = [{ thickness = "380 nm", ior = "water" }]
"#;
    let (m, se) = centre(&furnace_with(bubble, 128));
    println!("soap film in a uniform field: {m:.5} ± {se:.5}");
    assert!((m - 1.0).abs() < 4.0 * se.max(1e-4), "{m} ± {se}");
}

#[test]
fn a_white_coated_plastic_reflects_everything_its_coating_does_not_absorb() {
    // ρ = 1 with the inner reflections summed (`nonlinear`): the base absorbs nothing, so a
    // lossless coating's plastic reflects all the light at every angle and wavelength; a
    // silver layer absorbs some
    let toml = |coating: &str| {
        format!(
            "[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[film]\nwidth = 4\n\
             height = 4\n[materials.p]\ntype = \"plastic\"\nreflectance = 1\nnonlinear = true\n\
             coating = {coating}\n[[shapes]]\ntype = \"sphere\"\ncenter = [0, 0, 1]\nradius = 0.5\n\
             material = \"p\"\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"\n"
        )
    };
    use spectrace::units::{Angle, Length, angle::degree, length::nanometer};
    let s =
        spectrace::Scene::from_toml(&toml("[{ thickness = \"120 nm\", ior = \"ZnS\" }]")).unwrap();
    let wl: Vec<Length> = [420.0, 550.0, 680.0].map(Length::new::<nanometer>).to_vec();
    for deg in [0.0, 40.0, 75.0] {
        for r in s
            .material_albedo("p", Angle::new::<degree>(deg), &wl, 200_000)
            .unwrap()
        {
            println!("{deg}°: R {:.5} ± {:.5}", r.reflectance, r.reflectance_se);
            assert!(
                (r.reflectance - 1.0).abs() < 4.0 * r.reflectance_se + 1e-3,
                "{deg}: {r:?}"
            );
        }
    }
    let s =
        spectrace::Scene::from_toml(&toml("[{ thickness = \"10 nm\", metal = \"Ag\" }]")).unwrap();
    let r = s
        .material_albedo("p", Angle::new::<degree>(0.0), &wl[1..2], 100_000)
        .unwrap()[0];
    assert!(r.reflectance < 0.95, "{r:?}");
}
