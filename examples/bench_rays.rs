//! Ray-casting throughput of spectrace's BVH on fixed ray batches, for the comparison with
//! Embree 4 in `scripts/bench_embree.py` (which runs this example and reads the files it writes).
//!
//! ```text
//! cargo run --release --example bench_rays -- [--scene FILE] [--size N] [--reps R] [--out DIR]
//! ```
//!
//! Defaults: `benchmarks/scenes/heightfield.xml` (run `python3 scripts/gen_heightfield.py` first
//! if `benchmarks/scenes/heightfield.ply` is missing), `--size 1024`, `--reps 5`,
//! `--out target/bench`.
//!
//! Ray batches, deterministic (no dependence on threads, time or a random seed):
//! * `camera`: one ray per pixel centre of a SIZE×SIZE image from the scene's camera (the film
//!   resolution of the scene file is replaced by SIZE×SIZE before the scene is built), pixels in
//!   row-major order from the top-left.
//! * `diffuse`: one ray per camera ray that hits something: from the closest hit, a
//!   cosine-distributed direction about the geometric normal turned toward the side the camera
//!   ray came from (random numbers from a hash of the pixel index), origin offset along that
//!   normal with the hit's error bound exactly as the renderer spawns a bounce
//!   (`geometry::spawn_ray`).
//!
//! Queries, each timed single-threaded over the whole batch, REPS times (best and median):
//! * `closest`: `Accel::intersect` with `t_max = ∞`.
//! * `occluded`: `Accel::occluded` on the same origins and directions with a finite `t_max`:
//!   0.999 × the ray's own closest-hit distance (found by the `closest` query), or, for rays
//!   that hit nothing, the distance at which the ray leaves the scene's bounding sphere. Every
//!   occlusion ray is therefore unoccluded by construction (a shadow ray toward a visible point:
//!   the any-hit query cannot stop early and must traverse up to `t_max`). The count of occluded
//!   rays should be 0 or a handful of rays that graze a second surface within 0.1% of their hit.
//!
//! Files written to OUT (all little-endian, no headers; the ray count is size / record size):
//! * `rays_{camera,diffuse}.bin`: per ray 7 × f32: ox, oy, oz, dx, dy, dz, t_max with
//!   t_max = f32::INFINITY (the closest-hit batch).
//! * `rays_{camera,diffuse}_occluded.bin`: the same rays with the finite occlusion t_max.
//! * `hits_{camera,diffuse}.bin`: per ray f32, spectrace's closest-hit distance (∞ for a miss).
//! * `occluded_{camera,diffuse}.bin`: per ray u8, 1 if spectrace reports the occlusion ray
//!   occluded.
//! * `triangles.bin`: the triangles the BVH indexes, world space (after `to_world`), as the
//!   renderer holds them: u64 vertex count V, u64 triangle count T, V × 3 f32 positions, T × 3 u32
//!   vertex indices (all meshes of the scene concatenated, indices offset accordingly).
//!
//! Output: lines `RESULT batch=… query=… rays=… best_s=… median_s=… mrays_best=…
//! mrays_median=… hits=… tsum=…` (hits: rays that hit / are occluded; tsum: sum of closest-hit
//! distances in metres, closest query only), which the script parses.

use std::hint::black_box;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::{Vec2, Vec3};
use spectrace::geometry::{Frame, Ray, Shape, spawn_ray};
use spectrace::sampling::cosine_hemisphere;
use spectrace::scene::Scene;

/// SplitMix64's finaliser: a well-mixed 64-bit hash.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A uniform number in [0, 1) from (index, dimension).
fn hash01(index: u64, dim: u64) -> f32 {
    let h = mix64(index.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ mix64(dim + 0x5eed));
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}

struct Args {
    scene: PathBuf,
    size: u32,
    reps: usize,
    out: PathBuf,
}

