//! What a scattering event does to polarisation: the Mueller matrix of a [`Bsdf`] for a pair
//! of directions, for the polarised path tracer (`integrator::stokes`).
//!
//! Design: the polarised estimator keeps the unpolarised one's sampling and scalar weights
//! (f·|cos θ|/pdf per wavelength, from [`Bsdf::sample`] and [`Bsdf::eval_pdf`]) and multiplies
//! them by a *normalised* Mueller matrix P = M/M₀₀, whose (0, 0) entry is 1. For every
//! material M₀₀ is the reflectance or transmittance for unpolarised light that the scalar
//! weight already holds (Fresnel's (R_s + R_p)/2, a polariser's ½), so f·P is the material's
//! Mueller BSDF and one code path samples both modes: a scene without polarising materials
//! renders S0 with the very samples of the unpolarised render.
//!
//! Frames (Mitsuba 3's conventions, `polarisation`'s module doc): light arrives travelling
//! along −`wi` and leaves along `wo` (both local, pointing away from the surface). Each P is
//! returned re-expressed in the *implicit* world bases of its two beams,
//! [`stokes_basis`]`(−wi_world)` on input and `stokes_basis(wo_world)` on output, so that a
//! path's Mueller matrices chain by plain products.
//!
//! Models: Fresnel reflection and transmission with their phases for smooth dielectrics (per
//! wavelength, so dispersion and the retardance of total internal reflection are kept) and
//! conductors (complex n(λ)); rough conductors and dielectrics the same Fresnel matrices at the
//! microfacet normal (the half vector), in the frame of the microfacet's plane of incidence
//! (Mitsuba's `roughconductor` and `roughdielectric`); `polarizer` and `retarder` as Mitsuba's.
//! Diffuse-like lobes (Lambert, Phong, plastic, a blend) depolarise; light passing straight
//! through (`null`, a mask's opening, a thin sheet) keeps its state. A thin sheet's reflection
//! takes a single interface's normalised Fresnel matrix (its multiple reflections' partial
//! polarisation is not modelled). Mitsuba's `pplastic` sums a specular and a diffuse matrix
//! ([`pplastic`]).

use glam::Vec3;

use super::plastic::g1;
use super::{Bsdf, Material, UNPERTURBED, coated};
use crate::geometry::Frame;
use crate::polarisation::{Complex, Mueller, fresnel, rotate_stokes_basis, stokes_basis};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// The normalised Mueller matrix of a scattering event (see the module doc).
#[derive(Clone, Copy, Debug)]
pub enum Polarising<const N: usize> {
    /// The light leaves unpolarised: only P₀₀ = 1 (diffuse-like lobes).
    Depolarise,
    /// The light keeps its state: P is the identity (straight through).
    Keep,
    /// P per wavelength, P₀₀ = 1, in the implicit world bases of the two beams.
    Matrix([Mueller; N]),
}

impl<const N: usize> Bsdf<'_, N> {
    /// The normalised Mueller matrix (see the module doc) for light arriving along −`wi` and
    /// leaving along `wo` (local to `frame`, the shading frame), at the wavelengths `w`. For a
    /// dispersive material only the hero's matrix is meaningful (the others are copies).
    pub fn mueller(
        &self,
        frame: &Frame,
        wo: Vec3,
        wi: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Polarising<N> {
        of(
            self.material,
            frame,
            &self.perturb,
            (wo, wi),
            self.albedo,
            w,
        )
    }
}

/// A perturbed material's nested one in the perturbed frame (`perturb`, local to `frame`).
fn perturbed<const N: usize>(
    inner: &Material,
    frame: &Frame,
    perturb: &Frame,
    (wo, wi): (Vec3, Vec3),
    rho: SampledSpectrum<N>,
    w: &SampledWavelengths<N>,
) -> Polarising<N> {
    let f = Frame {
        s: frame.to_world(perturb.s),
        t: frame.to_world(perturb.t),
        n: frame.to_world(perturb.n),
    };
    let dirs = (perturb.to_local(wo), perturb.to_local(wi));
    of(inner, &f, &UNPERTURBED, dirs, rho, w)
}

