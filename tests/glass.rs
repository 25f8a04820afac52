//! Dispersion of the catalogue glasses against their catalogue values.

use spectrace::spectrum::ior::{FRAUNHOFER_C_NM, FRAUNHOFER_D_NM, FRAUNHOFER_F_NM, Ior};
use spectrace::spectrum::named::{Glass, Named, lookup};

fn glass(name: &str) -> Glass {
    match lookup(name) {
        Ok(Named::Dielectric(g)) => g,
        other => panic!("{name}: {other:?}"),
    }
}

#[test]
fn n_bk7_index_and_abbe_number() {
    let g = glass("glass:N-BK7");
    // SCHOTT N-BK7 data sheet: n_d = 1.51680, n_F = 1.52238, n_C = 1.51432, V_d = 64.17.
    let n = |l| g.ior.eval(l) as f64;
    assert!(
        (n(FRAUNHOFER_D_NM) - 1.5168).abs() < 5e-5,
        "n_d = {}",
        n(FRAUNHOFER_D_NM)
    );
    assert!(
        (n(FRAUNHOFER_F_NM) - 1.52238).abs() < 3e-5,
        "n_F = {}",
        n(FRAUNHOFER_F_NM)
    );
    assert!(
        (n(FRAUNHOFER_C_NM) - 1.51432).abs() < 3e-5,
        "n_C = {}",
        n(FRAUNHOFER_C_NM)
    );
    let vd = g.ior.abbe_number();
    assert!((vd - 64.17).abs() < 0.05, "V_d = {vd}");
    // normal dispersion: n falls with wavelength
    assert!(n(400.0) > n(500.0) && n(500.0) > n(700.0));
}

#[test]
fn catalogue_glasses_match_their_n_d() {
    // Catalogue n_d (SCHOTT data sheets; fused silica: Malitson 1965 / Heraeus nominal 1.4585).
    for (name, nd, vd) in [
        ("glass:N-BK7", 1.51680, 64.17),
        ("glass:N-SF11", 1.78472, 25.68),
        ("glass:N-F2", 1.62005, 36.43),
        ("glass:fused-silica", 1.4585, 67.82),
    ] {
        let g = glass(name);
        let got = g.ior.eval(FRAUNHOFER_D_NM) as f64;
        assert!(
            (got - nd).abs() < 1e-4,
            "{name}: n_d = {got}, catalogue {nd}"
        );
        let v = g.ior.abbe_number();
        assert!((v - vd).abs() < 0.05, "{name}: V_d = {v}, catalogue {vd}");
    }
}

#[test]
fn water_and_diamond_have_validity_ranges_and_plausible_indices() {
    // Handbook values at the sodium D line: water 1.333 (20 °C), diamond 2.417.
    for (name, nd) in [("glass:water", 1.333), ("glass:diamond", 2.417)] {
        let g = glass(name);
        let n = g.ior.eval(FRAUNHOFER_D_NM) as f64;
        assert!((n - nd).abs() < 1e-3, "{name}: n_d = {n}");
        assert!(
            g.range_nm.0 < 400.0 && g.range_nm.1 > 700.0,
            "{name}: {:?}",
            g.range_nm
        );
    }
}

#[test]
fn index_forms_agree_on_a_constant() {
    assert_eq!(Ior::Constant(1.5).eval(400.0), 1.5);
}
