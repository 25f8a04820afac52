//! Materials (BSDFs) evaluated per wavelength.
//!
//! # Conventions
//!
//! - **Directions** are in the local shading frame: the shading normal is +z. `wo` (towards the
//!   viewer, or the previous vertex) and `wi` (towards the light, or the next vertex) both point
//!   *away* from the surface and have unit length.
//! - **Wavelengths** are in nm, carried as [`SampledWavelengths`]; index 0 is the hero wavelength.
//! - **Values**: `eval` returns the BSDF f(wo, wi) in sr⁻¹ per wavelength. It does *not* include
//!   the cosine |cos θᵢ| = |wi.z|; the integrator multiplies by it.
//! - **Densities**: `pdf` is per unit solid angle (sr⁻¹) of `wi`, for the hero wavelength when the
//!   material is dispersive.
//! - **Delta lobes** (smooth [`Dielectric`], smooth [`Conductor`]): `eval` and `pdf` return 0.
//!   `sample` returns `f = F/|cos θᵢ|` and as `pdf` the discrete probability of the chosen lobe,
//!   with `specular = true`, so that `f·|cos θᵢ|/pdf` is the sample weight (pbrt's convention).
//! - **Sides**: the opaque materials ([`Lambert`], [`Phong`], [`Conductor`], [`RoughConductor`])
//!   are one-sided: they return 0 / `None` unless both `wo.z > 0` and `wi.z > 0`. The scene
//!   flips the shading frame for two-sided surfaces. The dielectrics are two-sided: `wo.z > 0`
//!   is outside (index `ext_ior`), `wo.z < 0` is inside (index `int_ior(λ)`).
//! - **Non-symmetric scattering**: radiance crossing a refracting interface scales by
//!   (n_wo/n_wi)² (PHYSICS.md, "Dielectrics"). In [`TransportMode::Radiance`] (paths from the
//!   camera) the transmission terms carry this factor, 1/η² with η = n(wi side)/n(wo side); in
//!   [`TransportMode::Importance`] (paths from lights) they do not. Equivalently,
//!   f_Importance(wo, wi) = f_Radiance(wi, wo) (the adjoint BSDF).
//! - **Dispersion**: when a sampled direction depends on wavelength (refraction through an
//!   `Ior` with [`Ior::is_dispersive`](crate::spectrum::ior::Ior::is_dispersive)), the sample is
//!   flagged `dispersive`; the caller must call
//!   [`SampledWavelengths::terminate_secondary`], and only `f[0]` is meaningful. The same holds
//!   for `eval` of a transmission pair (wo, wi on opposite sides) of a dispersive
//!   [`RoughDielectric`]: only the hero value is meaningful (see [`Material::is_dispersive`]).
//!
//! All variants are plain data (`Spectrum`, `Ior`, `ComplexIor`, `f32`) in a closed enum; no call
//! allocates.

mod blend;
mod conductor;
mod dielectric;
pub mod fresnel;
mod lambert;
mod mask;
pub mod microfacet;
mod perturb;
mod phong;
mod plastic;
mod rough_dielectric;
mod textured;

pub use blend::Blend;
pub use conductor::{Conductor, RoughConductor};
pub use dielectric::Dielectric;
pub use lambert::Lambert;
pub use mask::Mask;
pub use perturb::{BumpMap, LocalSurface, NormalMap};
pub use phong::Phong;
pub use plastic::{Plastic, RoughCoating, fresnel_diffuse_reflectance};
pub use rough_dielectric::RoughDielectric;
pub use textured::TexturedLobes;

use glam::{Vec2, Vec3};

use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Which quantity a path carries, which decides whether refraction scales by 1/η².
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TransportMode {
    /// Paths from the camera carrying radiance: transmission is scaled by 1/η², η = n_wi/n_wo.
    Radiance,
    /// Paths from the lights carrying importance (light tracing): no η² scaling.
    Importance,
}

/// A direction drawn from a BSDF, with everything the integrator needs.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample<const N: usize> {
    /// BSDF value in sr⁻¹ (no cosine); for a delta lobe F/|cos θᵢ|.
    pub f: SampledSpectrum<N>,
    /// Sampled direction, local frame, pointing away from the surface.
    pub wi: Vec3,
    /// Density in sr⁻¹ of `wi`, or for a delta lobe the discrete probability of choosing it.
    pub pdf: f32,
    /// Whether `wi` came from a delta lobe.
    pub specular: bool,
    /// Whether `wi` is on the other side of the surface from `wo`.
    pub transmission: bool,
    /// The direction depends on wavelength: the caller must terminate the secondary wavelengths;
    /// `f` is valid for the hero wavelength (index 0) only.
    pub dispersive: bool,
    /// Relative index crossed, n(wi side)/n(wo side) at the hero wavelength (1 for reflection),
    /// for Russian roulette (radiance scales by 1/eta² along the path).
    pub eta: f32,
}

