//! Shapes: areas against closed forms, area sampling (on the surface, pdf = 1/area, uniform),
//! and mesh validation.

mod support;

use glam::{Vec2, Vec3};
use spectrace::geometry::{
    Accel, Disk, GeometryError, Mesh, Ray, Shape, Sphere, SurfaceSample, Transform,
};
use std::f32::consts::PI;
use support::Rng;

const N: usize = 20000;

fn rotated(scale: Vec3, translate: Vec3) -> Transform {
    Transform::scale(scale)
        .unwrap()
        .then(&Transform::rotate(Vec3::new(0.3, -0.4, 0.9), 1.2).unwrap())
        .then(&Transform::translate(translate).unwrap())
}

fn samples(shape: &Shape, seed: u64) -> Vec<SurfaceSample> {
    let mut rng = Rng::new(seed);
    (0..N)
        .map(|_| shape.sample_area(Vec2::new(rng.uniform(), rng.uniform())))
        .collect()
}

/// Asserts that the mean of `f` over the samples is `expected` within 4 standard errors.
fn assert_mean(what: &str, values: impl Iterator<Item = f64>, expected: f64) {
    let v: Vec<f64> = values.collect();
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let se = (var / n).sqrt().max(1e-12);
    assert!(
        (mean - expected).abs() < 4.0 * se,
        "{what}: mean {mean} vs expected {expected} (SE {se}, {:.1} SE off)",
        (mean - expected).abs() / se
    );
}

fn assert_close(what: &str, got: f32, want: f32, rel: f32) {
    assert!(
        (got - want).abs() <= rel * want.abs(),
        "{what}: {got} vs closed form {want}"
    );
}

#[test]
fn areas_match_closed_forms() {
    let sphere = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 2.5).unwrap();
    assert_close(
        "sphere",
        Shape::Sphere(sphere).area(),
        4.0 * PI * 6.25,
        1e-6,
    );
    let t = Transform::scale(Vec3::splat(2.0))
        .unwrap()
        .then(&Transform::rotate(Vec3::X, 0.3).unwrap())
        .then(&Transform::translate(Vec3::new(5.0, 0.0, 0.0)).unwrap());
    let s = Sphere::with_transform(&t, 1.5).unwrap();
    assert_close("transformed sphere radius", s.radius(), 3.0, 1e-6);
    assert!((s.center() - Vec3::new(5.0, 0.0, 0.0)).length() < 1e-6);

    let disk = Disk::new(&rotated(Vec3::new(2.0, 3.0, 5.0), Vec3::ONE), 0.7).unwrap();
    assert_close("elliptic disk", disk.area(), PI * 1.4 * 2.1, 1e-5);

    let rect = Mesh::rectangle(&rotated(Vec3::new(2.0, 0.5, 7.0), Vec3::ONE));
    assert_close("rectangle", rect.area(), 4.0 * 2.0 * 0.5, 1e-5);
    assert_eq!(rect.triangle_count(), 2);

    for mirror in [1.0, -1.0] {
        let cube = Mesh::cuboid(&rotated(Vec3::new(mirror, 2.0, 3.0), Vec3::ONE));
        assert_close("cuboid", cube.area(), 8.0 * (2.0 + 6.0 + 3.0), 1e-5);
        assert_eq!(cube.triangle_count(), 12);
    }
}

#[test]
fn sphere_samples_are_on_the_surface_and_uniform() {
    let (c, r) = (Vec3::new(-3.0, 7.0, 100.0), 2.0);
    let shape = Shape::Sphere(Sphere::new(c, r).unwrap());
    let s = samples(&shape, 1);
    for x in &s {
        let d = x.p - c;
        assert!(
            (d.length() - r).abs() <= x.p_error.length() + 1e-6,
            "on sphere"
        );
        assert!((d / r - x.n).length() < 1e-5, "outward normal");
        assert_eq!(x.pdf_area, 1.0 / shape.area());
    }
    for axis in 0..3 {
        assert_mean(
            "sphere mean",
            s.iter().map(|x| f64::from(x.p[axis] - c[axis])),
            0.0,
        );
        // E[z²] = r²/3 for a uniform sphere (a uniform-in-θ sampler gives r²/2).
        let m2 = s.iter().map(|x| f64::from((x.p[axis] - c[axis]).powi(2)));
        assert_mean("sphere second moment", m2, f64::from(r * r) / 3.0);
    }
}

