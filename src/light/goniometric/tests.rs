//! Tests of `goniometric`.

use super::*;

fn table(fold: Fold, h: &[f32], v: &[f32], cd: &[f32]) -> IntensityTable {
    IntensityTable {
        vertical: v.to_vec(),
        horizontal: h.to_vec(),
        fold,
        cd: cd.to_vec(),
    }
}

#[test]
fn exact_at_measured_angles_and_folded() {
    let t = table(
        Fold::Quadrant,
        &[0.0, 90.0],
        &[0.0, 45.0, 90.0],
        &[100.0, 80.0, 10.0, 100.0, 40.0, 0.0],
    );
    assert_eq!(t.eval(45.0, 0.0), 80.0);
    assert_eq!(t.eval(45.0, 90.0), 40.0);
    // mirrored: C = 270 is C = 90, C = 180 is C = 0, C = 135 is C = 45
    assert_eq!(t.eval(45.0, 270.0), 40.0);
    assert_eq!(t.eval(45.0, 180.0), 80.0);
    assert_eq!(t.eval(45.0, 135.0), t.eval(45.0, 45.0));
    assert_eq!(t.eval(45.0, 45.0), 60.0);
    // bilinear between, and nothing above the last vertical angle
    assert_eq!(t.eval(22.5, 0.0), 90.0);
    assert_eq!(t.eval(91.0, 0.0), 0.0);
    let b = table(
        Fold::Bilateral90To270,
        &[90.0, 180.0, 270.0],
        &[0.0, 90.0],
        &[1.0, 1.0, 2.0, 2.0, 3.0, 3.0],
    );
    assert_eq!(b.eval(10.0, 0.0), 2.0); // C0 mirrors to C180
    assert_eq!(b.eval(10.0, 45.0), 1.5); // C45 mirrors to C135
    assert_eq!(b.eval(10.0, 315.0), 2.5); // C315 mirrors to C225
    let f = table(
        Fold::Full,
        &[0.0, 90.0, 180.0, 270.0],
        &[0.0, 180.0],
        &[0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0],
    );
    assert_eq!(f.eval(30.0, 315.0), 1.5); // wraps from 270 (3) to 360 (0)
}

#[test]
fn luminous_flux_is_exact() {
    // an isotropic 100 cd plane table: 400π lm, any symmetry
    let iso = table(Fold::Axial, &[0.0], &[0.0, 180.0], &[100.0, 100.0]);
    assert!((iso.luminous_flux() / (400.0 * std::f64::consts::PI) - 1.0).abs() < 1e-9);
    // I = 100 cos γ below the horizon, sampled at 1° steps: ∫ = 100π up to the bilinear
    // table's chord error (< 1e-4 relative)
    let v: Vec<f32> = (0..=90).map(|d| d as f32).collect();
    let cd: Vec<f32> = v.iter().map(|&d| 100.0 * d.to_radians().cos()).collect();
    let mut both = cd.clone();
    both.extend(&cd);
    let q = table(Fold::Quadrant, &[0.0, 90.0], &v, &both);
    let flux = q.luminous_flux();
    assert!(
        (flux / (100.0 * std::f64::consts::PI) - 1.0).abs() < 1e-4,
        "{flux}"
    );
}

#[test]
fn emission_density_integrates_to_one_and_bounds_intensity() {
    let t = table(
        Fold::Bilateral0To180,
        &[0.0, 60.0, 180.0],
        &[0.0, 30.0, 60.0],
        &[50.0, 40.0, 0.0, 50.0, 10.0, 0.0, 50.0, 45.0, 5.0],
    );
    let l = GoniometricLight::new(Vec3::ZERO, Mat3::IDENTITY, Spectrum::Constant(1.0), t).unwrap();
    // ∫ pdf dω over the cells = 1; no direction with light has zero density
    let n = 400;
    let mut sum = 0.0f64;
    for i in 0..n {
        for j in 0..2 * n {
            let cos_g = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let phi = std::f32::consts::TAU * (j as f32 + 0.5) / (2 * n) as f32;
            let s = (1.0 - cos_g * cos_g).sqrt();
            let d = Vec3::new(s * phi.cos(), s * phi.sin(), -cos_g);
            let pdf = l.pdf_le(d).dir;
            sum += pdf as f64 * 4.0 * std::f64::consts::PI / (2 * n * n) as f64;
            if l.candela(d) > 0.0 {
                assert!(pdf > 0.0, "{d:?}");
            }
        }
    }
    assert!((sum - 1.0).abs() < 1e-3, "{sum}");
}
