//! First-hit quantities beside the image (Mitsuba's `aov` integrator): depth, position, uv,
//! normals, surface derivatives and indices of what each camera ray hits first.
//!
//! A pass of its own after the render: each pixel's AOV is the mean over its first
//! `min(spp, MAX_SAMPLES)` camera samples — the same rays the render traces (sample `i` of
//! pixel (x, y) under the seed, `render::camera_sample`), whose offsets the film's filter
//! distributes, so the mean is the filter-weighted average Mitsuba's film accumulates. A ray that
//! escapes contributes zeros (Mitsuba's invalid interaction). Deterministic: the same seed gives
//! the same channels, whatever the thread count (one thread: a ray per sample is cheap beside
//! the render).

use crate::scene::{AovKind, Scene};
use crate::spectrum::WavelengthSampler;

/// At most this many samples per pixel feed the AOVs.
pub const MAX_SAMPLES: u32 = 64;

/// One output channel: its name (`nn.X`) and a value per pixel, row-major, top row first.
pub type AovChannel = (String, Vec<f32>);

/// The scene's AOV channels for a render of `spp` samples per pixel under `seed`, in the order
/// the scene lists them (Mitsuba's channel names: `name.T`, `name.X`, …); empty without AOVs.
pub fn render_aovs(scene: &Scene, seed: u32, spp: u32) -> Vec<AovChannel> {
    let aovs = &scene.integrator.aovs;
    if aovs.is_empty() {
        return Vec::new();
    }
    let (w, h) = (scene.film.width, scene.film.height);
    let lambda = WavelengthSampler::visible(scene.wavelengths);
    let n = spp.clamp(1, MAX_SAMPLES);
    let mut channels: Vec<AovChannel> = Vec::new();
    let mut first = Vec::with_capacity(aovs.len());
    for a in aovs {
        first.push(channels.len());
        for s in suffixes(a.kind) {
            channels.push((format!("{}.{s}", a.name), vec![0.0; (w * h) as usize]));
        }
    }
    for y in 0..h {
        for x in 0..w {
            let pixel = (y * w + x) as usize;
            for i in 0..n {
                let (_, _, ray, _) =
                    super::camera_sample(scene, &lambda, &scene.film.filter, seed, x, y, i);
                let Some(hit) = scene.accel.intersect(&scene.shapes, &ray) else {
                    continue;
                };
                for (a, &c) in aovs.iter().zip(&first) {
                    let v = values(a.kind, &hit, ray.d.length());
                    for (k, value) in v.iter().take(suffixes(a.kind).len()).enumerate() {
                        channels[c + k].1[pixel] += value / n as f32;
                    }
                }
            }
        }
    }
    channels
}

/// The channel suffixes of `kind`, Mitsuba's.
fn suffixes(kind: AovKind) -> &'static [&'static str] {
    match kind {
        AovKind::Depth => &["T"],
        AovKind::Uv => &["U", "V"],
        AovKind::PrimIndex | AovKind::ShapeIndex => &["I"],
        AovKind::Position
        | AovKind::GeoNormal
        | AovKind::ShNormal
        | AovKind::DpDu
        | AovKind::DpDv => &["X", "Y", "Z"],
    }
}

/// The values of `kind` at `hit` (up to three; the first `suffixes(kind).len()` count), the
/// ray's direction `d_len` long (its `t` in units of `d`).
fn values(kind: AovKind, hit: &crate::geometry::Intersection, d_len: f32) -> [f32; 3] {
    match kind {
        AovKind::Depth => [hit.t * d_len, 0.0, 0.0],
        AovKind::Position => hit.p.to_array(),
        AovKind::Uv => [hit.uv.x, hit.uv.y, 0.0],
        AovKind::GeoNormal => hit.n_geom.to_array(),
        AovKind::ShNormal => hit.n_shading.to_array(),
        AovKind::DpDu => hit.dpdu.to_array(),
        AovKind::DpDv => hit.dpdv.to_array(),
        AovKind::PrimIndex => [hit.prim as f32, 0.0, 0.0],
        AovKind::ShapeIndex => [hit.shape as f32, 0.0, 0.0],
    }
}
