//! The lens-file reader (pbrt-v4's format with glass names) and, for a file that reads, the
//! lens system's checks, its first-order optics and its exit-pupil search.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = std::path::Path::new("fuzz.lens");
    let Ok(desc) = spectrace::loader::lens::parse(text, path) else {
        return;
    };
    // a lens of many surfaces costs the pupil search time in proportion: bound it as a file of
    // real lenses is bounded (tens of surfaces)
    if desc.surfaces.len() > 64 {
        return;
    }
    if let Ok(sys) = spectrace::build::lens_system(&desc) {
        let _ = sys.paraxial(550.0);
        let _ = sys.focus_film_distance(1000.0, 550.0);
        let _ = spectrace::optics::ExitPupil::new(&sys, 20.0);
    }
});
