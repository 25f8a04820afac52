//! The materials only Mitsuba scenes make, built from their descriptions: `principled` (and
//! `principledthin`) and `hair`.

use super::textures;
use crate::loader::desc::TextureDesc;
use crate::material::Material;

/// A hair fibre: its absorption per radius as two spectra (the pigments', or σₐ·scale).
pub(super) fn hair(h: &crate::loader::desc::HairDesc) -> Material {
    use crate::loader::desc::HairAbsorption;
    use crate::spectrum::Spectrum;
    let sigma_a = match &h.absorption {
        HairAbsorption::Pigments {
            eumelanin,
            pheomelanin,
        } => crate::material::Hair::pigments(*eumelanin as f32, *pheomelanin as f32),
        HairAbsorption::Sigma { sigma_a, scale } => {
            [sigma_a.scaled(*scale as f32), Spectrum::Constant(0.0)]
        }
    };
    let hair = crate::material::Hair::new(
        sigma_a,
        h.eta as f32,
        h.roughness[0] as f32,
        h.roughness[1] as f32,
        super::materials::radians(&h.scale_tilt),
    );
    Material::Hair(Box::new(if h.pbrt { hair.with_pbrt() } else { hair }))
}

/// A principled material: its textures, the scalar ones grey.
pub(super) fn principled(p: &crate::loader::desc::PrincipledDesc) -> Result<Material, String> {
    let grey = |name: &str, t: &TextureDesc| -> Result<crate::texture::Texture, String> {
        let t = textures::texture(t)?;
        if !textures::is_grey(&t) {
            return Err(format!(
                "a principled material's {name} must be a number or a grey image, the same at every wavelength"
            ));
        }
        Ok(t)
    };
    let opt = |name: &str, t: &Option<TextureDesc>| t.as_ref().map(|t| grey(name, t)).transpose();
    Ok(Material::Principled(Box::new(
        crate::material::Principled {
            base_color: textures::texture(&p.base_color)?,
            roughness: grey("roughness", &p.roughness)?,
            anisotropic: opt("anisotropic", &p.anisotropic)?,
            spec_trans: opt("spec_trans", &p.spec_trans)?,
            metallic: opt("metallic", &p.metallic)?,
            clearcoat: opt("clearcoat", &p.clearcoat)?,
            clearcoat_gloss: grey("clearcoat_gloss", &p.clearcoat_gloss)?,
            sheen: opt("sheen", &p.sheen)?,
            sheen_tint: opt("sheen_tint", &p.sheen_tint)?,
            flatness: opt("flatness", &p.flatness)?,
            spec_tint: opt("spec_tint", &p.spec_tint)?,
            diff_trans: opt("diff_trans", &p.diff_trans)?,
            eta: p.eta as f32,
            rates: p.rates.map(|r| r as f32),
            thin: p.thin,
        },
    )))
}
