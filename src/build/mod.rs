//! `build`: the one place where a scene description becomes a render-ready [`Scene`]. Typed
//! quantities leave the uom world here, through `units::plain`.

mod camera;
mod lens;
pub use lens::{focused_lens, lens_system, located as lens_error};
mod lights;
mod materials;
mod materials_mitsuba;
mod materials_pbrt;
mod media;

use materials::material;
mod shapes;
mod textures;

use crate::scene::{FilmSettings, IntegratorSettings, Scene, Surface};
use glam::Vec3;
use std::sync::Arc;

use crate::geometry::accel::Accel;
use crate::geometry::instance::{Group, Instance};
use crate::loader::desc::{CameraKind, SceneDesc, ShapeKind};
use crate::loader::{LoadError, Loc};
use crate::spectrum::WavelengthRange;
use crate::units::plain;

/// Builds the render-ready scene. Errors (a missing or malformed mesh, a zero-area emitter, a
/// singular transform) name the scene file, the item's line and the field.
/// The film's settings in plain units.
fn film_settings(f: &crate::loader::desc::FilmDesc) -> FilmSettings {
    FilmSettings {
        width: f.width,
        height: f.height,
        spp: f.spp,
        filter: crate::film::Filter::from_desc(&f.filter),
        spectral_bins: f.spectral_bins,
        exposure_ev: f.exposure_ev.map(|e| e as f32),
        max_component: f.max_component.map(|m| m as f32),
        data_window: f.crop.filter(|c| c.data_window).map(|c| (c.at, c.full)),
    }
}

pub fn build(desc: &SceneDesc) -> Result<Scene, LoadError> {
    let err = |loc: Loc, field: String, msg: String| LoadError::new(&desc.path, loc, field, msg);
    let range = WavelengthRange::new(
        plain::nm(desc.wavelength_range[0]),
        plain::nm(desc.wavelength_range[1]),
    )
    .map_err(|e| {
        err(
            Loc { line: 1, col: 1 },
            "scene.wavelength_range".into(),
            e.to_string(),
        )
    })?;

    let (mut materials, wants_mesh) = materials(desc)?;

    let mut shape_list = Vec::with_capacity(desc.shapes.len());
    for (i, s) in desc.shapes.iter().enumerate() {
        shape_list.push(shapes::shape(s).map_err(|e| err(s.loc, format!("shapes[{i}]"), e))?);
    }

    let (lights, light_sampling_weights, mut surfaces) = lights::lights(desc, &shape_list, range)?;
    bind_mesh_attributes(
        desc,
        &shape_list,
        &wants_mesh,
        &mut materials,
        &mut surfaces,
    )?;
    let groups = groups(desc, &wants_mesh, &mut surfaces)?;
    let mut instances = Vec::with_capacity(desc.instances.len());
    for (i, d) in desc.instances.iter().enumerate() {
        let t = shapes::steps(&d.transform, d.unit_m, false)
            .map_err(|e| err(d.loc, format!("instances[{i}].to_world"), e))?;
        instances.push(Instance::new(groups[d.group].clone(), t));
    }
    let mut bounds = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for s in &shape_list {
        for p in 0..s.primitive_count() {
            let (lo, hi) = s.primitive_aabb(p);
            bounds = (bounds.0.min(lo), bounds.1.max(hi));
        }
    }
    for (lo, hi) in instances.iter().filter_map(|i| i.bounds()) {
        bounds = (bounds.0.min(lo), bounds.1.max(hi));
    }
    let accel =
        Accel::build_with_instances(&shape_list, instances).with_alpha(shapes::alpha_tests(desc)?);
    let radius = if bounds.0.x <= bounds.1.x {
        ((bounds.1 - bounds.0) * 0.5).length().max(1e-3)
    } else {
        1.0
    };
    let light_power: Vec<f64> = lights
        .iter()
        .map(|l| l.power(&shape_list, range, radius))
        .collect();
    let light_bounds: Vec<_> = lights
        .iter()
        .zip(&light_power)
        .map(|(l, &p)| l.bounds(&shape_list, p as f32))
        .collect();
    let light_tree = crate::light::LightTree::build(&light_bounds, &light_power);
    let camera = match &desc.camera.kind {
        // a lens's errors are located in its own file
        CameraKind::Realistic { .. } => lens::realistic_camera(desc)?,
        _ => camera::camera(desc).map_err(|e| err(desc.camera.loc, "camera".into(), e))?,
    };
    let (media, medium_interfaces) = media::scene_media(desc, range, surfaces.len())?;
    let polarised =
        desc.integrator.polarised || materials.iter().any(crate::material::Material::polarises);
    let f = &desc.film;
    let infinite_lights = (0..lights.len() as u32)
        .filter(|&i| lights[i as usize].is_at_infinity())
        .collect();
    Ok(Scene {
        shapes: shape_list,
        surfaces,
        accel,
        materials,
        lights,
        infinite_lights,
        light_sampling_weights,
        light_power,
        light_tree,
        camera,
        film: film_settings(f),
        integrator: IntegratorSettings {
            kind: desc.integrator.kind,
            max_depth: desc.integrator.max_depth,
            rr_depth: desc.integrator.rr_depth,
            light_selection: desc.integrator.light_selection,
            moment: desc.integrator.moment,
            polarised,
            split_dispersion: desc.integrator.split_dispersion,
            aovs: desc.integrator.aovs.clone(),
            skip_null: desc.integrator.skip_null,
        },
        wavelengths: range,
        bounds,
        meters: desc.sensors.iter().map(meter).collect(),
        camera_sensor: camera_sensor(desc)
            .map_err(|e| err(desc.camera.loc, "camera.sensor".into(), e))?,
        media,
        medium_interfaces,
        camera_medium: desc.camera_medium.map(|m| m as u32),
    })
}

