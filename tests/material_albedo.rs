//! `material::albedo` and the `spectrace material` and `spectrace lens` commands against
//! closed forms: Fresnel for smooth glass, the quarter-wave coating, a Lambertian albedo, and
//! the lens's paraxial focal lengths.

mod support;

use std::process::Command;

use spectrace::material::Material;
use spectrace::material::albedo::albedo;

/// The scene's materials by name (the description's order is the scene's).
fn materials() -> Vec<(String, Material)> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/inline.toml");
    let desc = spectrace::loader::load_str(SCENE, &path).unwrap();
    let scene = spectrace::build::build(&desc).unwrap();
    desc.materials
        .iter()
        .map(|m| m.name.clone())
        .zip(scene.materials)
        .collect()
}

fn material(name: &str) -> Material {
    materials().into_iter().find(|(n, _)| n == name).unwrap().1
}

const SCENE: &str = r#"
[camera]
eye = [0, 0, 4]
target = [0, 0, 0]
fov = "40 deg"
[film]
width = 8
height = 8
[materials.glass]
type = "dielectric"
ior = 1.5
[materials.ar]
type = "dielectric"
ior = 1.52
coating = [{ thickness = "100 nm", ior = 1.38 }]
[materials.white]
type = "diffuse"
reflectance = 0.7
[materials.frosted]
type = "dielectric"
ior = 1.5
roughness = 0.3
[[shapes]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "glass"
emission = { radiance = "1 W/m^2/sr" }
"#;

fn fresnel(n: f64, cos: f64) -> f64 {
    let sin_t = (1.0 - cos * cos).sqrt() / n;
    let ct = (1.0 - sin_t * sin_t).sqrt();
    let rs = ((cos - n * ct) / (cos + n * ct)).powi(2);
    let rp = ((ct - n * cos) / (ct + n * cos)).powi(2);
    0.5 * (rs + rp)
}

#[test]
fn smooth_glass_has_the_fresnel_reflectance_exactly() {
    let glass = &material("glass");
    for deg in [0.0f64, 30.0, 60.0, 85.0] {
        let a = albedo(glass, deg.to_radians() as f32, 550.0, 16, 0);
        let r = fresnel(1.5, deg.to_radians().cos());
        assert!(a.exact && a.reflectance_se == 0.0);
        assert!(
            (a.reflectance - r).abs() < 1e-6,
            "{deg}: {} vs {r}",
            a.reflectance
        );
        assert!((a.transmittance - (1.0 - r)).abs() < 1e-6, "{deg}");
    }
    // quarter wave of n 1.38 at 552 nm on n 1.52: ((1.52 − 1.38²)/(1.52 + 1.38²))²
    let ar = &material("ar");
    let a = albedo(ar, 0.0, 4.0 * 1.38 * 100.0, 16, 0);
    let n1 = 1.38f32 as f64;
    let n2 = 1.52f32 as f64;
    let closed = ((n2 - n1 * n1) / (n2 + n1 * n1)).powi(2);
    assert!(
        (a.reflectance - closed).abs() < 1e-6,
        "{} vs {closed}",
        a.reflectance
    );
}

#[test]
fn rough_and_diffuse_materials_are_estimated_with_their_standard_errors() {
    let white = albedo(&material("white"), 0.4, 550.0, 4096, 1);
    assert!((white.reflectance - 0.7).abs() < 1e-6 && white.transmittance == 0.0);
    // frosted glass: its microfacets lose a little energy (single scattering) but R + T is
    // close to 1, and R close to the smooth Fresnel value near normal incidence
    let f = albedo(&material("frosted"), 0.0, 550.0, 65536, 1);
    println!(
        "frosted: R {:.4} ± {:.4}, T {:.4} ± {:.4}",
        f.reflectance, f.reflectance_se, f.transmittance, f.transmittance_se
    );
    assert!(!f.exact && f.reflectance_se > 0.0 && f.transmittance_se > 0.0);
    let sum = f.reflectance + f.transmittance;
    assert!(
        sum < 1.0 + 4.0 * (f.reflectance_se + f.transmittance_se) && sum > 0.9,
        "{sum}"
    );
    assert!(
        (f.reflectance - fresnel(1.5, 1.0)).abs() < 0.02,
        "{}",
        f.reflectance
    );
}

fn stdout(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .args(args)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into()
}

#[test]
fn the_material_and_lens_commands_print_csv() {
    let dir = support::cli::tmpdir("material-cmd");
    let scene = dir.join("s.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let s = scene.to_str().unwrap();
    let out = stdout(&[
        "material",
        s,
        "glass",
        "--angle",
        "60deg",
        "--wavelengths",
        "500:600:50",
    ]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "wavelength_nm,reflectance,transmittance,reflectance_se,transmittance_se"
    );
    assert_eq!(lines.len(), 4, "{out}");
    let r: f64 = lines[2].split(',').nth(1).unwrap().parse().unwrap();
    assert!((r - fresnel(1.5, 0.5)).abs() < 1e-5, "{r}");
    let svg = dir.join("r.svg");
    stdout(&[
        "material",
        s,
        "frosted",
        "--wavelengths",
        "550",
        "--samples",
        "1000",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    // an unknown material names the closest
    let bad = Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .args(["material", s, "glas"])
        .output()
        .unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("did you mean \"glass\""));

    // the lens command: the double Gauss's paraxial EFL at the d line, as its own trace gives
    let lens = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lenses/dgauss50.lens");
    let out = stdout(&[
        "lens",
        lens.to_str().unwrap(),
        "--wavelengths",
        "587.5618",
        "--spot",
    ]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "wavelength_nm,efl_mm,bfl_mm,spot_rms_um");
    let v: Vec<f64> = lines[1].split(',').map(|x| x.parse().unwrap()).collect();
    // scaled from Tronnier's 100 mm design to 50 mm, in catalogue glasses
    assert!((v[1] - 50.0).abs() < 0.5, "EFL {}", v[1]);
    assert!(v[2] > 30.0 && v[2] < 40.0 && v[3] > 0.0, "{out}");
}

#[test]
fn bad_angles_wavelengths_and_lens_files_are_errors() {
    let dir = support::cli::tmpdir("material-bad");
    let scene = dir.join("s.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let s = scene.to_str().unwrap();
    let lens_path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lenses/dgauss50.lens");
    let lens = lens_path.to_str().unwrap();
    for (args, expect) in [
        (
            vec!["material", s, "glass", "--angle", "90deg"],
            "expected 0 to 90 deg",
        ),
        (vec!["material", s, "glass", "--angle", "30 m"], "--angle"),
        (
            vec!["material", s, "glass", "--wavelengths", "700:400:5"],
            "FROM:TO:STEP",
        ),
        (
            vec!["material", s, "glass", "--wavelengths", "500,-3"],
            "FROM:TO:STEP",
        ),
        (vec!["lens", "/nonexistent/x.lens"], "cannot read lens file"),
        (vec!["lens", lens, "--wavelengths", "0"], "must be positive"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_spectrace"))
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && err.contains(expect),
            "{args:?}: {err}"
        );
    }
}
