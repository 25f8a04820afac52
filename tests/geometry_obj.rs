//! OBJ loading: small files written by the test into a temporary directory.

use glam::{Vec2, Vec3};
use spectrace::geometry::{Accel, GeometryError, Mesh, Ray, Shape, Transform};
use std::path::{Path, PathBuf};

/// Writes `text` to a fresh file under Cargo's per-test temporary directory.
fn write_obj(name: &str, text: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("geometry_obj");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write obj");
    path
}

fn load(path: &Path) -> Result<Mesh, GeometryError> {
    Mesh::load_obj(path, &Transform::identity())
}

/// A 2 × 3 quad in z = 0 written as one quad face, no normals, no uvs.
const QUAD: &str = "# a quad\nv 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nf 1 2 3 4\n";

/// The cube [-1, 1]³ with per-face normals and uvs, quads, in two objects.
const CUBE: &str = "\
mtllib missing.mtl
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
o bottom_and_top
usemtl nothing
f 1/1/1 4/4/1 3/3/1 2/2/1
f 5/1/2 6/2/2 7/3/2 8/4/2
o sides
f 1/1/3 2/2/3 6/3/3 5/4/3
f 4/1/4 8/2/4 7/3/4 3/4/4
f 1/1/5 5/2/5 8/3/5 4/4/5
f 2/1/6 3/2/6 7/3/6 6/4/6
";

#[test]
fn quad_without_normals_or_uvs() {
    let mesh = load(&write_obj("quad.obj", QUAD)).unwrap();
    assert_eq!(mesh.triangle_count(), 2);
    assert!((mesh.area() - 6.0).abs() < 1e-6);
    assert!(!mesh.has_normals() && !mesh.has_uvs());
    // Transformed on load: scale x by 2, area doubles.
    let t = Transform::scale(Vec3::new(2.0, 1.0, 1.0)).unwrap();
    let scaled = Mesh::load_obj(&write_obj("quad2.obj", QUAD), &t).unwrap();
    assert!((scaled.area() - 12.0).abs() < 1e-5);
    // Counter-clockwise from +z: the front face is +z.
    let shapes = vec![Shape::Mesh(mesh)];
    let it = Accel::build(&shapes)
        .intersect(&shapes, &Ray::new(Vec3::new(1.5, 0.5, 2.0), -Vec3::Z))
        .unwrap();
    assert!((it.n_geom - Vec3::Z).length() < 1e-6 && (it.t - 2.0).abs() < 1e-6);
}

#[test]
fn cube_with_normals_uvs_quads_and_two_objects() {
    let mesh = load(&write_obj("cube.obj", CUBE)).unwrap();
    assert_eq!(mesh.triangle_count(), 12, "6 quads, both objects merged");
    assert!((mesh.area() - 24.0).abs() < 1e-5);
    assert!(mesh.has_normals() && mesh.has_uvs());
    let shapes = vec![Shape::Mesh(mesh)];
    let accel = Accel::build(&shapes);
    for (dir, n) in [
        (-Vec3::Z, Vec3::Z),
        (Vec3::X, -Vec3::X),
        (-Vec3::Y, Vec3::Y),
    ] {
        let off = Vec3::new(0.1, 0.2, 0.3);
        let ray = Ray::new(-dir * 5.0 + off - dir * off.dot(dir), dir);
        let it = accel.intersect(&shapes, &ray).unwrap();
        assert!(
            (it.n_geom - n).length() < 1e-6,
            "outward {n}: {}",
            it.n_geom
        );
        assert!((it.n_shading - n).length() < 1e-6);
        assert!(it.uv.cmpge(Vec2::ZERO).all() && it.uv.cmple(Vec2::ONE).all());
        assert!((it.t - 4.0).abs() < 1e-5);
    }
}

#[test]
fn missing_file_error_names_the_path() {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("no/such/mesh.obj");
    let err = load(&path).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, GeometryError::MeshOpen { .. }));
    assert!(msg.starts_with("cannot open mesh "), "{msg}");
    assert!(msg.contains("no/such/mesh.obj"), "{msg}");
    // A directory is not a mesh either.
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    assert!(
        load(&dir)
            .unwrap_err()
            .to_string()
            .contains("cannot open mesh")
    );
}

#[test]
fn malformed_files_are_errors_not_panics() {
    let cases = [
        (
            "bad_number.obj",
            "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n",
            "position",
        ),
        (
            "bad_face.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
            "face",
        ),
        (
            "index_range.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
            "out of bounds",
        ),
        (
            "no_faces.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
            "no triangles",
        ),
        (
            "flat.obj",
            "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
            "zero total area",
        ),
        (
            "nan.obj",
            "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
            "not finite",
        ),
    ];
    for (name, text, expect) in cases {
        let path = write_obj(name, text);
        let err = load(&path).expect_err(name);
        let msg = err.to_string();
        assert!(
            matches!(err, GeometryError::MeshParse { .. }),
            "{name}: {msg}"
        );
        assert!(
            msg.contains(name),
            "{name}: message does not name the file: {msg}"
        );
        assert!(msg.to_lowercase().contains(expect), "{name}: {msg}");
    }
    // Unknown statements are ignored, as in other OBJ readers.
    let ok = load(&write_obj("unknown.obj", &format!("garbage here\n{QUAD}"))).unwrap();
    assert_eq!(ok.triangle_count(), 2);
}
