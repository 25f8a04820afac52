//! pbrt-v4's microfacet roughness parameters (`roughness`, `uroughness`, `vroughness`,
//! `remaproughness`, with a prefix such as `interface.`), as numbers or float textures.

use super::materials::Named;
use super::params::{Params, R};
use crate::loader::desc::*;
use crate::spectrum::Spectrum;

/// pbrt-v4's microfacet roughness: `roughness`, or `uroughness`/`vroughness` (0), turned into
/// α by `remaproughness` (true: α = √r, pbrt-v4's `TrowbridgeReitzDistribution::RoughnessToAlpha`);
/// None when smooth (α = 0 in pbrt-v4 is its specular case).
pub(super) fn roughness(p: &Params, prefix: &str) -> R<Option<[f64; 2]>> {
    let r = p.float(&format!("{prefix}roughness"), 0.0)?;
    let u = p.float(&format!("{prefix}uroughness"), r)?;
    let v = p.float(&format!("{prefix}vroughness"), r)?;
    let remap = p.bool("remaproughness", true)?;
    let alpha = |x: f64| if remap { x.max(0.0).sqrt() } else { x };
    let (au, av) = (alpha(u), alpha(v));
    // pbrt-v4's `EffectivelySmooth`: max(α_x, α_y) < 10⁻³
    Ok((au.max(av) >= 1e-3).then_some([au, av]))
}

/// A microfacet roughness as pbrt-v4 reads it: numbers ([`roughness`]), or, when any of
/// `roughness`, `uroughness`, `vroughness` names a float texture, grey textures [u, v] (the
/// others numbers as uniform textures) with `remaproughness`.
pub(super) enum Rough {
    Fixed(Option<[f64; 2]>),
    Textured(Box<[TextureDesc; 2]>, bool),
}

impl Rough {
    /// The numbers, or for textures a placeholder α that makes the material rough (the
    /// textures replace it at each hit).
    pub(super) fn fixed(&self) -> Option<[f64; 2]> {
        match self {
            Rough::Fixed(a) => *a,
            Rough::Textured(..) => Some([0.5; 2]),
        }
    }

    pub(super) fn texture(self) -> Option<(Box<[TextureDesc; 2]>, bool)> {
        match self {
            Rough::Fixed(_) => None,
            Rough::Textured(t, remap) => Some((t, remap)),
        }
    }
}

pub(super) fn rough(named: &Named<'_>, p: &Params, prefix: &str) -> R<Rough> {
    let names = ["roughness", "uroughness", "vroughness"].map(|n| format!("{prefix}{n}"));
    let textured = names
        .iter()
        .any(|n| p.get(n).is_some_and(|q| q.ty == "texture"));
    if !textured {
        return roughness(p, prefix).map(Rough::Fixed);
    }
    let r = named
        .float(p, &names[0])?
        .unwrap_or_else(|| Spectrum::Constant(0.0).into());
    let u = named.float(p, &names[1])?.unwrap_or_else(|| r.clone());
    let v = named.float(p, &names[2])?.unwrap_or_else(|| r.clone());
    Ok(Rough::Textured(
        Box::new([u, v]),
        p.bool("remaproughness", true)?,
    ))
}

/// A conductor or dielectric with its roughness textured, when it is.
pub(super) fn textured(kind: MaterialKind, rough: Rough) -> MaterialKind {
    match rough {
        Rough::Fixed(_) => kind,
        Rough::Textured(alpha, remap) => MaterialKind::Textured {
            alpha: Some(alpha),
            remap,
            reflectance: Spectrum::Constant(1.0).into(),
            transmittance: Spectrum::Constant(1.0).into(),
            inner: Box::new(kind),
        },
    }
}
