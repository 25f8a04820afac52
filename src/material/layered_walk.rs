//! The random walks of [`super::layered`]'s slab (pbrt-v4's `LayeredBxDF::f`, `Sample_f` and
//! `PDF`, `src/pbrt/bxdfs.h`; Guo et al. 2018), step for step, with the one deliberate
//! difference argued in `layered.rs` (the exit's MIS weight, `Slab::exit_pdf`).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::layer_interfaces::{Events, Scatter};
use super::layered::Slab;
use super::{BsdfSample, TransportMode};
use crate::sampling::power_heuristic;
use crate::spectrum::SampledSpectrum;

/// PCG32 (O'Neill 2014), seeded by hashing a call's arguments.
pub(super) struct Pcg(u64, u64);

impl Pcg {
    pub(super) fn new(a: u64, b: u64) -> Self {
        let mut r = Pcg(0, (splitmix(b) << 1) | 1);
        r.next();
        r.0 = r.0.wrapping_add(splitmix(a));
        r.next();
        r
    }
    fn next(&mut self) -> u32 {
        let old = self.0;
        self.0 = old
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(self.1);
        let x = (((old >> 18) ^ old) >> 27) as u32;
        x.rotate_right((old >> 59) as u32)
    }
    /// Uniform in [0, 1).
    pub(super) fn u(&mut self) -> f32 {
        (self.next() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
    pub(super) fn u2(&mut self) -> Vec2 {
        Vec2::new(self.u(), self.u())
    }
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A hash of a direction's bits, to seed [`Pcg`].
pub(super) fn hash_vec(v: Vec3) -> u64 {
    let [x, y, z] = v.to_array().map(|c| c.to_bits() as u64);
    splitmix(x ^ splitmix(y ^ splitmix(z)))
}

/// The slab's transmittance over height `dz` along `w`: exp(−|dz/cos θ|).
pub(super) fn tr(dz: f32, w: Vec3) -> f32 {
    if dz.abs() <= f32::MIN_POSITIVE {
        1.0
    } else {
        (-(dz / w.z).abs()).exp()
    }
}

/// Whether an interface sample is usable (pbrt-v4: non-zero f and pdf, not grazing).
pub(super) fn usable<const N: usize>(s: &Option<Scatter<N>>) -> Option<Scatter<N>> {
    s.filter(|s| !s.f.is_zero() && s.pdf > 0.0 && s.wi.z != 0.0)
}

pub(super) fn adjoint(mode: TransportMode) -> TransportMode {
    match mode {
        TransportMode::Radiance => TransportMode::Importance,
        TransportMode::Importance => TransportMode::Radiance,
    }
}

impl<const N: usize> Slab<N> {
    /// The MIS competitor of a walk leaving the slab along −`w` toward `wi`: the density of
    /// sampling −`w` from `wi` through the coating, or pbrt-v4's (module docs).
    fn exit_pdf(&self, w: Vec3, wi: Vec3) -> f32 {
        if self.pbrt_exit_weight {
            self.top.pdf(-w, wi, Events::Transmission)
        } else {
            self.top.pdf(wi, -w, Events::Transmission)
        }
    }

    /// The estimate of f(wo, wi) (pbrt-v4's `LayeredBxDF::f`, entered from the top).
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> SampledSpectrum<N> {
        let (wo, wi) = if wo.z < 0.0 { (-wo, -wi) } else { (wo, wi) };
        // the bases reflect only: nothing crosses the slab
        if wo.z * wi.z <= 0.0 {
            return SampledSpectrum::zero();
        }
        let (top, th) = (&self.top, self.thickness);
        let mut f = top.f::<N>(wo, wi, mode) * self.n_samples as f32;
        let mut rng = Pcg::new(hash_vec(wo), hash_vec(wi));
        let exit_specular = top.is_specular();
        let clear = self.albedo.is_zero();
        for _ in 0..self.n_samples {
            // transmission into the slab along wo, and toward wi (the adjoint direction)
            let (uc, u) = (rng.u(), rng.u2());
            let Some(wos) = usable(&top.sample(wo, uc, u, mode, Events::Transmission)) else {
                continue;
            };
            let (uc, u) = (rng.u(), rng.u2());
            let Some(wis) = usable(&top.sample(wi, uc, u, adjoint(mode), Events::Transmission))
            else {
                continue;
            };
            let mut beta = wos.f * (wos.wi.z.abs() / wos.pdf);
            let (mut z, mut w) = (th, wos.wi);
            for depth in 0..self.max_depth {
                // Russian roulette (pbrt-v4's thresholds)
                if depth > 3 && beta.max_component() < 0.25 {
                    let q = (1.0 - beta.max_component()).max(0.0);
                    if rng.u() < q {
                        break;
                    }
                    beta /= 1.0 - q;
                }
                if clear {
                    z = if z == th { 0.0 } else { th };
                    beta *= tr(th, w);
                } else {
                    let dz = -(1.0 - rng.u()).ln() * w.z.abs();
                    let zp = if w.z > 0.0 { z + dz } else { z - dz };
                    if zp == z {
                        continue;
                    }
                    if 0.0 < zp && zp < th {
                        // scattering in the slab: next event out through the top along wis
                        let p = self.phase.eval(-w, -wis.wi);
                        let wt = if exit_specular {
                            1.0
                        } else {
                            power_heuristic(1.0, wis.pdf, 1.0, p)
                        };
                        f += beta * self.albedo * wis.f * (p * wt * tr(zp - th, wis.wi) / wis.pdf);
                        let ps = self.phase.sample(-w, rng.u2());
                        if ps.pdf == 0.0 || ps.wi.z == 0.0 {
                            continue;
                        }
                        beta *= self.albedo * (self.phase.eval(-w, ps.wi) / ps.pdf);
                        (w, z) = (ps.wi, zp);
                        if z < th && w.z > 0.0 && !exit_specular {
                            let f_exit = top.f::<N>(-w, wi, mode);
                            if !f_exit.is_zero() {
                                // the first strategy's density of this direction (pbrt-v4:
                                // top.pdf(-w, wi), see the module's docs)
                                let exit_pdf = self.exit_pdf(w, wi);
                                let wt = power_heuristic(1.0, ps.pdf, 1.0, exit_pdf);
                                f += beta * f_exit * (tr(zp - th, ps.wi) * wt);
                            }
                        }
                        continue;
                    }
                    z = zp.clamp(0.0, th);
                }
                if z == th {
                    // reflection back into the slab at the top
                    let (uc, u) = (rng.u(), rng.u2());
                    let Some(bs) = usable(&top.sample(-w, uc, u, mode, Events::Reflection)) else {
                        break;
                    };
                    beta *= bs.f * (bs.wi.z.abs() / bs.pdf);
                    w = bs.wi;
                } else {
                    let bottom = &self.bottom;
                    if !bottom.is_specular() {
                        // next event at the base, out through the top along wis
                        let wt = if exit_specular {
                            1.0
                        } else {
                            power_heuristic(1.0, wis.pdf, 1.0, bottom.pdf(-w, -wis.wi, Events::All))
                        };
                        f += beta
                            * bottom.f(-w, -wis.wi)
                            * wis.f
                            * (wis.wi.z.abs() * wt * tr(th, wis.wi) / wis.pdf);
                    }
                    let _uc = rng.u();
                    let Some(bs) = usable(&bottom.sample(-w, rng.u2(), Events::Reflection)) else {
                        break;
                    };
                    beta *= bs.f * (bs.wi.z.abs() / bs.pdf);
                    w = bs.wi;
                    if !exit_specular {
                        // next event along the base's sample, out through the top toward wi
                        let f_exit = top.f::<N>(-w, wi, mode);
                        if !f_exit.is_zero() {
                            let wt = if bottom.is_specular() {
                                1.0
                            } else {
                                // as above: the density of sampling -w from wi
                                let exit_pdf = self.exit_pdf(w, wi);
                                power_heuristic(1.0, bs.pdf, 1.0, exit_pdf)
                            };
                            f += beta * f_exit * (tr(th, bs.wi) * wt);
                        }
                    }
                }
            }
        }
        f * (1.0 / self.n_samples as f32)
    }

    /// Samples wi by a walk through the slab (pbrt-v4's `LayeredBxDF::Sample_f`); see the
    /// module's docs for the returned f and pdf.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<N>> {
        let flip = wo.z < 0.0;
        let wo_l = if flip { -wo } else { wo };
        let (top, th) = (&self.top, self.thickness);
        let bs = usable(&top.sample::<N>(wo_l, uc, u, mode, Events::All))?;
        let out = |f: SampledSpectrum<N>, wi: Vec3, pdf: f32, specular: bool| {
            let wi = if flip { -wi } else { wi };
            // a walk's f/pdf is its weight; its pdf for MIS is the estimate (pbrt-v4's
            // `pdfIsProportional`)
            let (f, pdf) = if specular {
                (f, pdf)
            } else {
                let est = self.pdf(wo, wi, mode);
                (f * (est / pdf), est)
            };
            Some(BsdfSample {
                f,
                wi,
                pdf,
                specular,
                transmission: false,
                dispersive: self.dispersive,
                eta: 1.0,
            })
        };
        if !bs.transmission {
            return out(bs.f, bs.wi, bs.pdf, bs.specular);
        }
        let mut rng = Pcg::new(
            hash_vec(wo_l),
            ((uc.to_bits() as u64) << 32) ^ hash_vec(u.extend(0.0)),
        );
        let (mut f, mut pdf) = (bs.f * bs.wi.z.abs(), bs.pdf);
        let (mut z, mut w, mut specular) = (th, bs.wi, bs.specular);
        let clear = self.albedo.is_zero();
        for depth in 0..self.max_depth {
            let rr = f.max_component() / pdf;
            if depth > 3 && rr < 0.25 {
                let q = (1.0 - rr).max(0.0);
                if rng.u() < q {
                    return None;
                }
                pdf *= 1.0 - q;
            }
            if w.z == 0.0 {
                return None;
            }
            if clear {
                z = if z == th { 0.0 } else { th };
                f *= tr(th, w);
            } else {
                let dz = -(1.0 - rng.u()).ln() * w.z.abs();
                let zp = if w.z > 0.0 { z + dz } else { z - dz };
                if zp == z {
                    return None;
                }
                if 0.0 < zp && zp < th {
                    let ps = self.phase.sample(-w, rng.u2());
                    if ps.pdf == 0.0 || ps.wi.z == 0.0 {
                        return None;
                    }
                    f *= self.albedo * self.phase.eval(-w, ps.wi);
                    pdf *= ps.pdf;
                    specular = false;
                    (w, z) = (ps.wi, zp);
                    continue;
                }
                z = zp.clamp(0.0, th);
            }
            let (uc, u) = (rng.u(), rng.u2());
            let s = if z == 0.0 {
                self.bottom.sample(-w, u, Events::All)
            } else {
                top.sample(-w, uc, u, mode, Events::All)
            };
            let s = usable(&s)?;
            f *= s.f;
            pdf *= s.pdf;
            specular &= s.specular;
            w = s.wi;
            if s.transmission {
                return out(f, w, pdf, specular);
            }
            f *= s.wi.z.abs();
        }
        None
    }

    /// The estimate of the sampling density of wi in sr⁻¹ (pbrt-v4's `LayeredBxDF::PDF`).
    pub fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        let (wo, wi) = if wo.z < 0.0 { (-wo, -wi) } else { (wo, wi) };
        let mut rng = Pcg::new(hash_vec(wi), hash_vec(wo));
        let (top, bottom) = (&self.top, &self.bottom);
        let mut sum = 0.0;
        if wo.z * wi.z > 0.0 {
            sum += self.n_samples as f32 * top.pdf(wo, wi, Events::Reflection);
            for _ in 0..self.n_samples {
                // the TRT term: in through the top, off the base, out through the top
                let (uc, u) = (rng.u(), rng.u2());
                let wos = usable(&top.sample::<N>(wo, uc, u, mode, Events::Transmission));
                let (uc, u) = (rng.u(), rng.u2());
                let wis = usable(&top.sample::<N>(wi, uc, u, adjoint(mode), Events::Transmission));
                let (Some(wos), Some(wis)) = (wos, wis) else {
                    continue;
                };
                if top.is_specular() {
                    sum += bottom.pdf(-wos.wi, -wis.wi, Events::All);
                    continue;
                }
                let _uc = rng.u();
                let Some(rs) = usable(&bottom.sample(-wos.wi, rng.u2(), Events::All)) else {
                    continue;
                };
                if bottom.is_specular() {
                    sum += top.pdf(-rs.wi, wi, Events::All);
                } else {
                    let r_pdf = bottom.pdf(-wos.wi, -wis.wi, Events::All);
                    sum += power_heuristic(1.0, wis.pdf, 1.0, r_pdf) * r_pdf;
                    let t_pdf = top.pdf(-rs.wi, wi, Events::All);
                    sum += power_heuristic(1.0, rs.pdf, 1.0, t_pdf) * t_pdf;
                }
            }
        }
        0.1 / (4.0 * PI) + 0.9 * sum / self.n_samples as f32
    }
}
