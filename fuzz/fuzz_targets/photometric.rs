//! The luminaire readers: IES LM-63 and EULUMDAT, as 8-bit text (both are read byte by byte).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text: String = data.iter().map(|&b| b as char).collect();
    // a tilt file named relatively resolves under a folder that does not exist
    let path = std::path::Path::new("/nonexistent-spectrace-fuzz/fuzz.ies");
    let _ = spectrace::loader::photometric::parse_ies(&text, path);
    let _ = spectrace::loader::photometric::parse_ldt(&text, std::path::Path::new("fuzz.ldt"));
});
