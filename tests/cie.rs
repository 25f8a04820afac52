//! CIE colorimetry against published values (`../shared/PHYSICS.md`, CIE 015).

mod support;

use spectrace::colour::cie::{CIE_Y_INTEGRAL, K_M, integrate_xyz, luminance_cd_m2, xyz_to_xy};
use spectrace::colour::spaces::{ACES2065_1, D65_WHITE, REC2020, SRGB, bradford, xy_to_xyz};
use support::curve;

#[test]
fn y_bar_integral_is_106_857() {
    let y = integrate_xyz(|_| 1.0)[1];
    assert!((y - 106.857).abs() < 0.01, "∫ȳ = {y}");
    assert!(
        (y - CIE_Y_INTEGRAL).abs() < 1e-4,
        "∫ȳ = {y}, PHYSICS.md {CIE_Y_INTEGRAL}"
    );
}

fn chromaticity(name: &str) -> [f64; 2] {
    let s = curve(name);
    xyz_to_xy(integrate_xyz(|l| s.eval(l) as f64))
}

#[test]
fn d65_and_a_chromaticities() {
    let d65 = chromaticity("cie-d65");
    assert!(
        (d65[0] - 0.3127).abs() < 2e-4 && (d65[1] - 0.3290).abs() < 2e-4,
        "D65 {d65:?}"
    );
    let a = chromaticity("cie-a");
    assert!(
        (a[0] - 0.4476).abs() < 2e-4 && (a[1] - 0.4074).abs() < 2e-4,
        "A {a:?}"
    );
    // CIE 015:2018 Table 9: D50 (0.3457, 0.3585), E (1/3, 1/3)
    let d50 = chromaticity("cie-d50");
    assert!(
        (d50[0] - 0.3457).abs() < 2e-4 && (d50[1] - 0.3585).abs() < 2e-4,
        "D50 {d50:?}"
    );
    let e = chromaticity("cie-e");
    assert!(
        (e[0] - 1.0 / 3.0).abs() < 2e-4 && (e[1] - 1.0 / 3.0).abs() < 2e-4,
        "E {e:?}"
    );
    // CIE 015:2018 Table 10: F2 (0.3721, 0.3751), F11 (0.3805, 0.3769)
    let f2 = chromaticity("cie-f2");
    assert!(
        (f2[0] - 0.3721).abs() < 3e-4 && (f2[1] - 0.3751).abs() < 3e-4,
        "F2 {f2:?}"
    );
    let f11 = chromaticity("cie-f11");
    assert!(
        (f11[0] - 0.3805).abs() < 3e-4 && (f11[1] - 0.3769).abs() < 3e-4,
        "F11 {f11:?}"
    );
}

#[test]
fn luminance_calibration_matches_physics_md() {
    // A flat 1 W·m⁻²·sr⁻¹·nm⁻¹ over 360–830 nm: Y = K_m ∫ȳ = 683.002 × 106.856895 cd/m².
    let y = luminance_cd_m2(|_| 1.0);
    assert!((y - 72_983.0).abs() < 1.0, "{y}");
    assert_eq!(K_M, 683.002);
}

fn assert_matrix(m: glam::DMat3, want: [[f64; 3]; 3], tol: f64, what: &str) {
    for (r, want_row) in want.iter().enumerate() {
        for (c, &w) in want_row.iter().enumerate() {
            let got = m.row(r)[c];
            assert!((got - w).abs() < tol, "{what}[{r}][{c}] = {got}, want {w}");
        }
    }
}

#[test]
fn srgb_matrix_matches_physics_md() {
    assert_matrix(
        SRGB.xyz_to_rgb(),
        [
            [3.2404542, -1.5371385, -0.4985314],
            [-0.9692660, 1.8760108, 0.0415560],
            [0.0556434, -0.2040259, 1.0572252],
        ],
        2e-6,
        "XYZ→sRGB",
    );
}

#[test]
fn rec2020_and_aces_matrices_match_their_standards() {
    // ITU-R BT.2020 RGB→XYZ (as published, 4 decimals in BT.2087; here to 1e-4).
    assert_matrix(
        REC2020.rgb_to_xyz(),
        [
            [0.6370, 0.1446, 0.1689],
            [0.2627, 0.6780, 0.0593],
            [0.0000, 0.0281, 1.0610],
        ],
        1e-4,
        "Rec.2020→XYZ",
    );
    // SMPTE ST 2065-1 AP0 → XYZ.
    assert!(
        (xy_to_xyz([0.3127, 0.3290]) - glam::DVec3::from(D65_WHITE))
            .abs()
            .max_element()
            < 3e-4
    );
    assert_matrix(
        ACES2065_1.rgb_to_xyz(),
        [
            [0.9525523959, 0.0, 0.0000936786],
            [0.3439664498, 0.7281660966, -0.0721325464],
            [0.0, 0.0, 1.0088251844],
        ],
        1e-7,
        "AP0→XYZ",
    );
}

#[test]
fn bradford_d65_to_d50_matches_lindbloom() {
    // Lindbloom's Bradford D65→D50 with whites (0.95047, 1, 1.08883) and (0.96422, 1, 0.82521).
    assert_matrix(
        bradford(D65_WHITE, [0.96422, 1.0, 0.82521]),
        [
            [1.0478112, 0.0228866, -0.0501270],
            [0.0295424, 0.9904844, -0.0170491],
            [-0.0092345, 0.0150436, 0.7521316],
        ],
        1e-6,
        "Bradford",
    );
}
