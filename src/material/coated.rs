//! Thin-film coatings on materials, and the free-standing film (a soap bubble): their
//! reflectance and transmittance per wavelength from the stack's characteristic matrix
//! ([`crate::optics::thin_film`]), unpolarised as the mean of s and p (the polarised renderer
//! takes both, `polarised.rs`).
//!
//! Indices are absolute: the coating's layers, the outside (`ext`, a real index) and the
//! substrate all in vacuum terms, so a coating in water (`exterior_ior` 1.333) interferes as it
//! does there.

use super::{BsdfSample, TransportMode};
use crate::optics::thin_film::{C64, Coating, StackResponse};
use crate::polarisation::Mueller;
use crate::spectrum::ior::{ComplexIor, Ior};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use glam::Vec3;

/// The stack's response at `l` nm for light arriving at signed cosine `cos` (> 0: from the
/// outside, index `ext`; < 0: from inside the dielectric substrate `int`).
pub fn on_dielectric(c: &Coating, ext: f32, int: &Ior, cos: f32, l: f32) -> StackResponse {
    let (n_int, l64) = (int.eval_f64(l as f64), l as f64);
    if cos >= 0.0 {
        c.response(l64, ext as f64, cos as f64, C64::real(n_int), false)
    } else {
        c.response(l64, n_int, -cos as f64, C64::real(ext as f64), true)
    }
}

/// The stack's response on a conductor of index n + ik at `l` nm, from the outside at cos θ.
pub fn on_conductor(c: &Coating, ext: f32, ior: &ComplexIor, cos: f32, l: f32) -> StackResponse {
    let (n, k) = ior.eval(l);
    c.response(
        l as f64,
        ext as f64,
        cos.clamp(0.0, 1.0) as f64,
        C64::new(n as f64, -(k as f64)),
        false,
    )
}

/// A free-standing film (the layers between two half-spaces of index `ext`), from either side.
pub fn film(c: &Coating, ext: f32, cos: f32, l: f32) -> StackResponse {
    let e = C64::real(ext as f64);
    c.response(l as f64, ext as f64, cos.abs() as f64, e, cos < 0.0)
}

/// The probability of choosing reflection over transmission: Σ R(λⱼ) / Σ (R + T)(λⱼ) over the
/// sampled wavelengths. A film's R swings between 0 and its maximum across the spectrum, so
/// the hero's own R/(R + T) (as the bare interface uses) would weigh the other wavelengths by
/// R(λⱼ)/R(λ₀), unbounded where the hero sits in a fringe's minimum; with the mean, each
/// weight is at most N times R + T. Both lobes share their direction across the wavelengths,
/// so any such probability is unbiased.
fn choice<const N: usize>(r: &[f32; N], t: &[f32; N]) -> f32 {
    let (sr, st) = (r.iter().sum::<f32>(), t.iter().sum::<f32>());
    if sr + st > 0.0 { sr / (sr + st) } else { 0.0 }
}

/// A free-standing coherent film in a medium of index `ext` (a soap bubble's wall): a delta
/// reflection and a delta transmission straight through, with the film's reflectance R(λ)
/// and transmittance T(λ) (interference between its faces; A = 1 − R − T if a layer absorbs).
/// Sampled by the wavelengths' mean R/(R + T) (`choice`); not dispersive in direction.
#[derive(Clone, Debug, PartialEq)]
pub struct ThinFilm {
    pub layers: Coating,
    /// Index of the medium on both sides.
    pub ext_ior: f32,
}

impl ThinFilm {
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        w: &SampledWavelengths<N>,
        uc: f32,
    ) -> Option<BsdfSample<N>> {
        let c = wo.z.abs();
        if c == 0.0 {
            return None;
        }
        let resp = w.lambda.map(|l| film(&self.layers, self.ext_ior, wo.z, l));
        let r = resp.map(|x| x.r_unpolarised() as f32);
        let t = resp.map(|x| x.t_unpolarised() as f32);
        let pr = choice(&r, &t);
        let (wi, f, pdf, transmission) = if uc < pr {
            (Vec3::new(-wo.x, -wo.y, wo.z), r, pr, false)
        } else {
            (-wo, t, 1.0 - pr, true)
        };
        if !(pdf > 0.0) {
            return None;
        }
        Some(BsdfSample {
            f: SampledSpectrum(f) * (1.0 / c),
            wi,
            pdf,
            specular: true,
            transmission,
            dispersive: false,
            eta: 1.0,
        })
    }
}

