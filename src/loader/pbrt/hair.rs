//! pbrt-v4's `hair` material (`HairMaterial::Create` and `GetBxDF`, src/pbrt/materials.cpp
//! and materials.h) as spectrace's fibre model read the pbrt-v4 way (`Hair::with_pbrt`: the
//! offset across the fibre from the surface's v, pbrt-v4's frame and its I₀).
//!
//! The absorption per fibre radius, first of: `sigma_a` (an unbounded `rgb` or a spectrum,
//! clamped at 0); `reflectance` (or `color`; an albedo in [0, 1]), turned into σₐ(λ) =
//! (ln c(λ) / (5.969 − 0.215β_n + 2.532β_n² − 10.73β_n³ + 5.574β_n⁴ + 0.245β_n⁵))², Chiang et
//! al. 2016's inversion, tabulated at 1 nm; `eumelanin` and `pheomelanin` concentrations, the
//! unbounded uplift of c_e·(0.419, 0.697, 1.37) + c_p·(0.187, 0.4, 1.05); by default
//! eumelanin 1.3. `eta` 1.55, `beta_m` and `beta_n` 0.3 (clamped to [0.01, 1] as pbrt-v4
//! clamps them), `alpha` 2°. Parameters as textures are refused.

use std::sync::Arc;

use super::media::coefficient;
use super::params::{Params, R};
use crate::loader::desc::{HairAbsorption, HairDesc, MaterialKind};
use crate::spectrum::{PiecewiseLinear, Spectrum, rgb2spec};
use crate::units::Angle;

/// A float parameter of the hair, refused as a texture.
fn number(p: &Params, name: &str, default: f64) -> R<f64> {
    if p.get(name).is_some_and(|q| q.ty == "texture") {
        return Err(p.err(
            p.loc_of(name),
            format!("\"{name}\": a hair's parameters as textures are not read yet"),
        ));
    }
    p.float(name, default)
}

/// σₐ from a reflectance (module doc), tabulated over 360–830 nm at 1 nm.
fn sigma_from_reflectance(c: &Spectrum, beta_n: f64) -> Option<Spectrum> {
    let b = beta_n;
    let d = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * b.powi(3)
        + 5.574 * b.powi(4)
        + 0.245 * b.powi(5);
    let l: Vec<f32> = (360..=830).map(|x| x as f32).collect();
    // c → 0 makes σₐ infinite (no light through): 10⁻⁶ keeps it finite and opaque
    let v = l
        .iter()
        .map(|&x| ((c.eval(x) as f64).clamp(1e-6, 1.0).ln() / d).powi(2) as f32)
        .collect();
    PiecewiseLinear::new(l, v)
        .ok()
        .map(|t| Spectrum::Piecewise(Arc::new(t)))
}

/// A `hair` material's description.
pub(super) fn hair(p: &Params) -> R<MaterialKind> {
    let eta = number(p, "eta", 1.55)?;
    if !(eta > 0.0 && eta.is_finite()) {
        return Err(p.err(p.loc_of("eta"), "a hair's \"eta\" must be positive"));
    }
    let beta_m = number(p, "beta_m", 0.3)?.clamp(0.01, 1.0);
    let beta_n = number(p, "beta_n", 0.3)?.clamp(0.01, 1.0);
    let alpha = number(p, "alpha", 2.0)?;
    let reflectance_name = ["reflectance", "color"]
        .into_iter()
        .find(|n| p.get(n).is_some());
    let (ce, cp) = (p.get("eumelanin"), p.get("pheomelanin"));
    let melanin = |name: &str| -> R<f32> { Ok(number(p, name, 0.0)?.max(0.0) as f32) };
    // `get` marks a parameter read: pbrt-v4 reads (and ignores, with a warning) the sources
    // after the first
    let sigma_a = if p.get("sigma_a").is_some() {
        coefficient(p, "sigma_a", 0.0)?
    } else if let Some(name) = reflectance_name {
        let c = super::spectra::reflectance(p, name, 0.5)?;
        sigma_from_reflectance(&c, beta_n)
            .ok_or_else(|| p.err(p.loc_of(name), "the reflectance gives no absorption"))?
    } else {
        let (e, ph) = if ce.is_some() || cp.is_some() {
            (melanin("eumelanin")?, melanin("pheomelanin")?)
        } else {
            (1.3, 0.0)
        };
        let rgb = [0, 1, 2].map(|k| e * [0.419, 0.697, 1.37][k] + ph * [0.187, 0.4, 1.05][k]);
        rgb2spec::unbounded(rgb).map_err(|m| p.err(p.loc_of("eumelanin"), m.to_string()))?
    };
    Ok(MaterialKind::Hair(Box::new(HairDesc {
        absorption: HairAbsorption::Sigma {
            sigma_a,
            scale: 1.0,
        },
        eta,
        roughness: [beta_m, beta_n],
        scale_tilt: Angle::new::<crate::units::angle::degree>(alpha),
        pbrt: true,
    })))
}
