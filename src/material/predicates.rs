//! What integrators and the shading step ask of a material beyond its values: whether its
//! frame must follow ∂p/∂u, whether it perturbs its frame, whether it is never flipped to face
//! the ray.

use super::Material;

impl Material {
    /// Whether the material's value depends on the shading frame's tangent (anisotropic or
    /// textured roughness, normal and bump maps), so that the frame must follow ∂p/∂u; for
    /// every other material any tangent gives the same values, and the cheaper frame is used.
    #[inline]
    pub fn needs_tangent(&self) -> bool {
        match self {
            Material::RoughConductor(m) => m.alpha_u != m.alpha_v,
            Material::RoughDielectric(m) => m.alpha_u != m.alpha_v,
            Material::PPlastic(m) => m.distribution.alpha_u != m.distribution.alpha_v,
            // an element's axes are in the frame of ∂p/∂u
            Material::NormalMap(_)
            | Material::BumpMap(_)
            | Material::Textured(_)
            | Material::Element(_) => true,
            Material::Mask(m) => m.inner.needs_tangent(),
            Material::Principled(m) => m.anisotropic.is_some(),
            // the fibre's axis is the frame's second tangent, n × ∂p/∂u
            Material::Hair(_) => true,
            Material::Layered(m) => m.is_anisotropic(),
            Material::Blend(m) => m.a.needs_tangent() || m.b.needs_tangent(),
            Material::Diffuse(_)
            | Material::DiffuseTransmission(_)
            | Material::Phong(_)
            | Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::Plastic(_)
            | Material::MeasuredPolarized(_)
            | Material::ThinDielectric { .. }
            | Material::ThinFilm(_)
            | Material::Null => false,
            // an anisotropic file's azimuths are in the frame of ∂p/∂u
            Material::Measured(m) => !m.isotropic,
        }
    }

    /// Whether the material evaluates its nested one in a perturbed frame (a normal or bump
    /// map, possibly inside a mask), which needs the hit's derivatives ([`LocalSurface`](super::LocalSurface)).
    #[inline]
    pub fn is_perturbed(&self) -> bool {
        match self {
            Material::NormalMap(_) | Material::BumpMap(_) => true,
            Material::Mask(m) => m.inner.is_perturbed(),
            Material::Diffuse(_)
            | Material::DiffuseTransmission(_)
            | Material::Phong(_)
            | Material::Dielectric(_)
            | Material::RoughDielectric(_)
            | Material::Conductor(_)
            | Material::RoughConductor(_)
            | Material::Plastic(_)
            | Material::PPlastic(_)
            | Material::MeasuredPolarized(_)
            | Material::Measured(_)
            | Material::ThinDielectric { .. }
            | Material::ThinFilm(_)
            | Material::Null
            | Material::Element(_)
            | Material::Blend(_)
            | Material::Principled(_)
            | Material::Hair(_)
            | Material::Layered(_)
            | Material::Textured(_) => false,
        }
    }

    /// Whether light can cross the surface through a lobe that distinguishes its sides
    /// (dielectrics, `null`, `thindielectric`, a blend holding one): such a material is never
    /// flipped to face the ray on a two-sided surface.
    #[inline]
    pub fn is_transmissive(&self) -> bool {
        match self {
            Material::Blend(m) => m.a.is_transmissive() || m.b.is_transmissive(),
            Material::NormalMap(m) => m.inner.is_transmissive(),
            Material::BumpMap(m) => m.inner.is_transmissive(),
            Material::Textured(m) => m.inner.is_transmissive(),
            // the sheet, and the solid one with transmission, tell their sides apart
            Material::Principled(m) => m.thin || m.spec_trans.is_some(),
            Material::Dielectric(_)
            | Material::RoughDielectric(_)
            | Material::Null
            | Material::Element(_)
            | Material::ThinFilm(_)
            | Material::ThinDielectric { .. } => true,
            // a mask's pass-through does not distinguish the sides, nor does a fibre or a
            // diffuse transmitter
            Material::Mask(_)
            | Material::DiffuseTransmission(_)
            | Material::Hair(_)
            | Material::Layered(_)
            | Material::Diffuse(_)
            | Material::Phong(_)
            | Material::Conductor(_)
            | Material::RoughConductor(_)
            | Material::Plastic(_)
            | Material::PPlastic(_)
            | Material::MeasuredPolarized(_)
            | Material::Measured(_) => false,
        }
    }

    /// Whether transmission through this material depends on wavelength in direction, so that
    /// a transmission event (sampled, or evaluated for light sampling) must terminate the
    /// secondary wavelengths.
    #[inline]
    pub fn is_dispersive(&self) -> bool {
        match self {
            Material::Dielectric(m) => m.int_ior.is_dispersive(),
            Material::ThinFilm(_) => false,
            Material::RoughDielectric(m) => m.int_ior.is_dispersive(),
            Material::Mask(m) => m.inner.is_dispersive(),
            Material::NormalMap(m) => m.inner.is_dispersive(),
            Material::BumpMap(m) => m.inner.is_dispersive(),
            Material::Textured(m) => m.inner.is_dispersive(),
            Material::Blend(m) => m.a.is_dispersive() || m.b.is_dispersive(),
            // the coating's index at the hero wavelength sets the walk (pbrt-v4 terminates)
            Material::Layered(m) => m.eta.is_dispersive(),
            // a thin sheet sends light on undeviated, and the rest do not transmit
            Material::ThinDielectric { .. }
            | Material::Null
            | Material::Element(_)
            | Material::Principled(_)
            | Material::Hair(_)
            | Material::Diffuse(_)
            | Material::DiffuseTransmission(_)
            | Material::Phong(_)
            | Material::Conductor(_)
            | Material::RoughConductor(_)
            | Material::Plastic(_)
            | Material::PPlastic(_)
            | Material::MeasuredPolarized(_)
            | Material::Measured(_) => false,
        }
    }
}
