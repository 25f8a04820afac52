//! `spectrace spectrum` prints values scripts can read, and clear errors.

use std::process::Command;

fn spectrace(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn numbers(s: &str) -> Vec<f64> {
    s.split_whitespace()
        .map(|t| t.parse().expect("plain number"))
        .collect()
}

#[test]
fn glass_index_at_d_line() {
    let (ok, out, _) = spectrace(&["spectrum", "glass:N-BK7", "587.56nm"]);
    assert!(ok);
    let v = numbers(&out);
    assert_eq!(v.len(), 1);
    assert!((v[0] - 1.5168).abs() < 5e-5, "{out}");
}

#[test]
fn metal_prints_n_and_k_per_line() {
    // Johnson & Christy Au, interpolated at 550 and 650 nm (tests/data/metals_check.csv)
    let (ok, out, _) = spectrace(&["spectrum", "metal:Au", "550nm", "0.65 um"]);
    assert!(ok);
    let lines: Vec<Vec<f64>> = out.lines().map(numbers).collect();
    assert_eq!(lines.len(), 2);
    assert!(
        (lines[0][0] - 0.424149).abs() < 1e-4 && (lines[0][1] - 2.472051).abs() < 1e-4,
        "{out}"
    );
    assert!(
        (lines[1][0] - 0.155574).abs() < 1e-4 && (lines[1][1] - 3.602445).abs() < 1e-4,
        "{out}"
    );
}

#[test]
fn illuminant_tabulated_value() {
    // CIE D65 is normalised to 100 at 560 nm.
    let (ok, out, _) = spectrace(&["spectrum", "cie-d65", "560nm", "560"]);
    assert!(ok);
    assert_eq!(numbers(&out), vec![100.0, 100.0]);
}

#[test]
fn summary_and_list() {
    let (ok, out, _) = spectrace(&["spectrum", "glass:N-BK7"]);
    assert!(ok && out.contains("V_d") && out.contains("64.17"), "{out}");
    let (ok, out, _) = spectrace(&["spectrum", "--list"]);
    assert!(ok);
    for name in [
        "cie-d65",
        "cie-f11",
        "glass:N-SF11",
        "metal:Ag",
        "colorchecker:dark-skin",
        "blackbody:<T>K",
    ] {
        assert!(
            out.lines().any(|l| l.starts_with(name)),
            "{name} not listed"
        );
    }
}

#[test]
fn unknown_name_suggests_and_fails() {
    let (ok, out, err) = spectrace(&["spectrum", "glass:BK7", "550nm"]);
    assert!(!ok && out.is_empty());
    assert!(
        err.contains("unknown spectrum \"glass:BK7\"") && err.contains("glass:N-BK7"),
        "{err}"
    );
}

#[test]
fn bad_wavelength_is_a_clear_error() {
    let (ok, _, err) = spectrace(&["spectrum", "cie-d65", "100W"]);
    assert!(
        !ok && err.contains("length") && err.contains("100W"),
        "{err}"
    );
    let (ok, _, err) = spectrace(&["spectrum", "cie-d65", "-5"]);
    assert!(!ok && err.contains("positive"), "{err}");
}

#[test]
fn spectrum_without_a_name_prints_the_data_summary() {
    let (ok, out, _) = spectrace(&["spectrum"]);
    assert!(
        ok && out.contains("∫ȳ") && out.contains("glass:N-BK7"),
        "{out}"
    );
}
