//! pbrt-v4's `coateddiffuse` and `coatedconductor`: a dielectric coating over a Lambertian or
//! conductor base, with a homogeneous slab between them, evaluated stochastically as pbrt-v4
//! does (Guo, Hašan, Yan and Zhao 2018, "Position-free Monte Carlo simulation for arbitrary
//! layered BSDFs"; pbrt-v4 book §14.3, `LayeredBxDF` in `src/pbrt/bxdfs.h`).
//!
//! **Why stochastic, and what that means here.** A layered BSDF has no closed form. pbrt-v4
//! estimates f, the pdf and a sample each by random walks through the slab, and that estimate
//! *is* its material: its expected value, truncated at `max_depth` walk steps, is what a
//! pbrt-v4 render converges to. spectrace follows the same walks step for step (so its
//! truncation is pbrt-v4's), with its own random numbers: each call seeds a PCG32 from its
//! arguments (pbrt-v4 hashes them too), so images do not depend on the thread count.
//!
//! Contract (the module's conventions): f in sr⁻¹ without the cosine, an unbiased estimate
//! with `n_samples` walks; the pdf a stochastic estimate in sr⁻¹, mixed with a uniform sphere
//! (0.1/(4π) + 0.9·estimate, as pbrt-v4) so it is never 0; a sample's f/pdf is the walk's
//! unbiased weight and its pdf is that estimate (pbrt-v4's `pdfIsProportional`, whose path
//! integrator asks `PDF()` for MIS). Both sides of the surface see the coating (pbrt-v4's
//! `twoSided`); the bases do not transmit, so there is no transmission.
//!
//! **One deliberate difference from pbrt-v4.** Where light leaves through a rough coating, f
//! adds two estimates by MIS: out along a direction sampled from `wi` through the coating (its
//! density `wis.pdf`), and out along the base's or the phase function's sample (its density).
//! pbrt-v4 weighs the second against `exitInterface.PDF(-w, wi)`, the density of the opposite
//! crossing, so its weights do not sum to 1 and its f exceeds what its sampler integrates to
//! (6 % at α 0.22: README, "pbrt-v4 scenes"). spectrace weighs it against the first strategy's
//! density of the same direction, `top.pdf(wi, -w)`, and its f agrees with its sampler.
//!
//! The slab's medium has σₜ = 1 per unit `thickness`, single-scattering `albedo` and a
//! Henyey–Greenstein phase function of mean cosine `g`; with albedo 0 it only attenuates, by
//! exp(−thickness/|cos θ|) per crossing.

use super::layer_interfaces::{BaseIf, DielectricIf, trowbridge_reitz};
use crate::medium::PhaseFunction;
use crate::spectrum::ior::{ComplexIor, Ior};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use crate::texture::Texture;

/// The base under the coating.
#[derive(Clone, Debug, PartialEq)]
pub enum LayeredBase {
    /// Lambertian of the material's `reflectance` (`coateddiffuse`).
    Diffuse,
    /// A conductor (`coatedconductor`) of index `ior` (absolute; divided by the coating's at
    /// the hit), or, when None, of the index pbrt-v4 makes of `reflectance` r: n = 1,
    /// k = 2√r/√(1 − r), r clamped to [0, 0.9999]. Smooth, or microfacets of α [α_u, α_v].
    Conductor {
        ior: Option<ComplexIor>,
        alpha: Option<[f32; 2]>,
    },
}

/// A coated material (see the module's docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Layered {
    pub base: LayeredBase,
    /// The diffuse base's reflectance, or a conductor base's r (dimensionless, in [0, 1]).
    pub reflectance: Texture,
    /// The coating's index (relative to the outside); a dispersive one keeps only the hero
    /// wavelength, as pbrt-v4 does (`TerminateSecondary`).
    pub eta: Ior,
    /// The coating's microfacet α [α_u, α_v] (Trowbridge–Reitz); None when smooth.
    pub alpha: Option<[f32; 2]>,
    /// The coating's roughness as grey textures (pbrt-v4's `texture roughness`), in place of
    /// `alpha`, with whether they hold pbrt-v4's r (α = √r) rather than α; looked up per hit,
    /// where α below 10⁻³ is smooth (pbrt-v4's `EffectivelySmooth`).
    pub alpha_texture: Option<([Texture; 2], bool)>,
    /// The slab's optical thickness (σₜ = 1), dimensionless.
    pub thickness: f32,
    /// The slab's single-scattering albedo (0: absorbing only).
    pub albedo: Texture,
    /// The slab's Henyey–Greenstein mean cosine, in (−1, 1).
    pub g: f32,
    /// Walk steps before a walk is cut (pbrt-v4's `maxdepth`, 10 by default).
    pub max_depth: u32,
    /// Walks per estimate (pbrt-v4's `nsamples`, 1 by default).
    pub n_samples: u32,
    /// Weigh the exit's second estimate against the opposite crossing's density, as pbrt-v4
    /// does (see the module's docs): its f is then biased high. Only for comparing renders
    /// with pbrt-v4's; no reader sets it.
    pub pbrt_exit_weight: bool,
}

