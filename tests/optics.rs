//! Lens systems against first-order optics computed here independently (the thick-lens formula,
//! ray-transfer matrices, Sellmeier coefficients typed from the SCHOTT data sheets), a maker's
//! published doublet, and the realistic camera's focus and radiometry.

mod support;

use glam::{Vec2, Vec3};
use spectrace::geometry::{Camera, Transform};
use spectrace::optics::LensSystem;
use support::render::{mean, render_with, scene_from};

/// F, d and C lines, nm.
const FDC: [f64; 3] = [486.1327, 587.5618, 656.2725];

fn sellmeier(b: [f64; 3], c: [f64; 3], l_nm: f64) -> f64 {
    let l2 = (l_nm * 1e-3).powi(2);
    (1.0 + (0..3).map(|i| b[i] * l2 / (l2 - c[i])).sum::<f64>()).sqrt()
}

/// SCHOTT N-BK7 and SF5 data sheets' Sellmeier coefficients (C in µm²).
fn n_bk7(l: f64) -> f64 {
    sellmeier(
        [1.03961212, 0.231792344, 1.01046945],
        [0.00600069867, 0.0200179144, 103.560653],
        l,
    )
}
fn n_sf5(l: f64) -> f64 {
    sellmeier(
        [1.46141885, 0.247713019, 0.949995832],
        [0.0111826126, 0.0508594669, 112.041888],
        l,
    )
}

fn lens(text: &str) -> LensSystem {
    let path = std::path::Path::new("inline.lens");
    let desc = spectrace::loader::lens::parse(text, path).unwrap_or_else(|e| panic!("{e}"));
    spectrace::build::lens_system(&desc).unwrap_or_else(|e| panic!("{e}"))
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

#[test]
fn a_singlet_has_the_thick_lens_focal_lengths_at_three_wavelengths() {
    // an equiconvex N-BK7 singlet, the stop 2 mm in front
    let sys = lens("0 2 0 20\n51.68 6 N-BK7 25.4\n-51.68 95 1 25.4\n");
    let (r1, r2, d) = (51.68, -51.68, 6.0);
    for l in FDC {
        let n = n_bk7(l);
        // thick lens (Hecht, Optics, eq. 6.2 and the back focal distance)
        let f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * d / (n * r1 * r2)));
        let bfl = f * (1.0 - (n - 1.0) * d / (n * r1));
        let p = sys.paraxial(l);
        println!(
            "{l} nm: n {n:.6} EFL {:.6} (formula {f:.6}), BFL {:.6} ({bfl:.6})",
            p.efl, p.bfl
        );
        assert!(rel(p.efl, f) < 1e-6 && rel(p.bfl, bfl) < 1e-6, "{l} nm");
    }
}

/// EFL and BFL of surfaces (radius, thickness to next, index behind) from the ray-transfer
/// matrices in reduced coordinates (y, n·u): refraction [[1, 0], [−φ, 1]], transfer
/// [[1, t/n], [0, 1]] (Gerrard & Burch, Introduction to Matrix Methods in Optics, ch. III).
fn matrix_efl_bfl(surfaces: &[(f64, f64, f64)]) -> (f64, f64) {
    let mul = |a: [[f64; 2]; 2], b: [[f64; 2]; 2]| {
        [
            [
                a[0][0] * b[0][0] + a[0][1] * b[1][0],
                a[0][0] * b[0][1] + a[0][1] * b[1][1],
            ],
            [
                a[1][0] * b[0][0] + a[1][1] * b[1][0],
                a[1][0] * b[0][1] + a[1][1] * b[1][1],
            ],
        ]
    };
    let mut m = [[1.0, 0.0], [0.0, 1.0]];
    let mut n = 1.0;
    for (k, &(r, t, n2)) in surfaces.iter().enumerate() {
        let phi = (n2 - n) / r;
        m = mul([[1.0, 0.0], [-phi, 1.0]], m);
        if k + 1 < surfaces.len() {
            m = mul([[1.0, t / n2], [0.0, 1.0]], m);
        }
        n = n2;
    }
    (-1.0 / m[1][0], -m[0][0] / m[1][0])
}

/// Thorlabs AC254-100-A, an N-BK7/SF5 cemented achromat (its Zemax file: R = 62.75, −45.71,
/// −128.23 mm, centre thicknesses 4.0 and 2.5 mm, Ø 25.4 mm).
const AC254_100: &str =
    "0 1 0 22.86\n62.75 4.0 N-BK7 25.4\n-45.71 2.5 SF5 25.4\n-128.23 97.1 1 25.4\n";

