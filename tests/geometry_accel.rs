//! The BVH against brute force over every primitive, in a mixed scene of spheres, disks,
//! rectangles, boxes and a triangle soup.

#[path = "support/geometry.rs"]
mod geo;
mod support;

use glam::{Vec2, Vec3};
use spectrace::geometry::{Accel, Cylinder, Disk, Mesh, Ray, Shape, Sphere, Transform, spawn_ray};
use support::Rng;

fn rand_vec(rng: &mut Rng, lo: f32, hi: f32) -> Vec3 {
    Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * (hi - lo) + Vec3::splat(lo)
}

fn rand_dir(rng: &mut Rng) -> Vec3 {
    geo::sphere_dir(Vec2::new(rng.uniform(), rng.uniform()))
}

/// A random rigid transform with a (possibly non-uniform, possibly mirroring) scale.
fn rand_transform(rng: &mut Rng, scale_lo: f32, scale_hi: f32, mirror: bool) -> Transform {
    let mut s = rand_vec(rng, scale_lo, scale_hi);
    if mirror {
        s.x = -s.x;
    }
    Transform::scale(s)
        .unwrap()
        .then(&Transform::rotate(rand_dir(rng), rng.uniform() * std::f32::consts::TAU).unwrap())
        .then(&Transform::translate(rand_vec(rng, -8.0, 8.0)).unwrap())
}

fn mixed_scene(rng: &mut Rng) -> Vec<Shape> {
    let mut shapes = Vec::new();
    for _ in 0..12 {
        let c = rand_vec(rng, -9.0, 9.0);
        shapes.push(Shape::Sphere(
            Sphere::new(c, 0.1 + 1.9 * rng.uniform()).unwrap(),
        ));
    }
    for i in 0..6 {
        let t = rand_transform(rng, 0.3, 2.0, i % 3 == 0);
        shapes.push(Shape::Disk(Disk::new(&t, 0.5 + rng.uniform()).unwrap()));
    }
    for i in 0..5 {
        shapes.push(Shape::Mesh(Mesh::cuboid(&rand_transform(
            rng,
            0.2,
            2.0,
            i == 0,
        ))));
    }
    for _ in 0..3 {
        shapes.push(Shape::Mesh(Mesh::rectangle(&rand_transform(
            rng, 0.5, 3.0, false,
        ))));
    }
    // A triangle soup of 300 small triangles.
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for k in 0..300u32 {
        let c = rand_vec(rng, -9.0, 9.0);
        for _ in 0..3 {
            positions.push(c + rand_vec(rng, -0.8, 0.8));
        }
        indices.push([3 * k, 3 * k + 1, 3 * k + 2]);
    }
    let soup = Mesh::new(positions, None, None, indices, &Transform::identity()).unwrap();
    shapes.push(Shape::Mesh(soup));
    // open cylinders of random axes (after every index the tests name)
    for i in 0..4 {
        let (p0, p1) = (rand_vec(rng, -8.0, 8.0), rand_vec(rng, -8.0, 8.0));
        let r = 0.2 + 1.2 * rng.uniform();
        shapes.push(Shape::Cylinder(
            Cylinder::new(p0, p1, r, i % 2 == 1).unwrap(),
        ));
    }
    shapes
}

