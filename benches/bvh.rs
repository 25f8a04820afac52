//! BVH rays per second: closest-hit camera rays and any-hit shadow rays in the Cornell box
//! (triangles only, the baseline for ratios) and in the same box with 64 spheres and 16 disks
//! added (mixed analytic and triangle primitives).

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use spectrace::build::build;
use spectrace::geometry::{Ray, spawn_ray_to};
use spectrace::scene::Scene;

fn cornell(extra: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.toml");
    let text = std::fs::read_to_string(&path).expect("cornell.toml") + extra;
    let desc = spectrace::loader::load_str(&text, &path).expect("loads");
    build(&desc).expect("builds")
}

fn mixed() -> Scene {
    let mut extra = String::new();
    for i in 0..64 {
        let (x, z) = (60.0 + (i % 8) as f32 * 60.0, 60.0 + (i / 8) as f32 * 60.0);
        extra += &format!(
            "\n[[shapes]]\ntype = \"sphere\"\ncenter = [{x}, 420, {z}]\nradius = 18\nmaterial = \"white\"\n"
        );
    }
    for i in 0..16 {
        let (x, z) = (80.0 + (i % 4) as f32 * 120.0, 80.0 + (i / 4) as f32 * 120.0);
        extra += &format!(
            "\n[[shapes]]\ntype = \"disk\"\nmaterial = \"white\"\ntransform = [{{ scale = 25 }}, {{ rotate = {{ axis = [1, 0, 0], angle = \"90 deg\" }} }}, {{ translate = [{x}, 300, {z}] }}]\n"
        );
    }
    cornell(&extra)
}

fn camera_rays(s: &Scene) -> Vec<Ray> {
    let (w, h) = (64u32, 64u32);
    let (fw, fh) = (s.film.width as f32, s.film.height as f32);
    (0..w * h)
        .map(|i| {
            let raster = Vec2::new(
                ((i % w) as f32 + 0.5) * fw / w as f32,
                ((i / w) as f32 + 0.5) * fh / h as f32,
            );
            s.camera.generate_ray(raster, Vec2::splat(0.5))
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    for (name, scene) in [
        ("cornell_triangles", cornell("")),
        ("cornell_mixed", mixed()),
    ] {
        let rays = camera_rays(&scene);
        let light = Vec3::new(0.278, 0.5486, 0.2795);
        let shadow: Vec<Ray> = rays
            .iter()
            .filter_map(|r| scene.accel.intersect(&scene.shapes, r))
            .map(|h| spawn_ray_to(h.p, h.p_error, h.n_geom, light, Vec3::ZERO, Vec3::NEG_Y))
            .collect();
        let mut g = c.benchmark_group(name);
        g.throughput(Throughput::Elements(rays.len() as u64));
        g.bench_function("closest_hit", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| scene.accel.intersect(&scene.shapes, black_box(r)).is_some())
                    .count()
            })
        });
        g.throughput(Throughput::Elements(shadow.len() as u64));
        g.bench_function("any_hit", |b| {
            b.iter(|| {
                shadow
                    .iter()
                    .filter(|r| scene.accel.occluded(&scene.shapes, black_box(r)))
                    .count()
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
