//! Conductor indices against the source tables (Johnson & Christy 1972; Rakić 1995), as
//! interpolated independently by `scripts/gen_spectra.py`.

mod support;

use spectrace::spectrum::named::{Named, lookup};
use support::Csv;

#[test]
fn metal_n_k_match_source_tables() {
    let t = Csv::read("metals_check.csv");
    let mut checked = 0;
    for r in 0..t.rows.len() {
        let name = format!("metal:{}", t.text(r, "metal"));
        let Ok(Named::Conductor(m)) = lookup(&name) else {
            panic!("{name} missing")
        };
        let l = t.num(r, "wavelength_nm") as f32;
        let (n, k) = m.ior.eval(l);
        let (wn, wk) = (t.num(r, "n"), t.num(r, "k"));
        assert!(
            ((n as f64 - wn) / wn).abs() < 1e-4,
            "{name} n({l}) = {n}, source {wn}"
        );
        assert!(
            ((k as f64 - wk) / wk).abs() < 1e-4,
            "{name} k({l}) = {k}, source {wk}"
        );
        checked += 1;
    }
    assert!(checked >= 4, "Au and Cu at 550 and 650 nm at least");
    assert!(t.rows.iter().any(|r| r[0] == "Au") && t.rows.iter().any(|r| r[0] == "Cu"));
}
