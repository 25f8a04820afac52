//! Materials as described → render-side [`Material`]s: textures looked up once, the rules
//! on what composites may hold checked.

use super::textures;
use crate::loader::desc::{MaterialKind, TextureDesc};
use crate::material::microfacet::Microfacet;
use crate::material::{
    Blend, BumpMap, Conductor, Dielectric, Element, Lambert, Mask, Material, MeasuredPolarized,
    NormalMap, PPlastic, Phong, Plastic, RoughConductor, RoughDielectric, TexturedLobes,
};

/// The render-side material for `k`; an error (for the user, without a location) if a
/// composite holds what it may not or a texture is not as its slot needs.
pub(super) fn material(k: &MaterialKind) -> Result<Material, String> {
    Ok(match k {
        MaterialKind::Diffuse { reflectance } => Material::Diffuse(Lambert {
            reflectance: textures::texture(reflectance)?,
        }),
        MaterialKind::Phong { kd, ks, exponent } => {
            Material::Phong(Phong::new(kd.clone(), ks.clone(), *exponent as f32)?)
        }
        MaterialKind::Dielectric {
            ior,
            exterior_ior,
            roughness: None,
            ..
        } => Material::Dielectric(Dielectric::new(ior.clone(), *exterior_ior as f32)),
        MaterialKind::Dielectric {
            roughness: Some(_), ..
        }
        | MaterialKind::Conductor {
            roughness: Some(_), ..
        } => rough(k),
        MaterialKind::Conductor {
            ior,
            exterior_ior,
            roughness: None,
            ..
        } => Material::Conductor(Conductor::new(ior.clone(), *exterior_ior as f32)),
        MaterialKind::Null => Material::Null,
        MaterialKind::Coated { layers, inner } => coated(layers, inner)?,
        MaterialKind::ThinFilm {
            layers,
            exterior_ior,
        } => Material::ThinFilm(Box::new(crate::material::ThinFilm {
            layers: coating(layers),
            ext_ior: *exterior_ior as f32,
        })),
        MaterialKind::Polariser {
            angle,
            transmittance,
            polarizing,
        } => Material::Element(Element::Polariser {
            theta: radians(angle),
            transmittance: *transmittance as f32,
            polarizing: *polarizing,
        }),
        MaterialKind::Retarder { angle, retardance } => Material::Element(Element::Retarder {
            theta: radians(angle),
            delta: radians(retardance),
        }),
        MaterialKind::Mask { opacity, inner } => mask(opacity, inner)?,
        MaterialKind::Blend { weight, a, b } => blend(weight, a, b)?,
        MaterialKind::Textured {
            alpha,
            remap,
            reflectance,
            transmittance,
            inner,
        } => textured(alpha.as_deref(), *remap, reflectance, transmittance, inner)?,
        MaterialKind::NormalMap { map, inner, pbrt } => normal_map(map, inner, *pbrt)?,
        MaterialKind::BumpMap {
            height,
            scale,
            inner,
            pbrt,
        } => bump_map(height, *scale, inner, *pbrt)?,
        MaterialKind::ThinDielectric {
            int_ior,
            exterior_ior,
        } => Material::ThinDielectric {
            eta: (*int_ior / *exterior_ior) as f32,
        },
        MaterialKind::Plastic {
            diffuse,
            specular,
            int_ior,
            exterior_ior,
            nonlinear,
            roughness,
            distribution,
        } => {
            let diffuse = textures::texture(diffuse)?;
            let mean = diffuse.mean();
            Material::Plastic(Plastic::new(
                diffuse,
                mean,
                *specular as f32,
                *int_ior as f32,
                *exterior_ior as f32,
                *nonlinear,
                roughness.map(|a| (a as f32, *distribution)),
            )?)
        }
        MaterialKind::PPlastic {
            diffuse,
            specular,
            int_ior,
            exterior_ior,
            roughness,
            distribution,
        } => pplastic(
            diffuse,
            *specular,
            *int_ior / *exterior_ior,
            roughness,
            *distribution,
        )?,
        MaterialKind::MeasuredPolarized { .. } => measured(k),
        MaterialKind::Principled(p) => super::materials_mitsuba::principled(p)?,
        MaterialKind::Hair(h) => super::materials_mitsuba::hair(h),
        MaterialKind::Layered(d) => super::materials_pbrt::layered(d)?,
        MaterialKind::Measured { table, jacobian } => {
            super::materials_pbrt::measured(table, *jacobian)?
        }
        MaterialKind::DiffuseTransmission {
            reflectance,
            transmittance,
        } => super::materials_pbrt::diffuse_transmission(reflectance, transmittance)?,
    })
}

