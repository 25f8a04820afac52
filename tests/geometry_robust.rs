//! Robust intersection: no self-intersection of spawned rays, and watertight triangle meshes.
//!
//! Each test counts failures over many rays and reports the first few, so that a regression
//! shows how often it happens, not only that it happens.

#[path = "support/geometry.rs"]
mod geo;
mod support;

use glam::{Vec2, Vec3};
use spectrace::geometry::{
    Accel, Disk, Intersection, Mesh, Ray, Shape, Sphere, Transform, spawn_ray, spawn_ray_to,
};
use support::Rng;

const FAN_TRIANGLES: usize = 64;
const FAN_RADIUS: f32 = 500.0; // a 1000 m × 1000 m disk-like polygon

/// The fan variants: at z = 0, and rotated and offset (z ≈ 123.456), and far from the origin.
fn fan_transforms() -> Vec<(&'static str, Transform)> {
    let rot = Transform::rotate(Vec3::new(1.0, 2.0, 0.5), 0.4).unwrap();
    vec![
        ("z=0", Transform::identity()),
        (
            "rotated, z+123.456",
            rot.then(&Transform::translate(Vec3::new(12.5, -7.25, 123.456)).unwrap()),
        ),
        (
            "rotated, far",
            rot.then(&Transform::translate(Vec3::new(3000.0, -2000.0, 123.456)).unwrap()),
        ),
    ]
}

/// Log-uniform grazing elevation in [0.01°, 1°], radians.
fn grazing(rng: &mut Rng) -> f32 {
    (0.01f32.ln() + rng.uniform() * (1.0f32.ln() - 0.01f32.ln()))
        .exp()
        .to_radians()
}

struct Fan {
    shapes: Vec<Shape>,
    accel: Accel,
    transform: Transform,
    n: Vec3,
}

impl Fan {
    fn new(transform: &Transform) -> Fan {
        let mesh = geo::fan(FAN_TRIANGLES, FAN_RADIUS, transform);
        let shapes = vec![Shape::Mesh(mesh)];
        let accel = Accel::build(&shapes);
        Fan {
            accel,
            shapes,
            transform: *transform,
            n: transform.normal(Vec3::Z).normalize(),
        }
    }

    /// World position of an object-space fan point.
    fn world(&self, p: Vec2) -> Vec3 {
        self.transform.point(p.extend(0.0))
    }

    /// Object-space rim vertex k.
    fn rim(&self, k: usize) -> Vec2 {
        let mesh = match &self.shapes[0] {
            Shape::Mesh(m) => m,
            _ => unreachable!(),
        };
        let p = self.transform.inverse().point(mesh.positions()[1 + k]);
        Vec2::new(p.x, p.y)
    }

    /// A target on the fan: a random interior point, a point on a random shared spoke edge,
    /// or the shared centre vertex.
    fn target(&self, rng: &mut Rng) -> Vec3 {
        let pick = rng.uniform();
        if pick < 0.1 {
            self.world(Vec2::ZERO)
        } else if pick < 0.6 {
            let k = (rng.uniform() * FAN_TRIANGLES as f32) as usize % FAN_TRIANGLES;
            self.world(self.rim(k) * (rng.uniform() * 0.95))
        } else {
            let r = FAN_RADIUS * 0.9 * rng.uniform().sqrt();
            let phi = rng.uniform() * std::f32::consts::TAU;
            self.world(Vec2::new(r * phi.cos(), r * phi.sin()))
        }
    }

    /// Hits the fan at `target` with a ray from above at a random angle.
    fn hit_from_above(&self, rng: &mut Rng, target: Vec3) -> Option<Intersection> {
        let elev = 0.02 + rng.uniform() * 1.5;
        let d = geo::direction_at_elevation(self.n, -elev, rng.uniform() * std::f32::consts::TAU);
        let dist = 1.0 + rng.uniform() * 300.0;
        self.accel
            .intersect(&self.shapes, &Ray::new(target - d * dist, d))
    }
}

