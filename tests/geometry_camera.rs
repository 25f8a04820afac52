//! Cameras against closed forms: field of view, image orientation, focal-length form, thin-lens
//! focus, orthographic projection, and parameter validation.

use glam::{Vec2, Vec3};
use spectrace::geometry::{Camera, FovAxis, GeometryError, Transform};
use std::f32::consts::PI;

const W: u32 = 640;
const H: u32 = 360;

fn angle(a: Vec3, b: Vec3) -> f32 {
    a.normalize().dot(b.normalize()).clamp(-1.0, 1.0).acos()
}

fn view() -> Transform {
    Transform::look_at(
        Vec3::new(2.0, 1.0, 5.0),
        Vec3::new(-1.0, 0.5, -3.0),
        Vec3::Y,
    )
    .unwrap()
}

fn centre() -> Vec2 {
    Vec2::new(W as f32 / 2.0, H as f32 / 2.0)
}

/// Rays through the middles of the left/right and top/bottom image edges.
fn edge_rays(cam: &Camera) -> [Vec3; 4] {
    let (w, h) = (W as f32, H as f32);
    [
        Vec2::new(0.0, h / 2.0),
        Vec2::new(w, h / 2.0),
        Vec2::new(w / 2.0, 0.0),
        Vec2::new(w / 2.0, h),
    ]
    .map(|r| cam.generate_ray(r, Vec2::splat(0.5)).d)
}

#[test]
fn centre_ray_goes_forward_and_edges_match_the_fov() {
    let fov = 1.1f32;
    let aspect = W as f32 / H as f32;
    let vertical_for_x = 2.0 * ((fov / 2.0).tan() / aspect).atan();
    let horizontal_for_y = 2.0 * ((fov / 2.0).tan() * aspect).atan();
    for (axis, want_x, want_y) in [
        (FovAxis::X, fov, vertical_for_x),
        (FovAxis::Y, horizontal_for_y, fov),
        (FovAxis::Larger, fov, vertical_for_x),
        (FovAxis::Smaller, horizontal_for_y, fov),
    ] {
        let cam = Camera::perspective(view(), fov, axis, W, H).unwrap();
        let to_target = (Vec3::new(-1.0, 0.5, -3.0) - Vec3::new(2.0, 1.0, 5.0)).normalize();
        assert!(
            (cam.forward() - to_target).length() < 1e-6,
            "forward points at the target"
        );
        let c = cam.generate_ray(centre(), Vec2::ZERO);
        assert!(
            (c.d - cam.forward()).length() < 1e-6,
            "{axis:?}: centre ray is forward"
        );
        assert!((c.o - cam.position()).length() < 1e-6);
        let [l, r, t, b] = edge_rays(&cam);
        for (edge, want) in [(l, want_x), (r, want_x), (t, want_y), (b, want_y)] {
            let got = angle(c.d, edge);
            assert!(
                (got - want / 2.0).abs() < 1e-5,
                "{axis:?}: {got} vs {}",
                want / 2.0
            );
        }
    }
}

#[test]
fn image_is_not_mirrored() {
    // Looking down -z with +y up: the right image edge sees +x, the top edge sees +y.
    let t = Transform::look_at(Vec3::ZERO, -Vec3::Z, Vec3::Y).unwrap();
    let cam = Camera::perspective(t, 1.0, FovAxis::X, W, H).unwrap();
    let [l, r, top, bottom] = edge_rays(&cam);
    assert!(r.x > 0.1 && l.x < -0.1, "right edge looks to +x: {r}");
    assert!(top.y > 0.1 && bottom.y < -0.1, "top edge looks up: {top}");
    // Raster (0, 0) is the top-left corner.
    let d = cam.generate_ray(Vec2::ZERO, Vec2::ZERO).d;
    assert!(d.x < 0.0 && d.y > 0.0 && d.z < 0.0, "{d}");
}

#[test]
fn focal_length_50mm_on_full_frame_is_39_6_degrees() {
    let cam = Camera::perspective_focal(view(), 0.050, 0.036, W, H).unwrap();
    let [l, r, _, _] = edge_rays(&cam);
    let fov = angle(l, r).to_degrees();
    assert!((fov - 39.5978).abs() < 1e-3, "horizontal fov {fov}°");
    assert!((fov - 39.6).abs() < 0.01);
}

