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
/// readers' `BSDFS`; `emitter`: `area` and the emitter readers' `EMITTERS`), else from
/// [`PLUGINS`].
pub(super) fn supported(what: &str) -> Vec<&'static str> {
    match what {
        "rfilter" => params::names(crate::film::filter::KINDS, Dialect::Mitsuba),
        "bsdf" => super::bsdf::BSDFS.iter().map(|(n, _)| *n).collect(),
        // `area` emitters belong to shapes; the others are the emitter readers' registry
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

/// Every kind of plugin, for naming the kind a misplaced plugin belongs to.
pub(super) fn kinds() -> impl Iterator<Item = &'static str> {
    PLUGINS
        .iter()
        .map(|(k, _)| *k)
        .chain(["rfilter", "bsdf", "emitter"])
}

/// The supported plugins by kind, for kinds without a registry of their own: an unknown type
/// is only ever compared with plugins of its own kind.
const PLUGINS: &[(&str, &[&str])] = &[
    ("sensor", &["perspective", "thinlens", "orthographic"]),
    ("film", &["hdrfilm"]),
    ("sampler", SAMPLERS),
    ("integrator", &["path", "volpath", "direct", "moment"]),
    (
        "shape",
        &[
            "obj",
            "ply",
            "serialized",
            "rectangle",
            "cube",
            "sphere",
            "disk",
            "cylinder",
            "shapegroup",
            "instance",
        ],
    ),
    ("shape emitter", &["area"]),
    ("spectrum", &["blackbody", "d65"]),
    ("texture", &["checkerboard", "bitmap"]),
    (
        "transform",
        &["translate", "scale", "rotate", "matrix", "lookat"],
    ),
];