#[test]
fn grazing_spawned_rays_do_not_rehit_the_fan() {
    for (name, transform) in fan_transforms() {
        let fan = Fan::new(&transform);
        let mut rng = Rng::new(17);
        let (mut rays, mut acne, mut below) = (0, Vec::new(), Vec::new());
        for _ in 0..4000 {
            let target = fan.target(&mut rng);
            let it = fan
                .hit_from_above(&mut rng, target)
                .unwrap_or_else(|| panic!("{name}: ray toward {target} missed the fan"));
            assert!(it.n_geom.dot(fan.n) > 0.999, "{name}: fan normal");
            for _ in 0..8 {
                let elev = grazing(&mut rng);
                let az = rng.uniform() * std::f32::consts::TAU;
                let up = spawn_ray(
                    it.p,
                    it.p_error,
                    it.n_geom,
                    geo::direction_at_elevation(it.n_geom, elev, az),
                );
                if let Some(h) = fan.accel.intersect(&fan.shapes, &up) {
                    acne.push((it.p, elev.to_degrees(), h.t));
                }
                let down = spawn_ray(
                    it.p,
                    it.p_error,
                    it.n_geom,
                    geo::direction_at_elevation(it.n_geom, -elev, az),
                );
                if let Some(h) = fan.accel.intersect(&fan.shapes, &down) {
                    below.push((it.p, elev.to_degrees(), h.t));
                }
                rays += 2;
            }
        }
        assert!(
            acne.is_empty() && below.is_empty(),
            "{name}: of {rays} spawned rays, {} upward rays re-hit the fan (first: {:?}) and {} \
             downward rays hit it (first: {:?})",
            acne.len(),
            acne.first(),
            below.len(),
            below.first()
        );
    }
}

/// Rays descending at 0.01°–1° exactly through shared edges and vertices must hit the fan (no
/// leaks), the BVH must agree with brute force, and continuing through the hit must not hit
/// it again.
#[test]
fn fan_is_watertight_at_shared_edges() {
    for (name, transform) in fan_transforms() {
        let fan = Fan::new(&transform);
        let mut rng = Rng::new(5);
        let mut failures = Vec::new();
        let mut check = |ray: Ray, what: &str| {
            let Some(it) = fan.accel.intersect(&fan.shapes, &ray) else {
                failures.push(format!("{what}: leak, ray {ray:?} missed"));
                return;
            };
            let brute = geo::brute_force(&fan.shapes, &ray).map(|h| h.2);
            if brute != Some(it.t) {
                failures.push(format!("{what}: BVH t {} vs brute force {brute:?}", it.t));
            }
            let through = spawn_ray(it.p, it.p_error, it.n_geom, ray.d);
            if let Some(h) = fan.accel.intersect(&fan.shapes, &through) {
                failures.push(format!("{what}: hit twice, again at t = {}", h.t));
            }
        };
        for i in 0..6000 {
            let k = i % FAN_TRIANGLES;
            let along = if i % 7 == 0 {
                0.0
            } else {
                rng.uniform() * 0.95
            };
            let target = fan.world(fan.rim(k) * along);
            let d = geo::direction_at_elevation(
                fan.n,
                -grazing(&mut rng),
                rng.uniform() * std::f32::consts::TAU,
            );
            let dist = 1.0 + rng.uniform() * 2000.0;
            check(Ray::new(target - d * dist, d), "spoke");
        }
        if name == "z=0" {
            // Exactly representable rays in the planes y = 0 and x = 0, which contain spokes
            // 0, 16, 32 and 48: every such ray crosses a shared edge exactly.
            for _ in 0..3000 {
                let elev = grazing(&mut rng);
                let sign = if rng.uniform() < 0.5 { 1.0 } else { -1.0 };
                let cross_at = (rng.uniform() * 2.0 - 1.0) * 0.95 * FAN_RADIUS;
                let run = 1.0 + rng.uniform() * 100.0;
                let (h, horiz) = (run * elev.tan(), run * sign);
                let d = Vec3::new(-horiz, 0.0, -h).normalize();
                check(
                    Ray::new(Vec3::new(cross_at + horiz, 0.0, h), d),
                    "exact y=0",
                );
                let d = Vec3::new(0.0, -horiz, -h).normalize();
                check(
                    Ray::new(Vec3::new(0.0, cross_at + horiz, h), d),
                    "exact x=0",
                );
            }
        }
        assert!(
            failures.is_empty(),
            "{name}: {} failures, first: {:?}",
            failures.len(),
            &failures[..failures.len().min(5)]
        );
    }
}

