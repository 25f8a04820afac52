//! The registry of the Mitsuba plugins the importer reads, by kind: the one list its errors,
//! suggestions and "supported" lists come from. `tests/mitsuba_plugins.rs` checks it against
//! what the readers accept, for every plugin Mitsuba 3.9.1 has, so the list cannot drift from
//! the code: a reader that learns a plugin fails that test until its name is added here.

use crate::params::{self, Dialect};

/// Mitsuba 3.9.1's samplers. spectrace reads their `sample_count` and renders with its own
/// Owen-scrambled Sobol sampler, whichever is named (and says so once).
pub(super) const SAMPLERS: &[&str] = &[
    "independent",
    "stratified",
    "multijitter",
    "orthogonal",
    "ldsampler",
];

/// The supported plugins of kind `what` (of [`Cx::unsupported`]), in order: from the kind's
/// own registry where it has one (`rfilter`: [`crate::film::filter::KINDS`]; `bsdf`: the BSDF
/// readers' `BSDFS`; `emitter`: `area` and the emitter readers' `EMITTERS`; `shape`: the shape readers'
/// `SHAPES`, `shapegroup` and `instance`), else from
/// [`PLUGINS`].
pub(super) fn supported(what: &str) -> Vec<&'static str> {
    match what {
        "rfilter" => params::names(crate::film::filter::KINDS, Dialect::Mitsuba),
        "bsdf" => super::bsdf::BSDFS.iter().map(|(n, _)| *n).collect(),
        // `shapegroup` and `instance` are read by the scene; the others are the shape readers'
        "shape" => super::shapes::SHAPES
            .iter()
            .map(|(n, _)| *n)
            .chain(["shapegroup", "instance"])
            .collect(),
        // `area` emitters belong to shapes; the others are the emitter readers' registry
        "medium" => super::media::MEDIA.to_vec(),
        "phase" => super::media::PHASES.to_vec(),
        "volume" => super::media::VOLUMES.to_vec(),
        "emitter" => std::iter::once("area")
            .chain(super::emitters::EMITTERS.iter().map(|(n, _)| *n))
            .collect(),
        _ => PLUGINS
            .iter()
            .find(|(k, _)| *k == what)
            .map(|(_, names)| names.to_vec())
            .unwrap_or_default(),
    }
}

/// Every kind of plugin, in the order searched when naming the kind a misplaced plugin belongs
/// to (`area` is an `emitter` before a `shape emitter`).
pub(super) fn kinds() -> impl Iterator<Item = &'static str> {
    [
        "sensor",
        "film",
        "rfilter",
        "sampler",
        "integrator",
        "shape",
        "bsdf",
        "emitter",
        "shape emitter",
        "medium",
        "phase",
        "volume",
        "spectrum",
        "texture",
        "transform",
    ]
    .into_iter()
}

/// The supported plugins by kind, for kinds without a registry of their own: an unknown type
/// is only ever compared with plugins of its own kind.
const PLUGINS: &[(&str, &[&str])] = &[
    ("sensor", &["perspective", "thinlens", "orthographic"]),
    ("film", &["hdrfilm"]),
    ("sampler", SAMPLERS),
    (
        "integrator",
        &[
            "path",
            "volpath",
            "volpathmis",
            "direct",
            "moment",
            "stokes",
            "ptracer",
            "aov",
        ],
    ),
    ("shape emitter", &["area"]),
    ("spectrum", &["blackbody", "d65"]),
    (
        "texture",
        &["checkerboard", "bitmap", "rawconstant", "mesh_attribute"],
    ),
    (
        "transform",
        &["translate", "scale", "rotate", "matrix", "lookat"],
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind with a list, whether from `PLUGINS` or a registry, is searched by `kinds`,
    /// and every kind searched has a list.
    #[test]
    fn kinds_are_the_listed_kinds() {
        let all: Vec<&str> = kinds().collect();
        for (k, _) in PLUGINS {
            assert!(all.contains(k), "{k}");
        }
        for k in all {
            assert!(!supported(k).is_empty(), "{k}");
        }
    }
}
