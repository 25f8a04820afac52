//! Materials that pbrt-v4's scenes bring (`crate::loader::pbrt`), made render-ready.

use super::textures;
use crate::loader::desc::{LayeredDesc, RglTable};
use crate::material::{Layered, LayeredBase, Material, Measured, Warp2D};

/// pbrt-v4's `coateddiffuse` or `coatedconductor`. The Henyey–Greenstein g, which pbrt-v4
/// clamps to [−1, 1], is kept inside (−0.999, 0.999): at ±1 the lobe is a delta that the
/// slab's walk cannot sample (pbrt-v4 itself divides 0 by 0 there).
pub(super) fn layered(d: &LayeredDesc) -> Result<Material, String> {
    let alpha = |a: Option<[f64; 2]>| a.map(|[u, v]| [u as f32, v as f32]);
    let base = match &d.conductor {
        None => LayeredBase::Diffuse,
        Some((ior, rough)) => LayeredBase::Conductor {
            ior: ior.clone(),
            alpha: alpha(*rough),
        },
    };
    Ok(Material::Layered(Box::new(Layered {
        base,
        reflectance: textures::texture(&d.reflectance)?,
        eta: d.eta.clone(),
        alpha: alpha(d.roughness),
        alpha_texture: match &d.roughness_texture {
            Some((t, remap)) => {
                let (u, v) = (textures::texture(&t[0])?, textures::texture(&t[1])?);
                if !(textures::is_grey(&u) && textures::is_grey(&v)) {
                    return Err("a textured roughness must be a grey image or a number".into());
                }
                Some(([u, v], *remap))
            }
            None => None,
        },
        thickness: d.thickness as f32,
        albedo: textures::texture(&d.albedo)?,
        g: d.g.clamp(-0.999, 0.999) as f32,
        max_depth: d.max_depth,
        n_samples: d.n_samples,
        pbrt_exit_weight: d.pbrt_exit_weight,
    })))
}

/// pbrt-v4's `diffusetransmission`: its reflectance and transmittance textures.
pub(super) fn diffuse_transmission(
    reflectance: &crate::loader::desc::TextureDesc,
    transmittance: &crate::loader::desc::TextureDesc,
) -> Result<Material, String> {
    Ok(Material::DiffuseTransmission(Box::new(
        crate::material::DiffuseTransmission {
            reflectance: textures::texture(reflectance)?,
            transmittance: textures::texture(transmittance)?,
        },
    )))
}

