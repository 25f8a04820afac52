//! [`Bsdf`]: a material at one surface point, its textured values looked up, which integrators
//! evaluate and sample (the conventions are the module's, `super`).

use glam::{Vec2, Vec3};

use super::{BsdfSample, DiffuseTransmission, DisneyAt, Material, TransportMode};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A material at one surface point, for one set of wavelengths: its textured values looked up
/// (see [`Material::at`]). Evaluating and sampling follow the conventions of this module.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf<'a, const N: usize> {
    pub material: &'a Material,
    /// The textured reflectance at the point (Lambert's ρ, a plastic's diffuse base; a blend's
    /// first component's), dimensionless; zero for materials without one.
    pub albedo: SampledSpectrum<N>,
    /// A blend's second component's textured reflectance; zero otherwise.
    pub albedo_b: SampledSpectrum<N>,
    /// A mask's opacity or a blend's weight at the point, in [0, 1]; 1 for every other material.
    pub weight: f32,
    /// A normal or bump map's perturbed frame at the point, in the local shading frame; the
    /// identity for every other material.
    pub perturb: crate::geometry::Frame,
    /// A `TexturedLobes`' roughness (α_u, α_v) at the point; unused otherwise.
    pub alpha: [f32; 2],
    /// A `TexturedLobes`' factors on the reflected and transmitted lobes; 1 otherwise.
    pub spec_r: SampledSpectrum<N>,
    pub spec_t: SampledSpectrum<N>,
    /// A principled material's parameters at the point; unused otherwise.
    pub disney: DisneyAt,
    /// A pbrt-v4 hair's offset across the fibre at the point, h = 2v − 1 ∈ [−1, 1]
    /// ([`super::Hair::with_pbrt`]); 0 and unused otherwise.
    pub fibre_h: f32,
}

/// The identity frame of [`Bsdf::perturb`].
pub(super) const UNPERTURBED: crate::geometry::Frame = crate::geometry::Frame {
    s: Vec3::X,
    t: Vec3::Y,
    n: Vec3::Z,
};

impl<'a, const N: usize> Bsdf<'a, N> {
    /// `material` with only a diffuse `albedo` looked up (every other value neutral).
    #[inline]
    pub(super) fn plain(material: &'a Material, albedo: SampledSpectrum<N>) -> Self {
        Bsdf {
            material,
            albedo,
            albedo_b: SampledSpectrum::zero(),
            weight: 1.0,
            perturb: UNPERTURBED,
            alpha: [0.0; 2],
            spec_r: SampledSpectrum::splat(1.0),
            spec_t: SampledSpectrum::splat(1.0),
            disney: DisneyAt::default(),
            fibre_h: 0.0,
        }
    }