/// Compares one ray; returns a description of the disagreement, if any.
fn compare(accel: &Accel, shapes: &[Shape], ray: &Ray) -> Option<String> {
    let got = accel.intersect(shapes, ray);
    let want = geo::brute_force(shapes, ray);
    match (got, want) {
        (None, None) => None,
        (Some(g), Some((s, i, t))) => {
            if g.t != t {
                return Some(format!(
                    "t {} vs brute force {t} ({s}, {i}) for {ray:?}",
                    g.t
                ));
            }
            let off = (g.p - ray.at(g.t)).length();
            if off > 1e-3 * (1.0 + g.t) {
                return Some(format!("hit point {} is {off} m off the ray", g.p));
            }
            if (g.shape as usize, g.prim as usize) != (s, i) {
                // Only acceptable for an exact tie (shared edges of a box).
                let ray_t = Ray {
                    t_max: f32::INFINITY,
                    ..*ray
                };
                let other = shapes[g.shape as usize].intersect_primitive(g.prim as usize, &ray_t);
                if other.map(|h| h.0) != Some(t) {
                    return Some(format!("primitive {:?} vs {:?}", (g.shape, g.prim), (s, i)));
                }
            }
            None
        }
        (g, w) => Some(format!(
            "BVH {:?} vs brute force {w:?} for {ray:?}",
            g.map(|h| (h.shape, h.prim, h.t))
        )),
    }
}

#[test]
fn closest_hit_matches_brute_force() {
    closest_hit_matches_brute_force_with(Accel::build);
}

/// Large scenes are built in parts (a top tree over separately built parts); parts of 8
/// primitives make this small scene take that path, with about 45 parts.
#[test]
fn closest_hit_matches_brute_force_when_built_in_parts() {
    closest_hit_matches_brute_force_with(|s| Accel::build_with(s, 8, 8));
}

/// The 4-wide tree (CPUs without AVX; the default above is 8-wide where AVX exists).
#[test]
fn closest_hit_matches_brute_force_four_wide() {
    closest_hit_matches_brute_force_with(|s| Accel::build_with(s, 1 << 19, 4));
    closest_hit_matches_brute_force_with(|s| Accel::build_with(s, 8, 4));
}

fn closest_hit_matches_brute_force_with(build: impl Fn(&[Shape]) -> Accel) {
    let mut rng = Rng::new(2024);
    let shapes = mixed_scene(&mut rng);
    let accel = build(&shapes);
    let prims: usize = shapes.iter().map(Shape::primitive_count).sum();
    assert_eq!(accel.primitive_count(), prims);
    let (mut failures, mut hits, mut n) = (Vec::new(), 0, 0);
    for i in 0..20000 {
        let o = rand_vec(&mut rng, -12.0, 12.0);
        let mut d = rand_dir(&mut rng);
        if i % 10 == 0 {
            // Nearly axis-aligned directions (tiny reciprocal components).
            let axis = (i / 10) % 3;
            d = Vec3::AXES[axis] * if i % 20 == 0 { 1.0 } else { -1.0 } + d * 1e-7;
            d = d.normalize();
        }
        let ray = Ray::new(o, d);
        n += 1;
        failures.extend(compare(&accel, &shapes, &ray));
        // A secondary ray spawned from the hit, as a path tracer would.
        if let Some(it) = accel.intersect(&shapes, &ray) {
            hits += 1;
            let next = spawn_ray(it.p, it.p_error, it.n_geom, rand_dir(&mut rng));
            n += 1;
            failures.extend(compare(&accel, &shapes, &next));
        }
    }
    assert!(hits > 2000, "scene too sparse: {hits} hits");
    assert!(
        failures.is_empty(),
        "{} of {n} rays disagree, first: {:?}",
        failures.len(),
        &failures[..failures.len().min(3)]
    );
}

#[test]
fn occluded_agrees_with_intersect_for_bounded_rays() {
    let mut rng = Rng::new(77);
    let shapes = mixed_scene(&mut rng);
    let accel = Accel::build(&shapes);
    let (mut mismatches, mut occluded) = (0, 0);
    for _ in 0..20000 {
        let mut ray = Ray::new(rand_vec(&mut rng, -12.0, 12.0), rand_dir(&mut rng));
        ray.t_max = 20.0 * rng.uniform();
        let occ = accel.occluded(&shapes, &ray);
        let hit = accel.intersect(&shapes, &ray);
        let brute = geo::brute_force(&shapes, &ray);
        if occ != hit.is_some() || occ != brute.is_some() {
            mismatches += 1;
        }
        if let Some(h) = hit {
            assert!(
                h.t > 0.0 && h.t < ray.t_max,
                "t {} outside (0, {})",
                h.t,
                ray.t_max
            );
        }
        occluded += occ as u32;
    }
    assert!(occluded > 1000 && occluded < 19000, "{occluded} occluded");
    assert_eq!(mismatches, 0);
}

