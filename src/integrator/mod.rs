//! Integrators: `path` (unidirectional path tracing with next-event estimation and multiple
//! importance sampling), `whitted` (the lecture notes' model evaluated literally), and the shared
//! pieces: light selection proportional to power, shading frames, shadow tests.
//!
//! An integrator returns the spectral radiance arriving along a camera ray at the path's
//! wavelengths, W·m⁻²·sr⁻¹·nm⁻¹. It may terminate the secondary wavelengths; the film then
//! drops them (their pdf is 0).

pub mod bdpt;
mod carrier;
mod direct;
pub mod light;
mod light_media;
pub mod meter;
mod path;
mod selector;
pub mod split;
mod volpath;
mod whitted;

pub use crate::scene::{IntegratorKind, LightSelection};
pub use selector::LightSelector;

/// Surfaces a shadow ray or a run of `null` crossings may pass before it is given up (a ray
/// caught between coincident surfaces must end).
pub(crate) const MAX_CROSSINGS: u32 = 256;

use glam::Vec3;

use crate::geometry::{Frame, Intersection, Ray, spawn_ray, spawn_ray_to};
use crate::light::LightSample;
use crate::material::{Bsdf, BsdfSample, LocalSurface, TransportMode};
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Everything an integrator reads: the scene and its light selectors.
pub struct Integrator<'a> {
    pub scene: &'a Scene,
    /// Light choice independent of position (by power, uniformly, or under the tree by
    /// [`crate::light::LightTree::position_free`]): emission sampling (`light`, `bdpt`), and
    /// next-event estimation when the scene does not select by the tree.
    pub lights: LightSelector,
    /// The scene's light tree when it selects by the tree ([`LightSelection::Tree`]): next-event
    /// estimation in `path` and `direct` ([`Integrator::pick_light`]).
    pub tree: Option<&'a crate::light::LightTree>,
    pub kind: IntegratorKind,
    pub max_depth: u32,
    /// Surface hits a camera path keeps before Russian roulette may end it (path tracer): the
    /// scene's `rr_depth`.
    pub rr_depth: u32,
    /// `bdpt` only: render one connection strategy alone (debugging; None renders them all).
    pub strategy: Option<bdpt::Strategy>,
    /// Split camera samples at dispersive hits ([`split`]): the scene asks for it, and it has
    /// no media and is not polarised (where the hero's free flights or Stokes frames would
    /// make the split depend on the hero).
    pub split_dispersion: bool,
}

impl<'a> Integrator<'a> {
    pub fn new(scene: &'a Scene, kind: IntegratorKind, max_depth: u32) -> Self {
        Self {
            scene,
            lights: LightSelector::new(&match scene.integrator.light_selection {
                LightSelection::Power => scene.light_power.clone(),
                LightSelection::Tree => scene.light_tree.position_free().to_vec(),
                // every light that emits anything, in proportion to its sampling weight
                LightSelection::Uniform => scene
                    .light_power
                    .iter()
                    .zip(&scene.light_sampling_weights)
                    .map(|(&p, &w)| if p > 0.0 { w } else { 0.0 })
                    .collect(),
            }),
            tree: (scene.integrator.light_selection == LightSelection::Tree)
                .then_some(&scene.light_tree),
            kind,
            max_depth,
            rr_depth: scene.integrator.rr_depth,
            strategy: None,
            split_dispersion: false,
        }
        .with_split_dispersion(scene.integrator.split_dispersion)
    }

    /// Splits camera samples at dispersion if `wanted` and the scene allows it (no media, not
    /// polarised: see [`Integrator::split_dispersion`]).
    pub fn with_split_dispersion(mut self, wanted: bool) -> Self {
        self.split_dispersion =
            wanted && self.scene.media.is_empty() && !self.scene.integrator.polarised;
        self
    }

    /// A light for next-event estimation at the shading point `p` with shading normal `n`
    /// (zero: none), its probability, and `u` rescaled to a fresh uniform number in [0, 1)
    /// for sampling the light: by the light tree if the scene selects by it, else by
    /// [`LightSelector::pick_reuse`]. None if no light can contribute.
    #[inline]
    pub fn pick_light(&self, p: Vec3, n: Vec3, u: f32) -> Option<(usize, f32, f32)> {
        match self.tree {
            Some(t) => t.pick(p, n, u),
            None => self.lights.pick_reuse(u),
        }
    }

    /// The probability with which [`Integrator::pick_light`] at `p`, `n` picks light `i`.
    #[inline]
    pub fn light_prob(&self, p: Vec3, n: Vec3, i: usize) -> f32 {
        match self.tree {
            Some(t) => t.pmf(p, n, i),
            None => self.lights.prob(i),
        }
    }