#[test]
fn a_cemented_doublet_matches_the_matrix_method_and_its_maker() {
    let sys = lens(AC254_100);
    for l in FDC {
        let (f, bfl) = matrix_efl_bfl(&[
            (62.75, 4.0, n_bk7(l)),
            (-45.71, 2.5, n_sf5(l)),
            (-128.23, 97.1, 1.0),
        ]);
        let p = sys.paraxial(l);
        println!(
            "{l} nm: EFL {:.6} (matrices {f:.6}), BFL {:.6} ({bfl:.6})",
            p.efl, p.bfl
        );
        assert!(rel(p.efl, f) < 1e-6 && rel(p.bfl, bfl) < 1e-6, "{l} nm");
    }
    // Thorlabs states f = 100.0 mm and a back focal length of 97.1 mm (its Zemax file focuses
    // 97.068 mm behind the last vertex at 587.6 nm); both are printed to 0.1 mm
    let d = sys.paraxial(587.5618);
    assert!((d.efl - 100.0).abs() < 0.1, "EFL {}", d.efl);
    assert!((d.bfl - 97.1).abs() < 0.1, "BFL {}", d.bfl);
    // the maker's design puts the image plane 97.068 mm behind the last vertex: the real
    // rays' best focus at full aperture (Ø 22.86 mm entrance beam), ahead of the paraxial one
    // by the residual spherical aberration
    let (best, _) = (0..=60)
        .map(|k| {
            let behind = 96.9 + 0.005 * k as f64;
            (
                behind,
                sys.axial_spot(587.5618, behind, 101).unwrap().rms_radius,
            )
        })
        .fold((0.0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
    println!("best real focus at 587.6 nm: {best:.3} mm behind the last vertex");
    assert!((best - 97.068).abs() < 0.03, "{best}");
    // an achromat: the F and C foci nearly coincide and the focal shift has its minimum
    // between them, in the blue-green (the secondary spectrum); an N-BK7 singlet of the same
    // focal length spreads them over f/V_d = 1.56 mm
    let bfl = |l: f64| sys.paraxial(l).bfl;
    let fc = (bfl(FDC[0]) - bfl(FDC[2])).abs();
    let (l_min, _) = (400..=700)
        .map(|l| (l, bfl(l as f64)))
        .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
    println!("F − C focal shift {fc:.4} mm; minimum back focal length at {l_min} nm");
    assert!(fc < 0.156, "{fc}");
    assert!((FDC[0] as i32..FDC[1] as i32).contains(&l_min), "{l_min}");
}

/// The RMS radius (m) at distance `z` (m) in front of the film of the camera rays from the
/// centre of the film at `lambda` (nm).
fn spread_at(camera: &Camera, z: f32, lambda: f32) -> f64 {
    let (w, h) = camera.resolution();
    let raster = Vec2::new(w as f32 / 2.0, h as f32 / 2.0);
    let mut pts = Vec::new();
    for i in 0..64 * 64 {
        let u = Vec2::new(
            ((i % 64) as f32 + 0.5) / 64.0,
            ((i / 64) as f32 + 0.5) / 64.0,
        );
        if let Some((r, _)) = camera.generate_ray_at(raster, u, lambda) {
            let t = (z - r.o.z) / r.d.z;
            pts.push(r.o + t * r.d);
        }
    }
    assert!(pts.len() > 100, "{} rays", pts.len());
    let c = pts.iter().copied().sum::<Vec3>() / pts.len() as f32;
    mean(
        pts.iter()
            .map(|p| (p.truncate() - c.truncate()).length_squared()),
    )
    .sqrt()
}

#[test]
fn the_camera_focuses_each_wavelength_at_its_paraxial_image_distance() {
    // an N-BK7 singlet of f = 51 mm at f/25 (stop Ø 2 mm): its spherical aberration moves the
    // sharpest film position by about 0.02 mm, far less than the chromatic focal shift
    // (0.5 mm from F to d), so each wavelength's sharpest film position is its paraxial one
    let sys = lens("0 2 0 2\n51.68 6 N-BK7 25.4\n-51.68 95 1 25.4\n");
    let object = 2000.0; // mm in front of the film
    let to_world = Transform::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y).unwrap();
    for l in FDC {
        let d = sys.focus_film_distance(object, l).unwrap();
        // the film at d, and 0.05 to 0.3 mm either side
        let spread = |delta: f64| {
            let s = sys.clone().with_film_distance(d + delta).unwrap();
            let cam = Camera::realistic(to_world, s, 0.01, 16, 16).unwrap();
            // the object plane sits 2 m from the film as it was focused
            spread_at(&cam, (object * 1e-3) as f32 + delta as f32 * 1e-3, l as f32)
        };
        let at = spread(0.0);
        for delta in [-0.3, -0.1, -0.05, 0.05, 0.1, 0.3] {
            assert!(spread(delta) > at, "{l} nm: film {delta:+} mm is sharper");
        }
        // and the other wavelengths are blurred there
        let cam = Camera::realistic(
            to_world,
            sys.clone().with_film_distance(d).unwrap(),
            0.01,
            16,
            16,
        )
        .unwrap();
        for other in FDC.iter().filter(|o| **o != l) {
            let s = spread_at(&cam, (object * 1e-3) as f32, *other as f32);
            println!("focused for {l} nm: spread {at:.3e} m; at {other} nm {s:.3e} m");
            assert!(s > 3.0 * at);
        }
    }
}

fn lens_path() -> String {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lenses/dgauss50.lens");
    p.display().to_string().replace('\\', "/")
}

#[test]
fn a_uniform_surround_reads_its_radiance_at_the_image_centre() {
    // inside a black sphere emitting 1 W·m⁻²·sr⁻¹ (band), through the double Gauss at f/2: the
    // centre of the image reads the radiance, as a pinhole camera's every pixel does; the
    // corners read less (the lens's relative illumination)
    let scene = scene_from(&format!(
        r#"
[camera]
type = "realistic"
eye = [0, 0, 0]
target = [0, 0, 1]
lens_file = "{}"
film_diagonal = "43.27 mm"
[film]
width = 30
height = 20
spp = 64
[integrator]
max_depth = 1
[materials.black]
type = "diffuse"
reflectance = 0
[[shapes]]
type = "sphere"
center = [0, 0, 0]
radius = 5
material = "black"
emission = {{ radiance = "1 W/m^2/sr", two_sided = true }}
"#,
        lens_path()
    ));
    let (img, _) = render_with(&scene, |_| {});
    let at = |x: usize, y: usize| img.band[y * 30 + x] as f64;
    let centre = mean(
        [at(14, 9), at(15, 9), at(14, 10), at(15, 10)]
            .map(|v| v as f32)
            .into_iter(),
    );
    let corner = mean(
        [at(0, 0), at(29, 0), at(0, 19), at(29, 19)]
            .map(|v| v as f32)
            .into_iter(),
    );
    println!("centre {centre:.4}, corners {corner:.4} W/m²/sr");
    // 256 ray samples per pixel over a smooth pupil: the centre within 1 %
    assert!((centre - 1.0).abs() < 0.01, "{centre}");
    assert!(corner < 0.8 * centre && corner > 0.05, "{corner}");
}

#[test]
fn light_tracing_and_bdpt_refuse_a_realistic_camera() {
    let scene = scene_from(&format!(
        "[camera]\ntype = \"realistic\"\neye = [0, 0, 0]\ntarget = [0, 0, 1]\nlens_file = \"{}\"\n\
         [film]\nwidth = 8\nheight = 8\nspp = 1\n[[shapes]]\ntype = \"sphere\"\ncenter = [0, 0, 5]\n\
         radius = 1\nemission = {{ radiance = \"1 W/m^2/sr\" }}\n",
        lens_path()
    ));
    support::render::assert_light_and_bdpt_refuse(&scene, "realistic (lens-system) camera");
}

/// The mean direction (unit, camera space) of the rays from raster position `raster` at
/// `lambda` through a realistic camera.
fn mean_direction(camera: &Camera, raster: Vec2, lambda: f32) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for i in 0..32 * 32 {
        let u = Vec2::new(
            ((i % 32) as f32 + 0.5) / 32.0,
            ((i / 32) as f32 + 0.5) / 32.0,
        );
        if let Some((r, w)) = camera.generate_ray_at(raster, u, lambda) {
            sum += r.d * w;
        }
    }
    sum.normalize()
}