/// The smooth dielectric's sample with a coating: reflect with probability `choice`,
/// f = R(λ)/|cos θᵢ| or T(λ)/|cos θᵢ|/η'² (radiance), the refracted direction Snell's between
/// the outside and the substrate (a stack of parallel layers does not change it).
#[allow(clippy::too_many_arguments)]
pub(super) fn dielectric_sample<const N: usize>(
    c: &Coating,
    ext: f32,
    int: &Ior,
    wo: Vec3,
    w: &SampledWavelengths<N>,
    uc: f32,
    mode: TransportMode,
) -> Option<BsdfSample<N>> {
    let resp = w.lambda.map(|l| on_dielectric(c, ext, int, wo.z, l));
    let r = resp.map(|x| x.r_unpolarised() as f32);
    let t = resp.map(|x| x.t_unpolarised() as f32);
    let pr = choice(&r, &t);
    if uc < pr {
        let wi = Vec3::new(-wo.x, -wo.y, wo.z);
        return Some(BsdfSample {
            f: SampledSpectrum(r) * (1.0 / wi.z.abs()),
            wi,
            pdf: pr,
            specular: true,
            transmission: false,
            dispersive: false,
            eta: 1.0,
        });
    }
    let etas = w.lambda.map(|l| int.eval(l) / ext);
    let (wi, etap) = super::fresnel::refract(wo, Vec3::Z, etas[0])?;
    if wi.z == 0.0 || wi.z * wo.z >= 0.0 || !(1.0 - pr > 0.0) {
        return None;
    }
    Some(BsdfSample {
        f: super::dielectric::transmitted(t, &etas, wo, wi, mode),
        wi,
        pdf: 1.0 - pr,
        specular: true,
        transmission: true,
        dispersive: int.is_dispersive(),
        eta: etap,
    })
}

/// The Mueller matrix of a stack's specular reflection, in the s/p frame and with the sign
/// conventions of [`crate::polarisation::fresnel::reflection`] (which it equals for a bare
/// interface): R_s, R_p and the retardance arg r_s − arg r_p.
pub fn reflection_mueller(r: &StackResponse) -> Mueller {
    let (rs, rp) = (r.reflectance.0 as f32, r.reflectance.1 as f32);
    let delta = (r.r.0.arg() - r.r.1.arg()) as f32;
    diattenuator_retarder(rs, rp, if rs * rp > 0.0 { delta } else { 0.0 })
}

/// The Mueller matrix of a stack's specular transmission: T_s, T_p and the retardance between
/// the transmitted s and p waves (0 for a bare interface, as
/// [`crate::polarisation::fresnel::transmission`]).
pub fn transmission_mueller(r: &StackResponse) -> Mueller {
    let (ts, tp) = (r.transmittance.0 as f32, r.transmittance.1 as f32);
    let delta = (r.transmission_phase.0 - r.transmission_phase.1) as f32;
    diattenuator_retarder(ts, tp, if ts * tp > 0.0 { delta } else { 0.0 })
}

/// A diattenuator with power factors `a` (s) and `b` (p) and retardance `delta` (radians)
/// about the s axis.
fn diattenuator_retarder(a: f32, b: f32, delta: f32) -> Mueller {
    let c = (a * b).sqrt();
    let (sin_d, cos_d) = delta.sin_cos();
    let (m, d) = (0.5 * (a + b), 0.5 * (a - b));
    Mueller([
        [m, d, 0.0, 0.0],
        [d, m, 0.0, 0.0],
        [0.0, 0.0, c * cos_d, -c * sin_d],
        [0.0, 0.0, c * sin_d, c * cos_d],
    ])
}

/// A smooth plastic's coating under thin-film layers: the layered interface's R(λ, cos θ) and
/// T(λ, cos θ) from outside replace 1 − F and F, and its internal reflectance
/// R_int(λ) = 2∫₀¹ R_inside(μ) μ dμ (the stack seen from the base, cosine-weighted over the
/// hemisphere) replaces Fdr, tabulated at build every [`PlasticFilm::STEP_NM`] nm and
/// interpolated. With this R_int a lossless stack over a white base (ρ = 1, `nonlinear`)
/// reflects all the light, as energy conservation requires (`tests/coatings.rs`).
#[derive(Clone, Debug, PartialEq)]
pub struct PlasticFilm {
    pub layers: Coating,
    /// The indices outside and of the coating's dielectric (absolute).
    pub ext_ior: f32,
    pub int_ior: f32,
    /// R_int at 300, 305, … nm up to 1000 nm.
    r_int: Vec<f32>,
}

impl PlasticFilm {
    /// Spacing of the R_int table, nm.
    pub const STEP_NM: f32 = 5.0;
    const FIRST_NM: f32 = 300.0;
    const LAST_NM: f32 = 1000.0;

