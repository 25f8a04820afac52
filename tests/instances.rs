//! Instancing (Mitsuba's `shapegroup` / `instance`): hits through instance transforms against
//! the closed-form intersection of the transformed shape, no self-intersection of rays spawned
//! from instanced surfaces, and a forest that stores its tree once.

mod support;

use std::sync::Arc;

use glam::Vec3;
use spectrace::geometry::{Accel, Group, Instance, Mesh, Ray, Shape, Sphere, Transform, spawn_ray};
use support::Rng;

fn sphere_group() -> Arc<Group> {
    let s = Sphere::new(Vec3::new(0.5, 0.0, 0.0), 0.25).unwrap();
    Arc::new(Group::new(vec![Shape::Sphere(s)], 7))
}

/// A unit sphere at (0.5, 0, 0) of radius 0.25, placed by scale 4, a rotation and a far
/// translation, is the sphere of radius 1 at M·(0.5, 0, 0): rays from outside hit it where the
/// closed form says, with the outward normal, and the hit names the group's surface.
#[test]
fn hits_through_instance_transforms_match_the_transformed_shape() {
    let m = Transform::scale(Vec3::splat(4.0))
        .unwrap()
        .then(&Transform::rotate(Vec3::new(0.3, 1.0, -0.2), 1.1).unwrap())
        .then(&Transform::translate(Vec3::new(250.0, -40.0, 1000.0)).unwrap());
    let centre = m.point(Vec3::new(0.5, 0.0, 0.0));
    let accel = Accel::build_with_instances(&[], vec![Instance::new(sphere_group(), m)]);
    let mut rng = Rng::new(3);
    for _ in 0..2000 {
        // a ray from a random point 5 m from the centre toward a random point within the sphere
        let dir_out = Vec3::new(
            rng.uniform() - 0.5,
            rng.uniform() - 0.5,
            rng.uniform() - 0.5,
        )
        .normalize();
        let o = centre + dir_out * 5.0;
        let target = centre
            + Vec3::new(
                rng.uniform() - 0.5,
                rng.uniform() - 0.5,
                rng.uniform() - 0.5,
            ) * 1.0;
        let ray = Ray::new(o, target - o);
        // closed form: |o + t d − c|² = 1
        let oc = o - centre;
        let b = oc.dot(ray.d);
        let disc = b * b - (oc.length_squared() - 1.0);
        let hit = accel.intersect(&[], &ray);
        if disc < 1e-3 {
            continue; // grazing: either answer is fine
        }
        let it = hit.expect("a ray through the sphere hits the instance");
        let t = -b - disc.sqrt();
        assert!((it.t - t).abs() < 1e-4, "t {} vs closed form {t}", it.t);
        assert!((it.p - ray.at(t)).length() < 1e-4);
        let n = (it.p - centre).normalize();
        assert!(
            (it.n_geom - n).length() < 1e-4,
            "normal {} vs {n}",
            it.n_geom
        );
        assert!(it.p_error.cmpge(Vec3::ZERO).all() && it.p_error.is_finite());
        assert_eq!(it.shape, 7, "the group's surface index");
        assert!((it.p - centre).length() - 1.0 <= it.p_error.length() + 1e-4);
    }
}

/// Rays spawned from instanced surfaces (spheres and triangles, scaled, rotated and far from
/// the origin) in every direction away from the surface never hit the surface they leave.
#[test]
fn spawned_rays_do_not_rehit_instanced_surfaces() {
    let quad = Mesh::rectangle(&Transform::rotate(Vec3::X, 0.3).unwrap());
    let group = Arc::new(Group::new(
        vec![
            Shape::Sphere(Sphere::new(Vec3::new(0.5, 0.0, 0.0), 0.25).unwrap()),
            Shape::Mesh(quad),
        ],
        0,
    ));
    let mut failures = Vec::new();
    let mut tested = 0;
    for (scale, far) in [(1.0f32, 0.0f32), (0.01, 3.0), (50.0, 5000.0)] {
        let m = Transform::scale(Vec3::new(scale, scale * 1.3, scale))
            .unwrap()
            .then(&Transform::rotate(Vec3::new(1.0, 2.0, 0.5), 0.7).unwrap())
            .then(&Transform::translate(Vec3::new(far, -far * 0.5, far * 0.25)).unwrap());
        let accel = Accel::build_with_instances(&[], vec![Instance::new(group.clone(), m)]);
        let mut rng = Rng::new(11);
        for _ in 0..4000 {
            // aim at the instance from outside to find surface points
            let o = m.point(Vec3::new(
                rng.uniform() * 4.0 - 2.0,
                rng.uniform() * 4.0 - 2.0,
                3.0,
            ));
            let t = m.point(Vec3::new(
                rng.uniform() * 2.0 - 1.0,
                rng.uniform() * 2.0 - 1.0,
                rng.uniform() * 0.5 - 0.25,
            ));
            let Some(h) = accel.intersect(&[], &Ray::new(o, t - o)) else {
                continue;
            };
            // leave on the side the ray came from, in a random direction of that hemisphere
            let side = if h.n_geom.dot(o - h.p) > 0.0 {
                h.n_geom
            } else {
                -h.n_geom
            };
            let mut d = Vec3::new(
                rng.uniform() - 0.5,
                rng.uniform() - 0.5,
                rng.uniform() - 0.5,
            );
            if d.dot(side) < 0.0 {
                d = -d;
            }
            let ray = spawn_ray(h.p, h.p_error, side, d);
            tested += 1;
            if let Some(h2) = accel.intersect(&[], &ray)
                && h2.shape == h.shape
                && h2.t < 1e-3 * scale
            {
                failures.push(format!("scale {scale}: re-hit at t = {}", h2.t));
            }
        }
    }
    assert!(tested > 5000, "only {tested} surface points");
    assert!(
        failures.is_empty(),
        "{} of {tested}: {:?}",
        failures.len(),
        &failures[..failures.len().min(5)]
    );
}

