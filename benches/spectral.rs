//! Per-sample spectral costs in the render loop: drawing 4 hero wavelengths and evaluating
//! each kind of spectrum curve at them. The `constant` curve is the baseline for ratios.

use std::hint::black_box;
use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use spectrace::spectrum::blackbody::Blackbody;
use spectrace::spectrum::named::{Named, lookup};
use spectrace::spectrum::rgb2spec::albedo;
use spectrace::spectrum::{PiecewiseLinear, Spectrum, WavelengthRange, WavelengthSampler};

fn curve(name: &str) -> Spectrum {
    match lookup(name) {
        Ok(Named::Curve { spectrum, .. }) => spectrum,
        _ => unreachable!("{name} is a curve"),
    }
}

fn bench(c: &mut Criterion) {
    let sampler = WavelengthSampler::visible(WavelengthRange::default());
    let ws: Vec<_> = (0..1024)
        .map(|i| sampler.sample::<4>((i as f32 + 0.5) / 1024.0, 0.5))
        .collect();

    let mut g = c.benchmark_group("sample_4_wavelengths");
    g.bench_function("visible", |b| {
        let mut i = 0u32;
        b.iter(|| {
            i = i.wrapping_add(2_654_435_761);
            black_box(sampler.sample::<4>(
                black_box((i >> 8) as f32 / (1u32 << 24) as f32),
                black_box((i & 0xff) as f32 / 256.0),
            ))
        })
    });
    g.finish();

    // a non-uniformly spaced table (binary search) of the same size as D65
    let d65 = curve("cie-d65");
    let Spectrum::Piecewise(t) = &d65 else {
        unreachable!()
    };
    let mut l: Vec<f32> = t.wavelengths().to_vec();
    l[1] += 0.5;
    let nonuniform = Spectrum::Piecewise(Arc::new(
        PiecewiseLinear::new(l, t.values().to_vec()).unwrap(),
    ));
    let curves = [
        ("constant", Spectrum::Constant(0.5)),
        ("piecewise_uniform", d65.clone()),
        ("piecewise_nonuniform", nonuniform),
        (
            "blackbody",
            Spectrum::Blackbody(Blackbody::absolute(5000.0)),
        ),
        ("rgb_sigmoid", albedo([0.7, 0.3, 0.2]).unwrap()),
    ];
    let mut g = c.benchmark_group("eval_4_wavelengths_x1024");
    for (name, s) in &curves {
        g.bench_function(*name, |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for w in &ws {
                    acc += s.sample(black_box(w)).0.iter().sum::<f32>();
                }
                black_box(acc)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
