//! The registry of the Mitsuba plugins the importer reads, by kind: the one list its errors,
//! suggestions and "supported" lists come from. `tests/mitsuba_plugins.rs` checks it against
//! what the readers accept, for every plugin Mitsuba 3.9.1 has, so the list cannot drift from
//! the code: a reader that learns a plugin fails that test until its name is added here.

/// Mitsuba 3.9.1's samplers. spectrace reads their `sample_count` and renders with its own
/// Owen-scrambled Sobol sampler, whichever is named (and says so once).
pub(super) const SAMPLERS: &[&str] = &[
    "independent",
    "stratified",
    "multijitter",
    "orthogonal",
    "ldsampler",
];

/// The supported plugins by kind (`what` of [`Cx::unsupported`]): an unknown type is only ever
/// compared with plugins of its own kind.
pub(super) const PLUGINS: &[(&str, &[&str])] = &[
    ("sensor", &["perspective", "thinlens", "orthographic"]),
    ("film", &["hdrfilm"]),
    ("rfilter", &["box", "gaussian"]),
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
    (
        "bsdf",
        &[
            "diffuse",
            "twosided",
            "conductor",
            "roughconductor",
            "dielectric",
            "roughdielectric",
            "plastic",
            "roughplastic",
            "null",
            "thindielectric",
            "mask",
            "blendbsdf",
            "normalmap",
            "bumpmap",
        ],
    ),
    (
        "emitter",
        &[
            "area",
            "point",
            "spot",
            "constant",
            "directional",
            "envmap",
            "projector",
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
