//! The Mitsuba importer's plugin registry against Mitsuba 3.9.1's own plugin list: for every
//! kind of element, a plugin is accepted (its scene fails, if at all, for another reason than
//! an unsupported type) exactly when the registry's "supported" list names it, and an unknown
//! plugin's error lists them all.
//!
//! Truth: `MITSUBA_PLUGINS` is the file list of Mitsuba 3.9.1's `mitsuba/plugins/` directory
//! (`pip install mitsuba==3.9.1`), every plugin Mitsuba can load, of any kind.

use std::path::Path;

const MITSUBA_PLUGINS: &[&str] = &[
    "aov",
    "area",
    "batch",
    "bitmap",
    "blackbody",
    "blendbsdf",
    "blender",
    "blendphase",
    "box",
    "bsplinecurve",
    "bumpmap",
    "catmullrom",
    "checkerboard",
    "circular",
    "conductor",
    "constant",
    "constvolume",
    "cube",
    "cylinder",
    "d65",
    "depth",
    "dielectric",
    "diffuse",
    "direct",
    "directional",
    "directionalarea",
    "disk",
    "distant",
    "ellipsoids",
    "ellipsoidsmesh",
    "envmap",
    "gaussian",
    "gridvolume",
    "hair",
    "hdrfilm",
    "heterogeneous",
    "hg",
    "homogeneous",
    "independent",
    "instance",
    "irradiancemeter",
    "irregular",
    "isotropic",
    "lanczos",
    "ldsampler",
    "linearcurve",
    "mask",
    "measured",
    "measured_polarized",
    "merge",
    "mesh_attribute",
    "mitchell",
    "moment",
    "multijitter",
    "normalmap",
    "null",
    "obj",
    "orthogonal",
    "orthographic",
    "path",
    "perspective",
    "plastic",
    "ply",
    "point",
    "polarizer",
    "pplastic",
    "principled",
    "principledthin",
    "projector",
    "ptracer",
    "radiancemeter",
    "rawconstant",
    "rayleigh",
    "rectangle",
    "regular",
    "retarder",
    "roughconductor",
    "roughdielectric",
    "roughplastic",
    "sdfgrid",
    "serialized",
    "sggx",
    "shapegroup",
    "specfilm",
    "sphere",
    "spot",
    "srgb",
    "stokes",
    "stratified",
    "sunsky",
    "tabphase",
    "tent",
    "thindielectric",
    "thinlens",
    "timed_sunsky",
    "twosided",
    "uniform",
    "volpath",
    "volpathmis",
    "volume",
];

