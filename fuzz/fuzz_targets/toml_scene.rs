//! The TOML scene loader and the build step: any text gives a scene or an error, never a
//! panic, hang or runaway allocation. Relative file names resolve under a folder that does
//! not exist, so no file on the machine is read.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = std::path::Path::new("/nonexistent-spectrace-fuzz/scene.toml");
    if let Ok(desc) = spectrace::loader::load_str(text, path) {
        let _ = spectrace::build::build(&desc);
    }
});
