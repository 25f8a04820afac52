//! A heterogeneous medium: extinction σt(p, λ) = `scale` × a volume, single-scattering albedo a
//! second volume, inside the box of the extinction volume's frame (outside it the medium is
//! clear, as Mitsuba 3's `heterogeneous` bounds its sampling by that box).
//!
//! Free flights are sampled by delta tracking against a majorant σ̄ ≥ σt, the same at every
//! wavelength (Woodcock et al. 1965; the null-scattering formulation of Miller, Georgiev and
//! Jarosz 2019, pbrt-v4 §14.1–14.2): tentative collisions at rate σ̄, each real with
//! probability σt(λ₀)/σ̄ and otherwise null. Shadow rays estimate transmittance by ratio
//! tracking (Novák et al. 2014), a product of σn/σ̄ over tentative collisions, unbiased.

use glam::{Mat4, Vec3};

use super::PhaseFunction;
use super::grid::Volume;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// A heterogeneous medium.
#[derive(Clone, Debug)]
pub struct Heterogeneous {
    /// Extinction over `scale`, dimensionless.
    pub density: Volume,
    /// Single-scattering albedo σs/σt, dimensionless (a Mitsuba scene may exceed 1).
    pub albedo: Volume,
    /// m⁻¹: σt = scale × density.
    pub scale: f32,
    pub phase: PhaseFunction,
    /// World space (m) to the frame whose unit cube bounds the medium.
    pub to_local: Mat4,
    /// The majorant σ̄, m⁻¹: at least σt anywhere, at any wavelength.
    pub majorant: f32,
}

/// A free flight through a medium as factors on the path's state (see the integrator's
/// `Path`): `beta` on the throughput, `r_u` on the walk's density ratios, `r_l` on next-event
/// estimation's, each per wavelength; `t` (m) is where it scatters, None when it passes.
#[derive(Clone, Copy, Debug)]
pub struct Walk<const N: usize> {
    pub t: Option<f32>,
    pub beta: SampledSpectrum<N>,
    pub r_u: SampledSpectrum<N>,
    pub r_l: SampledSpectrum<N>,
    /// The medium's emission collected on the way, as a value and, per wavelength, the
    /// density of the event that collected it had that wavelength been the hero (both
    /// relative to the path before this flight): the path adds β·value / avg(r_u·density).
    /// Next-event estimation does not sample media, so no other technique weighs in.
    pub emitted: Option<(SampledSpectrum<N>, SampledSpectrum<N>)>,
}

impl Heterogeneous {
    /// The part [t0, t1] of the ray `o + t d` (t in [0, `t_max`]) inside the medium's box,
    /// or None.
    pub fn clip(&self, o: Vec3, d: Vec3, t_max: f32) -> Option<(f32, f32)> {
        let lo = self.to_local.transform_point3(o);
        let ld = self.to_local.transform_vector3(d);
        let (mut t0, mut t1) = (0.0f32, t_max);
        for a in 0..3 {
            let inv = 1.0 / ld[a];
            let (mut near, mut far) = ((0.0 - lo[a]) * inv, (1.0 - lo[a]) * inv);
            if near > far {
                std::mem::swap(&mut near, &mut far);
            }
            // a ray parallel to a slab and outside it gives NaN or an empty interval
            if near.is_nan() || far.is_nan() {
                if lo[a] < 0.0 || lo[a] > 1.0 {
                    return None;
                }
                continue;
            }
            t0 = t0.max(near);
            t1 = t1.min(far);
        }
        (t0 < t1).then_some((t0, t1))
    }

    /// σt at the world point `p`, m⁻¹ (0 outside the medium's box). The albedo is looked up
    /// only where a collision is real.
    #[inline]
    pub fn sigma_t<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let local = self.to_local.transform_point3(p);
        let inside = local.cmpge(Vec3::ZERO).all() && local.cmple(Vec3::ONE).all();
        if !inside {
            return SampledSpectrum::zero();
        }
        self.density.eval(p, w) * self.scale
    }

    /// Visits the tentative collisions of the majorant along `o + t d` within the medium's box
    /// and [0, `t_max`] (rate σ̄, numbers from `u`), with σt there, until `visit` returns
    /// false or the segment ends.
    fn track<const N: usize>(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        w: &SampledWavelengths<N>,
        u: &mut impl FnMut() -> f32,
        mut visit: impl FnMut(f32, SampledSpectrum<N>, &mut dyn FnMut() -> f32) -> bool,
    ) {
        let Some((t0, t1)) = self.clip(o, d, t_max) else {
            return;
        };
        if self.majorant <= 0.0 {
            return;
        }
        let mut t = t0;
        loop {
            t += -(1.0 - u()).max(f32::MIN_POSITIVE).ln() / self.majorant;
            if t >= t1 {
                return;
            }
            if !visit(t, self.sigma_t(o + d * t, w), u) {
                return;
            }
        }
    }

    /// Delta tracking along `o + t d` up to `t_max` with uniform numbers from `u`.
    pub fn walk<const N: usize>(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        w: &SampledWavelengths<N>,
        u: &mut impl FnMut() -> f32,
    ) -> Walk<N> {
        let one = SampledSpectrum::splat(1.0);
        let mut walk = Walk {
            t: None,
            beta: one,
            r_u: one,
            r_l: one,
            emitted: None,
        };
        let majorant = self.majorant;
        self.track(o, d, t_max, w, u, |t, sigma_t, u| {
            // a real collision with probability σt(λ₀)/σ̄: density T̄·σt(λ₀) per metre, value
            // T̄·σs (T̄ the majorant's transmittance, the same for every wavelength)
            if u() * majorant < sigma_t[0] {
                walk.t = Some(t);
                walk.beta *= sigma_t * self.albedo.eval(o + d * t, w) / sigma_t[0];
                walk.r_u *= sigma_t / sigma_t[0];
                return false;
            }
            // null: density T̄·σn(λ₀), value T̄·σn; next-event estimation samples the same
            // point with density T̄·σ̄
            let sigma_n = (SampledSpectrum::splat(majorant) - sigma_t).map(|v| v.max(0.0));
            if sigma_n[0] <= 0.0 {
                walk.beta = SampledSpectrum::zero();
                return false;
            }
            walk.beta *= sigma_n / sigma_n[0];
            walk.r_u *= sigma_n / sigma_n[0];
            walk.r_l *= majorant / sigma_n[0];
            true
        });
        walk
    }

    /// Ratio tracking along `o + t d` over [0, `t_max`]: an unbiased estimate of the
    /// transmittance at each wavelength, from uniform numbers `u`.
    pub fn transmittance<const N: usize>(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        w: &SampledWavelengths<N>,
        u: &mut impl FnMut() -> f32,
    ) -> SampledSpectrum<N> {
        let mut tr = SampledSpectrum::splat(1.0);
        let majorant = self.majorant;
        self.track(o, d, t_max, w, u, |_, sigma_t, _| {
            tr *= (SampledSpectrum::splat(majorant) - sigma_t).map(|v| (v / majorant).max(0.0));
            !tr.is_zero()
        });
        tr
    }
}
