//! Mitsuba 3's `measured_polarized` (issue 28) on a table made from a closed form: a GGX
//! conductor (α, constant n + ik), its Mueller BRDF F(θ_d)·D(θ_h)·G / (4 cos θ_L cos θ_V)
//! (G separable, as Mitsuba's `roughconductor`)
//! written on a grid of Rusinkiewicz angles as a `.pbsdf` tensor file, as the KAIST pBRDF
//! data are laid out (Mitsuba's `measured_polarized.cpp`: s = ω_L × ω_V on both beams, φ_d
//! the light's azimuth about h). Mitsuba states that such a table renders as its
//! `roughconductor` does; so must ours:
//!
//! - at the grid's nodes, f and the normalised Mueller matrix equal the closed form's (F from
//!   Fresnel's complex amplitudes, D and G of GGX written out here), and the matrix equals
//!   `roughconductor`'s in world bases;
//! - a rendered sphere of it and one of `roughconductor` agree in S0–S3 per tile within noise;
//! - a missing or damaged file is a located error.

mod support;

use std::f32::consts::{FRAC_PI_2, PI};
use std::path::{Path, PathBuf};

use glam::Vec3;
use spectrace::loader::mitsuba::tensor::write_tensor_file;
use spectrace::polarisation::{Complex, fresnel};

const ALPHA: f32 = 0.3;
const ETA: f32 = 0.2;
const K: f32 = 3.0;
const WAVELENGTHS: [f32; 5] = [450.0, 500.0, 550.0, 600.0, 650.0];

/// GGX's D (isotropic, α = ALPHA) for a half vector of cosine `cos_h` to the normal.
fn ggx_d(cos_h: f32) -> f32 {
    let a2 = ALPHA * ALPHA;
    let t = 1.0 + (a2 - 1.0) * cos_h * cos_h;
    a2 / (PI * t * t)
}
/// Smith's Λ of GGX for a direction of cosine `c`; G = G₁(ω_L)·G₁(ω_V) with G₁ = 1/(1 + Λ),
/// the separable form of Mitsuba's `roughconductor`, which the test scene's is.
fn ggx_lambda(c: f32) -> f32 {
    let t2 = (1.0 - c * c).max(0.0) / (c * c);
    0.5 * ((1.0 + ALPHA * ALPHA * t2).sqrt() - 1.0)
}

/// The closed-form Mueller BRDF (sr⁻¹, no cosine) at (φ_d, θ_d, θ_h), in the s basis. Below
/// the horizon (never queried) it continues the values at the horizon, where G₁(c)/c stays
/// finite, so that interpolating next to the horizon does not blend in zeros.
fn closed_form(phi_d: f32, theta_d: f32, theta_h: f32) -> [[f32; 4]; 4] {
    let (sh, ch) = theta_h.sin_cos();
    let (sd, cd) = theta_d.sin_cos();
    let c_l = (ch * cd - sh * sd * phi_d.cos()).max(1e-4);
    let c_v = (ch * cd + sh * sd * phi_d.cos()).max(1e-4);
    let f = fresnel::reflection(cd, Complex::new(ETA, K));
    // Mitsuba's separable Smith G, as its `roughconductor` (the scene's) uses
    let g = 1.0 / ((1.0 + ggx_lambda(c_l)) * (1.0 + ggx_lambda(c_v)));
    let s = ggx_d(ch) * g / (4.0 * c_l * c_v);
    f.0.map(|row| row.map(|x| x * s))
}

/// The grids: φ_d every 10° over [−180°, 180°], θ_d and θ_h of 91 and 61 nodes, denser at
/// grazing and near the pole. (With 31 nodes of θ_d, S1 of the sphere's rim came out 1 % high:
/// linear interpolation across the conductor's peak of R_s − R_p near 75°, 5 standard errors.)
fn grids() -> (Vec<f32>, Vec<f32>, Vec<f32>) {
    let phi: Vec<f32> = (0..37).map(|i| -PI + i as f32 * PI / 18.0).collect();
    // θ_d denser toward grazing, where Fresnel and shadowing change fastest (the sphere's rim)
    let td: Vec<f32> = (0..91)
        .map(|i| FRAC_PI_2 * (FRAC_PI_2 * i as f32 / 90.0).sin())
        .collect();
    let th: Vec<f32> = (0..61)
        .map(|i| FRAC_PI_2 * (i as f32 / 60.0).powi(2))
        .collect();
    (phi, td, th)
}