    /// f(wo, wi) per wavelength in sr⁻¹, without the cosine. 0 for delta lobes.
    #[inline]
    pub fn eval(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> SampledSpectrum<N> {
        match self.material {
            Material::Diffuse(m) => m.eval(wo, wi, self.albedo),
            Material::Phong(m) => m.eval(wo, wi, w),
            Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::Null
            | Material::Element(_)
            | Material::ThinDielectric { .. }
            | Material::ThinFilm(_) => SampledSpectrum::zero(),
            Material::RoughDielectric(m) => m.eval(wo, wi, w, mode),
            Material::RoughConductor(m) => m.eval(wo, wi, w),
            Material::Plastic(m) => m.eval_pdf(wo, wi, self.albedo, w).0,
            Material::PPlastic(m) => m.eval_pdf(wo, wi, self.albedo).0,
            Material::MeasuredPolarized(m) => m.eval(wo, wi, w, mode),
            Material::Measured(m) => m.eval(wo, wi, w),
            Material::Mask(m) => self.masked(m).eval(wo, wi, w, mode) * self.weight,
            Material::Blend(m) => self.blend_eval_pdf(m, wo, wi, w, mode).0,
            Material::NormalMap(_) | Material::BumpMap(_) => {
                self.perturbed_eval_pdf(wo, wi, w, mode).0
            }
            Material::Textured(m) => self.textured_eval_pdf(m, wo, wi, w, mode).0,
            Material::Principled(m) => m.eval(&self.disney, self.albedo, wo, wi, mode),
            Material::Hair(m) => m.eval(self.albedo, self.fibre_h, wo, wi, mode),
            Material::Layered(m) => self.slab(m, w).eval(wo, wi, mode),
            Material::DiffuseTransmission(_) => {
                DiffuseTransmission::eval(wo, wi, self.albedo, self.albedo_b)
            }
        }
    }

    /// Density (sr⁻¹) with which [`Material::sample`] returns `wi` given `wo`, for the hero
    /// wavelength. 0 for delta lobes.
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3, w: &SampledWavelengths<N>, _mode: TransportMode) -> f32 {
        match self.material {
            Material::Diffuse(m) => m.pdf(wo, wi),
            Material::Phong(m) => m.pdf(wo, wi, w),
            Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::Null
            | Material::Element(_)
            | Material::ThinDielectric { .. }
            | Material::ThinFilm(_) => 0.0,
            Material::RoughDielectric(m) => m.pdf(wo, wi, w),
            Material::RoughConductor(m) => m.pdf(wo, wi),
            Material::Plastic(m) => m.eval_pdf(wo, wi, self.albedo, w).1,
            Material::PPlastic(m) => m.eval_pdf(wo, wi, self.albedo).1,
            Material::MeasuredPolarized(m) => m.pdf(wo, wi),
            Material::Measured(m) => m.pdf(wo, wi),
            Material::Mask(m) => self.masked(m).pdf(wo, wi, w, _mode) * self.weight,
            Material::Blend(m) => self.blend_eval_pdf(m, wo, wi, w, _mode).1,
            Material::NormalMap(_) | Material::BumpMap(_) => {
                self.perturbed_eval_pdf(wo, wi, w, _mode).1
            }
            Material::Textured(m) => self.textured_eval_pdf(m, wo, wi, w, _mode).1,
            Material::Principled(m) => m.pdf(&self.disney, wo, wi),
            Material::Hair(m) => m.pdf(self.albedo, self.fibre_h, wo, wi, w),
            Material::Layered(m) => self.slab(m, w).pdf(wo, wi, _mode),
            Material::DiffuseTransmission(_) => {
                DiffuseTransmission::pdf(wo, wi, self.albedo, self.albedo_b)
            }
        }
    }

