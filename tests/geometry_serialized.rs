//! Mitsuba `.serialized` meshes read as Mitsuba 3.9.1 reads them: the files in
//! `tests/reference/serialized/` are written by `scripts/gen_serialized.py`, whose `--check`
//! prints what Mitsuba itself loads from them (the numbers asserted here): version 4 with two
//! meshes (float32 with normals; float64 with uvs), version 3 with one, picked by shape_index.

use std::path::{Path, PathBuf};

use spectrace::geometry::shape::Mesh;
use spectrace::geometry::transform::Transform;

fn file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reference/serialized")
        .join(name)
}

#[test]
fn meshes_read_as_mitsuba_reads_them() {
    let id = Transform::identity();
    // Mitsuba: 4 vertices, 2 faces, area 1.0, vertex normals, no uvs
    let m = Mesh::load_serialized(&file("meshes.serialized"), 0, &id).unwrap();
    assert_eq!(m.triangle_count(), 2);
    assert!((m.area() - 1.0).abs() < 1e-6);
    assert!(m.has_normals() && !m.has_uvs());
    // Mitsuba: 289 vertices, 512 faces, area 4.130401, uvs, no stored normals
    let m = Mesh::load_serialized(&file("meshes.serialized"), 1, &id).unwrap();
    assert_eq!(m.triangle_count(), 512);
    assert!((m.area() - 4.130401).abs() < 1e-4, "{}", m.area());
    assert!(!m.has_normals() && m.has_uvs());
    // Mitsuba: version 3, 2 faces, area 2.0, uvs
    let m = Mesh::load_serialized(&file("quad_v3.serialized"), 0, &id).unwrap();
    assert_eq!(m.triangle_count(), 2);
    assert!((m.area() - 2.0).abs() < 1e-6);
    assert!(m.has_uvs());
}

#[test]
fn bad_files_are_named_errors() {
    let id = Transform::identity();
    let e = Mesh::load_serialized(&file("meshes.serialized"), 2, &id)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("meshes.serialized") && e.contains("holds 2 meshes"),
        "{e}"
    );
    // truncated inside the first mesh's compressed stream
    let bytes = std::fs::read(file("meshes.serialized")).unwrap();
    let cut = std::env::temp_dir().join(format!("spectrace-cut-{}.serialized", std::process::id()));
    std::fs::write(&cut, &bytes[..24]).unwrap();
    let e = Mesh::load_serialized(&cut, 0, &id).unwrap_err().to_string();
    assert!(e.contains("ends early or is corrupt"), "{e}");
    // a mesh table whose count claims 2³² − 1 meshes: an error, not an overflow
    let mut table = bytes.clone();
    let n = table.len();
    table[n - 4..].copy_from_slice(&u32::MAX.to_le_bytes());
    std::fs::write(&cut, &table).unwrap();
    let e = Mesh::load_serialized(&cut, 7, &id).unwrap_err().to_string();
    assert!(e.contains("mesh table"), "{e}");
    std::fs::write(&cut, b"not a mesh").unwrap();
    let e = Mesh::load_serialized(&cut, 0, &id).unwrap_err().to_string();
    assert!(e.contains("0x041C"), "{e}");
    std::fs::remove_file(&cut).ok();
}
