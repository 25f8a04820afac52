//! The PLY mesh reader, ASCII and binary.
#![no_main]

use libfuzzer_sys::fuzz_target;
use spectrace::geometry::shape::Mesh;
use spectrace::geometry::transform::Transform;

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.ply");
    let _ = Mesh::parse_ply(data, path, &Transform::default());
});