impl<const N: usize> BsdfSample<N> {
    /// A reflection sample from a non-delta lobe.
    #[inline]
    pub(crate) fn reflection(f: SampledSpectrum<N>, wi: Vec3, pdf: f32) -> Self {
        Self {
            f,
            wi,
            pdf,
            specular: false,
            transmission: false,
            dispersive: false,
            eta: 1.0,
        }
    }
}

/// A surface material. Closed enum, matched per call.
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    Diffuse(Lambert),
    Phong(Phong),
    Dielectric(Dielectric),
    RoughDielectric(RoughDielectric),
    Conductor(Conductor),
    RoughConductor(RoughConductor),
    Plastic(Plastic),
    /// Mitsuba's `thindielectric`: a sheet of index `eta` (relative to the outside) too thin to
    /// offset a ray. Reflectance with the sheet's inner reflections, R = 2F/(1 + F) for the
    /// Fresnel reflectance F at the incidence angle, else straight through: two delta lobes
    /// of weight 1 chosen with probabilities R and 1 − R.
    ThinDielectric {
        eta: f32,
    },
    /// Mitsuba's `null`: no surface for light, which passes straight through (a delta
    /// transmission of weight 1 that still counts as a scattering event, as in Mitsuba).
    Null,
    /// Mitsuba's `mask`: with probability 1 − opacity light passes straight through, else the
    /// nested material scatters it (see [`Mask`]).
    Mask(Box<Mask>),
    /// Mitsuba's `blendbsdf`: (1 − w)·f_a + w·f_b for a weight w at the hit (see [`Blend`]).
    Blend(Box<Blend>),
    /// Mitsuba's `normalmap`: the nested material in a frame whose normal an image gives.
    NormalMap(Box<NormalMap>),
    /// Mitsuba's `bumpmap`: the nested material in a frame tilted by a height's gradient.
    BumpMap(Box<BumpMap>),
    /// A conductor or dielectric with textured roughness or specular factors (see
    /// [`TexturedLobes`]).
    Textured(Box<TexturedLobes>),
}