#[test]
fn disk_samples_are_on_the_surface_and_uniform() {
    let t = rotated(Vec3::new(2.0, 0.5, 1.0), Vec3::new(4.0, -1.0, 2.0));
    let shape = Shape::Disk(Disk::new(&t, 1.5).unwrap());
    let Shape::Disk(disk) = &shape else {
        unreachable!()
    };
    let inv = t.inverse();
    let s = samples(&shape, 2);
    for x in &s {
        let local = inv.point(x.p);
        assert!(local.z.abs() < 1e-5, "in the disk plane: {local}");
        assert!(
            local.truncate().length() <= 1.5 * (1.0 + 1e-5),
            "inside the disk"
        );
        assert_eq!(x.n, disk.normal());
        assert_eq!(x.pdf_area, 1.0 / shape.area());
    }
    let local: Vec<Vec3> = s.iter().map(|x| inv.point(x.p) / 1.5).collect();
    assert_mean("disk mean x", local.iter().map(|p| f64::from(p.x)), 0.0);
    assert_mean("disk mean y", local.iter().map(|p| f64::from(p.y)), 0.0);
    // E[ρ²] = 1/2 for uniform area sampling (uniform in ρ gives 1/3).
    let rho2 = local
        .iter()
        .map(|p| f64::from(p.truncate().length_squared()));
    assert_mean("disk E[rho^2]", rho2, 0.5);
}

#[test]
fn rectangle_and_cuboid_samples_are_on_the_surface_and_uniform() {
    let t = rotated(Vec3::new(3.0, 1.0, 0.5), Vec3::new(0.0, 10.0, -2.0));
    let rect = Shape::Mesh(Mesh::rectangle(&t));
    let inv = t.inverse();
    let n = t.normal(Vec3::Z).normalize();
    let s = samples(&rect, 3);
    for x in &s {
        let l = inv.point(x.p);
        assert!(l.z.abs() < 1e-5 && l.x.abs() <= 1.0 + 1e-5 && l.y.abs() <= 1.0 + 1e-5);
        assert!((x.n - n).length() < 1e-5, "rectangle normal +z");
    }
    assert_mean("rect x", s.iter().map(|x| f64::from(inv.point(x.p).x)), 0.0);
    assert_mean("rect y", s.iter().map(|x| f64::from(inv.point(x.p).y)), 0.0);
    assert_mean(
        "rect E[x²]",
        s.iter().map(|x| f64::from(inv.point(x.p).x.powi(2))),
        1.0 / 3.0,
    );

    // Box with faces of areas 24 (±x), 12 (±y), 8 (±z): each face gets its share of samples.
    let t = rotated(Vec3::new(1.0, 2.0, 3.0), Vec3::new(-5.0, 0.0, 1.0));
    let cube = Shape::Mesh(Mesh::cuboid(&t));
    let inv = t.inverse();
    let s = samples(&cube, 4);
    let mut counts = [[0u32; 2]; 3];
    for x in &s {
        let l = inv.point(x.p);
        let axis = l.abs().max_position();
        assert!((l[axis].abs() - 1.0).abs() < 1e-5, "on a face: {l}");
        let side = usize::from(l[axis] < 0.0);
        counts[axis][side] += 1;
        let face_n = t.normal(Vec3::AXES[axis] * l[axis].signum()).normalize();
        assert!((x.n - face_n).length() < 1e-5, "outward face normal");
        assert_eq!(x.pdf_area, 1.0 / 88.0);
    }
    for (axis, area) in [24.0, 12.0, 8.0].into_iter().enumerate() {
        for side in 0..2 {
            let on_face = s.iter().map(|x| {
                let l = inv.point(x.p);
                let hit = l.abs().max_position() == axis && usize::from(l[axis] < 0.0) == side;
                f64::from(u8::from(hit))
            });
            assert_mean("face share", on_face, area / 88.0);
        }
    }
    assert!(counts.iter().flatten().all(|&c| c > 0));
}