    /// Radiance along `ray` at the wavelengths `w` (which may be terminated to the hero).
    pub fn radiance<const N: usize>(
        &self,
        ray: Ray,
        w: &mut SampledWavelengths<N>,
        s: &mut Sampler,
    ) -> SampledSpectrum<N> {
        match self.kind {
            // `light` traces from the lights (see `light::trace`); camera rays use `path`
            // `light` and `bdpt` also trace from the lights (see `render`); camera rays alone use
            // `path`
            IntegratorKind::Path if !self.scene.media.is_empty() => {
                volpath::radiance(self, ray, w, s)
            }
            IntegratorKind::Path | IntegratorKind::Light | IntegratorKind::Bdpt => {
                path::radiance(self, ray, w, s)
            }
            IntegratorKind::Whitted => whitted::radiance(self, ray, w, s, 0),
            IntegratorKind::Direct {
                emitter_samples,
                bsdf_samples,
            } => direct::radiance(self, ray, w, s, emitter_samples, bsdf_samples),
        }
    }
}

impl Integrator<'_> {
    /// Whether camera rays carry Stokes vectors ([`Integrator::stokes`]): the scene renders
    /// polarised.
    #[inline]
    pub fn polarised(&self) -> bool {
        self.scene.integrator.polarised
    }

    /// The Stokes vector (S0–S3, W·m⁻²·sr⁻¹·nm⁻¹ per wavelength) arriving along the camera ray
    /// `ray`, in the camera's frame (see `path::stokes`): the polarised path tracer. The
    /// render refuses polarised scenes under other integrators and with media.
    pub fn stokes<const N: usize>(
        &self,
        ray: Ray,
        w: &mut SampledWavelengths<N>,
        s: &mut Sampler,
    ) -> [SampledSpectrum<N>; 4] {
        path::stokes(self, ray, w, s)
    }
}

/// What a particle's splat carries to the film (light tracing, BDPT's t = 1 strategies), in
/// W·m⁻²·sr⁻¹·nm⁻¹ per wavelength (times the caller's scale): radiance, or in a polarised
/// render the Stokes vector S0–S3 in the camera's frame.
#[derive(Clone, Copy, Debug)]
pub enum Splatted<const N: usize> {
    Radiance(SampledSpectrum<N>),
    Stokes([SampledSpectrum<N>; 4]),
}

impl<const N: usize> Splatted<N> {
    /// The value times `k`.
    pub fn scaled(self, k: f32) -> Self {
        match self {
            Splatted::Radiance(l) => Splatted::Radiance(l * k),
            Splatted::Stokes(st) => Splatted::Stokes(st.map(|v| v * k)),
        }
    }

    /// The radiance (S0 of a Stokes vector).
    pub fn radiance(&self) -> &SampledSpectrum<N> {
        match self {
            Splatted::Radiance(l) | Splatted::Stokes([l, ..]) => l,
        }
    }
}

/// The shading situation at a surface hit, seen from the incoming ray: the material at the hit
/// (textures looked up) and the shading frame.
#[derive(Clone, Copy)]
pub(crate) struct Shading<'a, const N: usize> {
    pub bsdf: Bsdf<'a, N>,
    pub frame: Frame,
    /// Geometric normal on the side the material uses (flipped for a two-sided back face).
    pub n_geom: Vec3,
}

impl<const N: usize> Shading<'_, N> {
    /// The BSDF-sampling step shared by camera and light paths: samples the material with
    /// (uc, u) from `s`, keeps only the hero wavelength at any dispersive material, multiplies `beta`
    /// by f·|cos θ|/pdf and returns the sample with the ray that continues the path. None ends
    /// the path (no sample, zero pdf or zero value).
    pub fn scatter(
        &self,
        hit: &Intersection,
        wo: Vec3,
        w: &mut SampledWavelengths<N>,
        s: &mut Sampler,
        mode: TransportMode,
        beta: &mut SampledSpectrum<N>,
    ) -> Option<(BsdfSample<N>, Ray)> {
        let (uc, u) = (s.get_1d(), s.get_2d());
        // Terminate at every dispersive hit, before choosing a lobe: a choice made with the
        // hero's F(λ₀) that terminates on one branch only biases the secondaries.
        if self.bsdf.is_dispersive() {
            w.terminate_secondary();
        }
        let bs = self.bsdf.sample(wo, w, uc, u, mode)?;
        if bs.pdf <= 0.0 || bs.f.is_zero() {
            return None;
        }
        let wi = self.frame.to_world(bs.wi);
        let correction = match mode {
            TransportMode::Radiance => 1.0,
            TransportMode::Importance => self.adjoint_correction(wo, wi),
        };
        if correction == 0.0 {
            return None;
        }
        *beta *= bs.f * (bs.wi.z.abs() * correction / bs.pdf);
        Some((
            bs,
            spawn_ray(hit.p, hit.p_error, self.n_geom_toward(wi), wi),
        ))
    }

    /// The adjoint correction for shading normals (Veach 1997 §5.3, eq. 5.19; pbrt-v3 §16.1.3
    /// `CorrectShadingNormal`), for particles (importance transport): a particle that arrived
    /// from `wo` (local, toward where the light came from) and leaves along `wi_world` (world,
    /// unit) carries f·|ns·wi| ⟶ f·|ns·wo|·|ng·wi| / (|ng·wo|·|ns·wi|) times that. Multiplying
    /// by it makes light tracing estimate the same radiance as path tracing, which integrates
    /// f·|ns·wi| over the incident directions. Returns 0 for a direction tangent to the
    /// geometric surface (the particle carries nothing there).
    #[inline]
    pub fn adjoint_correction(&self, wo: Vec3, wi_world: Vec3) -> f32 {
        let wo_world = self.frame.to_world(wo);
        let den = self.n_geom.dot(wo_world).abs() * wi_world.dot(self.frame.n).abs();
        if den == 0.0 {
            return 0.0;
        }
        let c = wo.z.abs() * self.n_geom.dot(wi_world).abs() / den;
        if c.is_finite() { c } else { 0.0 }
    }

    /// The geometric normal flipped to the side of `dir`, for offsetting rays that leave there.
    /// (Written out, not [`crate::geometry::flip_toward`]: the branch compiles to 9 M fewer
    /// instructions in `scatter` on the Cornell box at 16 spp, callgrind.)
    #[inline]
    pub fn n_geom_toward(&self, dir: Vec3) -> Vec3 {
        if self.n_geom.dot(dir) < 0.0 {
            -self.n_geom
        } else {
            self.n_geom
        }
    }
}