fn parse_args() -> Args {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut a = Args {
        scene: root.join("benchmarks/scenes/heightfield.xml"),
        size: 1024,
        reps: 5,
        out: root.join("target/bench"),
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || {
            it.next().unwrap_or_else(|| {
                eprintln!("{flag} needs a value");
                std::process::exit(2)
            })
        };
        match flag.as_str() {
            "--scene" => a.scene = value().into(),
            "--size" => a.size = value().parse().expect("--size is a number"),
            "--reps" => a.reps = value().parse().expect("--reps is a number"),
            "--out" => a.out = value().into(),
            _ => {
                eprintln!(
                    "usage: bench_rays [--scene FILE] [--size N] [--reps R] [--out DIR] (unknown: {flag})"
                );
                std::process::exit(2)
            }
        }
    }
    assert!(
        a.size > 0 && a.reps > 0,
        "--size and --reps must be positive"
    );
    a
}

fn load(path: &Path, size: u32) -> Scene {
    let mut desc = spectrace::loader::load_any(path, &[]).unwrap_or_else(|e| {
        eprintln!("{e}");
        eprintln!("(for the height field: python3 scripts/gen_heightfield.py)");
        std::process::exit(1)
    });
    desc.film.width = size;
    desc.film.height = size;
    spectrace::build::build(&desc).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    })
}

fn write_file(path: &Path, bytes: &[u8]) {
    let mut f = std::fs::File::create(path)
        .unwrap_or_else(|e| panic!("cannot create {}: {e}", path.display()));
    f.write_all(bytes).expect("writes");
}

fn write_rays(path: &Path, rays: &[Ray]) {
    let mut b = Vec::with_capacity(rays.len() * 28);
    for r in rays {
        for x in [r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.t_max] {
            b.extend_from_slice(&x.to_le_bytes());
        }
    }
    write_file(path, &b);
}

/// The triangles of every mesh, concatenated. Panics if the scene has analytic shapes (Embree
/// would need user geometry for them) or if the BVH indexes a different number of primitives.
fn write_triangles(path: &Path, scene: &Scene) -> usize {
    let (mut pos, mut idx): (Vec<Vec3>, Vec<[u32; 3]>) = (Vec::new(), Vec::new());
    for s in &scene.shapes {
        match s {
            Shape::Mesh(m) => {
                let base = pos.len() as u32;
                pos.extend_from_slice(m.positions());
                idx.extend(m.indices().iter().map(|t| t.map(|v| v + base)));
            }
            _ => panic!("bench_rays handles triangle meshes only (the scene has a sphere or disk)"),
        }
    }
    assert_eq!(
        idx.len(),
        scene.accel.primitive_count(),
        "the BVH indexes a different set of triangles than the meshes hold"
    );
    let mut b = Vec::with_capacity(16 + pos.len() * 12 + idx.len() * 12);
    b.extend_from_slice(&(pos.len() as u64).to_le_bytes());
    b.extend_from_slice(&(idx.len() as u64).to_le_bytes());
    for p in &pos {
        for x in [p.x, p.y, p.z] {
            b.extend_from_slice(&x.to_le_bytes());
        }
    }
    for t in &idx {
        for v in t {
            b.extend_from_slice(&v.to_le_bytes());
        }
    }
    write_file(path, &b);
    idx.len()
}

struct Timing {
    best: f64,
    median: f64,
}

/// Runs `f` `reps` times; returns the timing and the result of the last run.
fn time<T>(reps: usize, mut f: impl FnMut() -> T) -> (Timing, T) {
    let mut secs = Vec::with_capacity(reps);
    let mut last = None;
    for _ in 0..reps {
        let t = Instant::now();
        let r = f();
        secs.push(t.elapsed().as_secs_f64());
        last = Some(r);
    }
    secs.sort_by(f64::total_cmp);
    let timing = Timing {
        best: secs[0],
        median: secs[secs.len() / 2],
    };
    (timing, last.expect("reps > 0"))
}