/// The camera's sensor, if the scene gives one.
fn camera_sensor(desc: &SceneDesc) -> Result<Option<crate::sensor::CameraSensor>, String> {
    let Some(s) = &desc.camera.sensor else {
        return Ok(None);
    };
    crate::sensor::CameraSensor::new(
        s.name.clone(),
        s.curves.clone(),
        (
            s.iso,
            s.shutter.get::<crate::units::time::second>(),
            s.f_number,
            s.calibration,
        ),
        s.white_balance.clone(),
    )
    .map(Some)
}

/// A meter's points in metres: a grid's at the centres of its cells.
fn meter(s: &crate::loader::desc::SensorDesc) -> crate::scene::Meter {
    use crate::loader::desc::SensorKind;
    // normalised in f64, so a tiny but non-zero normal stays a direction
    let unit = |n: &[f64; 3]| {
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        Vec3::new((n[0] / l) as f32, (n[1] / l) as f32, (n[2] / l) as f32)
    };
    match &s.kind {
        SensorKind::Point { position, normal } => crate::scene::Meter {
            name: s.name.clone(),
            grid: [1, 1],
            points: vec![crate::scene::MeterPoint {
                p: v3(position),
                n: unit(normal),
            }],
        },
        SensorKind::Grid {
            corner,
            edge_u,
            edge_v,
            count,
            normal,
        } => {
            let (c, a, b) = (v3(corner), v3(edge_u), v3(edge_v));
            let n = unit(normal);
            let points = (0..count[1])
                .flat_map(|j| (0..count[0]).map(move |i| (i, j)))
                .map(|(i, j)| crate::scene::MeterPoint {
                    p: c + a * ((i as f32 + 0.5) / count[0] as f32)
                        + b * ((j as f32 + 0.5) / count[1] as f32),
                    n,
                })
                .collect();
            crate::scene::Meter {
                name: s.name.clone(),
                grid: *count,
                points,
            }
        }
    }
}

