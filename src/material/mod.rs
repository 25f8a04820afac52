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

pub mod albedo;
mod blend;
mod bsdf;
pub mod coated;
mod conductor;
mod dielectric;
mod diffuse_transmission;
mod disney;
mod element;
mod erf;
pub mod fresnel;
mod hair;
mod hair_terms;
mod lambert;
mod layer_interfaces;
mod layered;
mod layered_walk;
mod mask;
mod measured;
mod measured_polarized;
pub mod microfacet;
mod null;
mod perturb;
mod phong;
mod plastic;
mod polarised;
mod pplastic;
mod predicates;
mod principled;
mod principled_thin;
mod rough_dielectric;
mod smith;
mod textured;

pub use blend::Blend;
pub use bsdf::Bsdf;
use bsdf::UNPERTURBED;
pub use coated::ThinFilm;
pub use conductor::{Conductor, RoughConductor};
pub use dielectric::Dielectric;
pub use diffuse_transmission::DiffuseTransmission;
pub use disney::DisneyAt;
pub use element::Element;
pub use hair::Hair;
pub use lambert::Lambert;
pub use layered::{Layered, LayeredBase};
pub use mask::Mask;
pub use measured::{Measured, Warp2D};
pub use measured_polarized::MeasuredPolarized;
pub use null::thin_reflectance;
pub use perturb::{BumpMap, LocalSurface, NormalMap};
pub use phong::Phong;
pub use plastic::{Plastic, RoughCoating, fresnel_diffuse_reflectance};
pub use polarised::Polarising;
pub use pplastic::PPlastic;
pub use principled::Principled;
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
    /// Mitsuba's `pplastic`: a polarising plastic (see [`PPlastic`]).
    PPlastic(PPlastic),
    /// Mitsuba's `measured_polarized`: a measured pBRDF (see [`MeasuredPolarized`]).
    MeasuredPolarized(Box<MeasuredPolarized>),
    /// pbrt-v4's and Mitsuba's `measured`: an RGL measured BRDF (see [`Measured`]), shared.
    Measured(std::sync::Arc<Measured>),
    /// Mitsuba's `thindielectric`: a sheet of index `eta` (relative to the outside) too thin to
    /// offset a ray. Reflectance with the sheet's inner reflections, R = 2F/(1 + F) for the
    /// Fresnel reflectance F at the incidence angle, else straight through: two delta lobes
    /// of weight 1 chosen with probabilities R and 1 − R.
    ThinDielectric {
        eta: f32,
    },
    /// A free-standing coherent film (a soap bubble's wall; see [`ThinFilm`]).
    ThinFilm(Box<ThinFilm>),
    /// Mitsuba's `null`: no surface for light, which passes straight through (a delta
    /// transmission of weight 1 that still counts as a scattering event, as in Mitsuba).
    Null,
    /// Mitsuba's `polarizer` and `retarder`: a thin polarising element crossed undeviated (see
    /// [`Element`]); in an unpolarised render, a grey filter.
    Element(Element),
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
    /// Mitsuba's `principled` and `principledthin`: the Disney/Burley model (see
    /// [`Principled`]).
    Principled(Box<Principled>),
    /// Mitsuba's `hair`: Chiang et al.'s fibre model on a curve's frame (see [`Hair`]).
    Hair(Box<Hair>),
    /// pbrt-v4's `coateddiffuse` and `coatedconductor`: a dielectric coating over a base,
    /// evaluated by random walks as pbrt-v4 does (see [`Layered`]).
    Layered(Box<Layered>),
    /// pbrt-v4's `diffusetransmission`: a Lambertian lobe on each side (see
    /// [`DiffuseTransmission`]).
    DiffuseTransmission(Box<DiffuseTransmission>),
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
        let at = |t: &crate::texture::Texture| t.sample_at(uv, s.p, s.prim, s.bary, w);
        let albedo = match self {
            Material::Diffuse(m) => at(&m.reflectance),
            Material::Plastic(m) => at(&m.diffuse),
            Material::PPlastic(m) => at(&m.diffuse),
            Material::Mask(m) => {
                return Bsdf {
                    weight: at(&m.opacity)[0].clamp(0.0, 1.0),
                    ..m.inner.at_surface(s, w).with_material(self)
                };
            }
            Material::Blend(m) => {
                return Bsdf {
                    material: self,
                    albedo: m.a.at_surface(s, w).albedo,
                    albedo_b: m.b.at_surface(s, w).albedo,
                    weight: at(&m.weight)[0].clamp(0.0, 1.0),
                    perturb: UNPERTURBED,
                    alpha: [0.0; 2],
                    spec_r: SampledSpectrum::splat(1.0),
                    spec_t: SampledSpectrum::splat(1.0),
                    disney: DisneyAt::default(),
                    fibre_h: 0.0,
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
            Material::Principled(m) => {
                let base = at(&m.base_color);
                return Bsdf {
                    disney: m.at_hit(at, base, w),
                    ..Bsdf::plain(self, base)
                };
            }
            // the base's reflectance or relative (η, k), and the slab's albedo
            Material::Layered(m) => {
                let (a, b) = m.base_at(at(&m.reflectance), w);
                let alpha = match &m.alpha_texture {
                    Some(([u, v], remap)) => textured::roughness_at([u, v], *remap, uv, s.p, w),
                    None => [0.0; 2],
                };
                return Bsdf {
                    albedo: a,
                    albedo_b: b,
                    alpha,
                    spec_r: at(&m.albedo),
                    ..Bsdf::plain(self, a)
                };
            }
            // R and T in the two albedos' places, clamped as pbrt-v4 clamps them
            Material::DiffuseTransmission(m) => {
                let unit = |x: SampledSpectrum<N>| x.map(|v| v.clamp(0.0, 1.0));
                return Bsdf {
                    albedo_b: unit(at(&m.transmittance)),
                    ..Bsdf::plain(self, unit(at(&m.reflectance)))
                };
            }
            // the absorption σₐ per radius in the albedo's place; pbrt-v4's offset h = 2v − 1
            Material::Hair(m) => {
                let sigma_a = m.sigma_a[0].sample(w) + m.sigma_a[1].sample(w);
                return Bsdf {
                    fibre_h: if m.h_from_surface() {
                        2.0 * uv.y - 1.0
                    } else {
                        0.0
                    },
                    ..Bsdf::plain(self, sigma_a)
                };
            }
            Material::Textured(m) => {
                return Bsdf {
                    alpha: m.alpha_at(uv, s.p, w),
                    spec_r: at(&m.reflectance),
                    spec_t: at(&m.transmittance),
                    ..m.inner.at_surface(s, w).with_material(self)
                };
            }
            // no diffuse albedo: the lobes read their own parameters
            Material::Phong(_)
            | Material::Dielectric(_)
            | Material::RoughDielectric(_)
            | Material::Conductor(_)
            | Material::RoughConductor(_)
            | Material::ThinDielectric { .. }
            | Material::ThinFilm(_)
            | Material::Element(_)
            | Material::MeasuredPolarized(_)
            | Material::Measured(_)
            | Material::Null => SampledSpectrum::zero(),
        };
        Bsdf::plain(self, albedo)
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
            Material::Layered(m) => m.is_specular(),
            Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::Null
            | Material::Element(_)
            | Material::ThinFilm(_)
            | Material::ThinDielectric { .. } => true,
            Material::Principled(_)
            | Material::Hair(_)
            | Material::Diffuse(_)
            | Material::DiffuseTransmission(_)
            | Material::Phong(_)
            | Material::RoughDielectric(_)
            | Material::RoughConductor(_)
            | Material::Plastic(_)
            | Material::PPlastic(_)
            | Material::MeasuredPolarized(_)
            | Material::Measured(_) => false,
        }
    }
}