impl Material {
    /// The material at a surface point with surface coordinates `uv`, for the wavelengths `w`:
    /// its textures are looked up here, once per hit (pbrt-v4's `GetBSDF`), and the returned
    /// [`Bsdf`] is what integrators evaluate and sample.
    #[inline]
    pub fn at<const N: usize>(&self, uv: Vec2, w: &SampledWavelengths<N>) -> Bsdf<'_, N> {
        self.at_surface(&LocalSurface::flat(uv), w)
    }

    /// [`Material::at`] with the hit's surface derivatives in its local shading frame, which
    /// normal and bump maps need for their perturbed frames.
    #[inline]
    pub fn at_surface<const N: usize>(
        &self,
        s: &LocalSurface,
        w: &SampledWavelengths<N>,
    ) -> Bsdf<'_, N> {
        let uv = s.uv;
        let albedo = match self {
            Material::Diffuse(m) => m.reflectance.sample(uv, w),
            Material::Plastic(m) => m.diffuse.sample(uv, w),
            Material::Mask(m) => {
                return Bsdf {
                    weight: m.opacity.sample(uv, w)[0].clamp(0.0, 1.0),
                    ..m.inner.at_surface(s, w).with_material(self)
                };
            }
            Material::Blend(m) => {
                return Bsdf {
                    material: self,
                    albedo: m.a.at(uv, w).albedo,
                    albedo_b: m.b.at(uv, w).albedo,
                    weight: m.weight.sample(uv, w)[0].clamp(0.0, 1.0),
                    perturb: UNPERTURBED,
                    alpha: [0.0; 2],
                    spec_r: SampledSpectrum::splat(1.0),
                    spec_t: SampledSpectrum::splat(1.0),
                };
            }
            Material::NormalMap(m) => {
                return Bsdf {
                    perturb: m.frame(s),
                    ..m.inner.at_surface(s, w).with_material(self)
                };
            }
            Material::BumpMap(m) => {
                return Bsdf {
                    perturb: m.frame(s),
                    ..m.inner.at_surface(s, w).with_material(self)
                };
            }
            Material::Textured(m) => {
                return Bsdf {
                    alpha: m.alpha_at(uv, w),
                    spec_r: m.reflectance.sample(uv, w),
                    spec_t: m.transmittance.sample(uv, w),
                    ..m.inner.at_surface(s, w).with_material(self)
                };
            }
            _ => SampledSpectrum::zero(),
        };
        Bsdf {
            material: self,
            albedo,
            albedo_b: SampledSpectrum::zero(),
            weight: 1.0,
            perturb: UNPERTURBED,
            alpha: [0.0; 2],
            spec_r: SampledSpectrum::splat(1.0),
            spec_t: SampledSpectrum::splat(1.0),
        }
    }

    /// [`Bsdf::eval`] at uv = (0, 0): for untextured materials, the value anywhere.
    #[inline]
    pub fn eval<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> SampledSpectrum<N> {
        self.at(Vec2::ZERO, w).eval(wo, wi, w, mode)
    }

    /// [`Bsdf::pdf`] at uv = (0, 0).
    #[inline]
    pub fn pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> f32 {
        self.at(Vec2::ZERO, w).pdf(wo, wi, w, mode)
    }

    /// [`Bsdf::eval_pdf`] at uv = (0, 0).
    #[inline]
    pub fn eval_pdf<const N: usize>(
        &self,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> (SampledSpectrum<N>, f32) {
        self.at(Vec2::ZERO, w).eval_pdf(wo, wi, w, mode)
    }

    /// [`Bsdf::sample`] at uv = (0, 0).
    #[inline]
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample<N>> {
        self.at(Vec2::ZERO, w).sample(wo, w, uc, u, mode)
    }

    /// Whether the material has only delta lobes (smooth dielectric, smooth conductor), so that
    /// light sampling (next-event estimation) is pointless.
    #[inline]
    pub fn is_specular(&self) -> bool {
        match self {
            Material::Mask(m) => m.inner.is_specular(),
            Material::NormalMap(m) => m.inner.is_specular(),
            Material::BumpMap(m) => m.inner.is_specular(),
            Material::Textured(m) => m.inner.is_specular(),
            Material::Blend(m) => m.a.is_specular() && m.b.is_specular(),
            _ => matches!(
                self,
                Material::Dielectric(_)
                    | Material::Conductor(_)
                    | Material::Null
                    | Material::ThinDielectric { .. }
            ),
        }
    }

    /// Whether transmission through this material depends on wavelength in direction, so that
    /// a transmission event (sampled, or evaluated for light sampling) must terminate the
    /// secondary wavelengths.
    #[inline]
    pub fn is_dispersive(&self) -> bool {
        match self {
            Material::Dielectric(m) => m.int_ior.is_dispersive(),
            Material::RoughDielectric(m) => m.int_ior.is_dispersive(),
            Material::Mask(m) => m.inner.is_dispersive(),
            Material::NormalMap(m) => m.inner.is_dispersive(),
            Material::BumpMap(m) => m.inner.is_dispersive(),
            Material::Textured(m) => m.inner.is_dispersive(),
            Material::Blend(m) => m.a.is_dispersive() || m.b.is_dispersive(),
            _ => false,
        }
    }

    /// Whether the material's value depends on the shading frame's tangent (anisotropic or
    /// textured roughness, normal and bump maps), so that the frame must follow ∂p/∂u; for
    /// every other material any tangent gives the same values, and the cheaper frame is used.
    #[inline]
    pub fn needs_tangent(&self) -> bool {
        match self {
            Material::RoughConductor(m) => m.alpha_u != m.alpha_v,
            Material::RoughDielectric(m) => m.alpha_u != m.alpha_v,
            Material::NormalMap(_) | Material::BumpMap(_) | Material::Textured(_) => true,
            Material::Mask(m) => m.inner.needs_tangent(),
            Material::Blend(m) => m.a.needs_tangent() || m.b.needs_tangent(),
            _ => false,
        }
    }

    /// Whether the material evaluates its nested one in a perturbed frame (a normal or bump
    /// map, possibly inside a mask), which needs the hit's derivatives ([`LocalSurface`]).
    #[inline]
    pub fn is_perturbed(&self) -> bool {
        match self {
            Material::NormalMap(_) | Material::BumpMap(_) => true,
            Material::Mask(m) => m.inner.is_perturbed(),
            _ => false,
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
            _ => matches!(
                self,
                Material::Dielectric(_)
                    | Material::RoughDielectric(_)
                    | Material::Null
                    | Material::ThinDielectric { .. }
            ),
        }
    }
}

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
    /// A [`TexturedLobes`]' roughness (α_u, α_v) at the point; unused otherwise.
    pub alpha: [f32; 2],
    /// A [`TexturedLobes`]' factors on the reflected and transmitted lobes; 1 otherwise.
    pub spec_r: SampledSpectrum<N>,
    pub spec_t: SampledSpectrum<N>,
}

