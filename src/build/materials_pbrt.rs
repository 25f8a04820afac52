//! Materials that pbrt-v4's scenes bring (`crate::loader::pbrt`), made render-ready.

use super::textures;
use crate::loader::desc::LayeredDesc;
use crate::material::{Layered, LayeredBase, Material};

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
