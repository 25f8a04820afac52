//! Planck's law against colour-science values, and Wien's displacement law.

mod support;

use spectrace::spectrum::blackbody::{Blackbody, planck, wien_peak_nm};
use support::Csv;

#[test]
fn planck_matches_colour_science() {
    let t = Csv::read("planck.csv");
    assert!(t.rows.len() >= 3);
    for r in 0..t.rows.len() {
        let (l, temp) = (t.num(r, "wavelength_nm"), t.num(r, "temperature_K"));
        let want = t.num(r, "spectral_radiance_W_m2_sr_nm");
        let got = planck(l, temp);
        assert!(
            ((got - want) / want).abs() < 1e-4,
            "L({l} nm, {temp} K) = {got}, want {want}"
        );
        // the f32 curve used in the render loop agrees too
        let g32 = Blackbody::absolute(temp as f32).eval(l as f32) as f64;
        assert!(
            ((g32 - want) / want).abs() < 1e-4,
            "f32 L({l} nm, {temp} K) = {g32}, want {want}"
        );
    }
}

#[test]
fn peak_follows_wien() {
    for temp in [2856.0, 4000.0, 5778.0, 6504.0, 10_000.0] {
        // brute-force maximum on a 0.01 nm grid around b/T (Wien's b = 2.897771955e-3 m·K)
        let expect = 2.897_771_955e-3 / temp * 1e9;
        let mut best = (0.0, 0.0);
        let mut l = expect - 100.0;
        while l < expect + 100.0 {
            let v = planck(l, temp);
            if v > best.1 {
                best = (l, v);
            }
            l += 0.01;
        }
        assert!(
            (best.0 - expect).abs() < 0.5,
            "T = {temp}: peak at {} nm, Wien {expect} nm",
            best.0
        );
        assert!((wien_peak_nm(temp) - expect).abs() < 1e-9);
    }
}