/// [`Bsdf::mueller`] of material `m`; `perturb` is a normal or bump map's frame (local to
/// `frame`) for the perturbed material `m` holds; `rho` the diffuse reflectance at the hit.
fn of<const N: usize>(
    m: &Material,
    frame: &Frame,
    perturb: &Frame,
    (wo, wi): (Vec3, Vec3),
    rho: SampledSpectrum<N>,
    w: &SampledWavelengths<N>,
) -> Polarising<N> {
    let straight = (wo + wi).length_squared() < 1e-10;
    match m {
        Material::Diffuse(_)
        | Material::Phong(_)
        | Material::Plastic(_)
        | Material::Blend(_)
        | Material::Principled(_)
        | Material::Hair(_)
        | Material::Layered(_)
        | Material::DiffuseTransmission(_)
        | Material::Measured(_) => Polarising::Depolarise,
        Material::Null => Polarising::Keep,
        Material::Mask(_) | Material::ThinDielectric { .. } if straight => Polarising::Keep,
        Material::Mask(k) => of(&k.inner, frame, perturb, (wo, wi), rho, w),
        Material::Textured(k) => of(&k.inner, frame, perturb, (wo, wi), rho, w),
        Material::NormalMap(k) => perturbed(&k.inner, frame, perturb, (wo, wi), rho, w),
        Material::BumpMap(k) => perturbed(&k.inner, frame, perturb, (wo, wi), rho, w),
        Material::PPlastic(p) => pplastic(p, frame, (wo, wi), rho),
        Material::MeasuredPolarized(m) => m.mueller(frame, (wo, wi), w),
        Material::ThinDielectric { eta } => {
            let (e, c) = side(wi.z, *eta);
            let m = fresnel::reflection(c, Complex::new(e, 0.0));
            interface(frame, Vec3::Z, wo, wi, |_| m, false).with(w)
        }
        Material::ThinFilm(f) => coated::stack(frame, (wo, wi), w, false, |l| {
            coated::film(&f.layers, f.ext_ior, wi.z, l)
        }),
        Material::Dielectric(d) => {
            let reflect = wi.z * wo.z > 0.0;
            if let Some(c) = &d.coating {
                let resp = |l| coated::on_dielectric(c, d.ext_ior, &d.int_ior, wi.z, l);
                return coated::stack(frame, (wo, wi), w, d.int_ior.is_dispersive(), resp);
            }
            let dispersive = d.int_ior.is_dispersive();
            interface(
                frame,
                Vec3::Z,
                wo,
                wi,
                |l| dielectric(wi.z, d.eta(l), reflect),
                dispersive,
            )
            .with(w)
        }
        Material::RoughDielectric(d) => {
            let reflect = wi.z * wo.z > 0.0;
            let dispersive = d.int_ior.is_dispersive();
            let eta = |l: f32| d.int_ior.eval(l) / d.ext_ior;
            // the microfacet normal: the half vector, generalised for refraction by the hero's
            // index (Walter et al. 2007, eq. 16); its sign does not matter
            let e0 = eta(w.lambda[0]);
            let (ni, no) = if wi.z > 0.0 { (1.0, e0) } else { (e0, 1.0) };
            let h = if reflect {
                wi + wo
            } else {
                -(wi * ni + wo * no)
            };
            let Some(h) = h.try_normalize() else {
                return Polarising::Depolarise;
            };
            let h = if h.z < 0.0 { -h } else { h };
            let cos = wi.dot(h);
            interface(
                frame,
                h,
                wo,
                wi,
                |l| dielectric(cos, eta(l), reflect),
                dispersive,
            )
            .with(w)
        }
        Material::Conductor(c) => {
            let eta = |l: f32| conductor_eta(&c.ior, c.ext_ior, l);
            let cos = wi.z;
            let m = |l: f32| match &c.coating {
                Some(k) => {
                    coated::reflection_mueller(&coated::on_conductor(k, c.ext_ior, &c.ior, cos, l))
                }
                None => fresnel::reflection(cos, eta(l)),
            };
            interface(frame, Vec3::Z, wo, wi, m, false).with(w)
        }
        Material::RoughConductor(c) => {
            let eta = |l: f32| conductor_eta(&c.ior, c.ext_ior, l);
            let Some(h) = (wi + wo).try_normalize() else {
                return Polarising::Depolarise;
            };
            let cos = wi.dot(h);
            let m = |l: f32| match &c.coating {
                Some(k) => {
                    coated::reflection_mueller(&coated::on_conductor(k, c.ext_ior, &c.ior, cos, l))
                }
                None => fresnel::reflection(cos, eta(l)),
            };
            interface(frame, h, wo, wi, m, false).with(w)
        }
        Material::Element(e) => {
            let (m, basis) = e.mueller(wo);
            let Some(p) = normalised(m) else {
                return Polarising::Keep;
            };
            Polarising::Matrix([to_world(frame, &p, wo, wi, basis, basis); N])
        }
    }
}

