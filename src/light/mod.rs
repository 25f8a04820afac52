//! Lights in physical units. Each light is a spectral shape already multiplied by the physical
//! scale that `build::build` computed from the scene file (see `build/lights.rs`), so the
//! spectra here are absolute:
//!
//! | light | spectrum unit |
//! | --- | --- |
//! | point, spot | spectral intensity, W·sr⁻¹·nm⁻¹ |
//! | goniometric (a luminaire file) | spectral intensity per candela of its table, W·sr⁻¹·nm⁻¹·cd⁻¹ |
//! | area, environment, environment map | spectral radiance, W·m⁻²·sr⁻¹·nm⁻¹ |
//! | directional | spectral irradiance on a plane perpendicular to it, W·m⁻²·nm⁻¹ |
//! | beam | total spectral power, W·nm⁻¹ |
//!
//! Sampling returns the radiance arriving at a reference point and the pdf of the direction
//! per unit solid angle; delta lights (point, spot, collimated directional) return pdf 1 with
//! `delta = true` and `li` = the irradiance-producing pseudo-radiance (I/r² or E).

mod area;
mod beam;
mod bounds;
mod directional;
mod distribution2d;
mod environment;
mod envmap;
mod goniometric;
mod octahedral;
mod point;
mod projector;
mod sample;
mod spot;
mod tree;

pub use area::AreaLight;
pub use beam::{BeamLight, Section as BeamSection};
pub use bounds::{DirectionCone, Importance, LightBounds};
pub use directional::DirectionalLight;
pub use environment::EnvironmentLight;
pub use envmap::EnvMapLight;
pub use goniometric::equal_area::GoniometricMapLight;
pub use goniometric::{Fold, GoniometricLight, IntensityTable};
pub use octahedral::{OctahedralMapLight, sphere_to_square, square_to_sphere};
pub use point::PointLight;
pub use projector::{ProjectorLaw, ProjectorLight};
use sample::point_like_sample;
pub use sample::{EmissionPdf, EmissionSample, LightSample};
pub use spot::{SpotFalloff, SpotLight, SpotTexture};
pub use tree::LightTree;

use glam::{Vec2, Vec3};

use crate::geometry::shape::Shape;
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum, WavelengthRange};

/// A light source: a closed enum matched in the render loop.
#[derive(Clone, Debug)]
pub enum Light {
    Point(PointLight),
    Spot(SpotLight),
    Area(AreaLight),
    Directional(DirectionalLight),
    Environment(EnvironmentLight),
    EnvMap(Box<EnvMapLight>),
    /// pbrt-v4's image `infinite` light: an equal-area octahedral map.
    Octahedral(Box<OctahedralMapLight>),
    Beam(BeamLight),
    /// Mitsuba's `projector`: an image projected from a point.
    Projector(Box<ProjectorLight>),
    /// A measured luminaire (IES LM-63 or EULUMDAT): a point with a tabulated distribution.
    Goniometric(Box<GoniometricLight>),
    /// pbrt-v4's `goniometric`: a point with an equal-area intensity image.
    GoniometricMap(Box<GoniometricMapLight>),
}