#[test]
fn the_double_gauss_shows_lateral_colour_toward_the_corners_and_none_at_the_centre() {
    // the same object direction lands at different film heights for F and C light: seen from
    // the film, the rays of one film point leave in different directions; the angle between
    // them times the focal length is the lateral colour on the film
    let path = lens_path();
    let desc = spectrace::loader::lens::read(std::path::Path::new(&path)).unwrap();
    let sys = spectrace::build::lens_system(&desc).unwrap();
    let efl = sys.paraxial(587.5618).efl;
    let to_world = Transform::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y).unwrap();
    let cam = Camera::realistic(to_world, sys, 0.04327, 360, 240).unwrap();
    let shift = |raster: Vec2| {
        let (f, c) = (
            mean_direction(&cam, raster, 486.13),
            mean_direction(&cam, raster, 656.27),
        );
        f.cross(c).length() as f64 * efl * 1e3 // µm on the film (sin of the angle)
    };
    let (centre, corner) = (shift(Vec2::new(180.0, 120.0)), shift(Vec2::new(8.0, 8.0)));
    println!("lateral colour F − C: centre {centre:.2} µm, corner {corner:.2} µm (pixels 100 µm)");
    assert!(centre < 0.5, "{centre}");
    assert!(corner > 2.0, "{corner}");
}