/// pbrt-v4's and Mitsuba's `measured` from the file's tables (pbrt-v4's `MeasuredBxDFData`):
/// `ndf`, `sigma` and `spectra` as interpolants, `vndf` and `luminance` as normalised warps
/// over (φ_i, θ_i); isotropic when φ_i has at most two nodes; `jacobian` as
/// [`Measured::jacobian`].
pub(super) fn measured(t: &RglTable, jacobian: bool) -> Result<Material, String> {
    let angles = || vec![t.phi_i.clone(), t.theta_i.clone()];
    let size = |s: [usize; 2]| (s[0], s[1]);
    let warp = |name: &str, v: &[f32], s, params, normalize| {
        Warp2D::new(v, size(s), params, normalize).map_err(|e| format!("measured `{name}`: {e}"))
    };
    Ok(Material::Measured(std::sync::Arc::new(Measured {
        ndf: warp("ndf", &t.ndf, t.ndf_size, vec![], false)?,
        sigma: warp("sigma", &t.sigma, t.sigma_size, vec![], false)?,
        vndf: warp("vndf", &t.vndf, t.vndf_size, angles(), true)?,
        luminance: warp("luminance", &t.luminance, t.sample_size, angles(), true)?,
        spectra: warp(
            "spectra",
            &t.spectra,
            t.sample_size,
            vec![t.phi_i.clone(), t.theta_i.clone(), t.wavelengths.clone()],
            false,
        )?,
        isotropic: t.phi_i.len() <= 2,
        jacobian,
    })))
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use crate::material::Material;
    use crate::spectrum::SampledWavelengths;

    /// The measured material of `tests/reference/pbrt/measured/ggx.bsdf`, which
    /// scripts/gen_rgl_bsdf.py wrote from an analytic GGX conductor.
    fn ggx_file() -> std::sync::Arc<crate::material::Measured> {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/reference/pbrt/measured/ggx.bsdf"
        );
        let t = crate::loader::mitsuba::rgl::read_rgl_bsdf(path.as_ref()).expect("reads");
        match super::measured(&t, true).expect("builds") {
            Material::Measured(m) => m,
            _ => unreachable!(),
        }
    }

    /// The GGX conductor the file was made from (the script's closed form): Schlick's F with
    /// F0 from 0.25 at 380 nm to 0.95 at 780 nm, α = 0.3, height-correlated Smith.
    fn ggx(wo: Vec3, wi: Vec3, lambda: f32) -> f32 {
        let a2 = 0.09f32;
        let m = (wo + wi).normalize();
        let d = a2 / (std::f32::consts::PI * ((a2 - 1.0) * m.z * m.z + 1.0).powi(2));
        let lam = |c: f32| (-1.0 + (1.0 + a2 * (1.0 - c * c) / (c * c)).sqrt()) / 2.0;
        let g2 = 1.0 / (1.0 + lam(wo.z) + lam(wi.z));
        let f0 = 0.25 + 0.7 * (lambda - 380.0) / 400.0;
        let f = f0 + (1.0 - f0) * (1.0 - wo.dot(m)).powi(5);
        f * d * g2 / (4.0 * wo.z * wi.z)
    }

    fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    /// pbrt-v4's `measured` evaluation of the file reproduces the BRDF it was written from
    /// (bilinear tables: within 1 %), at in-plane and out-of-plane pairs and between the
    /// file's incidence angles (every 10°) and wavelengths (every 50 nm).
    #[test]
    fn measured_ggx_file_matches_its_closed_form() {
        let m = ggx_file();
        let w = SampledWavelengths::<4> {
            lambda: [450.0, 555.0, 650.0, 700.0],
            pdf: [1.0; 4],
        };
        for (to, po, ti, pi) in [
            (30.0, 0.0, 30.0, 180.0),
            (45.0, 20.0, 40.0, 190.0),
            (15.0, 90.0, 25.0, 250.0),
            (62.0, -40.0, 55.0, 150.0),
        ] {
            let (wo, wi) = (dir(to, po), dir(ti, pi));
            let f = m.eval(wo, wi, &w);
            for j in 0..4 {
                let want = ggx(wo, wi, w.lambda[j]);
                let err = f.0[j] / want - 1.0;
                assert!(
                    err.abs() < 0.01,
                    "θo {to}, θi {ti}, λ {}: {err:+.4}",
                    w.lambda[j]
                );
            }
        }
    }

    /// Sampling returns the value and the density `eval` and `pdf` give for the direction
    /// drawn, and the sampled estimate of the directional albedo ∫ f cos θᵢ dωᵢ agrees with
    /// the closed form's, integrated on a fine grid (the estimator's own noise is < 0.2 %).
    #[test]
    fn measured_sampling_is_consistent_with_its_density() {
        let m = ggx_file();
        let w = SampledWavelengths::<4> {
            lambda: [550.0; 4],
            pdf: [1.0; 4],
        };
        let wo = dir(50.0, 30.0);
        let (n, mut sum) = (256usize, 0.0f64);
        for i in 0..n {
            for j in 0..n {
                let u = glam::Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let Some(s) = m.sample(wo, u, &w) else {
                    continue;
                };
                let (f, pdf) = (m.eval(wo, s.wi, &w), m.pdf(wo, s.wi));
                assert!((pdf / s.pdf - 1.0).abs() < 2e-3, "pdf {pdf} vs {}", s.pdf);
                assert!((f.0[0] / s.f.0[0] - 1.0).abs() < 2e-3);
                sum += (s.f.0[0] * s.wi.z / s.pdf) as f64;
            }
        }
        let estimate = sum / (n * n) as f64;
        let k = 400;
        let mut exact = 0.0f64;
        for a in 0..k {
            for b in 0..2 * k {
                let t = (a as f32 + 0.5) / k as f32 * std::f32::consts::FRAC_PI_2;
                let p = (b as f32 + 0.5) / k as f32 * std::f32::consts::PI;
                let wi = Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
                let da = t.sin()
                    * (std::f32::consts::FRAC_PI_2 / k as f32)
                    * (std::f32::consts::PI / k as f32);
                exact += (ggx(wo, wi, 550.0) * wi.z * da) as f64;
            }
        }
        println!("albedo at 50°, 550 nm: sampled {estimate:.5}, closed form {exact:.5}");
        assert!(
            (estimate / exact - 1.0).abs() < 0.01,
            "{estimate} vs {exact}"
        );
    }
}
