//! The Mitsuba XML importer and the build step, with includes served from memory: the input is
//! the scene text, then, after each NUL byte, the text of an include named `0.xml`, `1.xml`, …
//! (the scene may include them by those names, or each other).
#![no_main]

use std::collections::HashMap;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut parts = data.split(|&b| b == 0);
    let Some(Ok(main)) = parts.next().map(std::str::from_utf8) else {
        return;
    };
    let mut includes = HashMap::new();
    for (i, p) in parts.enumerate().take(8) {
        if let Ok(t) = std::str::from_utf8(p) {
            includes.insert(format!("{i}.xml"), t.to_string());
        }
    }
    let path = std::path::Path::new("/nonexistent-spectrace-fuzz/scene.xml");
    let defines = [("spp".to_string(), "4".to_string())];
    if let Ok(desc) =
        spectrace::loader::mitsuba::load_str_with_includes(main, path, &defines, &includes)
    {
        let _ = spectrace::build::build(&desc);
    }
});