#[test]
fn normals_are_outward_and_hit_points_on_the_surface() {
    let mut rng = Rng::new(5);
    let shapes = mixed_scene(&mut rng);
    let accel = Accel::build(&shapes);
    for _ in 0..5000 {
        let ray = Ray::new(rand_vec(&mut rng, -12.0, 12.0), rand_dir(&mut rng));
        let Some(it) = accel.intersect(&shapes, &ray) else {
            continue;
        };
        assert!((it.n_geom.length() - 1.0).abs() < 1e-5);
        assert!(it.n_shading.dot(it.n_geom) > 0.0);
        match &shapes[it.shape as usize] {
            Shape::Sphere(s) => {
                let r = it.p - s.center();
                assert!((r.length() - s.radius()).abs() <= it.p_error.length() * 2.0);
                assert!(
                    r.normalize().dot(it.n_geom) > 0.9999,
                    "sphere normal outward"
                );
            }
            Shape::Disk(d) => {
                assert!((it.n_geom - d.normal()).length() < 1e-6);
                assert!((it.p - d.center()).dot(d.normal()).abs() < 1e-5);
            }
            Shape::Mesh(_)
            | Shape::Cylinder(_)
            | Shape::Curve(_)
            | Shape::BSpline(_)
            | Shape::SdfGrid(_) => {}
        }
    }
    // Box normals point outward even for the mirrored box (shape index 18).
    let Shape::Mesh(mirrored) = &shapes[18] else {
        panic!("shape 18 is the mirrored box")
    };
    let centre = mirrored.positions().iter().copied().sum::<Vec3>() / 24.0;
    let single = &shapes[18..19];
    let box_accel = Accel::build(single);
    for _ in 0..200 {
        let d = rand_dir(&mut rng);
        let it = box_accel
            .intersect(single, &Ray::new(centre - d * 40.0, d))
            .expect("ray through the box centre hits it");
        assert!(
            (it.p - centre).dot(it.n_geom) > 0.0,
            "box normal points outward"
        );
        assert!(it.n_geom.dot(d) < 0.0, "front face seen from outside");
    }
}

#[test]
fn empty_and_single_shape_scenes() {
    let accel = Accel::build(&[]);
    let ray = Ray::new(Vec3::ZERO, Vec3::Z);
    assert!(accel.intersect(&[], &ray).is_none());
    assert!(!accel.occluded(&[], &ray));
    assert!(accel.bounds().is_none());

    let shapes = vec![Shape::Sphere(
        Sphere::new(Vec3::new(0.0, 0.0, 5.0), 1.0).unwrap(),
    )];
    let accel = Accel::build(&shapes);
    let it = accel.intersect(&shapes, &ray).unwrap();
    assert!((it.t - 4.0).abs() < 1e-5 && it.shape == 0 && it.prim == 0);
    let (lo, hi) = accel.bounds().unwrap();
    assert!(lo.cmple(Vec3::new(-1.0, -1.0, 4.0)).all() && hi.cmpge(Vec3::new(1.0, 1.0, 6.0)).all());
    // Bounded rays stop short; NaN rays hit nothing and do not panic.
    assert!(!accel.occluded(&shapes, &Ray { t_max: 3.9, ..ray }));
    assert!(accel.occluded(&shapes, &Ray { t_max: 4.1, ..ray }));
    let nan = Ray {
        o: Vec3::NAN,
        ..ray
    };
    assert!(accel.intersect(&shapes, &nan).is_none() && !accel.occluded(&shapes, &nan));
}