/// A conductor's complex index n + ik at `l` nm relative to the outside's index `ext`.
fn conductor_eta(ior: &crate::spectrum::ior::ComplexIor, ext: f32, l: f32) -> Complex {
    let (n, k) = ior.eval(l);
    Complex::new(n / ext, k / ext)
}

/// Mitsuba's `pplastic` (see [`super::PPlastic`]): the specular lobe's Fresnel reflection about
/// the half vector, and the diffuse term's two transmissions (in at `wi`, out at `wo`'s
/// refracted direction) around a depolarising ρ/π, summed per wavelength and normalised.
fn pplastic<const N: usize>(
    p: &super::PPlastic,
    frame: &Frame,
    (wo, wi): (Vec3, Vec3),
    rho: SampledSpectrum<N>,
) -> Polarising<N> {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Polarising::Depolarise;
    }
    // the specular lobe's beams share the s axis about h; the diffuse term's two beams are
    // unrelated, each with its own plane about the normal (a fixed axis near the pole)
    let own = |n: Vec3, v: Vec3| {
        let c = n.cross(v);
        if c.length_squared() > 1e-8 {
            c.normalize()
        } else {
            Frame::from_normal(n).s
        }
    };
    // the specular lobe: its scalar value times Fresnel's matrix at the half vector
    let spec = match (wo + wi).try_normalize() {
        Some(h) if p.specular > 0.0 => {
            let g = g1(&p.distribution, wo, h) * g1(&p.distribution, wi, h);
            let value = p.specular * p.distribution.d(h) * g / (4.0 * wo.z * wi.z);
            let m = fresnel::reflection(wi.dot(h), Complex::new(p.eta, 0.0)).scale(value);
            let a = s_axis(h, wi, wo);
            to_world(frame, &m, wo, wi, a, a)
        }
        _ => Mueller([[0.0; 4]; 4]),
    };
    // the diffuse term per unit ρ: out of the surface (from inside at wo's refracted cosine)
    // after a depolarising scattering after the way in
    let t_in = fresnel::transmission(wi.z, p.eta);
    let cos_t = (1.0 - (1.0 - wo.z * wo.z) / (p.eta * p.eta))
        .max(0.0)
        .sqrt();
    let t_out = fresnel::transmission(cos_t, 1.0 / p.eta);
    let d = Mueller(std::array::from_fn(|r| {
        std::array::from_fn(|c| t_out.0[r][0] * t_in.0[0][c] * std::f32::consts::FRAC_1_PI)
    }));
    let diff = to_world(frame, &d, wo, wi, own(Vec3::Z, -wi), own(Vec3::Z, wo));
    Polarising::Matrix(std::array::from_fn(|j| {
        let mut m = spec;
        for (row, drow) in m.0.iter_mut().zip(diff.0) {
            for (v, dv) in row.iter_mut().zip(drow) {
                *v += rho[j] * dv;
            }
        }
        normalised(m).unwrap_or(Mueller::IDENTITY)
    }))
}

/// (η seen from the side light arrives from, |cos θᵢ|) for relative index `eta` (inside over
/// outside) and the signed cosine of the arriving light's side `cos` (> 0: outside).
#[inline]
fn side(cos: f32, eta: f32) -> (f32, f32) {
    if cos >= 0.0 {
        (eta, cos)
    } else {
        (1.0 / eta, -cos)
    }
}

/// The Fresnel matrix of a dielectric interface of relative index `eta` (inside over outside)
/// for light arriving at signed cosine `cos` (> 0: from outside): reflection or transmission.
fn dielectric(cos: f32, eta: f32, reflect: bool) -> Mueller {
    let (e, c) = side(cos, eta);
    if reflect {
        fresnel::reflection(c, Complex::new(e, 0.0))
    } else {
        fresnel::transmission(c, e)
    }
}