#[test]
fn mesh_samples_pick_triangles_by_area() {
    // One big triangle (area 50) and one small (area 0.5), far apart: the mean position is the
    // area-weighted centroid (picking triangles uniformly would put it halfway).
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(10.0, 0.0, 0.0),
        Vec3::new(0.0, 10.0, 0.0),
        Vec3::new(100.0, 0.0, 0.0),
        Vec3::new(101.0, 0.0, 0.0),
        Vec3::new(100.0, 1.0, 0.0),
    ];
    let mesh = Mesh::new(
        positions,
        None,
        None,
        vec![[0, 1, 2], [3, 4, 5]],
        &Transform::identity(),
    );
    let shape = Shape::Mesh(mesh.unwrap());
    assert_close("two triangles", shape.area(), 50.5, 1e-6);
    let s = samples(&shape, 5);
    let centroid_x = (50.0 * 10.0 / 3.0 + 0.5 * (100.0 + 1.0 / 3.0)) / 50.5;
    assert_mean(
        "area-weighted centroid",
        s.iter().map(|x| f64::from(x.p.x)),
        centroid_x,
    );
    assert!(s.iter().all(|x| x.pdf_area == 1.0 / 50.5 && x.p.z == 0.0));
}

#[test]
fn mesh_shading_normals_and_uvs_interpolate() {
    // A rectangle whose vertex normals lean outward and whose winding faces -z: the geometric
    // normal follows the vertex normals (+z side), the shading normal interpolates them.
    let positions = vec![
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
    ];
    let normals: Vec<Vec3> = positions
        .iter()
        .map(|p| (*p * 0.5 + Vec3::Z).normalize())
        .collect();
    let uvs = vec![
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(0.0, 1.0),
    ];
    let indices = vec![[0, 1, 2], [0, 3, 1]];
    let mesh = Mesh::new(
        positions,
        Some(normals),
        Some(uvs),
        indices,
        &Transform::identity(),
    );
    let shapes = vec![Shape::Mesh(mesh.unwrap())];
    let accel = Accel::build(&shapes);
    let it = accel
        .intersect(&shapes, &Ray::new(Vec3::new(0.5, -0.5, 1.0), -Vec3::Z))
        .unwrap();
    assert!(
        (it.n_geom - Vec3::Z).length() < 1e-6,
        "n_geom follows vertex normals"
    );
    let want = Vec3::new(0.25, -0.25, 1.0).normalize();
    assert!(
        (it.n_shading - want).length() < 0.02,
        "interpolated {}",
        it.n_shading
    );
    assert!(
        (it.uv - Vec2::new(0.75, 0.25)).length() < 1e-5,
        "uv {}",
        it.uv
    );
    assert!((it.p - Vec3::new(0.5, -0.5, 0.0)).length() < 1e-6);
}

#[test]
fn mesh_validation_errors() {
    let tri = || vec![Vec3::ZERO, Vec3::X, Vec3::Y];
    let id = Transform::identity();
    let err = |r: Result<Mesh, GeometryError>| r.unwrap_err().to_string();

    assert!(err(Mesh::new(tri(), None, None, vec![], &id)).contains("no triangles"));
    let e = err(Mesh::new(tri(), None, None, vec![[0, 1, 3]], &id));
    assert!(e.contains("index 3") && e.contains("3 vertices"), "{e}");
    let e = err(Mesh::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::NAN],
        None,
        None,
        vec![[0, 1, 2]],
        &id,
    ));
    assert!(e.contains("position 2") && e.contains("not finite"), "{e}");
    let e = err(Mesh::new(
        tri(),
        Some(vec![Vec3::Z]),
        None,
        vec![[0, 1, 2]],
        &id,
    ));
    assert!(e.contains("3 positions but 1 normals"), "{e}");
    let e = err(Mesh::new(
        tri(),
        None,
        Some(vec![Vec2::INFINITY; 3]),
        vec![[0, 1, 2]],
        &id,
    ));
    assert!(e.contains("uv 0"), "{e}");
    let collinear = vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
    let e = err(Mesh::new(
        collinear,
        None,
        None,
        vec![[0, 1, 2], [0, 0, 1]],
        &id,
    ));
    assert!(e.contains("zero total area"), "{e}");

    // Degenerate triangles are dropped, the rest kept.
    let mesh = Mesh::new(tri(), None, None, vec![[0, 1, 2], [0, 0, 1]], &id).unwrap();
    assert_eq!(mesh.triangle_count(), 1);
    assert_close("kept area", mesh.area(), 0.5, 1e-7);
}

