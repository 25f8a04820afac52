//! The top level of a Mitsuba scene: includes, `default`s, ids, then each top-level element
//! handed to its plugin family (sensor, integrator, bsdf, shape, emitter).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use super::bsdf::bsdf;
use super::cx::{Cx, R};
use super::emitters::emitter;
use super::integrator::integrator_settings;
use super::sensor::sensor;
use super::shapes::{instance, shape, shapegroup};
use super::xml::Element;
use crate::loader::desc::*;
use crate::units::{Length, length};

/// Includes a scene may make in all, whatever their nesting: bounds a file that includes
/// itself several times per level (4 per level would be 4¹⁶ files by the depth limit alone).
const MAX_INCLUDES: u32 = 1000;

pub(super) fn scene(
    mut root: Element,
    text: &str,
    path: &Path,
    defines: &HashMap<String, String>,
    served_includes: Option<&HashMap<String, String>>,
) -> R<SceneDesc> {
    let mut cx = Cx {
        sources: vec![(path.to_path_buf(), text.to_string())],
        defines,
        params: HashMap::new(),
        ids: HashMap::new(),
        search: vec![path.parent().map(Path::to_path_buf).unwrap_or_default()],
        notes: Default::default(),
        bsdf_depth: Default::default(),
        line_starts: Default::default(),
        queried: Default::default(),
        media: Default::default(),
    };
    if root.tag != "scene" {
        return Err(cx.err(&root, "the root element must be <scene>"));
    }
    match root.attr("version") {
        Some(v) if v.starts_with("3.") || v.starts_with("2.") => {}
        Some(v) => {
            return Err(cx.err(
                &root,
                format!("scene version {v} is not supported; use 2.x or 3.x"),
            ));
        }
        None => return Err(cx.err(&root, "missing version (e.g. version=\"3.0.0\")")),
    }
    splice_includes(&mut cx, &mut root, served_includes)?;
    for c in root.children.iter().filter(|c| c.tag == "default") {
        let (Some(n), Some(v)) = (c.attr("name"), c.attr("value")) else {
            return Err(cx.err(c, "a <default> needs name and value"));
        };
        // the first definition wins, as in Mitsuba 3.9.1 (a scene's default before an include
        // that defaults the same name keeps the scene's)
        cx.params
            .entry(n.to_string())
            .or_insert_with(|| v.to_string());
    }
    cx.substitute(&mut root)?;
    for c in &root.children {
        if let Some(id) = c.attr("id") {
            cx.ids.insert(id.to_string(), c.clone());
        }
    }

    contents(cx, &root, path)
}

/// `<path>` folders and includes in document order, as Mitsuba 3.9.1's parser meets them: a
/// path of the scene file joins the file resolver (searched before the scene's folder, the
/// latest first); one inside an included file has no effect in Mitsuba (it changes a copy of
/// the resolver) and is skipped with a note. An include is looked for next to the file that
/// includes it, then by the resolver. Everything else an included file names (meshes, images,
/// spectra) is resolved by the scene's resolver, not against the included file's folder.
/// Included children are spliced in place (depth-limited).
fn splice_includes(
    cx: &mut Cx<'_>,
    root: &mut Element,
    served_includes: Option<&HashMap<String, String>>,
) -> R<()> {
    let mut depth = 0;
    let (mut includes, mut bytes) = (0u32, cx.sources[0].1.len() as u64);
    while root
        .children
        .iter()
        .any(|c| c.tag == "include" || c.tag == "path")
    {
        depth += 1;
        if depth > 16 {
            return Err(cx.err(root, "includes nest more than 16 deep"));
        }
        let mut out = Vec::new();
        for c in std::mem::take(&mut root.children) {
            let own_dir = cx.sources[c.src]
                .0
                .parent()
                .map(Path::to_path_buf)
                .unwrap_or_default();
            match c.tag.as_str() {
                "path" if c.src != 0 => cx.note(
                    &c,
                    "a <path> inside an included file has no effect (as in Mitsuba); put it in the scene file",
                ),
                "path" => {
                    let v = c
                        .attr("value")
                        .ok_or_else(|| cx.err(&c, "missing value (a folder)"))?;
                    let dir = own_dir.join(v);
                    if !dir.is_dir() {
                        return Err(cx.err(
                            &c,
                            format!("folder {} does not exist", dir.display()),
                        ));
                    }
                    cx.search.insert(0, dir);
                }
                "include" => {
                    let f = c
                        .attr("filename")
                        .ok_or_else(|| cx.err(&c, "missing filename"))?;
                    let (p, served) = match served_includes {
                        Some(map) => (
                            PathBuf::from(f),
                            Some(map.get(f).cloned().ok_or_else(|| {
                                cx.err(&c, format!("cannot read {f}: not among the given includes"))
                            })?),
                        ),
                        None => match own_dir.join(f) {
                            p if p.is_file() => (p, None),
                            _ => (cx.resolve_file(f), None),
                        },
                    };
                    includes += 1;
                    if includes > MAX_INCLUDES {
                        return Err(cx.err(
                            &c,
                            format!("more than {MAX_INCLUDES} includes in all (does a file include itself?)"),
                        ));
                    }
                    let t = match served {
                        Some(t) => t,
                        None => crate::files::read_text(&p, crate::files::MAX_TEXT_BYTES)
                            .map_err(|e| {
                                cx.err(&c, format!("cannot read {}: {e}", p.display()))
                            })?,
                    };
                    bytes += t.len() as u64;
                    if bytes > crate::files::MAX_TEXT_BYTES {
                        return Err(cx.err(
                            &c,
                            format!(
                                "the scene and its includes exceed {} MiB of text in all (does a file include itself?)",
                                crate::files::MAX_TEXT_BYTES >> 20
                            ),
                        ));
                    }
                    let mut inc = super::parse_file(&t, &p)?;
                    cx.sources.push((p, t));
                    inc.set_source(cx.sources.len() - 1);
                    out.extend(inc.children);
                }
                _ => out.push(c),
            }
        }
        root.children = out;
    }
    Ok(())
}

