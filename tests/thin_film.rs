//! Thin-film coatings (`optics::thin_film`) against closed forms computed here: bare Fresnel,
//! the quarter-wave layer, the Airy single-layer formula, energy conservation and reciprocity.

use spectrace::material::fresnel::fresnel_dielectric;
use spectrace::optics::thin_film::{C64, Coating, Layer, LayerIndex};
use spectrace::spectrum::ior::Ior;
use spectrace::spectrum::named::{Named, lookup};

fn glass(name: &str) -> Ior {
    match lookup(name) {
        Ok(Named::Dielectric(g)) => g.ior,
        other => panic!("{other:?}"),
    }
}

fn layer(ior: Ior, d: f64) -> Layer {
    Layer {
        index: LayerIndex::Dielectric(ior),
        thickness_nm: d,
    }
}

#[test]
fn a_coating_of_zero_thickness_is_the_bare_interface() {
    let bk7 = glass("glass:N-BK7");
    let c = Coating {
        layers: vec![layer(glass("glass:MgF2"), 0.0)],
    };
    for l in [420.0, 550.0, 680.0] {
        let n = bk7.eval_f64(l);
        for cos in [1.0, 0.8, 0.5, 0.2, 0.05] {
            let out = c.response(l, 1.0, cos, C64::real(n), false).r_unpolarised();
            let bare = fresnel_dielectric(cos as f32, n as f32) as f64;
            assert!((out - bare).abs() < 1e-6, "{l} {cos}: {out} vs {bare}");
            // from inside the glass, toward air (total internal reflection past 41°)
            let inside = c.response(l, n, cos, C64::real(1.0), true).r_unpolarised();
            let bare = fresnel_dielectric(-(cos as f32), n as f32) as f64;
            assert!(
                (inside - bare).abs() < 1e-6,
                "inside {l} {cos}: {inside} vs {bare}"
            );
        }
    }
}

#[test]
fn a_quarter_wave_mgf2_layer_on_n_bk7() {
    let (mgf2, bk7) = (glass("glass:MgF2"), glass("glass:N-BK7"));
    let l0 = 550.0;
    let (n1, n2) = (mgf2.eval_f64(l0), bk7.eval_f64(l0));
    let c = Coating {
        layers: vec![layer(mgf2.clone(), l0 / (4.0 * n1))],
    };
    let r = c
        .response(l0, 1.0, 1.0, C64::real(n2), false)
        .r_unpolarised();
    let closed = ((n2 - n1 * n1) / (n2 + n1 * n1)).powi(2);
    println!(
        "R(550 nm) = {r:.6} (closed form {closed:.6}; bare glass {:.6})",
        ((n2 - 1.0) / (n2 + 1.0)).powi(2)
    );
    assert!((r - closed).abs() < 1e-9);
    // the design wavelength is the reflectance minimum of the visible
    let min = (400..=700)
        .map(|l| {
            let l = l as f64;
            (
                l,
                c.response(l, 1.0, 1.0, C64::real(bk7.eval_f64(l)), false)
                    .r_unpolarised(),
            )
        })
        .fold((0.0, 1.0), |a, b| if b.1 < a.1 { b } else { a });
    assert!((min.0 - l0).abs() <= 3.0, "minimum at {} nm", min.0);
}

/// The Airy formula of one layer (index n1, thickness d) between n0 and n2 for s or p light:
/// r = (r01 + r12 e^{2iβ}) / (1 + r01 r12 e^{2iβ}), β = 2π n1 d cos θ1 / λ (Born & Wolf §1.6.4,
/// eq. 58), with the interfaces' Fresnel coefficients.
fn airy(n0: f64, n1: f64, n2: f64, d: f64, l: f64, cos0: f64, p: bool) -> f64 {
    let s0 = n0 * (1.0 - cos0 * cos0).sqrt();
    let cos = |n: f64| (1.0 - (s0 / n).powi(2)).sqrt();
    let (c0, c1, c2) = (cos0, cos(n1), cos(n2));
    let fr = |na: f64, ca: f64, nb: f64, cb: f64| {
        if p {
            (nb * ca - na * cb) / (nb * ca + na * cb)
        } else {
            (na * ca - nb * cb) / (na * ca + nb * cb)
        }
    };
    let (r01, r12) = (fr(n0, c0, n1, c1), fr(n1, c1, n2, c2));
    let beta = 2.0 * std::f64::consts::PI * n1 * d * c1 / l;
    let e = C64::new((2.0 * beta).cos(), (2.0 * beta).sin());
    let num = C64::real(r01) + C64::real(r12) * e;
    let den = C64::real(1.0) + C64::real(r01 * r12) * e;
    num.norm2() / den.norm2()
}