fn report(batch: &str, query: &str, n: usize, t: &Timing, hits: usize, tsum: f64) {
    println!(
        "RESULT batch={batch} query={query} rays={n} best_s={:.6} median_s={:.6} \
         mrays_best={:.4} mrays_median={:.4} hits={hits} tsum={tsum:.9e}",
        t.best,
        t.median,
        n as f64 / t.best / 1e6,
        n as f64 / t.median / 1e6,
    );
}

fn main() {
    let args = parse_args();
    std::fs::create_dir_all(&args.out).expect("creates the output directory");
    let t0 = Instant::now();
    let scene = load(&args.scene, args.size);
    eprintln!(
        "{}: {} primitives, loaded and BVH built in {:.2} s",
        args.scene.display(),
        scene.accel.primitive_count(),
        t0.elapsed().as_secs_f64()
    );
    let ntri = write_triangles(&args.out.join("triangles.bin"), &scene);
    let (centre, radius) = scene.bounding_sphere();
    let (w, h) = (args.size, args.size);

    let camera: Vec<Ray> = (0..w * h)
        .map(|i| {
            let raster = Vec2::new((i % w) as f32 + 0.5, (i / w) as f32 + 0.5);
            scene.camera.generate_ray(raster, Vec2::splat(0.5))
        })
        .collect();
    let diffuse: Vec<Ray> = camera
        .iter()
        .enumerate()
        .filter_map(|(i, r)| {
            let it = scene.accel.intersect(&scene.shapes, r)?;
            let n = if it.n_geom.dot(r.d) > 0.0 {
                -it.n_geom
            } else {
                it.n_geom
            };
            let u = Vec2::new(hash01(i as u64, 0), hash01(i as u64, 1));
            let wi = Frame::from_normal(n).to_world(cosine_hemisphere(u));
            Some(spawn_ray(it.p, it.p_error, n, wi))
        })
        .collect();
    eprintln!(
        "{ntri} triangles; {} camera rays, {} diffuse rays; {} repetitions, single-threaded",
        camera.len(),
        diffuse.len(),
        args.reps
    );

    for (batch, rays) in [("camera", &camera), ("diffuse", &diffuse)] {
        write_rays(&args.out.join(format!("rays_{batch}.bin")), rays);
        // Warm-up (page faults, caches), untimed.
        for r in rays.iter().take(10_000) {
            black_box(scene.accel.intersect(&scene.shapes, r));
        }
        let (t, (hits, tsum, ts)) = time(args.reps, || {
            let mut ts = Vec::with_capacity(rays.len());
            let (mut hits, mut tsum) = (0usize, 0f64);
            for r in rays.iter() {
                match scene.accel.intersect(&scene.shapes, black_box(r)) {
                    Some(it) => {
                        hits += 1;
                        tsum += it.t as f64;
                        ts.push(it.t);
                    }
                    None => ts.push(f32::INFINITY),
                }
            }
            (hits, tsum, ts)
        });
        report(batch, "closest", rays.len(), &t, hits, tsum);
        let b: Vec<u8> = ts.iter().flat_map(|t| t.to_le_bytes()).collect();
        write_file(&args.out.join(format!("hits_{batch}.bin")), &b);

        let occ: Vec<Ray> = rays
            .iter()
            .zip(&ts)
            .map(|(r, &t)| {
                let t_max = if t.is_finite() {
                    0.999 * t
                } else {
                    // Past the bounding sphere along the ray: |o − c| + r bounds it.
                    (r.o - centre).length() + radius
                };
                Ray { t_max, ..*r }
            })
            .collect();
        write_rays(&args.out.join(format!("rays_{batch}_occluded.bin")), &occ);
        let (t, flags) = time(args.reps, || {
            occ.iter()
                .map(|r| scene.accel.occluded(&scene.shapes, black_box(r)) as u8)
                .collect::<Vec<u8>>()
        });
        let n_occ = flags.iter().filter(|&&f| f != 0).count();
        report(batch, "occluded", occ.len(), &t, n_occ, 0.0);
        write_file(&args.out.join(format!("occluded_{batch}.bin")), &flags);
    }
}
