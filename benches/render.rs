//! Samples per second on `scenes/cornell.toml` at 512×512 (path tracing, max depth 16, one
//! sample per pixel per iteration, every core), with `whitted` as a same-run reference and
//! `bdpt` for its cost per sample (its error per sample, and so its efficiency against `path`,
//! comes from `scripts/bench_bdpt.py`).

use std::path::Path;
use std::sync::atomic::AtomicBool;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use spectrace::loader::desc::IntegratorKind;
use spectrace::render::{RenderOptions, render};

fn bench(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.toml");
    let scene =
        spectrace::build::build(&spectrace::loader::load(&path).expect("loads")).expect("builds");
    let mut g = c.benchmark_group("cornell_512");
    g.sample_size(10);
    g.throughput(Throughput::Elements(512 * 512));
    for (name, kind) in [
        ("path", IntegratorKind::Path),
        ("whitted", IntegratorKind::Whitted),
        ("bdpt", IntegratorKind::Bdpt),
    ] {
        let mut o = RenderOptions::from_scene(&scene);
        o.spp = 1;
        o.integrator = kind;
        let cancel = AtomicBool::new(false);
        g.bench_function(name, |b| {
            b.iter(|| render(&scene, &o, &cancel, &|_, _| {}).expect("renders"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