    pub fn new(layers: Coating, ext_ior: f32, int_ior: f32) -> PlasticFilm {
        let n = ((Self::LAST_NM - Self::FIRST_NM) / Self::STEP_NM) as usize + 1;
        let int = Ior::Constant(int_ior);
        let r_int = (0..n)
            .map(|i| {
                let l = Self::FIRST_NM + Self::STEP_NM * i as f32;
                // midpoint rule in μ² (dμ² = 2μ dμ): 512 points
                let k = 512;
                (0..k)
                    .map(|j| {
                        let mu = (((j as f32) + 0.5) / k as f32).sqrt();
                        on_dielectric(&layers, ext_ior, &int, -mu, l).r_unpolarised() as f32
                    })
                    .sum::<f32>()
                    / k as f32
            })
            .collect();
        PlasticFilm {
            layers,
            ext_ior,
            int_ior,
            r_int,
        }
    }

    /// R_int at `l` nm (clamped to the table's ends).
    pub fn r_int(&self, l: f32) -> f32 {
        let x = ((l - Self::FIRST_NM) / Self::STEP_NM).clamp(0.0, (self.r_int.len() - 1) as f32);
        let i = (x as usize).min(self.r_int.len() - 2);
        let t = x - i as f32;
        self.r_int[i] * (1.0 - t) + self.r_int[i + 1] * t
    }

    /// (R, T) of the stack from outside at cos θ = `cos` (> 0) and `l` nm.
    pub fn outside(&self, cos: f32, l: f32) -> (f32, f32) {
        let r = on_dielectric(
            &self.layers,
            self.ext_ior,
            &Ior::Constant(self.int_ior),
            cos,
            l,
        );
        (r.r_unpolarised() as f32, r.t_unpolarised() as f32)
    }
}

impl super::Plastic {
    /// The same smooth plastic under thin-film `layers` (indices `ext_ior` outside and
    /// `int_ior` of the coating, absolute). Errors for a rough plastic.
    pub fn with_film(
        mut self,
        layers: Coating,
        ext_ior: f32,
        int_ior: f32,
    ) -> Result<Self, String> {
        if self.rough.is_some() {
            return Err(
                "a coating goes on a smooth plastic only (roughplastic does not take one yet)"
                    .into(),
            );
        }
        self.film = Some(Box::new(PlasticFilm::new(layers, ext_ior, int_ior)));
        Ok(self)
    }

    /// The coated smooth plastic's f (no cosine) and pdf: the diffuse base through the stack's
    /// T(λ) both ways under R_int(λ) (see `Plastic::eval_pdf` and [`PlasticFilm`]).
    pub(super) fn film_eval_pdf<const N: usize>(
        &self,
        f: &PlasticFilm,
        wo: Vec3,
        wi: Vec3,
        rho: SampledSpectrum<N>,
        w: &SampledWavelengths<N>,
    ) -> (SampledSpectrum<N>, f32) {
        let (_, t_o) = film_terms(f, wo.z, w);
        let (_, t_i) = film_terms(f, wi.z, w);
        let mut v = [0.0; N];
        for j in 0..N {
            let r_int = f.r_int(w.lambda[j]);
            let d = rho[j];
            let den = 1.0 - if self.nonlinear { d * r_int } else { r_int };
            let eff = if den > 0.0 { d / den } else { 0.0 };
            v[j] = eff * std::f32::consts::FRAC_1_PI * t_o[j] * t_i[j] / (self.eta * self.eta);
        }
        let ps = self.p_spec(mean(&t_o));
        (
            SampledSpectrum(v),
            (1.0 - ps) * crate::sampling::cosine_hemisphere_pdf(wi.z),
        )
    }
}

/// Per wavelength (R, T) of a plastic's coated interface from outside at `cos`.
#[inline]
pub(super) fn film_terms<const N: usize>(
    f: &PlasticFilm,
    cos: f32,
    w: &SampledWavelengths<N>,
) -> ([f32; N], [f32; N]) {
    let rt = w.lambda.map(|l| f.outside(cos, l));
    (rt.map(|x| x.0), rt.map(|x| x.1))
}

/// The mean of the sampled values (a coated interface's transmittance for the lobe choice).
pub(super) fn mean<const N: usize>(v: &[f32; N]) -> f32 {
    v.iter().sum::<f32>() / N as f32
}

/// A thin-film stack's matrices across a smooth interface: its reflection or its transmission
/// by the side `wi` lies on, from the stack's response `resp(λ)` (`coated.rs`).
pub(super) fn stack<const N: usize>(
    frame: &crate::geometry::Frame,
    (wo, wi): (Vec3, Vec3),
    w: &SampledWavelengths<N>,
    hero_only: bool,
    resp: impl Fn(f32) -> StackResponse,
) -> super::Polarising<N> {
    let reflect = wi.z * wo.z > 0.0;
    let m = |l: f32| {
        let r = resp(l);
        if reflect {
            reflection_mueller(&r)
        } else {
            transmission_mueller(&r)
        }
    };
    super::polarised::interface(frame, Vec3::Z, wo, wi, m, hero_only).with(w)
}
