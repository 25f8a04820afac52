use super::*;

fn s(radius: f64, thickness: f64, n: f32, aperture: f64) -> Surface {
    Surface {
        radius,
        thickness,
        medium: Ior::Constant(n),
        semi_aperture: aperture / 2.0,
    }
}

#[test]
fn sag_of_a_sphere_and_a_plane() {
    let a = s(10.0, 1.0, 1.5, 10.0);
    // R − √(R² − h²) at h = 6: 10 − 8 = 2, toward the film for a positive radius
    assert!((a.sag(6.0).unwrap() - 2.0).abs() < 1e-12);
    assert!((s(-10.0, 1.0, 1.5, 10.0).sag(6.0).unwrap() + 2.0).abs() < 1e-12);
    assert_eq!(s(0.0, 1.0, 1.0, 10.0).sag(3.0), Some(0.0));
    assert_eq!(a.sag(11.0), None);
}

#[test]
fn a_system_needs_one_stop_and_no_crossings() {
    let ok = || {
        vec![
            s(50.0, 5.0, 1.5, 20.0),
            s(0.0, 1.0, 1.0, 10.0),
            s(-50.0, 40.0, 1.0, 20.0),
        ]
    };
    assert!(LensSystem::new(ok()).is_ok());
    let mut two = ok();
    two[2].radius = 0.0;
    assert!(matches!(
        LensSystem::new(two),
        Err(LensError::TwoStops {
            first: 2,
            second: 3
        })
    ));
    let none = vec![s(50.0, 5.0, 1.5, 20.0), s(-50.0, 40.0, 1.0, 20.0)];
    assert!(matches!(
        LensSystem::new(none),
        Err(LensError::NoStop { .. })
    ));
    let mut big = ok();
    big[0].semi_aperture = 60.0;
    assert!(matches!(
        LensSystem::new(big),
        Err(LensError::ApertureBeyondSphere { surface: 1, .. })
    ));
    // a biconvex lens 1 mm thick at the centre and 20 mm across: its surfaces (sag 1.0 each at
    // h = 10 for R = 50) cross
    let thin = vec![
        s(50.0, 1.0, 1.5, 20.0),
        s(-50.0, 1.0, 1.0, 20.0),
        s(0.0, 30.0, 1.0, 5.0),
    ];
    assert!(matches!(
        LensSystem::new(thin),
        Err(LensError::Crossing {
            surface: 1,
            next: 2,
            ..
        })
    ));
    let mut film = ok();
    film[2].thickness = 0.0;
    assert!(matches!(
        LensSystem::new(film),
        Err(LensError::FilmBehindNothing { .. })
    ));
}

#[test]
fn paraxial_singlet_is_the_thick_lens_formula() {
    // n = 1.5, R1 = 50, R2 = −50, d = 5: 1/f = (n−1)(1/R1 − 1/R2 + (n−1)d/(n R1 R2))
    let sys = LensSystem::new(vec![
        s(50.0, 5.0, 1.5, 20.0),
        s(-50.0, 2.0, 1.0, 20.0),
        s(0.0, 40.0, 1.0, 10.0),
    ])
    .unwrap();
    let (n, r1, r2, d) = (1.5, 50.0, -50.0, 5.0);
    let f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * d / (n * r1 * r2)));
    let bfl = f * (1.0 - (n - 1.0) * d / (n * r1));
    let p = sys.paraxial(550.0);
    assert!((p.efl - f).abs() < 1e-9 * f, "{} vs {f}", p.efl);
    // the stop lies 2 mm behind the lens: the BFL from the last vertex (the stop) is 2 less
    assert!(
        (p.bfl - (bfl - 2.0)).abs() < 1e-9 * f,
        "{} vs {}",
        p.bfl,
        bfl - 2.0
    );
}

#[test]
fn real_rays_near_the_axis_focus_at_the_paraxial_focus() {
    let sys = LensSystem::new(vec![
        s(0.0, 1.0, 1.0, 20.0),
        s(50.0, 5.0, 1.5, 20.0),
        s(-50.0, 48.0, 1.0, 20.0),
    ])
    .unwrap();
    let p = sys.paraxial(550.0);
    let h = 0.01;
    let r = sys
        .trace(
            LensRay {
                o: glam::DVec3::new(0.0, h, sys.total_length() + 10.0),
                d: glam::DVec3::NEG_Z,
            },
            550.0,
            Direction::FromObject,
        )
        .unwrap();
    // where the ray crosses the axis, measured from the last vertex (z_last = 48)
    let t = -r.o.y / r.d.y;
    let z_cross = r.o.z + t * r.d.z;
    let bfl_real = sys.vertex_z(2) - z_cross;
    assert!(
        (bfl_real - p.bfl).abs() < 1e-5 * p.bfl,
        "{bfl_real} vs {}",
        p.bfl
    );
}