/// The cube's uv and ∂p/∂u, ∂p/∂v on each face as Mitsuba 3.9.1's `cube` reports them (values
/// measured with `scene.ray_intersect` on the unit cube), so that textures and anisotropic lobes
/// on cubes read as in Mitsuba.
#[test]
fn cube_uv_matches_mitsuba() {
    use spectrace::geometry::{Accel, Ray};
    let shapes = vec![Shape::Mesh(Mesh::cuboid(&Transform::identity()))];
    let accel = Accel::build(&shapes);
    // (origin, direction, uv, ∂p/∂u, ∂p/∂v)
    type Case = ([f32; 3], [f32; 3], [f32; 2], [f32; 3], [f32; 3]);
    let cases: [Case; 6] = [
        (
            [0.3, 0.2, 5.0],
            [0.0, 0.0, -1.0],
            [0.6, 0.65],
            [0.0, 2.0, 0.0],
            [2.0, 0.0, 0.0],
        ),
        (
            [0.3, 5.0, 0.2],
            [0.0, -1.0, 0.0],
            [0.35, 0.4],
            [-2.0, 0.0, 0.0],
            [0.0, 0.0, -2.0],
        ),
        (
            [5.0, 0.3, 0.2],
            [-1.0, 0.0, 0.0],
            [0.65, 0.4],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, -2.0],
        ),
        (
            [0.3, 0.2, -5.0],
            [0.0, 0.0, 1.0],
            [0.4, 0.65],
            [0.0, -2.0, 0.0],
            [2.0, 0.0, 0.0],
        ),
        (
            [0.3, -5.0, 0.2],
            [0.0, 1.0, 0.0],
            [0.6, 0.65],
            [0.0, 0.0, 2.0],
            [2.0, 0.0, 0.0],
        ),
        (
            [-5.0, 0.3, 0.2],
            [1.0, 0.0, 0.0],
            [0.65, 0.6],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 2.0],
        ),
    ];
    for (o, d, uv, du, dv) in cases {
        let h = accel
            .intersect(&shapes, &Ray::new(Vec3::from(o), Vec3::from(d)))
            .expect("hits the cube");
        let ok = |a: Vec3, b: [f32; 3]| (a - Vec3::from(b)).length() < 1e-4;
        assert!(
            (h.uv - glam::Vec2::from(uv)).length() < 1e-5,
            "{o:?}: uv {}",
            h.uv
        );
        assert!(
            ok(h.dpdu, du) && ok(h.dpdv, dv),
            "{o:?}: ∂p/∂u {}, ∂p/∂v {}",
            h.dpdu,
            h.dpdv
        );
        assert!(h.n_geom.dot(-Vec3::from(d)) > 0.99, "outward normal");
    }
}

/// A mesh without uvs is parameterised by its barycentrics, uv = (b₁, b₂), as Mitsuba 3.9.1
/// does (measured: the triangle (0,0,0), (2,0,0), (0,3,0) hit at (0.5, 0.5) has uv
/// (0.25, 0.1667), ∂p/∂u (2, 0, 0), ∂p/∂v (0, 3, 0)).
#[test]
fn mesh_without_uvs_uses_mitsuba_barycentric_uv() {
    use spectrace::geometry::{Accel, Ray};
    let mesh = Mesh::new(
        vec![
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 3.0, 0.0),
        ],
        None,
        None,
        vec![[0, 1, 2]],
        &Transform::identity(),
    )
    .unwrap();
    let shapes = vec![Shape::Mesh(mesh)];
    let accel = Accel::build(&shapes);
    let h = accel
        .intersect(&shapes, &Ray::new(Vec3::new(0.5, 0.5, 1.0), -Vec3::Z))
        .expect("hits the triangle");
    assert!(
        (h.uv - glam::Vec2::new(0.25, 1.0 / 6.0)).length() < 1e-5,
        "uv {}",
        h.uv
    );
    assert!(
        (h.dpdu - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-5,
        "{}",
        h.dpdu
    );
    assert!(
        (h.dpdv - Vec3::new(0.0, 3.0, 0.0)).length() < 1e-5,
        "{}",
        h.dpdv
    );
}
