//! Shared helpers for the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

/// Path of a file under `tests/data/`.
pub fn data_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// A test-vector CSV from `tests/data/`: `#` comments, a header, then rows of fields.
pub struct Csv {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Csv {
    pub fn read(name: &str) -> Csv {
        let text = std::fs::read_to_string(data_path(name)).expect("test data file exists");
        let mut lines = text
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#'));
        let columns = lines
            .next()
            .expect("header")
            .split(',')
            .map(String::from)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(String::from).collect())
            .collect();
        Csv { columns, rows }
    }
    fn col(&self, name: &str) -> usize {
        self.columns
            .iter()
            .position(|c| c == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    }
    /// Field `name` of row `r` as text.
    pub fn text(&self, r: usize, name: &str) -> &str {
        &self.rows[r][self.col(name)]
    }
    /// Field `name` of row `r` as a number.
    pub fn num(&self, r: usize, name: &str) -> f64 {
        self.text(r, name).parse().expect("numeric field")
    }
}

/// A small deterministic generator (SplitMix64) for Monte Carlo checks.
pub mod cli;
pub mod corpus;
pub mod idiff;
pub mod media;
pub mod photometric;
pub mod prism;
pub mod render;

pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// A named curve from spectrace's registry (panics if the name is not a curve).
pub fn curve(name: &str) -> spectrace::spectrum::Spectrum {
    match spectrace::spectrum::named::lookup(name) {
        Ok(spectrace::spectrum::named::Named::Curve { spectrum, .. }) => spectrum,
        other => panic!("{name} is not a curve: {other:?}"),
    }
}
