//! The OBJ mesh reader (tobj, then spectrace's checks).
#![no_main]

use libfuzzer_sys::fuzz_target;
use spectrace::geometry::shape::Mesh;
use spectrace::geometry::transform::Transform;

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.obj");
    let _ = Mesh::parse_obj(&mut std::io::Cursor::new(data), path, &Transform::default());
});