impl Layered {
    /// The base's values at a hit, from the textured `reflectance` r: (r, 0) for a diffuse
    /// base, a conductor's (η, k) relative to the coating.
    pub fn base_at<const N: usize>(
        &self,
        r: SampledSpectrum<N>,
        w: &SampledWavelengths<N>,
    ) -> (SampledSpectrum<N>, SampledSpectrum<N>) {
        let ieta = self.coat_eta(w);
        match &self.base {
            LayeredBase::Diffuse => (r.map(|x| x.clamp(0.0, 1.0)), SampledSpectrum::zero()),
            LayeredBase::Conductor { ior: Some(ior), .. } => {
                let (mut n, mut k) = (SampledSpectrum::zero(), SampledSpectrum::zero());
                for j in 0..N {
                    (n[j], k[j]) = ior.eval(w.lambda[j]);
                }
                (n * (1.0 / ieta), k * (1.0 / ieta))
            }
            LayeredBase::Conductor { ior: None, .. } => {
                let k = r.map(|x| {
                    let x = x.clamp(0.0, 0.9999);
                    2.0 * x.sqrt() / (1.0 - x).sqrt()
                });
                (SampledSpectrum::splat(1.0 / ieta), k * (1.0 / ieta))
            }
        }
    }

    /// The coating's index at the hero wavelength (1 where pbrt-v4 would read 0).
    fn coat_eta<const N: usize>(&self, w: &SampledWavelengths<N>) -> f32 {
        let e = self.eta.eval(w.lambda[0]);
        if e == 0.0 { 1.0 } else { e }
    }

    /// The slab at a hit: `base` from [`Layered::base_at`], the medium's `albedo` looked up.
    /// `alpha` is the coating's α looked up at the hit when it is textured.
    pub fn slab<const N: usize>(
        &self,
        base: (SampledSpectrum<N>, SampledSpectrum<N>),
        albedo: SampledSpectrum<N>,
        alpha: [f32; 2],
        w: &SampledWavelengths<N>,
    ) -> Slab<N> {
        let coat = if self.alpha_texture.is_some() {
            Some(alpha)
        } else {
            self.alpha
        };
        let bottom = match &self.base {
            LayeredBase::Diffuse => BaseIf::Diffuse(base.0),
            LayeredBase::Conductor { alpha, .. } => BaseIf::Conductor {
                eta: base.0,
                k: base.1,
                mf: alpha.and_then(trowbridge_reitz),
            },
        };
        Slab {
            top: DielectricIf {
                eta: self.coat_eta(w),
                mf: coat.and_then(trowbridge_reitz),
            },
            bottom,
            thickness: self.thickness.max(f32::MIN_POSITIVE),
            albedo: albedo.map(|a| a.clamp(0.0, 1.0)),
            phase: PhaseFunction::HenyeyGreenstein { g: self.g },
            max_depth: self.max_depth,
            n_samples: self.n_samples.max(1),
            dispersive: self.eta.is_dispersive(),
            pbrt_exit_weight: self.pbrt_exit_weight,
        }
    }

    /// Whether an interface's roughness differs along the two tangents (which then need ∂p/∂u).
    pub fn is_anisotropic(&self) -> bool {
        let base = match &self.base {
            LayeredBase::Conductor { alpha: Some(a), .. } => a[0] != a[1],
            _ => false,
        };
        let textured = self
            .alpha_texture
            .as_ref()
            .is_some_and(|([u, v], _)| u != v);
        base || textured || self.alpha.is_some_and(|a| a[0] != a[1])
    }

    /// Whether every lobe is a delta: a smooth coating over a smooth conductor and a clear slab
    /// (with a constant albedo texture of 0).
    pub fn is_specular(&self) -> bool {
        let clear = matches!(&self.albedo, Texture::Uniform(crate::spectrum::Spectrum::Constant(a)) if *a == 0.0);
        self.alpha.is_none()
            && self.alpha_texture.is_none()
            && clear
            && matches!(self.base, LayeredBase::Conductor { alpha: None, .. })
    }
}

/// A layered BSDF at one hit (see the module's docs).
#[derive(Clone, Copy, Debug)]
pub struct Slab<const N: usize> {
    pub top: DielectricIf,
    pub bottom: BaseIf<N>,
    pub thickness: f32,
    pub albedo: SampledSpectrum<N>,
    pub phase: PhaseFunction,
    pub max_depth: u32,
    pub n_samples: u32,
    pub dispersive: bool,
    pub pbrt_exit_weight: bool,
}
