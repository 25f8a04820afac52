//! The N-BK7 prism of the dispersion tests (`tests/prism.rs`, `tests/media_bdpt.rs`), its glass
//! and Snell's law, evaluated independently of the renderer.

use glam::DVec2;

/// N-BK7's refractive index (SCHOTT's Sellmeier coefficients), λ in nm.
pub fn n_bk7(l_nm: f64) -> f64 {
    let l2 = (l_nm * 1e-3).powi(2);
    let b = [1.03961212, 0.231792344, 1.01046945];
    let c = [0.00600069867, 0.0200179144, 103.560653];
    (1.0 + (0..3).map(|i| b[i] * l2 / (l2 - c[i])).sum::<f64>()).sqrt()
}

/// Refraction of unit `d` at a surface with unit normal `n` facing the incoming side, η = n₁/n₂.
pub fn refract(d: DVec2, n: DVec2, eta: f64) -> DVec2 {
    let cos_i = -d.dot(n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    assert!(k > 0.0, "total internal reflection");
    eta * d + (eta * cos_i - k.sqrt()) * n
}

// The prism in the xy plane (metres), apex up, 10 cm deep in z: A, B on the base, C the apex.
pub const A: DVec2 = DVec2::new(-0.05, 0.0);
pub const B: DVec2 = DVec2::new(0.05, 0.0);
pub const C: DVec2 = DVec2::new(0.0, 0.0866025);

/// The prism as a TOML mesh (`vertices` and `faces` keys).
pub const MESH: &str = "vertices = [[-0.05, 0, 0.05], [0.05, 0, 0.05], [0, 0.0866025, 0.05], \
    [-0.05, 0, -0.05], [0.05, 0, -0.05], [0, 0.0866025, -0.05]]\n\
    faces = [[0, 1, 2], [3, 5, 4], [0, 3, 4], [0, 4, 1], [0, 2, 5], [0, 5, 3], [1, 4, 5], \
    [1, 5, 2]]\n";

/// The outward unit normals of the left face AC and the right face BC.
pub fn normals() -> (DVec2, DVec2) {
    (
        DVec2::new(-(C - A).y, (C - A).x).normalize(),
        DVec2::new((C - B).y, -(C - B).x).normalize(),
    )
}

/// The ray of direction `d` (unit, in the plane) through the point `o`, refracted into the
/// prism at its left face and out of its right face at wavelength `l` nm: the entry point, the
/// exit point and the exit direction.
pub fn through(o: DVec2, d: DVec2, l: f64) -> (DVec2, DVec2, DVec2) {
    let (n_left, n_right) = normals();
    let entry = o + d * ((A - o).dot(n_left) / d.dot(n_left));
    let n = n_bk7(l);
    let t = refract(d, n_left, 1.0 / n);
    let exit = entry + t * ((B - entry).dot(n_right) / t.dot(n_right));
    (entry, exit, refract(t, -n_right, n))
}

/// The retardance of one total internal reflection from inside glass of index n at incidence
/// θ (Born and Wolf §1.5.4): tan(δ/2) = cos θ √(sin²θ − 1/n²) / sin²θ.
pub fn tir_retardance(n: f64, theta: f64) -> f64 {
    let s2 = theta.sin().powi(2);
    2.0 * (theta.cos() * (s2 - 1.0 / (n * n)).sqrt() / s2).atan()
}