#[test]
fn spawned_rays_do_not_rehit_spheres_at_any_scale() {
    let centres = [
        Vec3::ZERO,
        Vec3::new(1.0e4, -2.5e3, 7.0e3),
        Vec3::new(-3.3e3, 5.1e2, -8.7e3),
    ];
    let mut rng = Rng::new(99);
    for c in centres {
        for r in [1.0e-3, 1.0e-2, 1.0, 1.0e2, 1.0e4] {
            let shapes = vec![Shape::Sphere(Sphere::new(c, r).unwrap())];
            let accel = Accel::build(&shapes);
            let well_conditioned = c == Vec3::ZERO || r > 1e-3 * c.abs().max_element();
            let (mut rehits, mut bad_inside, mut hits, mut wrong_primary) =
                (Vec::new(), Vec::new(), 0, 0);
            for _ in 0..2000 {
                let from = geo::sphere_dir(Vec2::new(rng.uniform(), rng.uniform()));
                let to = geo::sphere_dir(Vec2::new(rng.uniform(), rng.uniform()));
                let to = if to.dot(from) < 0.0 { -to } else { to };
                let origin = c + from * (3.0 * r);
                let primary = Ray::new(origin, c + to * r - origin);
                let found = accel.intersect(&shapes, &primary);
                if let Some(truth) = exact_sphere_hit(c, r, &primary)
                    && truth != found.is_some()
                {
                    wrong_primary += 1;
                }
                let Some(it) = found else {
                    continue;
                };
                hits += 1;
                for _ in 0..4 {
                    let elev = (1.57 * rng.uniform().powi(3)).max(1e-5);
                    let az = rng.uniform() * std::f32::consts::TAU;
                    let out = geo::direction_at_elevation(it.n_geom, elev, az);
                    let ray = spawn_ray(it.p, it.p_error, it.n_geom, out);
                    if let Some(h) = accel.intersect(&shapes, &ray) {
                        rehits.push((r, elev, h.t));
                    }
                    let inward = geo::direction_at_elevation(it.n_geom, -elev, az);
                    let ray = spawn_ray(it.p, it.p_error, it.n_geom, inward);
                    let chord = 2.0 * r * elev.sin();
                    let max_coord = it.p.abs().max_element();
                    let depth =
                        2.0 * it.p_error.element_sum() + 2.0 * (max_coord.next_up() - max_coord);
                    if well_conditioned && elev > 1e-3 {
                        match accel.intersect(&shapes, &ray) {
                            // The spawned origin sits up to `depth` inside (error box, offset
                            // and one float step), which moves the exit by ≈ depth / sin(elev).
                            Some(h)
                                if (h.t - chord).abs()
                                    <= 1e-4 * chord + 1.5 * depth / elev.sin() => {}
                            other => bad_inside.push((r, elev, chord, other.map(|h| h.t))),
                        }
                    }
                }
            }
            // Near the float grid spacing (r = 1 mm at 10 km) the rounded rays often miss.
            assert!(hits > 1000, "centre {c}, r {r}: only {hits} primary hits");
            assert_eq!(
                wrong_primary, 0,
                "centre {c}, r {r}: primary hits disagree with f64"
            );
            assert!(
                rehits.is_empty(),
                "centre {c}, r {r}: {} outward spawned rays re-hit the sphere, first {:?}",
                rehits.len(),
                rehits.first()
            );
            assert!(
                bad_inside.is_empty(),
                "centre {c}, r {r}: {} inward rays did not hit the far side at the chord \
                 length, first (r, elev, chord, t) = {:?}",
                bad_inside.len(),
                bad_inside.first()
            );
        }
    }
}

/// Whether the float ray hits the float sphere, evaluated in f64; `None` if too close to call
/// in f32 (nearly tangent, or the origin within a few ε of the surface).
fn exact_sphere_hit(c: Vec3, r: f32, ray: &Ray) -> Option<bool> {
    let o = ray.o.as_dvec3() - c.as_dvec3();
    let d = ray.d.as_dvec3();
    let r = f64::from(r);
    let (a, b, cc) = (d.dot(d), o.dot(d), o.dot(o) - r * r);
    let disc = b * b - a * cc;
    if disc.abs() < 1e-6 * (b * b + a * r * r) || cc.abs() < 1e-6 * (o.dot(o) + r * r) {
        return None;
    }
    Some(disc > 0.0 && (-b + disc.sqrt()) / a > 0.0)
}

#[test]
fn spawned_rays_do_not_rehit_a_large_tilted_disk() {
    let t = Transform::rotate(Vec3::new(0.3, -1.0, 0.2), 1.1)
        .unwrap()
        .then(&Transform::translate(Vec3::new(-250.0, 4000.0, 77.7)).unwrap());
    let shapes = vec![Shape::Disk(Disk::new(&t, 800.0).unwrap())];
    let accel = Accel::build(&shapes);
    let mut rng = Rng::new(3);
    let mut rehits = Vec::new();
    for _ in 0..4000 {
        let s = shapes[0].sample_area(Vec2::new(rng.uniform(), rng.uniform()));
        let it = accel
            .intersect(&shapes, &Ray::new(s.p + s.n * 10.0, -s.n))
            .expect("ray along the normal hits the disk");
        for side in [1.0, -1.0] {
            let d = geo::direction_at_elevation(
                it.n_geom,
                side * grazing(&mut rng),
                rng.uniform() * std::f32::consts::TAU,
            );
            if let Some(h) = accel.intersect(&shapes, &spawn_ray(it.p, it.p_error, it.n_geom, d)) {
                rehits.push(h.t);
            }
        }
    }
    assert!(
        rehits.is_empty(),
        "{} re-hits, first t {:?}",
        rehits.len(),
        rehits.first()
    );
}

