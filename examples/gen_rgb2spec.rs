//! Regenerates `spectra/rgb2spec/srgb.bin`, the Jakob–Hanika coefficient table for sRGB, with
//! spectrace's own optimiser (`spectrace::spectrum::rgb2spec::opt`).
//!
//! ```text
//! cargo run --release --example gen_rgb2spec -- [RESOLUTION] [OUTPUT]
//! ```
//! Defaults: resolution 64, output `spectra/rgb2spec/srgb.bin`. The white is CIE D65 from
//! `spectra/illuminants/cie_d65.csv` and the observer CIE 1931 2°.

use std::time::Instant;

use spectrace::colour::spaces::SRGB;
use spectrace::spectrum::named::{Named, lookup};
use spectrace::spectrum::rgb2spec::opt::{Fitter, build_table};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let res: usize = args.next().map(|s| s.parse()).transpose()?.unwrap_or(64);
    let out = args
        .next()
        .unwrap_or_else(|| "spectra/rgb2spec/srgb.bin".into());
    let Named::Curve { spectrum: d65, .. } = lookup("cie-d65")? else {
        return Err("cie-d65 is not a curve".into());
    };
    let fitter = Fitter::new(&SRGB, &d65);
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    let t0 = Instant::now();
    let table = build_table(&fitter, res, threads);
    eprintln!(
        "fitted {} entries in {:.1} s on {threads} threads",
        table.coeffs.len(),
        t0.elapsed().as_secs_f64()
    );
    let tmp = format!("{out}.tmp");
    std::fs::write(&tmp, table.to_bytes())?;
    std::fs::rename(&tmp, &out)?;
    eprintln!("wrote {out}");
    Ok(())
}
