//! The 24 ColorChecker patches under D65 against colour-science, and CIEDE2000 against
//! Sharma, Wu & Dalal (2005).

mod support;

use spectrace::colour::cie::reflectance_xyz;
use spectrace::colour::lab::{delta_e_2000, xyz_to_lab};
use spectrace::colour::spaces::{D65_WHITE, srgb_to_xyz, xyz_to_srgb};
use support::{Csv, curve};

#[test]
fn ciede2000_matches_sharma_test_data() {
    let t = Csv::read("ciede2000.csv");
    assert_eq!(t.rows.len(), 34);
    for r in 0..t.rows.len() {
        let lab = |s: &str| {
            [
                t.num(r, &format!("L{s}")),
                t.num(r, &format!("a{s}")),
                t.num(r, &format!("b{s}")),
            ]
        };
        let want = t.num(r, "dE00");
        let got = delta_e_2000(lab("1"), lab("2"));
        assert!(
            (got - want).abs() < 1e-4,
            "pair {}: ΔE00 = {got}, published {want}",
            r + 1
        );
        assert!(
            (delta_e_2000(lab("2"), lab("1")) - got).abs() < 1e-9,
            "symmetry"
        );
    }
}

#[test]
fn colorchecker_srgb_under_d65_matches_colour_science() {
    let t = Csv::read("colorchecker_d65.csv");
    let d65 = curve("cie-d65");
    assert_eq!(t.rows.len(), 24);
    let mut worst = 0.0f64;
    for r in 0..24 {
        let name = t.text(r, "name");
        let patch = curve(&format!("colorchecker:{name}"));
        let xyz = reflectance_xyz(|l| patch.eval(l) as f64, |l| d65.eval(l) as f64);
        let rgb = xyz_to_srgb(xyz);
        let want_rgb = [t.num(r, "R_lin"), t.num(r, "G_lin"), t.num(r, "B_lin")];
        // compare the two sRGB colours in CIELAB (D65 white), through the same sRGB → XYZ
        let lab = |c: [f64; 3]| xyz_to_lab(srgb_to_xyz(c), D65_WHITE);
        let de = delta_e_2000(lab(rgb), lab(want_rgb));
        let want_lab = [t.num(r, "L"), t.num(r, "a"), t.num(r, "b")];
        let de_lab = delta_e_2000(xyz_to_lab(xyz, D65_WHITE), want_lab);
        worst = worst.max(de).max(de_lab);
        assert!(
            de < 0.5,
            "{name}: sRGB {rgb:?} vs colour-science {want_rgb:?}, ΔE00 = {de}"
        );
        assert!(de_lab < 0.5, "{name}: Lab ΔE00 = {de_lab}");
    }
    println!("worst ColorChecker ΔE00 = {worst:.3}");
}