impl Light {
    /// Samples incident light at `p`. `u` is uniform in [0, 1)².
    /// Returns None when the sample carries no light (behind a one-sided emitter, outside a
    /// spot's cone, degenerate geometry).
    pub fn sample_li<const N: usize>(
        &self,
        shapes: &[Shape],
        p: Vec3,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> Option<LightSample<N>> {
        match self {
            Light::Point(l) => l.sample_li(p, w),
            Light::Spot(l) => l.sample_li(p, w),
            Light::Area(l) => l.sample_li(shapes, p, w, u),
            Light::Directional(l) => l.sample_li(w, u),
            Light::Environment(l) => l.sample_li(w, u),
            Light::EnvMap(l) => l.sample_li(w, u),
            Light::Octahedral(l) => l.sample_li(w, u),
            Light::Beam(l) => l.sample_li(p, w),
            Light::Projector(l) => l.sample_li(p, w),
            Light::Goniometric(l) => l.sample_li(p, w),
            Light::GoniometricMap(l) => l.sample_li(p, w),
        }
    }

    /// Density per unit solid angle with which [`Light::sample_li`] at `p` would produce the
    /// direction `wi` that reaches the light at `p_light` with normal `n_light` (for area
    /// lights; ignored otherwise). 0 for delta lights.
    pub fn pdf_li(&self, shapes: &[Shape], p: Vec3, wi: Vec3, p_light: Vec3, n_light: Vec3) -> f32 {
        match self {
            Light::Area(l) => l.pdf_li(&shapes[l.shape as usize], p, wi, p_light, n_light),
            Light::Directional(l) => l.pdf_li(wi),
            Light::Environment(_) => crate::sampling::UNIFORM_SPHERE_PDF,
            Light::EnvMap(l) => l.pdf_li(wi),
            Light::Octahedral(l) => l.pdf_li(wi),
            Light::Point(_)
            | Light::Spot(_)
            | Light::Beam(_)
            | Light::Projector(_)
            | Light::Goniometric(_)
            | Light::GoniometricMap(_) => 0.0,
        }
    }

    /// Radiance leaving an area light's surface with geometric normal `n` and surface
    /// coordinates `uv` toward `w_out` (unit, pointing away from the surface),
    /// W·m⁻²·sr⁻¹·nm⁻¹. Zero for other lights.
    pub fn emitted<const N: usize>(
        &self,
        n: Vec3,
        w_out: Vec3,
        uv: glam::Vec2,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self {
            Light::Area(l) => l.emitted(n, w_out, uv, w),
            _ => SampledSpectrum::zero(),
        }
    }

    /// Radiance arriving along a ray that escapes the scene in direction `dir` (environment, and
    /// the disk of a directional light with an angular diameter), W·m⁻²·sr⁻¹·nm⁻¹.
    pub fn escaped<const N: usize>(
        &self,
        dir: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self {
            Light::Environment(l) => l.radiance.sample(w),
            Light::EnvMap(l) => l.escaped(dir, w),
            Light::Octahedral(l) => l.escaped(dir, w),
            Light::Directional(l) => l.escaped(dir, w),
            _ => SampledSpectrum::zero(),
        }
    }

    /// A particle leaving the light (light tracing, light subpaths of `bdpt`): `u_pos` chooses
    /// the origin, `u_dir` the direction (both uniform in [0, 1)²), `sphere` is the scene's
    /// bounding sphere (centre, radius in m) for lights at infinity. None when the light emits
    /// nothing there (a degenerate shape). See [`EmissionSample`] for units and measures.
    pub fn sample_le<const N: usize>(
        &self,
        shapes: &[Shape],
        sphere: (Vec3, f32),
        w: &SampledWavelengths<N>,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<EmissionSample<N>> {
        let (center, radius) = sphere;
        match self {
            Light::Area(l) => l.sample_le(&shapes[l.shape as usize], w, u_pos, u_dir),
            Light::Point(l) => Some(l.sample_le(w, u_dir)),
            Light::Spot(l) => Some(l.sample_le(w, u_dir)),
            Light::Beam(l) => Some(l.sample_le(w, u_pos)),
            Light::Projector(l) => Some(l.sample_le(w, u_dir)),
            Light::Goniometric(l) => Some(l.sample_le(w, u_dir)),
            Light::GoniometricMap(l) => Some(l.sample_le(w, u_dir)),
            Light::Directional(l) => Some(l.sample_le(center, radius, w, u_pos, u_dir)),
            Light::Environment(l) => Some(l.sample_le(center, radius, w, u_pos, u_dir)),
            Light::EnvMap(l) => Some(l.sample_le(center, radius, w, u_pos, u_dir)),
            Light::Octahedral(l) => Some(l.sample_le(center, radius, w, u_pos, u_dir)),
        }
    }

    /// The densities with which [`Light::sample_le`] produces a particle travelling along `d`
    /// (unit) from `p`, a point on the light with normal `n` (area lights; `n` on the emitting
    /// side or either side for two-sided ones). For lights that emit parallel light
    /// ([`Light::emits_parallel`]) `p` is any point the particle reaches and `pos` the density
    /// of its line on the disk perpendicular to `d`. Zero for particles the light cannot emit.
    pub fn pdf_le(
        &self,
        shapes: &[Shape],
        sphere: (Vec3, f32),
        p: Vec3,
        n: Vec3,
        d: Vec3,
    ) -> EmissionPdf {
        let disk = 1.0 / (std::f32::consts::PI * sphere.1 * sphere.1);
        match self {
            Light::Area(l) => l.pdf_le(&shapes[l.shape as usize], n, d),
            Light::Point(_) => EmissionPdf {
                pos: 0.0,
                dir: crate::sampling::UNIFORM_SPHERE_PDF,
            },
            Light::Spot(l) => l.pdf_le(d),
            Light::Projector(l) => l.pdf_le(d),
            Light::Goniometric(l) => l.pdf_le(d),
            Light::GoniometricMap(l) => l.pdf_le(d),
            Light::Beam(l) => l.pdf_le(p),
            Light::Directional(l) => EmissionPdf {
                pos: disk,
                dir: l.pdf_li(-d),
            },
            Light::Environment(_) => EmissionPdf {
                pos: disk,
                dir: crate::sampling::UNIFORM_SPHERE_PDF,
            },
            Light::EnvMap(l) => EmissionPdf {
                pos: disk,
                dir: l.pdf_li(-d),
            },
            Light::Octahedral(l) => EmissionPdf {
                pos: disk,
                dir: l.pdf_li(-d),
            },
        }
    }

    /// Whether the light emits parallel light from a disk (lights at infinity, beams): its
    /// particles' origins are chosen per unit area across the direction, which is chosen first
    /// (or fixed), so the density of a particle's first hit is `pdf_le(..).pos`·|cos θ| there
    /// and the density of the light's own vertex is `pdf_le(..).dir` (Veach 1997 §8.3.2;
    /// pbrt-v4's `PdfLightOrigin`/`PdfLight` for infinite lights).
    pub fn emits_parallel(&self) -> bool {
        match self {
            Light::Directional(_)
            | Light::Environment(_)
            | Light::EnvMap(_)
            | Light::Octahedral(_)
            | Light::Beam(_) => true,
            Light::Point(_)
            | Light::Spot(_)
            | Light::Area(_)
            | Light::Projector(_)
            | Light::Goniometric(_)
            | Light::GoniometricMap(_) => false,
        }
    }

    /// Whether the light is at infinity: the only kind [`Light::escaped`] can be non-zero for.
    pub fn is_at_infinity(&self) -> bool {
        match self {
            Light::Environment(_)
            | Light::EnvMap(_)
            | Light::Octahedral(_)
            | Light::Directional(_) => true,
            Light::Point(_)
            | Light::Spot(_)
            | Light::Area(_)
            | Light::Beam(_)
            | Light::Projector(_)
            | Light::Goniometric(_)
            | Light::GoniometricMap(_) => false,
        }
    }

    /// Whether the light is a delta distribution in position or direction.
    pub fn is_delta(&self) -> bool {
        match self {
            Light::Point(_)
            | Light::Spot(_)
            | Light::Beam(_)
            | Light::Projector(_)
            | Light::Goniometric(_)
            | Light::GoniometricMap(_) => true,
            Light::Directional(l) => l.is_delta(),
            Light::Area(l) => l.invisible,
            Light::Environment(_) | Light::EnvMap(_) | Light::Octahedral(_) => false,
        }
    }

    /// Bounds of the light's emission for the light tree, with power `phi` (W, as
    /// [`Light::power`] gives); None for the lights the tree does not hold (at infinity, or a
    /// beam, whose reach is a cylinder), which are chosen beside it ([`LightTree`]).
    pub fn bounds(&self, shapes: &[Shape], phi: f32) -> Option<LightBounds> {
        match self {
            Light::Point(l) => Some(l.bounds(phi)),
            Light::Spot(l) => Some(l.bounds(phi)),
            Light::Area(l) => Some(l.bounds(&shapes[l.shape as usize], phi)),
            Light::Projector(l) => Some(l.bounds(phi)),
            Light::Goniometric(l) => Some(l.bounds(phi)),
            Light::GoniometricMap(l) => Some(l.bounds(phi)),
            Light::Directional(_)
            | Light::Environment(_)
            | Light::EnvMap(_)
            | Light::Octahedral(_)
            | Light::Beam(_) => None,
        }
    }

    /// Total emitted power over `range`, W. Lights at infinity count the power crossing a disk
    /// of radius `scene_radius` (m) that faces them, as pbrt-v4 does for light selection.
    pub fn power(&self, shapes: &[Shape], range: WavelengthRange, scene_radius: f32) -> f64 {
        let band = |s: &Spectrum| s.integrate(range.min_nm, range.max_nm, 1.0);
        let pi = std::f64::consts::PI;
        match self {
            Light::Point(l) => 4.0 * pi * band(&l.intensity),
            Light::Spot(l) => l.solid_angle_factor() * band(&l.intensity),
            Light::Area(l) => {
                let sides = if l.two_sided { 2.0 } else { 1.0 };
                // a textured radiance: its mean over the surface and 360–830 nm, for selection
                let radiance = match &l.radiance {
                    crate::texture::Texture::Uniform(s) => band(s),
                    t => t.mean() as f64 * (range.max_nm - range.min_nm) as f64,
                };
                sides * pi * shapes[l.shape as usize].area() as f64 * radiance
            }
            Light::Directional(l) => pi * (scene_radius as f64).powi(2) * band(&l.irradiance),
            Light::Environment(l) => {
                4.0 * pi * pi * (scene_radius as f64).powi(2) * band(&l.radiance)
            }
            Light::EnvMap(l) => pi * (scene_radius as f64).powi(2) * l.band_radiant_exitance(range),
            Light::Octahedral(l) => {
                pi * (scene_radius as f64).powi(2) * l.band_radiant_exitance(range)
            }
            Light::Beam(l) => band(&l.power),
            Light::Projector(l) => l.power(band(&l.spectrum)),
            Light::Goniometric(l) => l.power(band(&l.spectrum)),
            Light::GoniometricMap(l) => l.power(band(&l.spectrum)),
        }
    }
}

/// The midpoints of 10-nm steps over `range` (nm) and, at each, illuminant(λ)·g(λ)·Δλ: the
/// spectral quadrature the image lights' integrals share.
pub(crate) fn spectral_steps(
    range: WavelengthRange,
    illuminant: &Spectrum,
    g: &impl Fn(f32) -> f64,
) -> (Vec<f32>, Vec<f64>) {
    let steps = ((range.max_nm - range.min_nm) / 10.0).ceil().max(1.0) as usize;
    let dl = (range.max_nm - range.min_nm) as f64 / steps as f64;
    let lambdas: Vec<f32> = (0..steps)
        .map(|k| range.min_nm + (k as f32 + 0.5) * dl as f32)
        .collect();
    let shape = lambdas
        .iter()
        .map(|&l| illuminant.eval(l) as f64 * g(l) * dl)
        .collect();
    (lambdas, shape)
}