#[test]
fn thin_lens_rays_converge_on_the_focus_plane() {
    let (f_number, focal, focus) = (2.0, 0.05, 3.5);
    let cam = Camera::thin_lens(view(), 0.8, FovAxis::X, f_number, focal, focus, W, H).unwrap();
    let pinhole = Camera::perspective(view(), 0.8, FovAxis::X, W, H).unwrap();
    let (pos, fwd) = (cam.position(), cam.forward());
    let lens_radius = focal / (2.0 * f_number);
    for raster in [centre(), Vec2::new(10.5, 20.25), Vec2::new(600.0, 300.0)] {
        // Where the pinhole ray crosses the focus plane (distance `focus` along forward).
        let p = pinhole.generate_ray(raster, Vec2::ZERO);
        let target = p.at(focus / p.d.dot(fwd));
        let mut max_lens = 0.0f32;
        for lens in [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.9, 0.5),
            Vec2::new(0.5, 0.99),
            Vec2::ZERO,
        ] {
            let ray = cam.generate_ray(raster, lens);
            let on_lens = ray.o - pos;
            assert!(on_lens.dot(fwd).abs() < 1e-6, "origin on the lens plane");
            assert!(on_lens.length() <= lens_radius * (1.0 + 1e-5));
            max_lens = max_lens.max(on_lens.length());
            let t = (focus - on_lens.dot(fwd)) / ray.d.dot(fwd);
            let hit = ray.at(t);
            assert!(
                (hit - target).length() < 1e-5 * focus,
                "{raster}: {hit} vs {target}"
            );
        }
        assert!(
            max_lens > 0.9 * lens_radius,
            "aperture radius f/(2N) = {lens_radius}"
        );
    }
}

#[test]
fn orthographic_rays_are_parallel_and_span_the_view() {
    let cam = Camera::orthographic(view(), 4.0, W, H).unwrap();
    let fwd = cam.forward();
    let rays = [
        Vec2::ZERO,
        Vec2::new(W as f32, H as f32 / 2.0),
        Vec2::new(0.0, H as f32 / 2.0),
        centre(),
    ]
    .map(|r| cam.generate_ray(r, Vec2::ZERO));
    for r in &rays {
        assert!((r.d - fwd).length() < 1e-6, "parallel to forward");
    }
    let width = (rays[1].o - rays[2].o).length();
    assert!((width - 4.0).abs() < 1e-5, "view width {width}");
    assert!((rays[3].o - cam.position()).length() < 1e-6);
    // The corner is half the width and half the height (aspect) away from the centre.
    let half_h = 2.0 * H as f32 / W as f32;
    assert!(((rays[0].o - rays[3].o).length() - (4.0 + half_h * half_h).sqrt()).abs() < 1e-5);
}

#[test]
fn invalid_parameters_are_errors() {
    let p = |fov, w, h| Camera::perspective(view(), fov, FovAxis::X, w, h);
    for fov in [0.0, -0.5, PI, 4.0, f32::NAN, f32::INFINITY] {
        assert!(p(fov, W, H).is_err(), "fov {fov}");
    }
    assert!(p(1.0, W, H).is_ok());
    for (w, h) in [(0, 10), (10, 0), (40000, 10), (20000, 20000)] {
        assert!(
            matches!(p(1.0, w, h), Err(GeometryError::Resolution { .. })),
            "{w}x{h}"
        );
    }
    assert!(p(1.0, 16384, 16384).is_ok(), "2^28 pixels is allowed");
    let tl = |n, f, d| Camera::thin_lens(view(), 1.0, FovAxis::Y, n, f, d, W, H);
    assert!(
        tl(0.0, 0.05, 2.0)
            .unwrap_err()
            .to_string()
            .contains("f-number")
    );
    assert!(tl(2.8, -0.05, 2.0).is_err());
    assert!(
        tl(2.8, 0.05, 0.0)
            .unwrap_err()
            .to_string()
            .contains("focus distance")
    );
    assert!(tl(2.8, 0.05, f32::NAN).is_err());
    assert!(tl(2.8, 0.05, 2.0).is_ok());
    assert!(Camera::perspective_focal(view(), 0.0, 0.036, W, H).is_err());
    assert!(Camera::perspective_focal(view(), 0.05, -1.0, W, H).is_err());
    assert!(Camera::orthographic(view(), 0.0, W, H).is_err());
    assert!(Camera::orthographic(view(), 1.0, 0, H).is_err());
}