/// Writes the table to `dir/conductor.pbsdf`.
fn write_table(dir: &Path) -> PathBuf {
    let (phi, td, th) = grids();
    let mut m = Vec::with_capacity(phi.len() * td.len() * th.len() * 5 * 16);
    for &p in &phi {
        for &d in &td {
            for &h in &th {
                let v = closed_form(p, d, h);
                for _ in WAVELENGTHS {
                    m.extend(v.iter().flatten());
                }
            }
        }
    }
    let shape = vec![phi.len() as u64, td.len() as u64, th.len() as u64, 5, 4, 4];
    let bytes = write_tensor_file(&[
        ("phi_d", 10, vec![1, phi.len() as u64], phi),
        ("theta_d", 10, vec![1, td.len() as u64], td),
        ("theta_h", 10, vec![1, th.len() as u64], th),
        ("wvls", 3, vec![5], WAVELENGTHS.to_vec()),
        ("M", 10, shape, m),
    ]);
    let p = dir.join("conductor.pbsdf");
    std::fs::write(&p, bytes).expect("written");
    p
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("spectrace-pbsdf-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// A scene of one sphere of `bsdf` lit by a point light and a dim constant sky, seen whole.
fn scene_xml(bsdf: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="stokes"><integrator type="path"><integer name="max_depth" value="2"/></integrator></integrator>
    <sensor type="perspective">
        <float name="fov" value="32"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="36"/></film>
    </sensor>
    <emitter type="point"><point name="position" x="2.5" y="2" z="2"/><spectrum name="intensity" value="30"/></emitter>
    <emitter type="constant"><spectrum name="radiance" value="0.2"/></emitter>
    <shape type="sphere">{bsdf}</shape>
</scene>"#
    )
}

fn measured_bsdf(file: &Path) -> String {
    format!(
        r#"<bsdf type="measured_polarized"><string name="filename" value="{}"/><float name="alpha_sample" value="0.3"/></bsdf>"#,
        file.display()
    )
}

const ROUGH: &str = r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/><spectrum name="eta" value="0.2"/><spectrum name="k" value="3"/></bsdf>"#;

fn build(dir: &Path, bsdf: &str) -> spectrace::scene::Scene {
    let p = dir.join("scene.xml");
    std::fs::write(&p, scene_xml(bsdf)).expect("written");
    let desc = spectrace::loader::load_any(&p, &[]).unwrap_or_else(|e| panic!("{e}"));
    spectrace::build::build(&desc).unwrap_or_else(|e| panic!("{e}"))
}

/// Directions (light, view), local, of the node (φ_d, θ_d, θ_h) with φ_h = 0.
fn node_dirs(phi_d: f32, theta_d: f32, theta_h: f32) -> (Vec3, Vec3) {
    let h = Vec3::new(theta_h.sin(), 0.0, theta_h.cos());
    let b = Vec3::Y;
    let t = b.cross(h);
    let l =
        t * (theta_d.sin() * phi_d.cos()) + b * (theta_d.sin() * phi_d.sin()) + h * theta_d.cos();
    let v = 2.0 * h.dot(l) * h - l;
    (l, v)
}

#[test]
fn at_the_nodes_the_table_is_the_closed_form_and_roughconductor() {
    let dir = tmpdir("nodes");
    let file = write_table(&dir);
    let measured = build(&dir, &measured_bsdf(&file));
    let rough = build(&dir, ROUGH);
    assert!(measured.integrator.polarised);
    let (mm, mr) = (&measured.materials[0], &rough.materials[0]);
    let w = spectrace::spectrum::SampledWavelengths::<4> {
        lambda: [480.0, 520.0, 575.0, 630.0],
        pdf: [1.0; 4],
    };
    let frame = spectrace::geometry::Frame::from_normal(Vec3::Z);
    let (phi, td, th) = grids();
    let mut checked = 0;
    for &p in phi.iter().step_by(5) {
        for &d in td.iter().skip(1).step_by(4) {
            for &h in th.iter().skip(2).step_by(7) {
                let (l, v) = node_dirs(p, d, h);
                if l.z < 0.05 || v.z < 0.05 {
                    continue;
                }
                let truth = closed_form(p, d, h);
                let b = mm.at(glam::Vec2::ZERO, &w);
                // radiance transport: wo is the view, wi the light
                let f = b.eval(v, l, &w, spectrace::material::TransportMode::Radiance);
                for j in 0..4 {
                    let rel = (f[j] - truth[0][0]).abs() / truth[0][0];
                    assert!(
                        rel < 2e-3,
                        "f at ({p}, {d}, {h}): {} vs {}",
                        f[j],
                        truth[0][0]
                    );
                }
                let (
                    spectrace::material::Polarising::Matrix(pm),
                    spectrace::material::Polarising::Matrix(pr),
                ) = (
                    b.mueller(&frame, v, l, &w),
                    mr.at(glam::Vec2::ZERO, &w).mueller(&frame, v, l, &w),
                )
                else {
                    panic!("both polarise at ({p}, {d}, {h})");
                };
                for j in 0..4 {
                    for r in 0..4 {
                        for c in 0..4 {
                            let (a, e) = (pm[j].0[r][c], pr[j].0[r][c]);
                            assert!(
                                (a - e).abs() < 2e-3,
                                "P[{r}][{c}] at ({p}, {d}, {h}): {a} vs roughconductor {e}"
                            );
                        }
                    }
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 40, "{checked} nodes checked");
    std::fs::remove_dir_all(&dir).ok();
}

/// The asymmetric table of `scripts/gen_pbsdf_vectors.py` (`table()`): grids and values
/// computed in f64 as numpy does, stored as f32.
fn asym_table(dir: &Path) -> PathBuf {
    let lin = |a: f64, b: f64, n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| {
                if i + 1 == n {
                    b
                } else {
                    a + i as f64 * (b - a) / (n - 1) as f64
                }
            })
            .collect()
    };
    let pi = std::f64::consts::PI;
    let (phi, td, th) = (
        lin(-pi, pi, 9),
        lin(0.0, pi / 2.0, 7),
        lin(0.0, pi / 2.0, 8),
    );
    let mut m = Vec::new();
    for &p in &phi {
        for &d in &td {
            for &h in &th {
                for l in WAVELENGTHS {
                    let x = (l as f64 - 550.0) / 100.0;
                    for e in 0..16 {
                        let v = if e == 0 {
                            2.0 + 0.3 * p + 0.2 * d * d + 0.5 * h + 0.1 * x + 0.15 * p * d
                        } else {
                            0.02 * (e as f64 - 7.5)
                                * (1.0 + 0.2 * p - 0.3 * d + 0.25 * h * h + 0.1 * x)
                        };
                        m.push(v as f32);
                    }
                }
            }
        }
    }
    let f = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<f32>>();
    let bytes = write_tensor_file(&[
        ("phi_d", 10, vec![1, 9], f(&phi)),
        ("theta_d", 10, vec![1, 7], f(&td)),
        ("theta_h", 10, vec![1, 8], f(&th)),
        ("wvls", 3, vec![5], WAVELENGTHS.to_vec()),
        ("M", 10, vec![9, 7, 8, 5, 4, 4], m),
    ]);
    let p = dir.join("asym.pbsdf");
    std::fs::write(&p, bytes).expect("written");
    p
}

/// Mitsuba 3.9.1's own `eval` and `pdf` of the asymmetric table
/// (tests/reference/pbsdf/vectors.txt, by `scripts/gen_pbsdf_vectors.py`): in radiance and
/// importance transport, at wavelengths inside and beyond the table's (clamped), the Mueller
/// matrix times cos θ of Mitsuba's `wo`, in the implicit bases of the two beams, to 10⁻⁴ of
/// M₀₀; and the sampling density to 10⁻⁴ relative.
#[test]
fn an_asymmetric_table_evaluates_as_mitsuba_evaluates_it() {
    use spectrace::material::{Polarising, TransportMode};
    let dir = tmpdir("asym");
    let file = asym_table(&dir);
    let xml = format!(
        r#"<bsdf type="measured_polarized"><string name="filename" value="{}"/><float name="alpha_sample" value="0.2"/></bsdf>"#,
        file.display()
    );
    let scene = build(&dir, &xml);
    let mat = &scene.materials[0];
    let frame = spectrace::geometry::Frame::from_normal(Vec3::Z);
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/pbsdf/vectors.txt"),
    )
    .expect("vectors.txt");
    let mut n = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let mut it = line.split_whitespace();
        let mode = it.next().expect("mode");
        let v: Vec<f32> = it.map(|x| x.parse().expect("a number")).collect();
        let (si_wi, wo) = (Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5]));
        let (lambda, pdf) = (v[6], v[7]);
        let want = &v[8..24];
        let w = spectrace::spectrum::SampledWavelengths::<4> {
            lambda: [lambda; 4],
            pdf: [1.0; 4],
        };
        let b = mat.at(glam::Vec2::ZERO, &w);
        // the light and view directions of Mitsuba's query
        let (light, view) = if mode == "radiance" {
            (wo, si_wi)
        } else {
            (si_wi, wo)
        };
        let f = b.eval(view, light, &w, TransportMode::Radiance)[0];
        let f_imp = b.eval(light, view, &w, TransportMode::Importance)[0];
        assert!(
            (f - f_imp).abs() <= 1e-6 * f.abs(),
            "{line}: importance {f_imp} vs {f}"
        );
        let p = match b.mueller(&frame, view, light, &w) {
            Polarising::Matrix(p) => p[0],
            other => panic!("{line}: {other:?}"),
        };
        let scale = f * wo.z;
        let tol = 1e-4 * want[0].abs();
        for r in 0..4 {
            for c in 0..4 {
                let (ours, theirs) = (p.0[r][c] * scale, want[4 * r + c]);
                assert!(
                    (ours - theirs).abs() <= tol,
                    "{mode} {line}: M[{r}][{c}] {ours} vs Mitsuba {theirs}"
                );
            }
        }
        let ours_pdf = b.pdf(si_wi, wo, &w, TransportMode::Radiance);
        assert!(
            (ours_pdf - pdf).abs() <= 1e-4 * pdf,
            "{line}: pdf {ours_pdf} vs Mitsuba {pdf}"
        );
        n += 1;
    }
    assert_eq!(n, 48);
    std::fs::remove_dir_all(&dir).ok();
}