/// The unit vector perpendicular to the plane of `n` and the beams along −`wi` and `wo`,
/// from the better conditioned of n × wi and n × wo, or a fixed perpendicular to `n` when both
/// are near zero (incidence within 0.006° of the normal).
fn s_axis(n: Vec3, wi: Vec3, wo: Vec3) -> Vec3 {
    let (a, b) = (n.cross(-wi), n.cross(wo));
    let c = if a.length_squared() >= b.length_squared() {
        a
    } else {
        b
    };
    if c.length_squared() > 1e-8 {
        c.normalize()
    } else {
        Frame::from_normal(n).s
    }
}

/// An interface's matrices before they are put per wavelength: `m(λ)` in the frame of the
/// plane of incidence about the (local) normal `n`, and whether they differ per wavelength
/// only at the hero (dispersive: the secondaries are terminated).
pub(super) struct Interface<'a, F: Fn(f32) -> Mueller> {
    frame: &'a Frame,
    s_in: Vec3,
    s_out: Vec3,
    wo: Vec3,
    wi: Vec3,
    m: F,
    hero_only: bool,
}

pub(super) fn interface<F: Fn(f32) -> Mueller>(
    frame: &Frame,
    n: Vec3,
    wo: Vec3,
    wi: Vec3,
    m: F,
    hero_only: bool,
) -> Interface<'_, F> {
    // the s basis, perpendicular to the plane of incidence, which the incident, reflected and
    // refracted beams share (Mitsuba computes `cross(n, -wo_hat)` and `cross(n, wi_hat)`,
    // parallel for a specular pair): one vector for both sides, so that near normal incidence,
    // where the cross products are rounding noise, the two cannot disagree and turn the light;
    // there (and at normal incidence) any common axis, the matrix being nearly invariant
    let s_in = s_axis(n, wi, wo);
    let s_out = s_in;
    Interface {
        frame,
        s_in,
        s_out,
        wo,
        wi,
        m,
        hero_only,
    }
}

impl<F: Fn(f32) -> Mueller> Interface<'_, F> {
    /// The normalised matrices at the wavelengths `w`, in world implicit bases.
    pub(super) fn with<const N: usize>(self, w: &SampledWavelengths<N>) -> Polarising<N> {
        let one = |l: f32| -> Mueller {
            match normalised((self.m)(l)) {
                Some(p) => to_world(self.frame, &p, self.wo, self.wi, self.s_in, self.s_out),
                None => Mueller::IDENTITY,
            }
        };
        let hero = one(w.lambda[0]);
        Polarising::Matrix(std::array::from_fn(|j| {
            if j == 0 || self.hero_only || w.pdf[j] == 0.0 {
                hero
            } else {
                one(w.lambda[j])
            }
        }))
    }
}

/// M/M₀₀, or None when M₀₀ is not positive or an element of the quotient exceeds 1 in
/// magnitude (the event carries nothing, or next to nothing: a transmission at the critical
/// angle, where M₀₀ underflows while the other elements do not vanish as fast).
#[inline]
fn normalised(m: Mueller) -> Option<Mueller> {
    let a = m.0[0][0];
    if !(a > 0.0 && a.is_finite()) {
        return None;
    }
    let p = m.scale(1.0 / a);
    // a physical Mueller matrix has |mᵢⱼ| ≤ m₀₀; a larger element is rounding
    p.0.iter().flatten().all(|v| v.abs() <= 1.001).then_some(p)
}

/// `p`, acting from the basis `s_in` of the beam along −`wi` to `s_out` of the beam along `wo`
/// (all local to `frame`), re-expressed in the implicit world bases of the two beams.
pub(super) fn to_world(
    frame: &Frame,
    p: &Mueller,
    wo: Vec3,
    wi: Vec3,
    s_in: Vec3,
    s_out: Vec3,
) -> Mueller {
    let f_in = frame.to_world(-wi).normalize();
    let f_out = frame.to_world(wo).normalize();
    let r_in = rotate_stokes_basis(f_in, frame.to_world(s_in), stokes_basis(f_in));
    let r_out = rotate_stokes_basis(f_out, frame.to_world(s_out), stokes_basis(f_out));
    r_out * *p * r_in.transpose()
}