#[test]
fn one_layer_follows_the_airy_formula_at_every_angle_and_wavelength() {
    for (n1, d) in [(1.38, 99.6), (2.35, 60.0), (1.6, 400.0)] {
        let c = Coating {
            layers: vec![layer(Ior::Constant(n1 as f32), d)],
        };
        let n1 = n1 as f32 as f64;
        for l in [400.0, 487.0, 550.0, 633.0, 700.0] {
            for cos in [1.0, 0.9, 0.6, 0.3, 0.1] {
                let resp = c.response(l, 1.0, cos, C64::real(1.52), false);
                let (rs, rp) = (
                    airy(1.0, n1, 1.52, d, l, cos, false),
                    airy(1.0, n1, 1.52, d, l, cos, true),
                );
                assert!((resp.reflectance.0 - rs).abs() < 1e-6, "s {n1} {l} {cos}");
                assert!((resp.reflectance.1 - rp).abs() < 1e-6, "p {n1} {l} {cos}");
            }
        }
    }
}

#[test]
fn energy_is_conserved_and_absorbed_only_by_absorbing_layers() {
    let bk7 = glass("glass:N-BK7");
    let lossless = Coating {
        layers: vec![
            layer(glass("glass:ZnS"), 55.0),
            layer(glass("glass:MgF2"), 95.0),
        ],
    };
    let silver = match lookup("metal:Ag") {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    };
    let lossy = Coating {
        layers: vec![
            layer(glass("glass:MgF2"), 80.0),
            Layer {
                index: LayerIndex::Absorbing(silver),
                thickness_nm: 12.0,
            },
        ],
    };
    for l in [410.0, 520.0, 650.0] {
        let n = bk7.eval_f64(l);
        for cos in [1.0, 0.7, 0.4, 0.15] {
            let out = lossless.response(l, 1.0, cos, C64::real(n), false);
            for (r, t) in [
                (out.reflectance.0, out.transmittance.0),
                (out.reflectance.1, out.transmittance.1),
            ] {
                assert!((r + t - 1.0).abs() < 1e-9, "lossless: R {r} + T {t}");
            }
            // the same beam backwards: from the glass at the refracted angle
            let cos_in = (1.0 - (1.0 - cos * cos) / (n * n)).sqrt();
            let back = lossless.response(l, n, cos_in, C64::real(1.0), true);
            assert!(
                (back.t_unpolarised() - out.t_unpolarised()).abs() < 1e-9,
                "reciprocity"
            );
            let lo = lossy.response(l, 1.0, cos, C64::real(n), false);
            for (r, t) in [
                (lo.reflectance.0, lo.transmittance.0),
                (lo.reflectance.1, lo.transmittance.1),
            ] {
                let a = 1.0 - r - t;
                assert!(
                    a > 1e-3 && a < 1.0 && r > 0.0 && t > 0.0,
                    "silver: R {r} T {t} A {a}"
                );
            }
        }
    }
}

#[test]
fn a_soap_film_reflects_most_where_its_optical_thickness_is_an_odd_quarter_wave() {
    // water film (n ≈ 1.333) 400 nm thick in air: maxima at λ = 4nd/(2m+1), minima at 2nd/m
    let n = 1.333;
    let c = Coating {
        layers: vec![layer(Ior::Constant(n as f32), 400.0)],
    };
    let r = |l: f64| {
        c.response(l, 1.0, 1.0, C64::real(1.0), false)
            .r_unpolarised()
    };
    let n = n as f32 as f64;
    let max_at = 4.0 * n * 400.0 / 5.0; // m = 2: 426.5 nm
    let min_at = 2.0 * n * 400.0 / 2.0; // m = 2: 533.2 nm
    let f = ((1.0 - n) / (1.0 + n)).powi(2);
    // R_max = 4F/(1+F)² · … : the Airy maximum of a symmetric film, (2√F/(1+F))²
    let r_max = (2.0 * f.sqrt() / (1.0 + f)).powi(2);
    assert!((r(max_at) - r_max).abs() < 1e-9, "{} vs {r_max}", r(max_at));
    assert!(r(min_at) < 1e-12, "{}", r(min_at));
}