/// Per seed, per 12 × 12 tile, the X, Y, Z of S0–S3 of `scene` at `spp`.
fn tile_means(scene: &spectrace::scene::Scene, seeds: u32, spp: u32) -> Vec<Vec<[f64; 12]>> {
    (0..seeds)
        .map(|seed| {
            let (img, stats) = support::render::render_with(scene, |o| {
                o.spp = spp;
                o.seed = 11 + seed;
            });
            assert_eq!(stats.nan_samples + stats.inf_samples, 0);
            let (w, h) = (img.width, img.height);
            let mut out = vec![[0.0; 12]; (w / 12) * (h / 12)];
            for y in 0..h {
                for x in 0..w {
                    let (i, t) = (y * w + x, (y / 12) * (w / 12) + x / 12);
                    for c in 0..3 {
                        out[t][c] += img.xyz[i][c] as f64 / 144.0;
                        for k in 0..3 {
                            out[t][3 * (k + 1) + c] += img.stokes[i][k][c] as f64 / 144.0;
                        }
                    }
                }
            }
            out
        })
        .collect()
}

/// A sphere of the tabulated conductor and one of `roughconductor` (GGX, the same α, n + ik)
/// render alike, S0–S3 per tile within 5 combined standard errors (16 seeds each): the table's
/// interpolation is fine enough, and sampling, the scalar weights and the Mueller matrices
/// of a render agree.
#[test]
fn a_tabulated_conductor_renders_as_roughconductor() {
    let dir = tmpdir("render");
    let file = write_table(&dir);
    let measured = tile_means(&build(&dir, &measured_bsdf(&file)), 16, 8);
    let rough = tile_means(&build(&dir, ROUGH), 16, 8);
    let stats = |r: &[Vec<[f64; 12]>], t: usize, c: usize| {
        let n = r.len() as f64;
        let m = r.iter().map(|s| s[t][c]).sum::<f64>() / n;
        let v = r.iter().map(|s| (s[t][c] - m).powi(2)).sum::<f64>() / (n - 1.0);
        (m, (v / n).sqrt())
    };
    let (mut worst, mut polarised, mut failures) = (0.0f64, 0, Vec::new());
    for t in 0..measured[0].len() {
        for c in 0..12 {
            let ((a, sa), (b, sb)) = (stats(&measured, t, c), stats(&rough, t, c));
            let floor = 1e-6 * stats(&rough, t, c % 3).0.abs();
            let se = (sa * sa + sb * sb + floor * floor).sqrt();
            let z = if se > 0.0 { (a - b) / se } else { 0.0 };
            worst = worst.max(z.abs());
            if c >= 3 && b.abs() > 5.0 * sb {
                polarised += 1;
            }
            if z.abs() > 5.0 {
                failures.push(format!(
                    "tile {t} value {c}: {a:.5} vs roughconductor {b:.5} (z {z:+.1})"
                ));
            }
        }
    }
    println!("worst |z| {worst:.2}, {polarised} clearly polarised values");
    assert!(polarised >= 10, "only {polarised} clearly polarised values");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    std::fs::remove_dir_all(&dir).ok();
}