    /// [`Material::eval`] and [`Material::pdf`] together, for next-event estimation, which
    /// needs both: the work they share (half vectors, indices, lobe values) is done once. The
    /// same values as the two calls.
    #[inline]
    pub fn eval_pdf(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> (SampledSpectrum<N>, f32) {
        match self.material {
            Material::Diffuse(m) => (m.eval(wo, wi, self.albedo), m.pdf(wo, wi)),
            Material::Phong(m) => m.eval_pdf(wo, wi, w),
            Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::Null
            | Material::Element(_)
            | Material::ThinDielectric { .. }
            | Material::ThinFilm(_) => (SampledSpectrum::zero(), 0.0),
            Material::RoughDielectric(m) => m.eval_pdf(wo, wi, w, mode),
            Material::RoughConductor(m) => m.eval_pdf(wo, wi, w),
            Material::Plastic(m) => m.eval_pdf(wo, wi, self.albedo, w),
            Material::PPlastic(m) => m.eval_pdf(wo, wi, self.albedo),
            Material::MeasuredPolarized(m) => (m.eval(wo, wi, w, mode), m.pdf(wo, wi)),
            Material::Measured(m) => m.eval_pdf(wo, wi, w),
            Material::Mask(m) => {
                let (f, pdf) = self.masked(m).eval_pdf(wo, wi, w, mode);
                (f * self.weight, pdf * self.weight)
            }
            Material::Blend(m) => self.blend_eval_pdf(m, wo, wi, w, mode),
            Material::NormalMap(_) | Material::BumpMap(_) => {
                self.perturbed_eval_pdf(wo, wi, w, mode)
            }
            Material::Textured(m) => self.textured_eval_pdf(m, wo, wi, w, mode),
            Material::Principled(m) => (
                m.eval(&self.disney, self.albedo, wo, wi, mode),
                m.pdf(&self.disney, wo, wi),
            ),
            Material::Hair(m) => (
                m.eval(self.albedo, self.fibre_h, wo, wi, mode),
                m.pdf(self.albedo, self.fibre_h, wo, wi, w),
            ),
            Material::Layered(m) => {
                let slab = self.slab(m, w);
                (slab.eval(wo, wi, mode), slab.pdf(wo, wi, mode))
            }
            Material::DiffuseTransmission(_) => (
                DiffuseTransmission::eval(wo, wi, self.albedo, self.albedo_b),
                DiffuseTransmission::pdf(wo, wi, self.albedo, self.albedo_b),
            ),
        }
    }

    /// Samples `wi` given `wo`: `uc` chooses a lobe, `u` the direction within it. `None` when
    /// the sample carries no contribution (wrong side, below the horizon, degenerate `wo`).
    #[inline]
    pub fn sample(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        match self.material {
            Material::Diffuse(m) => m.sample(wo, self.albedo, u),
            Material::Phong(m) => m.sample(wo, w, uc, u),
            Material::Dielectric(m) => m.sample(wo, w, uc, mode),
            Material::RoughDielectric(m) => m.sample(wo, w, uc, u, mode),
            Material::Conductor(m) => m.sample(wo, w),
            Material::RoughConductor(m) => m.sample(wo, w, u),
            Material::Plastic(m) => m.sample(wo, self.albedo, w, uc, u),
            Material::PPlastic(m) => m.sample(wo, self.albedo, uc, u),
            Material::MeasuredPolarized(m) => m.sample(wo, uc, u, w, mode),
            Material::Measured(m) => m.sample(wo, u, w),
            Material::ThinFilm(m) => m.sample(wo, w, uc),
            Material::ThinDielectric { eta } => {
                let c = wo.z.abs();
                if c == 0.0 {
                    return None;
                }
                let r = super::thin_reflectance(c, *eta);
                let (wi, p, transmission) = if uc < r {
                    (Vec3::new(-wo.x, -wo.y, wo.z), r, false)
                } else {
                    (-wo, 1.0 - r, true)
                };
                Some(BsdfSample {
                    f: SampledSpectrum::splat(p / c),
                    wi,
                    pdf: p,
                    specular: true,
                    transmission,
                    dispersive: false,
                    eta: 1.0,
                })
            }
            Material::Mask(m) => self.mask_sample(m, wo, w, uc, u, mode),
            Material::Blend(m) => self.blend_sample(m, wo, w, uc, u, mode),
            Material::NormalMap(_) | Material::BumpMap(_) => {
                self.perturbed_sample(wo, w, uc, u, mode)
            }
            Material::Textured(m) => self.textured_sample(m, wo, w, uc, u, mode),
            Material::Principled(m) => m.sample(&self.disney, self.albedo, wo, uc, u, mode),
            Material::Hair(m) => m.sample(self.albedo, self.fibre_h, wo, w, uc, u, mode),
            Material::Layered(m) => self.slab(m, w).sample(wo, uc, u, mode),
            Material::DiffuseTransmission(_) => {
                DiffuseTransmission::sample(wo, self.albedo, self.albedo_b, uc, u)
            }
            // straight through: f·|cos θᵢ|/pdf = 1
            Material::Null => (wo.z != 0.0).then(|| BsdfSample {
                f: SampledSpectrum::splat(1.0 / wo.z.abs()),
                wi: -wo,
                pdf: 1.0,
                specular: true,
                transmission: true,
                dispersive: false,
                eta: 1.0,
            }),
            // straight through, passing the unpolarised fraction
            Material::Element(e) => (wo.z != 0.0).then(|| BsdfSample {
                f: SampledSpectrum::splat(e.transmittance() / wo.z.abs()),
                wi: -wo,
                pdf: 1.0,
                specular: true,
                transmission: true,
                dispersive: false,
                eta: 1.0,
            }),
        }
    }

    /// A layered material's slab at this point (its base and albedo looked up).
    #[inline]
    fn slab(&self, m: &super::Layered, w: &SampledWavelengths<N>) -> super::layered::Slab<N> {
        m.slab((self.albedo, self.albedo_b), self.spec_r, self.alpha, w)
    }

    /// Whether the material has only delta lobes (smooth dielectric, smooth conductor), so that
    /// light sampling (next-event estimation) is pointless.
    #[inline]
    pub fn is_specular(&self) -> bool {
        self.material.is_specular()
    }

    /// The same looked-up values for another material (a wrapper's nested one).
    #[inline]
    pub(super) fn with_material<'b>(&self, material: &'b Material) -> Bsdf<'b, N> {
        Bsdf {
            material,
            albedo: self.albedo,
            albedo_b: self.albedo_b,
            weight: self.weight,
            perturb: self.perturb,
            alpha: self.alpha,
            spec_r: self.spec_r,
            spec_t: self.spec_t,
            disney: self.disney,
            fibre_h: self.fibre_h,
        }
    }

    /// Whether transmission through this material depends on wavelength in direction, so that
    /// a transmission event (sampled, or evaluated for light sampling) must terminate the
    /// secondary wavelengths.
    #[inline]
    pub fn is_dispersive(&self) -> bool {
        self.material.is_dispersive()
    }
}
