//! Path vertices of bidirectional path tracing and the densities between them (Veach 1997
//! §10.2–10.3; pbrt-v4 §13.3 names the same quantities `pdfFwd` and `pdfRev`).
//!
//! Every density here is per unit **area** at the vertex it produces (per unit solid angle
//! for a vertex at infinity, whose "position" is a direction), so that the ratios of the MIS
//! weights compare like with like. A vertex in a medium is a point in space: its area density
//! is the solid-angle density over d², with no cosine. The free flights' densities (σ·Tr) are
//! left out of these densities, as pbrt-v3's `BDPT` leaves them out (Pharr, Jakob and
//! Humphreys 2016, §16.3.4): the MIS weights are then a function of the path's geometry alone,
//! the same for every strategy and every hero wavelength, so they still sum to one over the
//! strategies and the estimate stays unbiased; the flights' own spectral MIS is each
//! vertex's [`Vertex::r_u`].

use glam::{Vec2, Vec3};

use super::super::{Integrator, Shading};
use crate::material::TransportMode;
use crate::medium::{MediumInterface, PhaseFunction};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// What a vertex is.
#[derive(Clone, Copy)]
pub(super) enum Kind {
    /// A point on the camera's lens (the pinhole for a pinhole camera): the first vertex of a
    /// camera subpath, or the point a t = 1 strategy samples.
    Camera,
    /// A point on light `light` (index into `Scene::lights`): the first vertex of a light
    /// subpath, or the point an s = 1 strategy samples. For a light that emits parallel light
    /// from infinity the vertex stands for a direction (see [`Vertex::d`]).
    Light { light: u32 },
    /// A surface hit of either subpath; an emitting surface also carries its light.
    Surface { emitter: Option<u32> },
    /// A scattering event in a participating medium (its phase function plays the BSDF's
    /// part, with no cosine).
    Medium { phase: PhaseFunction },
    /// A camera ray that left the scene: the end of a camera subpath on the lights at
    /// infinity, in direction [`Vertex::d`].
    Escaped,
}

/// One vertex of a subpath.
#[derive(Clone, Copy)]
pub(super) struct Vertex<'a, const N: usize> {
    pub kind: Kind,
    /// Position, m (unused for vertices at infinity).
    pub p: Vec3,
    /// Absolute error bound of `p`, m.
    pub p_error: Vec3,
    /// Unit geometric normal as the shape defines it (not flipped toward any side); zero for
    /// vertices not on a surface (pinhole, point-like lights, vertices at infinity).
    pub ng: Vec3,
    /// For vertices at infinity: the unit direction from the scene toward the light.
    pub d: Vec3,
    /// Surface coordinates (emitters with textured radiance).
    pub uv: Vec2,
    /// The material and frame at a surface hit (None for a black emitter, which ends the path).
    pub shading: Option<Shading<'a, N>>,
    /// Unit world direction toward the previous vertex of the subpath (surfaces).
    pub wo: Vec3,
    /// The subpath's throughput up to and including this vertex: for a camera subpath the
    /// importance-weighted product W·Π f|cos|/pdf (dimensionless, 1 at the lens); for a light
    /// subpath the spectral power per unit probability, Le·Π f|cos|/pdf (W·nm⁻¹ past the
    /// light; at the light itself Le/pdf of its choice).
    pub beta: SampledSpectrum<N>,
    /// Density of this vertex as its own subpath generated it (per area, see the module).
    pub pdf_fwd: f32,
    /// Density of this vertex as the other subpath would have generated it, walking the same
    /// path the other way.
    pub pdf_rev: f32,
    /// Whether the vertex scattered by a delta lobe (it cannot be connected to).
    pub delta: bool,
    /// Per wavelength k, the density of the subpath's free flights up to this vertex had k
    /// been the hero, over the hero's own (`volpath`'s `r_u`; 1 without media). A strategy
    /// divides its contribution by the average over the live wavelengths of the product of
    /// its two subpaths' ratios: the balance heuristic over hero choices.
    pub r_u: SampledSpectrum<N>,
    /// The medium the vertex is in (a medium vertex, the lens), or the one the ray that
    /// reached it travelled in (a surface); None for vacuum.
    pub medium: Option<u32>,
    /// The media on either side of the surface (a surface vertex; none elsewhere).
    pub interface: MediumInterface,
}

impl<'a, const N: usize> Vertex<'a, N> {
    /// A vertex of kind `kind` at `p` with nothing else known yet.
    pub fn new(kind: Kind, p: Vec3, beta: SampledSpectrum<N>, pdf_fwd: f32) -> Self {
        Self {
            kind,
            p,
            p_error: Vec3::ZERO,
            ng: Vec3::ZERO,
            d: Vec3::ZERO,
            uv: Vec2::ZERO,
            shading: None,
            wo: Vec3::ZERO,
            beta,
            pdf_fwd,
            pdf_rev: 0.0,
            delta: false,
            r_u: SampledSpectrum::splat(1.0),
            medium: None,
            interface: MediumInterface::default(),
        }
    }