impl Integrator<'_> {
    /// Material (looked up at the hit's uv for the wavelengths `w`) and frame at `hit` for a
    /// ray travelling along `dir`; None for a black emitter.
    pub(crate) fn shading<const N: usize>(
        &self,
        hit: &Intersection,
        dir: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<Shading<'_, N>> {
        let surf = &self.scene.surfaces[hit.shape as usize];
        let material = &self.scene.materials[surf.material? as usize];
        let mut ng = hit.n_geom;
        let mut frame = if material.needs_tangent() {
            Frame::from_normal_tangent(hit.n_shading, hit.dpdu)
        } else {
            Frame::from_normal(hit.n_shading)
        };
        // a two-sided surface seen from behind: the normal flips and the tangents stay, a
        // mirror image of the front frame as Mitsuba's `twosided` sees the back (so a normal
        // map's tangent-space normal reads the same on both sides)
        if surf.two_sided && !material.is_transmissive() && ng.dot(-dir) < 0.0 {
            ng = -ng;
            frame.n = -frame.n;
        }
        let local = if material.is_perturbed() || surf.attributes {
            let bary = if surf.attributes {
                self.scene.barycentrics(hit)
            } else {
                [1.0, 0.0, 0.0]
            };
            LocalSurface {
                uv: hit.uv,
                p: hit.p,
                dpdu: frame.to_local(hit.dpdu),
                dpdv: frame.to_local(hit.dpdv),
                n_geom: frame.to_local(ng),
                prim: hit.prim,
                bary,
            }
        } else {
            LocalSurface {
                p: hit.p,
                ..LocalSurface::flat(hit.uv)
            }
        };
        Some(Shading {
            bsdf: material.at_surface(&local, w),
            frame,
            n_geom: ng,
        })
    }

    /// The ray going on past `hit` along `d` when the path tracers pass it without a bounce:
    /// a `null` surface in a scene whose integrator skips them (pbrt-v4's `interface`,
    /// [`crate::scene::IntegratorSettings::skip_null`]); None for any other hit, which
    /// scatters. Reads no sample. The path tracer then counts no bounce and weighs an emitter
    /// hit after it by 1, as light sampling's shadow rays stop at it (pbrt-v4 §13.4,
    /// `PathIntegrator::Li` calling `SkipIntersection`). (Inlined: on every hit of every path,
    /// and the scene's flag alone decides for Mitsuba's and TOML scenes.)
    #[inline(always)]
    pub(crate) fn skip_null(&self, hit: &Intersection, d: Vec3) -> Option<Ray> {
        if !self.scene.integrator.skip_null {
            return None;
        }
        let m = self.scene.surfaces[hit.shape as usize].material?;
        if !matches!(
            self.scene.materials[m as usize],
            crate::material::Material::Null
        ) {
            return None;
        }
        Some(spawn_ray(hit.p, hit.p_error, hit.n_geom_toward(d), d))
    }

    /// Whether the light sample `ls` is blocked as seen from `hit`.
    pub(crate) fn occluded<const N: usize>(
        &self,
        hit: &Intersection,
        n: Vec3,
        ls: &LightSample<N>,
    ) -> bool {
        let ray = if ls.distance.is_finite() {
            spawn_ray_to(hit.p, hit.p_error, n, ls.p, ls.p_error, ls.n)
        } else {
            spawn_ray(hit.p, hit.p_error, n, ls.wi)
        };
        self.scene.accel.occluded(&self.scene.shapes, &ray)
    }
}
