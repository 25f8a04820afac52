//! Renders a scene without writing output, for profilers (`perf`, `valgrind --tool=callgrind`):
//! `cargo run --release --example profile_render -- SCENE [SPP] [THREADS] [INTEGRATOR]`
//! (INTEGRATOR: path, bdpt, light or whitted; default the scene's).
//! Prints the render time and samples per second; the image is discarded. With SPP = 0 it only
//! loads and builds the scene and prints how long each took (for the large-mesh benchmark:
//! `/usr/bin/time -v target/release/examples/profile_render SCENE 0` also gives peak memory).

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use spectrace::render::{RenderOptions, render};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: profile_render SCENE [SPP] [THREADS]");
    let spp: u32 = args
        .next()
        .map_or(1, |s| s.parse().expect("SPP is a number"));
    let threads: usize = args
        .next()
        .map_or(1, |s| s.parse().expect("THREADS is a number"));
    let t_load = Instant::now();
    let desc = spectrace::loader::load_any(std::path::Path::new(&path), &[]).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    let load_secs = t_load.elapsed().as_secs_f64();
    let t_build = Instant::now();
    let scene = spectrace::build::build(&desc).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    if spp == 0 {
        let triangles: usize = scene.shapes.iter().map(|s| s.primitive_count()).sum();
        println!(
            "{path}: {triangles} primitives; load {load_secs:.2} s, build {:.2} s",
            t_build.elapsed().as_secs_f64()
        );
        return;
    }
    let mut o = RenderOptions::from_scene(&scene);
    o.spp = spp;
    o.threads = Some(threads);
    if let Some(kind) = args.next() {
        use spectrace::loader::desc::IntegratorKind as K;
        o.integrator = match kind.as_str() {
            "path" => K::Path,
            "bdpt" => K::Bdpt,
            "light" => K::Light,
            "whitted" => K::Whitted,
            other => {
                eprintln!("unknown integrator {other}: expected path, bdpt, light or whitted");
                std::process::exit(2)
            }
        };
    }
    let cancel = AtomicBool::new(false);
    let t = Instant::now();
    let (film, stats) = render(&scene, &o, &cancel, &|_, _| {}).expect("renders");
    let secs = t.elapsed().as_secs_f64();
    let samples = (film.width * film.height) as f64 * spp as f64;
    println!(
        "{path}: {spp} spp, {threads} threads: {secs:.3} s, {:.3} M samples/s ({} dropped)",
        samples / secs / 1e6,
        stats.nan_samples + stats.inf_samples
    );
}
