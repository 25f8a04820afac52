//! Polarised bidirectional path tracing (issue 28): the Stokes–Mueller factor of each
//! strategy, beside its scalar contribution.
//!
//! The subpaths are walked exactly as in an unpolarised render (the same samples, densities,
//! scalar throughputs and MIS weights; Jarabo and Arellano 2018, §5, show that polarisation
//! changes only the path's throughput, a matrix product along it). After the walks, [`Pol`]
//! records each subpath's *normalised* polarisation (every scattering event's Mueller matrix
//! P = M/M₀₀, `material::polarised`, with the physical directions: light travels from the
//! light subpath's past toward the camera subpath's past):
//!
//! - camera vertex i: the product P₁·P₂·…·P_{i−1} of the camera subpath's events before it,
//!   which maps the Stokes vector of the light that vertex i sends toward vertex i − 1 (in the
//!   implicit basis of its direction of travel) to the one reaching the lens; the identity at
//!   the lens and the first hit;
//! - light vertex i: the Stokes vector of the light arriving there, P_{i−1}·…·P₁ applied to
//!   unpolarised emission (1, 0, 0, 0).
//!
//! A strategy's Stokes vector at the lens is its scalar contribution times the camera
//! product at its camera end, times the connection's own events (at either end, with the
//! connecting direction), times the light end's Stokes vector ([`Pol::factor`]); emitters
//! are unpolarised. Every matrix is expressed in the implicit world bases of its beams
//! (`polarisation::stokes_basis`), so the products need no rotations; the caller rotates the
//! result into the camera's frame.

use glam::Vec3;

use super::super::Integrator;
use super::super::carrier::{Carrier, Polarised, scatter_stokes};
use super::vertex::Vertex;
use crate::polarisation::{Mueller, Stokes};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// The normalised polarisation of one sample's two subpaths (see the module doc), kept between
/// samples so that no sample allocates.
#[derive(Default)]
pub(super) struct Pol<const N: usize> {
    camera: Vec<[Mueller; N]>,
    light: Vec<[Stokes; N]>,
}

/// The normalised matrix of the event at surface vertex `v` for light arriving from world
/// direction `from` (pointing away from `v`, toward where the light comes from) and leaving
/// toward `to`, applied to `st`; `st` unchanged where `v` scatters nothing (no shading).
fn event<const N: usize>(
    v: &Vertex<'_, N>,
    from: Vec3,
    to: Vec3,
    w: &SampledWavelengths<N>,
    st: &[Stokes; N],
) -> [Stokes; N] {
    match &v.shading {
        Some(sh) => scatter_stokes(sh, (sh.frame.to_local(to), sh.frame.to_local(from)), w, st),
        None => *st,
    }
}

/// The product of `m` and the normalised matrix of the event at `v` (as [`event`]), per
/// wavelength: the camera path's [`Carrier::scattered`] with a scalar weight of 1.
fn then_event<const N: usize>(
    m: &[Mueller; N],
    v: &Vertex<'_, N>,
    from: Vec3,
    to: Vec3,
    w: &SampledWavelengths<N>,
) -> [Mueller; N] {
    let Some(sh) = &v.shading else {
        return *m;
    };
    let dirs = (sh.frame.to_local(to), sh.frame.to_local(from));
    Polarised(*m)
        .scattered(sh, dirs, w, SampledSpectrum::splat(1.0))
        .0
}

impl<const N: usize> Pol<N> {
    /// Records the polarisation of the subpaths `camera` and `light` at the wavelengths `w`
    /// (a dispersive event's matrices are the hero's: the strategies through it keep the hero
    /// alone).
    pub fn build(
        &mut self,
        it: &Integrator<'_>,
        camera: &[Vertex<'_, N>],
        light: &[Vertex<'_, N>],
        w: &SampledWavelengths<N>,
    ) {
        self.camera.clear();
        let mut m = [Mueller::IDENTITY; N];
        for (i, v) in camera.iter().enumerate() {
            self.camera.push(m);
            if i >= 1 && i + 1 < camera.len() {
                m = then_event(&m, v, v.dir_to(it, &camera[i + 1]), v.wo, w);
            }
        }
        self.light.clear();
        let mut st = [Stokes::unpolarised(1.0); N];
        for (i, v) in light.iter().enumerate() {
            self.light.push(st);
            if i >= 1 && i + 1 < light.len() {
                st = event(v, v.wo, v.dir_to(it, &light[i + 1]), w, &st);
            }
        }
    }

    /// The normalised Stokes vector per wavelength that strategy (s, t) delivers to the lens
    /// (to be scaled by its scalar contribution), in the implicit basis of its direction of
    /// travel there, and that direction (world, unit; from the scene toward the lens).
    /// `sampled` is the vertex an s = 1 or t = 1 strategy sampled; `ray_d` the camera ray's
    /// direction.
    #[allow(clippy::too_many_arguments)]
    pub fn factor(
        &self,
        it: &Integrator<'_>,
        light: &[Vertex<'_, N>],
        camera: &[Vertex<'_, N>],
        (s, t): (usize, usize),
        sampled: Option<&Vertex<'_, N>>,
        ray_d: Vec3,
        w: &SampledWavelengths<N>,
    ) -> ([Stokes; N], Vec3) {
        let unpolarised = [Stokes::unpolarised(1.0); N];
        if t == 1 {
            // a light vertex seen through the lens point `sampled`
            let (qs, lens) = (&light[s - 1], sampled.unwrap_or(&camera[0]));
            let to = qs.dir_to(it, lens);
            return (event(qs, qs.wo, to, w, &self.light[s - 1]), to);
        }
        let pt = &camera[t - 1];
        let arriving = match (s, sampled) {
            // the camera subpath ends on an emitter (or the lights at infinity)
            (0, _) => unpolarised,
            // next-event estimation: unpolarised light from the sampled light vertex
            (1, Some(v)) => event(pt, pt.dir_to(it, v), pt.wo, w, &unpolarised),
            _ => {
                let qs = &light[s - 1];
                let d = pt.dir_to(it, qs);
                let at_qs = event(qs, qs.wo, -d, w, &self.light[s - 1]);
                event(pt, d, pt.wo, w, &at_qs)
            }
        };
        let m = &self.camera[t - 1];
        (std::array::from_fn(|j| m[j] * arriving[j]), -ray_d)
    }
}