    /// The medium a ray leaving this vertex in direction `d` travels in.
    pub fn medium_toward(&self, d: Vec3) -> Option<u32> {
        self.interface.target(self.ng, d, self.medium)
    }

    /// Whether the vertex lies at infinity (escaped camera rays, lights at infinity).
    pub fn at_infinity(&self, it: &Integrator<'_>) -> bool {
        match self.kind {
            Kind::Escaped => true,
            Kind::Light { light } => it.scene.lights[light as usize].is_at_infinity(),
            Kind::Camera | Kind::Surface { .. } | Kind::Medium { .. } => false,
        }
    }

    /// Whether this is a light vertex of a light that emits parallel light (its next vertex's
    /// density is per area across the direction).
    pub fn kind_is_parallel_light(&self, it: &Integrator<'_>) -> bool {
        match self.kind {
            Kind::Light { light } => it.scene.lights[light as usize].emits_parallel(),
            _ => false,
        }
    }

    /// Unit direction from `self` toward `to`.
    pub fn dir_to(&self, it: &Integrator<'_>, to: &Vertex<'_, N>) -> Vec3 {
        if to.at_infinity(it) {
            to.d
        } else {
            (to.p - self.p).normalize_or_zero()
        }
    }

    /// Whether a connection can end at this vertex: a surface whose material has a non-delta
    /// lobe, a camera, or a light that does not emit in a single direction.
    pub fn connectible(&self, it: &Integrator<'_>) -> bool {
        match self.kind {
            Kind::Camera | Kind::Medium { .. } => true,
            // not a light that emits in one direction only (collimated: directional, beam)
            Kind::Light { light } => {
                let l = &it.scene.lights[light as usize];
                !(l.emits_parallel() && l.is_delta())
            }
            Kind::Surface { .. } => self
                .shading
                .as_ref()
                .is_some_and(|sh| !sh.bsdf.is_specular()),
            Kind::Escaped => false,
        }
    }

    /// Whether the vertex is on a light that is a delta in position or direction (which no
    /// path can hit).
    pub fn is_delta_light(&self, it: &Integrator<'_>) -> bool {
        match self.kind {
            Kind::Light { light } => it.scene.lights[light as usize].is_delta(),
            _ => false,
        }
    }