/// (kind as the importer's messages name it, a scene with the plugin `{}` in that place).
const KINDS: &[(&str, &str)] = &[
    ("bsdf", r#"<shape type="sphere"><bsdf type="{}"/></shape>"#),
    ("emitter", r#"<emitter type="{}"/>"#),
    ("shape", r#"<shape type="{}"/>"#),
    (
        "shape emitter",
        r#"<shape type="sphere"><emitter type="{}"/></shape>"#,
    ),
    ("sensor", r#"<sensor type="{}"/>"#),
    (
        "film",
        r#"<sensor type="perspective"><film type="{}"/></sensor>"#,
    ),
    (
        "rfilter",
        r#"<sensor type="perspective"><film type="hdrfilm"><rfilter type="{}"/></film></sensor>"#,
    ),
    (
        "sampler",
        r#"<sensor type="perspective"><sampler type="{}"/></sensor>"#,
    ),
    ("integrator", r#"<integrator type="{}"/>"#),
    (
        "medium",
        r#"<integrator type="volpath"/><shape type="sphere"><medium type="{}" name="interior"/></shape>"#,
    ),
    (
        "phase",
        r#"<integrator type="volpath"/><shape type="sphere"><medium type="homogeneous" name="interior"><phase type="{}"/></medium></shape>"#,
    ),
    (
        "texture",
        r#"<shape type="sphere"><bsdf type="diffuse"><texture type="{}" name="reflectance"/></bsdf></shape>"#,
    ),
    (
        "spectrum",
        r#"<shape type="sphere"><bsdf type="diffuse"><spectrum type="{}" name="reflectance"/></bsdf></shape>"#,
    ),
];

/// The load error of `body` in a scene, if any.
fn load_error(body: &str) -> Option<String> {
    let text = format!(r#"<scene version="3.0.0">{body}</scene>"#);
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.xml");
    spectrace::loader::mitsuba::load_str(&text, &path, &[])
        .err()
        .map(|e| e.to_string())
}

/// The "supported" list in an unsupported-type message for `kind`.
fn supported_list(message: &str) -> Option<Vec<String>> {
    let i = message.find("(supported")?;
    let rest = &message[i..];
    let list = &rest[rest.find(':')? + 1..rest.rfind(')')?];
    Some(list.split(',').map(|s| s.trim().to_string()).collect())
}

#[test]
fn every_kind_accepts_exactly_the_plugins_its_supported_list_names() {
    let mut problems = Vec::new();
    for (kind, template) in KINDS {
        // an unknown name's message: the list the registry gives for this kind
        let unknown = load_error(&template.replace("{}", "no_such_plugin"))
            .unwrap_or_else(|| panic!("{kind}: an unknown plugin loads"));
        let listed = supported_list(&unknown)
            .unwrap_or_else(|| panic!("{kind}: no supported list in: {unknown}"));
        for name in MITSUBA_PLUGINS {
            let err = load_error(&template.replace("{}", name));
            let refused = err.as_deref().is_some_and(|e| {
                e.contains(&format!("type \"{name}\" is not supported"))
                    || e.contains(&format!("\"{name}\" is a"))
            });
            let in_list = listed.iter().any(|l| l == name);
            if refused == in_list {
                problems.push(format!(
                    "{kind} \"{name}\": {} but {} (error: {err:?})",
                    if refused { "refused" } else { "accepted" },
                    if in_list { "listed" } else { "not listed" }
                ));
            }
        }
        for l in &listed {
            if !MITSUBA_PLUGINS.contains(&l.as_str()) {
                problems.push(format!(
                    "{kind}: lists \"{l}\", which Mitsuba 3.9.1 has not"
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// A misspelt property is an error naming it and the property meant, as Mitsuba 3 refuses an
/// unreferenced property; a property spectrace does not read and that is close to nothing it
/// asked for loads with a note (Mitsuba may read it: the scene must still render). A misspelt
/// key in a TOML scene is an error naming it too.
#[test]
fn misspelt_keys_are_errors_naming_them() {
    let sensor = r#"<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>"#;
    for (body, bad, meant) in [
        (
            r#"<shape type="sphere"><float name="radiuss" value="2"/></shape>"#,
            "radiuss",
            "radius",
        ),
        (
            r#"<shape type="sphere"><bsdf type="diffuse"><rgb name="reflectanc" value="0.5"/></bsdf></shape>"#,
            "reflectanc",
            "reflectance",
        ),
        (
            r#"<emitter type="point"><rgb name="intensty" value="1"/></emitter>"#,
            "intensty",
            "intensity",
        ),
    ] {
        let e = load_error(&format!("{sensor}{body}")).expect("a misspelt property is refused");
        assert!(
            e.contains(&format!("unknown property \"{bad}\""))
                && e.contains(&format!("\"{meant}\"")),
            "{e}"
        );
    }
    let text = format!(
        r#"<scene version="3.0.0">{sensor}<shape type="sphere"><boolean name="zzz_flag" value="true"/></shape></scene>"#
    );
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.xml");
    let desc = spectrace::loader::mitsuba::load_str(&text, &path, &[]).expect("loads");
    assert!(
        desc.notes
            .iter()
            .any(|n| n.contains("zzz_flag") && n.contains("not read")),
        "{:?}",
        desc.notes
    );
    let toml = "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[film]\nwidth = 8\nheight = 8\nspp = 1\n[materials.m]\ntype = \"diffuse\"\nreflectanse = 0.5\n";
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.toml");
    let e = spectrace::loader::load_str(toml, &path)
        .unwrap_err()
        .to_string();
    assert!(e.contains("reflectanse") && e.contains(":11:"), "{e}");
}