/// The scene's materials, and for each whether it reads mesh attributes (and must be built
/// again for each mesh it is on, see `bind_mesh_attributes`).
fn materials(desc: &SceneDesc) -> Result<(Vec<crate::material::Material>, Vec<bool>), LoadError> {
    textures::take_wanted();
    let mut wants_mesh = Vec::with_capacity(desc.materials.len());
    let mut materials = Vec::with_capacity(desc.materials.len());
    for m in &desc.materials {
        materials.push(
            material(&m.kind).map_err(|e| {
                LoadError::new(&desc.path, m.loc, format!("materials.{}", m.name), e)
            })?,
        );
        wants_mesh.push(textures::take_wanted());
    }
    Ok((materials, wants_mesh))
}

/// The shape groups, in their own object space; their surfaces are appended to `surfaces`
/// after the scene's own.
fn groups(
    desc: &SceneDesc,
    wants_mesh: &[bool],
    surfaces: &mut Vec<Surface>,
) -> Result<Vec<Arc<Group>>, LoadError> {
    let mut groups = Vec::with_capacity(desc.groups.len());
    for g in &desc.groups {
        let base = surfaces.len() as u32;
        let mut list = Vec::with_capacity(g.shapes.len());
        for (i, s) in g.shapes.iter().enumerate() {
            let err = |m: String| {
                LoadError::new(
                    &desc.path,
                    s.loc,
                    format!("shapegroup \"{}\".shapes[{i}]", g.id),
                    m,
                )
            };
            if s.material.is_some_and(|m| wants_mesh[m]) {
                return Err(err(
                    "a material reading mesh attributes is not supported in a shape group".into(),
                ));
            }
            list.push(shapes::shape(s).map_err(err)?);
            surfaces.push(surface(s.material, s.two_sided, None));
        }
        groups.push(Arc::new(Group::new(list, base)));
    }
    Ok(groups)
}

/// Gives each shape whose material reads mesh attributes (`wants_mesh`) its own copy of the
/// material, built with the shape's attributes bound (see `textures::with_mesh`); such a
/// shape must be a PLY mesh.
fn bind_mesh_attributes(
    desc: &SceneDesc,
    shapes: &[crate::geometry::shape::Shape],
    wants_mesh: &[bool],
    materials: &mut Vec<crate::material::Material>,
    surfaces: &mut [Surface],
) -> Result<(), LoadError> {
    // the lights were built after the materials: a mesh attribute met there is an emitter's
    if textures::take_wanted() {
        return Err(LoadError::new(
            &desc.path,
            Loc { line: 1, col: 1 },
            "lights".to_string(),
            "a mesh_attribute texture is only read as a material's texture here".to_string(),
        ));
    }
    for (i, s) in desc.shapes.iter().enumerate() {
        let Some(m) = s.material.filter(|&m| wants_mesh[m]) else {
            continue;
        };
        let e = |msg: String| LoadError::new(&desc.path, s.loc, format!("shapes[{i}]"), msg);
        let (ShapeKind::Ply { path, .. }, crate::geometry::shape::Shape::Mesh(mesh)) =
            (&s.kind, &shapes[i])
        else {
            return Err(e(format!(
                "material \"{}\" reads mesh attributes, which only a PLY mesh has",
                desc.materials[m].name
            )));
        };
        let (_, attributes) =
            crate::geometry::shape::Mesh::load_ply_attributes(path, &Default::default())
                .map_err(|x| e(x.to_string()))?;
        let bound = textures::with_mesh(mesh, &attributes, || material(&desc.materials[m].kind))
            .and_then(|r| r)
            .map_err(|x| e(format!("materials.{}: {x}", desc.materials[m].name)))?;
        surfaces[i].material = Some(materials.len() as u32);
        surfaces[i].attributes = true;
        materials.push(bound);
    }
    Ok(())
}

/// Surfaces per shape: filled by `lights` (which also knows the emitters).
pub(super) fn surface(material: Option<usize>, two_sided: bool, light: Option<usize>) -> Surface {
    Surface {
        material: material.map(|m| m as u32),
        two_sided,
        light: light.map(|l| l as u32),
        attributes: false,
    }
}

pub(super) fn v3(p: &crate::loader::desc::Point) -> Vec3 {
    Vec3::new(
        plain::metres(p[0]),
        plain::metres(p[1]),
        plain::metres(p[2]),
    )
}