/// A missing file, and a damaged one, are errors naming the scene's line and the file.
#[test]
fn a_missing_or_damaged_pbsdf_is_a_located_error() {
    let dir = tmpdir("errors");
    let p = dir.join("scene.xml");
    let missing = dir.join("nowhere.pbsdf");
    std::fs::write(&p, scene_xml(&measured_bsdf(&missing))).expect("written");
    let e = spectrace::loader::load_any(&p, &[])
        .expect_err("no file")
        .to_string();
    assert!(
        e.contains("scene.xml:") && e.contains("nowhere.pbsdf") && e.contains("does not exist"),
        "{e}"
    );
    let damaged = dir.join("damaged.pbsdf");
    std::fs::write(&damaged, b"tensor_file\0\x01\x00\x05\x00\x00\x00").expect("written");
    std::fs::write(&p, scene_xml(&measured_bsdf(&damaged))).expect("written");
    let e = spectrace::loader::load_any(&p, &[])
        .expect_err("damaged")
        .to_string();
    assert!(
        e.contains("scene.xml:") && e.contains("damaged.pbsdf") && e.contains("header ends early"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The TOML material reads a `.pbsdf` file as the Mitsuba importer does: the same table,
/// sampling roughness and fixed wavelength make the same material.
#[test]
fn toml_and_mitsuba_read_the_same_measured_material() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/pbsdf/synthetic.pbsdf");
    let toml = format!(
        r#"
[camera]
eye = [0, 0, 4]
target = [0, 0, 0]
fov = "30 deg"

[film]
width = 8
height = 8

[materials.m]
type = "measured_polarized"
file = "{}"
alpha_sample = 0.06
wavelength = "550 nm"

[[shapes]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "m"

[[lights]]
type = "point"
position = [0, 2, 3]
power = "100 W"
"#,
        file.display()
    );
    let desc =
        spectrace::loader::load_str(&toml, Path::new("m.toml")).unwrap_or_else(|e| panic!("{e}"));
    let from_toml = spectrace::build::build(&desc).expect("builds");
    let dir = tmpdir("toml");
    let xml = format!(
        r#"<bsdf type="measured_polarized"><string name="filename" value="{}"/><float name="alpha_sample" value="0.06"/><float name="wavelength" value="550"/></bsdf>"#,
        file.display()
    );
    let from_xml = build(&dir, &xml);
    assert!(
        from_toml.integrator.polarised,
        "a measured pBRDF renders polarised"
    );
    assert_eq!(from_toml.materials[0], from_xml.materials[0]);
    std::fs::remove_dir_all(&dir).ok();
}