#[test]
fn the_polarised_matrices_of_a_bare_stack_are_fresnel_s() {
    use spectrace::material::coated::{
        on_conductor, on_dielectric, reflection_mueller, transmission_mueller,
    };
    use spectrace::polarisation::{Complex, fresnel};
    let empty = Coating {
        layers: vec![layer(Ior::Constant(1.38), 0.0)],
    };
    let gold = match lookup("metal:Au") {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    };
    let close = |a: [[f32; 4]; 4], b: [[f32; 4]; 4], what: &str| {
        for i in 0..4 {
            for j in 0..4 {
                assert!(
                    (a[i][j] - b[i][j]).abs() < 2e-5,
                    "{what} [{i}][{j}]: {a:?} vs {b:?}"
                );
            }
        }
    };
    for cos in [0.95f32, 0.7, 0.4, 0.1] {
        // a conductor: reflectances and the retardance, with its sign
        let (n, k) = gold.eval(550.0);
        let coated = reflection_mueller(&on_conductor(&empty, 1.0, &gold, cos, 550.0)).0;
        close(
            coated,
            fresnel::reflection(cos, Complex::new(n, k)).0,
            "gold",
        );
        // glass from outside: reflection and transmission
        let glass = Ior::Constant(1.5);
        let r = on_dielectric(&empty, 1.0, &glass, cos, 550.0);
        close(
            reflection_mueller(&r).0,
            fresnel::reflection(cos, Complex::new(1.5, 0.0)).0,
            "glass R",
        );
        close(
            transmission_mueller(&r).0,
            fresnel::transmission(cos, 1.5).0,
            "glass T",
        );
        // from inside, past the critical angle at cos 0.4 and 0.1: total internal reflection
        // with its retardance
        let r = on_dielectric(&empty, 1.0, &glass, -cos, 550.0);
        close(
            reflection_mueller(&r).0,
            fresnel::reflection(cos, Complex::new(1.0 / 1.5, 0.0)).0,
            "inside R",
        );
    }
}

#[test]
fn a_layer_on_gold_has_the_airy_amplitudes_and_phases() {
    // Born & Wolf's conventions (n + ik, e^{2iβ}), with the p sign of polarisation::fresnel:
    // r_p = (n_t cos θᵢ − n_i cos θₜ)/(n_t cos θᵢ + n_i cos θₜ)
    let gold = match lookup("metal:Au") {
        Ok(Named::Conductor(m)) => m.ior,
        other => panic!("{other:?}"),
    };
    let (n1, d) = (2.0f32, 80.0);
    let c = Coating {
        layers: vec![layer(Ior::Constant(n1), d)],
    };
    let n1 = C64::real(n1 as f64);
    let one = C64::real(1.0);
    for l in [450.0f32, 600.0] {
        let (n, k) = gold.eval(l);
        let n2 = C64::new(n as f64, k as f64);
        for cos0 in [0.9f64, 0.5] {
            let s2 = C64::real(1.0 - cos0 * cos0);
            let cos_in = |m: C64| (one - s2 / (m * m)).sqrt();
            let (c0, c1, c2) = (C64::real(cos0), cos_in(n1), cos_in(n2));
            let rs = |na: C64, ca: C64, nb: C64, cb: C64| (na * ca - nb * cb) / (na * ca + nb * cb);
            let rp = |na: C64, ca: C64, nb: C64, cb: C64| (nb * ca - na * cb) / (nb * ca + na * cb);
            let beta = n1 * c1 * C64::real(2.0 * std::f64::consts::PI * d / l as f64);
            let e = C64::new((2.0 * beta.re).cos(), (2.0 * beta.re).sin());
            let airy = |a: C64, b: C64| (a + b * e) / (one + a * b * e);
            let want_s = airy(rs(one, c0, n1, c1), rs(n1, c1, n2, c2));
            let want_p = airy(rp(one, c0, n1, c1), rp(n1, c1, n2, c2));
            let got = c.response(l as f64, 1.0, cos0, C64::new(n as f64, -(k as f64)), false);
            for (g, w, what) in [(got.r.0, want_s, "s"), (got.r.1, want_p, "p")] {
                assert!(
                    (g - w).norm2().sqrt() < 1e-6,
                    "{what} {l} {cos0}: {g:?} vs {w:?}"
                );
            }
        }
    }
}