/// An angle in radians, as the render side keeps it.
pub(super) fn radians(a: &crate::units::Angle) -> f32 {
    a.get::<crate::units::angle::radian>() as f32
}

/// `pplastic`: its diffuse texture (and mean, for the lobe choice), relative index `eta` and
/// microfacets.
fn pplastic(
    diffuse: &TextureDesc,
    specular: f64,
    eta: f64,
    roughness: &[f64; 2],
    distribution: crate::material::microfacet::Distribution,
) -> Result<Material, String> {
    let diffuse = textures::texture(diffuse)?;
    let mean = diffuse.mean();
    Ok(Material::PPlastic(PPlastic::new(
        diffuse,
        mean,
        specular as f32,
        eta as f32,
        Microfacet::anisotropic(roughness[0] as f32, roughness[1] as f32, distribution),
    )))
}

/// `mask`: `opacity` (grey) of `inner`, which is no mask or blend.
fn mask(opacity: &TextureDesc, inner: &MaterialKind) -> Result<Material, String> {
    let opacity = textures::texture(opacity)?;
    if !textures::is_grey(&opacity) {
        return Err(
            "a mask's opacity must be a number or a grey image, the same at every wavelength"
                .into(),
        );
    }
    let inner = material(inner)?;
    if matches!(inner, Material::Mask(_) | Material::Blend(_)) {
        return Err("a mask cannot hold another mask or a blend".into());
    }
    Ok(Material::Mask(Box::new(Mask { opacity, inner })))
}

/// `blend`: (1 − `weight`)·a + `weight`·b (grey weight) of two plain materials.
fn blend(weight: &TextureDesc, a: &MaterialKind, b: &MaterialKind) -> Result<Material, String> {
    let weight = textures::texture(weight)?;
    if !textures::is_grey(&weight) {
        return Err(
            "a blend's weight must be a number or a grey image, the same at every wavelength"
                .into(),
        );
    }
    let (a, b) = (material(a)?, material(b)?);
    if [&a, &b].iter().any(|m| {
        matches!(
            m,
            Material::Mask(_)
                | Material::Blend(_)
                | Material::NormalMap(_)
                | Material::BumpMap(_)
                | Material::Textured(_)
                | Material::Principled(_)
                | Material::Hair(_)
                | Material::Layered(_)
                | Material::DiffuseTransmission(_)
        )
    }) {
        return Err(
            "a blend cannot hold a mask, another blend, a normal or bump map, textured roughness or specular factors, a principled material, hair, a coated (layered) material or a diffuse transmitter".into(),
        );
    }
    Ok(Material::Blend(Box::new(Blend { weight, a, b })))
}

/// Textured roughness (grey α_u, α_v) and lobe factors around a conductor or dielectric.
fn textured(
    alpha: Option<&[TextureDesc; 2]>,
    remap: bool,
    reflectance: &TextureDesc,
    transmittance: &TextureDesc,
    inner: &MaterialKind,
) -> Result<Material, String> {
    let inner = material(inner)?;
    if !matches!(
        inner,
        Material::Conductor(_)
            | Material::RoughConductor(_)
            | Material::Dielectric(_)
            | Material::RoughDielectric(_)
    ) {
        return Err(
            "textured roughness and specular factors apply to conductors and dielectrics only"
                .into(),
        );
    }
    let alpha = match alpha {
        Some([u, v]) => {
            let (u, v) = (textures::texture(u)?, textures::texture(v)?);
            if !(textures::is_grey(&u) && textures::is_grey(&v)) {
                return Err("a textured alpha must be a grey image or a number".into());
            }
            Some([u, v])
        }
        None => None,
    };
    Ok(Material::Textured(Box::new(TexturedLobes {
        alpha,
        remap,
        reflectance: textures::texture(reflectance)?,
        transmittance: textures::texture(transmittance)?,
        inner,
    })))
}