/// The identity frame of [`Bsdf::perturb`].
const UNPERTURBED: crate::geometry::Frame = crate::geometry::Frame {
    s: Vec3::X,
    t: Vec3::Y,
    n: Vec3::Z,
};

impl<const N: usize> Bsdf<'_, N> {
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
            | Material::ThinDielectric { .. } => SampledSpectrum::zero(),
            Material::RoughDielectric(m) => m.eval(wo, wi, w, mode),
            Material::RoughConductor(m) => m.eval(wo, wi, w),
            Material::Plastic(m) => m.eval_pdf(wo, wi, self.albedo).0,
            Material::Mask(m) => self.masked(m).eval(wo, wi, w, mode) * self.weight,
            Material::Blend(m) => self.blend_eval_pdf(m, wo, wi, w, mode).0,
            Material::NormalMap(_) | Material::BumpMap(_) => {
                self.perturbed_eval_pdf(wo, wi, w, mode).0
            }
            Material::Textured(m) => self.textured_eval_pdf(m, wo, wi, w, mode).0,
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
            | Material::ThinDielectric { .. } => 0.0,
            Material::RoughDielectric(m) => m.pdf(wo, wi, w),
            Material::RoughConductor(m) => m.pdf(wo, wi),
            Material::Plastic(m) => m.eval_pdf(wo, wi, self.albedo).1,
            Material::Mask(m) => self.masked(m).pdf(wo, wi, w, _mode) * self.weight,
            Material::Blend(m) => self.blend_eval_pdf(m, wo, wi, w, _mode).1,
            Material::NormalMap(_) | Material::BumpMap(_) => {
                self.perturbed_eval_pdf(wo, wi, w, _mode).1
            }
            Material::Textured(m) => self.textured_eval_pdf(m, wo, wi, w, _mode).1,
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
            | Material::ThinDielectric { .. } => (SampledSpectrum::zero(), 0.0),
            Material::RoughDielectric(m) => m.eval_pdf(wo, wi, w, mode),
            Material::RoughConductor(m) => m.eval_pdf(wo, wi, w),
            Material::Plastic(m) => m.eval_pdf(wo, wi, self.albedo),
            Material::Mask(m) => {
                let (f, pdf) = self.masked(m).eval_pdf(wo, wi, w, mode);
                (f * self.weight, pdf * self.weight)
            }
            Material::Blend(m) => self.blend_eval_pdf(m, wo, wi, w, mode),
            Material::NormalMap(_) | Material::BumpMap(_) => {
                self.perturbed_eval_pdf(wo, wi, w, mode)
            }
            Material::Textured(m) => self.textured_eval_pdf(m, wo, wi, w, mode),
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
            Material::Plastic(m) => m.sample(wo, self.albedo, uc, u),
            Material::ThinDielectric { eta } => {
                let c = wo.z.abs();
                if c == 0.0 {
                    return None;
                }
                let f = fresnel::fresnel_dielectric(c, *eta);
                let r = 2.0 * f / (1.0 + f);
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
        }
    }

    /// Whether the material has only delta lobes (smooth dielectric, smooth conductor), so that
    /// light sampling (next-event estimation) is pointless.
    #[inline]
    pub fn is_specular(&self) -> bool {
        self.material.is_specular()
    }

    /// The same looked-up values for another material (a wrapper's nested one).
    #[inline]
    fn with_material<'b>(&self, material: &'b Material) -> Bsdf<'b, N> {
        Bsdf {
            material,
            albedo: self.albedo,
            albedo_b: self.albedo_b,
            weight: self.weight,
            perturb: self.perturb,
            alpha: self.alpha,
            spec_r: self.spec_r,
            spec_t: self.spec_t,
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