/// All points on the inside of a closed box see each other: shadow rays between sampled points
/// (including points on the same face and on adjacent faces near their shared edge) must not be
/// occluded by the box itself.
#[test]
fn shadow_rays_inside_a_box_are_never_blocked() {
    let t = Transform::scale(Vec3::new(3.0, 2.0, 5.0))
        .unwrap()
        .then(&Transform::rotate(Vec3::new(1.0, 1.0, 0.0), 0.7).unwrap())
        .then(&Transform::translate(Vec3::new(40.0, -12.0, 9.0)).unwrap());
    let shapes = vec![Shape::Mesh(Mesh::cuboid(&t))];
    let accel = Accel::build(&shapes);
    let mut rng = Rng::new(11);
    let mut blocked = Vec::new();
    for _ in 0..20000 {
        let a = shapes[0].sample_area(Vec2::new(rng.uniform(), rng.uniform()));
        let b = shapes[0].sample_area(Vec2::new(rng.uniform(), rng.uniform()));
        let ray = spawn_ray_to(a.p, a.p_error, a.n, b.p, b.p_error, b.n);
        if accel.occluded(&shapes, &ray) {
            blocked.push((a.p, b.p, a.n.dot(b.n)));
        }
    }
    assert!(
        blocked.is_empty(),
        "{} of 20000 shadow rays blocked, first (a, b, na·nb) {:?}",
        blocked.len(),
        blocked.first()
    );
}

/// Open cylinders at every scale and far from the origin: a ray spawned from a point sampled on
/// the outside of the tube and leaving it (any elevation, grazing included) never hits the tube
/// again — it leaves a convex surface — while a ray spawned inward from the same point reaches
/// the opposite wall whenever the exact (f64) far root lies clearly between the open ends.
#[test]
fn spawned_rays_do_not_rehit_cylinders_at_any_scale() {
    use spectrace::geometry::Cylinder;
    let mut rng = Rng::new(7);
    for base in [Vec3::ZERO, Vec3::new(2.0e3, -1.0e3, 5.0e2)] {
        for r in [1.0e-2, 1.0, 1.0e2] {
            let axis = Vec3::new(0.3, 1.0, -0.2).normalize() * (10.0 * r);
            let shapes = vec![Shape::Cylinder(
                Cylinder::new(base, base + axis, r, false).unwrap(),
            )];
            let accel = Accel::build(&shapes);
            let (mut rehits, mut misses) = (0, 0);
            for _ in 0..2000 {
                // a point away from the open ends, so inward rays cannot escape through them
                let s = shapes[0].sample_area(Vec2::new(rng.uniform(), 0.3 + 0.4 * rng.uniform()));
                let elev = (1.57 * rng.uniform().powi(3)).max(1e-4);
                let az = rng.uniform() * std::f32::consts::TAU;
                let out = geo::direction_at_elevation(s.n, elev, az);
                if accel
                    .intersect(&shapes, &spawn_ray(s.p, s.p_error, s.n, out))
                    .is_some()
                {
                    rehits += 1;
                }
                let inward = geo::direction_at_elevation(s.n, -0.3 - rng.uniform(), az);
                // exact far wall: in the tube's frame the point is at distance r from the axis
                // and the ray crosses the circle again after t = −2 (p⊥·d⊥)/|d⊥|²
                let (a, d) = (axis.as_dvec3().normalize(), inward.as_dvec3());
                let p = s.p.as_dvec3() - base.as_dvec3();
                let (pp, dp) = (p - a * p.dot(a), d - a * d.dot(a));
                let t = -2.0 * pp.dot(dp) / dp.length_squared();
                let h = (p + d * t).dot(a) / axis.as_dvec3().length();
                let clearly_inside = h > 0.01 && h < 0.99;
                if clearly_inside
                    && accel
                        .intersect(&shapes, &spawn_ray(s.p, s.p_error, s.n, inward))
                        .is_none()
                {
                    misses += 1;
                }
            }
            assert_eq!(
                rehits, 0,
                "r = {r} at {base}: rays leaving the tube hit it again"
            );
            assert_eq!(
                misses, 0,
                "r = {r} at {base}: inward rays missed the far wall"
            );
        }
    }
}