/// A rough dielectric or conductor (called for those only).
fn rough(k: &MaterialKind) -> Material {
    match k {
        MaterialKind::Dielectric {
            ior,
            exterior_ior,
            roughness: Some(a),
            distribution,
            smith,
        } => Material::RoughDielectric(
            RoughDielectric::new(ior.clone(), *exterior_ior as f32, a[0] as f32)
                .with_anisotropy(a[0] as f32, a[1] as f32)
                .with_distribution(*distribution)
                .with_smith(*smith),
        ),
        MaterialKind::Conductor {
            ior,
            exterior_ior,
            roughness: Some(a),
            distribution,
            smith,
        } => Material::RoughConductor(
            RoughConductor::new(ior.clone(), *exterior_ior as f32, a[0] as f32)
                .with_anisotropy(a[0] as f32, a[1] as f32)
                .with_distribution(*distribution)
                .with_smith(*smith),
        ),
        _ => unreachable!("called for rough dielectrics and conductors only"),
    }
}

/// A normal map around a material that is no normal or bump map.
fn normal_map(map: &TextureDesc, inner: &MaterialKind, pbrt: bool) -> Result<Material, String> {
    let inner = material(inner)?;
    if matches!(inner, Material::NormalMap(_) | Material::BumpMap(_)) {
        return Err("a normal map cannot hold another normal or bump map".into());
    }
    Ok(Material::NormalMap(Box::new(NormalMap {
        map: textures::vector_texture(map)?,
        inner,
        pbrt,
    })))
}

/// A bump map (grey height times `scale`) around a material that is no normal or bump map.
fn bump_map(
    height: &TextureDesc,
    scale: f64,
    inner: &MaterialKind,
    pbrt: bool,
) -> Result<Material, String> {
    let inner = material(inner)?;
    if matches!(inner, Material::NormalMap(_) | Material::BumpMap(_)) {
        return Err("a bump map cannot hold another normal or bump map".into());
    }
    let height = textures::scalar_texture(height)?;
    if !textures::is_grey(&height) {
        return Err("a bump map's height must be a grey image".into());
    }
    Ok(Material::BumpMap(Box::new(BumpMap {
        height,
        scale: scale as f32,
        inner,
        pbrt,
    })))
}

/// Mitsuba's `measured_polarized` from its table (shared, not copied: the matrices stay in
/// one `Arc`).
fn measured(k: &MaterialKind) -> Material {
    let MaterialKind::MeasuredPolarized {
        table,
        alpha_sample,
        wavelength,
    } = k
    else {
        unreachable!("called for measured_polarized only")
    };
    Material::MeasuredPolarized(Box::new(MeasuredPolarized {
        phi_d: table.phi_d.clone(),
        theta_d: table.theta_d.clone(),
        theta_h: table.theta_h.clone(),
        wavelengths: table.wavelengths.clone(),
        m: table.m.clone(),
        sampling: crate::material::microfacet::Ggx::new(*alpha_sample as f32),
        wavelength: wavelength.map(|l| l as f32),
    }))
}

/// The render-side coating of `layers` (thicknesses in nm).
fn coating(layers: &[crate::loader::desc::CoatingLayerDesc]) -> crate::optics::thin_film::Coating {
    crate::optics::thin_film::Coating {
        layers: layers
            .iter()
            .map(|l| crate::optics::thin_film::Layer {
                index: l.medium.clone(),
                thickness_nm: l.thickness.get::<crate::units::length::nanometer>(),
            })
            .collect(),
    }
}

/// `inner` under the thin-film `layers`: a smooth dielectric or a conductor (smooth or rough).
fn coated(
    layers: &[crate::loader::desc::CoatingLayerDesc],
    inner: &MaterialKind,
) -> Result<Material, String> {
    let c = Some(Box::new(coating(layers)));
    Ok(match material(inner)? {
        Material::Dielectric(mut d) => {
            d.coating = c;
            Material::Dielectric(d)
        }
        Material::Conductor(mut m) => {
            m.coating = c;
            Material::Conductor(m)
        }
        Material::RoughConductor(m) => Material::RoughConductor(m.with_coating(c)),
        Material::Plastic(p) => {
            let MaterialKind::Plastic {
                int_ior,
                exterior_ior,
                ..
            } = inner
            else {
                return Err("a coated plastic".into());
            };
            let layers = c
                .map(|b| *b)
                .unwrap_or(crate::optics::thin_film::Coating { layers: Vec::new() });
            Material::Plastic(p.with_film(layers, *exterior_ior as f32, *int_ior as f32)?)
        }
        _ => {
            return Err(
                "a coating goes on a smooth dielectric, a conductor (smooth or rough) or a smooth \
                 plastic; rough dielectrics and textured lobes do not take one yet"
                    .into(),
            );
        }
    })
}