/// A thousand instances of a 20 000-triangle mesh: the top-level BVH holds a thousand
/// primitives (one box per instance) and the mesh is stored once (every instance shares the
/// group), and a rendered image is not empty.
#[test]
fn a_forest_stores_its_tree_once() {
    let dir = std::env::temp_dir().join(format!("spectrace-forest-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // a 100 × 100-quad height field: 20 000 triangles
    let n = 100;
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (i as f32 / n as f32 - 0.5, j as f32 / n as f32 - 0.5);
            obj += &format!("v {x} {} {z}\n", 0.05 * (9.0 * x).sin() * (7.0 * z).cos());
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            obj += &format!(
                "f {a} {} {}\nf {a} {} {}\n",
                a + n + 2,
                a + 1,
                a + n + 1,
                a + n + 2
            );
        }
    }
    std::fs::write(dir.join("tree.obj"), obj).unwrap();
    let mut xml = String::from(
        r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="60"/>
    <transform name="to_world"><lookat origin="0,20,-30" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <emitter type="constant"/>
  <shape type="shapegroup" id="tree"><shape type="obj"><string name="filename" value="tree.obj"/></shape></shape>
"#,
    );
    for k in 0..1000 {
        let (x, z) = ((k % 40) as f32 - 20.0, (k / 40) as f32 - 12.0);
        xml += &format!(
            r#"  <shape type="instance"><ref id="tree"/><transform name="to_world"><rotate y="1" angle="{}"/><translate x="{x}" z="{z}"/></transform></shape>
"#,
            k * 37 % 360
        );
    }
    xml += "</scene>\n";
    let path = dir.join("forest.xml");
    std::fs::write(&path, xml).unwrap();
    let desc = spectrace::loader::load_any(&path, &[]).unwrap();
    assert_eq!((desc.groups.len(), desc.instances.len()), (1, 1000));
    let scene = spectrace::build::build(&desc).unwrap();
    assert_eq!(scene.accel.primitive_count(), 1000, "one box per instance");
    assert!(scene.shapes.is_empty(), "no shape outside the group");
    let (img, _) = support::render::render_with(&scene, |o| o.spp = 4);
    let lit = img.band.iter().filter(|&&v| v > 0.0).count();
    println!("{lit} of 256 pixels see the forest or the sky");
    assert_eq!(lit, 256);
}

/// TOML `[[groups.NAME.shapes]]` and `[[instances]]` render what the same shapes written out
/// with each instance's transform appended to theirs render (the same sampler, so the two
/// images differ only by rounding in the transforms), and a missing group is a located error.
#[test]
fn toml_instances_render_as_their_flattened_shapes() {
    let head = r#"
[camera]
eye = [0, 2, 6]
target = [0, 0.5, 0]
fov = "40 deg"
[film]
width = 32
height = 24
spp = 16
[materials.red]
type = "diffuse"
reflectance = "colorchecker:red"
[materials.gold]
type = "conductor"
metal = "Au"
roughness = 0.3
[[shapes]]
type = "rectangle"
material = "red"
transform = [{ scale = 4 }, { rotate = { axis = [1, 0, 0], angle = "-90 deg" } }]
[[lights]]
type = "environment"
radiance = "1 W/m^2/sr"
"#;
    let parts = [
        (
            "type = \"sphere\"\nradius = 0.3\ncenter = [0.4, 0.3, 0]\nmaterial = \"gold\"",
            "",
        ),
        (
            "type = \"box\"\nmaterial = \"red\"",
            "{ scale = 0.2 }, { translate = [-0.3, 0.2, 0] }",
        ),
    ];
    let places = [
        "{ rotate = { axis = [0, 1, 0], angle = \"30 deg\" } }, { translate = [-1, 0, 0] }",
        "{ scale = 1.5 }, { translate = [1, 0, -0.5] }",
    ];
    let mut grouped = String::from(head);
    for (shape, t) in parts {
        grouped += &format!("[[groups.thing.shapes]]\n{shape}\ntransform = [{t}]\n");
    }
    for p in places {
        grouped += &format!("[[instances]]\ngroup = \"thing\"\ntransform = [{p}]\n");
    }
    let mut flat = String::from(head);
    for p in places {
        for (shape, t) in parts {
            let list = if t.is_empty() {
                p.to_string()
            } else {
                format!("{t}, {p}")
            };
            flat += &format!("[[shapes]]\n{shape}\ntransform = [{list}]\n");
        }
    }
    let (a, _) = support::render::render_with(&support::render::scene_from(&grouped), |_| {});
    let (b, _) = support::render::render_with(&support::render::scene_from(&flat), |_| {});
    let mean = |v: &[f32]| v.iter().map(|&x| x as f64).sum::<f64>() / v.len() as f64;
    let diff: Vec<f32> = a
        .band
        .iter()
        .zip(&b.band)
        .map(|(x, y)| (x - y).abs())
        .collect();
    let rel = mean(&diff) / mean(&b.band);
    println!("mean |instanced − flattened| / mean = {rel:.2e}");
    assert!(rel < 2e-3, "instanced and flattened images differ by {rel}");
    // a missing group is named with its place in the file
    let bad = grouped.replace("group = \"thing\"", "group = \"thong\"");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.toml");
    let e = spectrace::loader::load_str(&bad, &path)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("instances[0].group") && e.contains("\"thong\""),
        "{e}"
    );
}
