//! The spectrum CSV reader (wavelength_nm,value tables).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = spectrace::spectrum::data::parse_spectrum_text(text, "fuzz.csv");
    }
});