/// Mitsuba's film before its `<film>` is read: 768 × 576, 4 samples, its Gaussian filter.
fn default_film() -> FilmDesc {
    FilmDesc {
        width: 768,
        height: 576,
        spp: 4,
        filter: crate::film::filter::gaussian::Desc::mitsuba(0.5), // Mitsuba's default
        spectral_bins: 0,
        exposure_ev: None,
        max_component: None,
        crop: None,
        loc: Default::default(),
    }
}

/// The scene's top-level elements, each handed to its plugin family, as a description.
fn contents(owned: Cx<'_>, root: &Element, path: &Path) -> R<SceneDesc> {
    let cx = &owned;
    let mut film = default_film();
    let mut integrator = IntegratorDesc {
        kind: IntegratorKind::Path,
        max_depth: 1024,
        rr_depth: DEFAULT_RR_DEPTH,
        light_selection: LightSelection::Tree, // decided after the emitters are read (below)
        moment: false,
        polarised: false,
        split_dispersion: true,
        aovs: Vec::new(),
        skip_null: false,
    };
    let mut camera = None;
    let mut materials: Vec<MaterialDesc> = Vec::new();
    let mut material_ids: HashMap<String, (usize, bool)> = HashMap::new();
    let mut shapes = Vec::new();
    let mut groups: Vec<GroupDesc> = Vec::new();
    let mut instances = Vec::new();
    let mut lights = Vec::new();
    let mut volumetric = false;
    let mut camera_medium = None;

    for c in &root.children {
        match c.tag.as_str() {
            "default" => {}
            "integrator" => volumetric = integrator_settings(cx, c, &mut integrator)?,
            "sensor" => {
                camera = Some(sensor(cx, c, &mut film)?);
                camera_medium = super::media::sensor_medium(cx, c)?;
            }
            "bsdf" => {
                if let Some(id) = c.attr("id") {
                    let (m, two) = bsdf(cx, c, id)?;
                    material_ids.insert(id.to_string(), (materials.len(), two));
                    materials.push(m);
                }
            }
            // a group of shapes drawn only through instances; an instance places one
            "shape" if c.attr("type") == Some("shapegroup") => {
                groups.push(shapegroup(cx, c, &mut materials, &material_ids)?);
            }
            "shape" if c.attr("type") == Some("instance") => {
                instances.push(instance(cx, c, &groups)?);
            }
            "shape" => shapes.push(shape(cx, c, &mut materials, &material_ids)?),
            // declarations that shapes and sensors refer to by id (read on first use)
            "medium" => {
                if c.attr("id").is_none() {
                    return Err(cx.err(
                        c,
                        "a <medium> at the top level needs an id for shapes to refer to",
                    ));
                }
            }
            // an area emitter at the top level is a declaration that shapes refer to by id
            "emitter" if c.attr("type") == Some("area") => {
                if c.attr("id").is_none() {
                    return Err(cx.err(
                        c,
                        "an area emitter belongs inside a <shape> (or give it an id and <ref> it from one)",
                    ));
                }
            }
            "emitter" => lights.push(emitter(cx, c)?),
            // declarations that sensors, shapes and BSDFs refer to by id
            "spectrum" | "texture" | "rgb" | "float" | "sampler" | "rfilter" => {}
            other => {
                return Err(cx.err(
                    c,
                    format!("<{other}> is not supported at the top level of a scene"),
                ));
            }
        }
    }
    let camera = camera.ok_or_else(|| cx.err(root, "the scene has no <sensor>"))?;
    // Mitsuba chooses emitters in proportion to their sampling_weight (1 by default); a scene
    // that sets one keeps that rule, every other one gets the light tree (either is unbiased)
    let weighted = lights.iter().any(|l| l.sampling_weight != 1.0)
        || shapes.iter().any(|s| {
            s.emission
                .as_ref()
                .is_some_and(|e| e.sampling_weight != 1.0)
        });
    if weighted {
        integrator.light_selection = LightSelection::Uniform;
    }
    let media = super::media::scene_media(cx, root, volumetric, &mut shapes, &mut camera_medium)?;
    cx.check_unreferenced(root)?;
    let nm = |x: f64| Length::new::<length::nanometer>(x);
    Ok(SceneDesc {
        path: path.to_path_buf(),
        wavelength_range: [nm(360.0), nm(830.0)],
        camera,
        film,
        integrator,
        materials,
        shapes,
        groups,
        instances,
        lights,
        media,
        camera_medium,
        sensors: Vec::new(),
        notes: owned
            .notes
            .into_inner()
            .into_iter()
            .map(|(_, l)| l)
            .collect(),
    })
}