    /// The BSDF value f (sr⁻¹, no cosine) at a surface vertex for light arriving from `wo` (its
    /// subpath's previous vertex) and leaving toward `wi` (unit, world), times the adjoint
    /// shading-normal correction for importance transport (Veach 1997 §5.3); the phase
    /// function's value at a medium vertex (sr⁻¹). Zero elsewhere.
    pub fn f(
        &self,
        wi: Vec3,
        w: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> SampledSpectrum<N> {
        if let Kind::Medium { phase } = self.kind {
            return SampledSpectrum::splat(phase.eval(self.wo, wi));
        }
        let Some(sh) = &self.shading else {
            return SampledSpectrum::zero();
        };
        let wo = sh.frame.to_local(self.wo);
        let f = sh.bsdf.eval(wo, sh.frame.to_local(wi), w, mode);
        match mode {
            TransportMode::Radiance => f,
            TransportMode::Importance => f * sh.adjoint_correction(wo, wi),
        }
    }

    /// |cos θ| between the shading normal and `wi` at a surface vertex; 1 elsewhere (a medium
    /// vertex has no cosine).
    pub fn cos_shading(&self, wi: Vec3) -> f32 {
        match &self.shading {
            Some(sh) => sh.frame.n.dot(wi).abs(),
            None => 1.0,
        }
    }

    /// Radiance this vertex emits toward `to` (the previous vertex of a camera subpath),
    /// W·m⁻²·sr⁻¹·nm⁻¹: an emitting surface's, or the lights at infinity along an escaped
    /// ray. Zero for other vertices.
    pub fn le(
        &self,
        it: &Integrator<'_>,
        to: &Vertex<'_, N>,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let scene = it.scene;
        match self.kind {
            Kind::Surface { emitter: Some(l) } => {
                let w_out = (to.p - self.p).normalize_or_zero();
                scene.lights[l as usize].emitted(self.ng, w_out, self.uv, w)
            }
            Kind::Escaped => {
                let mut le = SampledSpectrum::zero();
                for &i in &scene.infinite_lights {
                    le += scene.lights[i as usize].escaped(self.d, w);
                }
                le
            }
            _ => SampledSpectrum::zero(),
        }
    }

    /// Converts a solid-angle density `pdf` (sr⁻¹) of the direction from `self` toward `next`
    /// into a density per unit area at `next`: × |cos θ_next| / d² (Veach 1997 eq. 8.10); a
    /// vertex at infinity keeps the solid-angle density, and a vertex without a surface has no
    /// cosine.
    pub fn convert(&self, it: &Integrator<'_>, pdf: f32, next: &Vertex<'_, N>) -> f32 {
        if next.at_infinity(it) {
            return pdf;
        }
        let v = next.p - self.p;
        let d2 = v.length_squared();
        if !(d2 > 0.0) {
            return 0.0;
        }
        let mut pdf = pdf / d2;
        if next.ng != Vec3::ZERO {
            pdf *= next.ng.dot(v).abs() / d2.sqrt();
        }
        pdf
    }

    /// Density per unit area with which this vertex, reached from `prev`, generates `next`:
    /// the camera's directional density, the BSDF's sampling density, or the light's emission
    /// density ([`Vertex::pdf_light`]), converted to area at `next`. Zero where none exists.
    pub fn pdf(
        &self,
        it: &Integrator<'_>,
        prev: Option<&Vertex<'_, N>>,
        next: &Vertex<'_, N>,
        w: &SampledWavelengths<N>,
    ) -> f32 {
        let wn = self.dir_to(it, next);
        let pdf_sa = match self.kind {
            Kind::Light { .. } | Kind::Escaped => return self.pdf_light(it, next),
            Kind::Camera => it.scene.camera.pdf_we(self.p, wn),
            Kind::Medium { phase } => match prev {
                Some(prev) => phase.eval(self.dir_to(it, prev), wn),
                None => return 0.0,
            },
            Kind::Surface { .. } => {
                let (Some(sh), Some(prev)) = (&self.shading, prev) else {
                    return 0.0;
                };
                let wp = self.dir_to(it, prev);
                sh.bsdf.pdf(
                    sh.frame.to_local(wp),
                    sh.frame.to_local(wn),
                    w,
                    TransportMode::Radiance,
                )
            }
        };
        self.convert(it, pdf_sa, next)
    }

    /// The light this vertex is on (a light vertex, an emitting surface), if any.
    fn light(&self) -> Option<u32> {
        match self.kind {
            Kind::Light { light }
            | Kind::Surface {
                emitter: Some(light),
            } => Some(light),
            _ => None,
        }
    }

    /// The direction of travel from this vertex of a light that emits parallel light toward
    /// `next`: a vertex at infinity stores the direction toward the light; a beam's vertex is
    /// on its disk and emits along the beam.
    fn parallel_travel(&self, it: &Integrator<'_>, next: &Vertex<'_, N>) -> Vec3 {
        if self.at_infinity(it) {
            -self.d
        } else {
            (next.p - self.p).normalize_or_zero()
        }
    }

    /// Density per unit area with which this light vertex's emission generates `next`
    /// (`Light::pdf_le`): the directional density over d² for lights at a point or on a
    /// surface; the positional density across the direction for parallel light. × |cos θ_next|.
    /// For an escaped camera ray, the lights at infinity's disk density 1/(π r²).
    pub fn pdf_light(&self, it: &Integrator<'_>, next: &Vertex<'_, N>) -> f32 {
        let scene = it.scene;
        let sphere = scene.bounding_sphere();
        let cos_next = |d: Vec3| {
            if next.ng == Vec3::ZERO {
                1.0
            } else {
                next.ng.dot(d).abs()
            }
        };
        if let Kind::Escaped = self.kind {
            let disk = 1.0 / (std::f32::consts::PI * sphere.1 * sphere.1);
            return disk * cos_next(self.d);
        }
        let Some(li) = self.light() else {
            return 0.0;
        };
        let light = &scene.lights[li as usize];
        if light.emits_parallel() {
            let travel = self.parallel_travel(it, next);
            let pdf = light.pdf_le(&scene.shapes, sphere, next.p, self.ng, travel);
            return pdf.pos * cos_next(travel);
        }
        let d = next.p - self.p;
        let d2 = d.length_squared();
        if !(d2 > 0.0) {
            return 0.0;
        }
        let dir = d / d2.sqrt();
        let pdf = light.pdf_le(&scene.shapes, sphere, self.p, self.ng, dir);
        pdf.dir * cos_next(dir) / d2
    }

    /// Density of choosing this light vertex as the first vertex of a light subpath that goes
    /// on to `next`: the light's selection probability times its positional density (per area),
    /// or for parallel light its directional density (per solid angle). For an escaped camera
    /// ray, the sum over the lights at infinity (pbrt-v4's `PdfLightOrigin`).
    pub fn pdf_light_origin(&self, it: &Integrator<'_>, next: &Vertex<'_, N>) -> f32 {
        let scene = it.scene;
        let sphere = scene.bounding_sphere();
        if let Kind::Escaped = self.kind {
            let mut pdf = 0.0;
            for &i in &scene.infinite_lights {
                let i = i as usize;
                let l = &scene.lights[i];
                pdf += it.lights.prob(i) * l.pdf_li(&scene.shapes, next.p, self.d, self.p, self.ng);
            }
            return pdf;
        }
        let Some(li) = self.light() else {
            return 0.0;
        };
        let light = &scene.lights[li as usize];
        let sel = it.lights.prob(li as usize);
        if light.emits_parallel() {
            let travel = self.parallel_travel(it, next);
            return sel
                * light
                    .pdf_le(&scene.shapes, sphere, next.p, self.ng, travel)
                    .dir;
        }
        let dir = (next.p - self.p).normalize_or_zero();
        sel * light
            .pdf_le(&scene.shapes, sphere, self.p, self.ng, dir)
            .pos
    }
}
