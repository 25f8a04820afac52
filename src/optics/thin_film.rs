//! Thin-film interference: the characteristic (transfer) matrix of a stack of parallel layers
//! (Macleod, *Thin-Film Optical Filters*, 4th ed., §2.2–2.4; Born & Wolf §1.6), per wavelength
//! and per polarisation.
//!
//! Conventions (Macleod's): a medium's index is N = n − ik; its tilted optical admittance, in
//! units of the free-space admittance, is η_s = N cos θ for s (TE) light and η_p = N / cos θ for
//! p (TM), with N cos θ = √(N² − n₀² sin²θ₀) in the fourth quadrant (the root whose wave decays
//! into the medium). A layer of physical thickness d has the phase δ = 2π N cos θ d / λ and the
//! matrix [[cos δ, i sin δ / η], [i η sin δ, cos δ]]. For the stack on a substrate of admittance
//! η_m, [B, C]ᵀ = Π M_j [1, η_m]ᵀ and
//! r = (η₀B − C)/(η₀B + C), R = |r|², T = 4 η₀ Re(η_m) / |η₀B + C|², A = 1 − R − T
//! (Macleod eqs. 2.97–2.100; η₀ real: the incident medium is transparent).
//!
//! Everything here is f64; lengths in nm (as wavelengths are).

use std::ops::{Add, Div, Mul, Neg, Sub};

use crate::spectrum::ior::{ComplexIor, Ior};

/// A complex number in f64 (the stack's fields and admittances).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct C64 {
    pub re: f64,
    pub im: f64,
}

impl C64 {
    pub const fn new(re: f64, im: f64) -> C64 {
        C64 { re, im }
    }
    pub fn real(re: f64) -> C64 {
        C64 { re, im: 0.0 }
    }
    pub fn norm2(self) -> f64 {
        self.re * self.re + self.im * self.im
    }
    pub fn arg(self) -> f64 {
        self.im.atan2(self.re)
    }
    pub fn conj(self) -> C64 {
        C64::new(self.re, -self.im)
    }
    /// Principal square root (Re ≥ 0).
    pub fn sqrt(self) -> C64 {
        let r = self.norm2().sqrt();
        let re = (0.5 * (r + self.re)).max(0.0).sqrt();
        let im = (0.5 * (r - self.re)).max(0.0).sqrt();
        C64::new(re, if self.im < 0.0 { -im } else { im })
    }
    /// (cos z, sin z).
    fn cos_sin(self) -> (C64, C64) {
        let (s, c) = self.re.sin_cos();
        let (sh, ch) = (self.im.sinh(), self.im.cosh());
        (C64::new(c * ch, -s * sh), C64::new(s * ch, c * sh))
    }
}

impl Add for C64 {
    type Output = C64;
    fn add(self, o: C64) -> C64 {
        C64::new(self.re + o.re, self.im + o.im)
    }
}
impl Sub for C64 {
    type Output = C64;
    fn sub(self, o: C64) -> C64 {
        C64::new(self.re - o.re, self.im - o.im)
    }
}
impl Mul for C64 {
    type Output = C64;
    fn mul(self, o: C64) -> C64 {
        C64::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}
impl Div for C64 {
    type Output = C64;
    fn div(self, o: C64) -> C64 {
        let d = o.norm2();
        C64::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
}
impl Neg for C64 {
    type Output = C64;
    fn neg(self) -> C64 {
        C64::new(-self.re, -self.im)
    }
}

const I: C64 = C64::new(0.0, 1.0);

/// A layer's material: a dielectric (real n(λ)) or an absorbing one (n + ik, as conductors'
/// tables give it).
#[derive(Clone, Debug, PartialEq)]
pub enum LayerIndex {
    Dielectric(Ior),
    Absorbing(ComplexIor),
}

impl LayerIndex {
    /// N = n − ik at `lambda_nm` (Macleod's sign).
    pub fn at(&self, lambda_nm: f64) -> C64 {
        match self {
            LayerIndex::Dielectric(n) => C64::real(n.eval_f64(lambda_nm)),
            LayerIndex::Absorbing(c) => {
                let (n, k) = c.eval(lambda_nm as f32);
                C64::new(n as f64, -(k as f64))
            }
        }
    }
}

/// One layer: its material and physical thickness, nm.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    pub index: LayerIndex,
    pub thickness_nm: f64,
}

/// A coating: layers listed from the outside (the incident medium) in toward the substrate.
#[derive(Clone, Debug, PartialEq)]
pub struct Coating {
    pub layers: Vec<Layer>,
}

/// What a stack does to light at one wavelength, incidence angle and side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackResponse {
    /// Amplitude reflection coefficients (s, p), in the conventions of
    /// [`crate::polarisation::fresnel`] (n + ik; normal incidence on bare glass gives
    /// r_p = −r_s).
    pub r: (C64, C64),
    /// Power reflectances (s, p).
    pub reflectance: (f64, f64),
    /// Power transmittances (s, p) into the exit medium.
    pub transmittance: (f64, f64),
    /// Amplitude transmission phases (s, p), radians, for the transmitted beam's retardance.
    pub transmission_phase: (f64, f64),
}

impl StackResponse {
    /// Unpolarised reflectance (R_s + R_p)/2.
    pub fn r_unpolarised(&self) -> f64 {
        0.5 * (self.reflectance.0 + self.reflectance.1)
    }
    /// Unpolarised transmittance (T_s + T_p)/2.
    pub fn t_unpolarised(&self) -> f64 {
        0.5 * (self.transmittance.0 + self.transmittance.1)
    }
}

impl Coating {
    /// The response of this coating between an incident medium of real index `n0` (light
    /// arriving at cos θ₀ = `cos0` ∈ (0, 1]) and a substrate of index `substrate` (N = n − ik),
    /// the layers met in the order given (`reversed`: from the last to the first, for light
    /// arriving from the substrate's side, `n0` then being the substrate's and `substrate` the
    /// outside's).
    pub fn response(
        &self,
        lambda_nm: f64,
        n0: f64,
        cos0: f64,
        substrate: C64,
        reversed: bool,
    ) -> StackResponse {
        let cos0 = cos0.clamp(0.0, 1.0);
        let ns2 = C64::real(n0 * n0 * (1.0 - cos0 * cos0)); // (n₀ sin θ₀)²
        // N cos θ in a medium, fourth quadrant (Im ≤ 0)
        let y = |n: C64| {
            let v = (n * n - ns2).sqrt();
            if v.im > 0.0 { -v } else { v }
        };
        let eta0 = (C64::real(n0 * cos0), C64::real(n0 / cos0.max(1e-12)));
        let ym = y(substrate);
        let eta_m = (ym, substrate * substrate / nonzero(ym));
        // the characteristic matrices, for s and p
        let mut ms = [
            [C64::real(1.0), C64::real(0.0)],
            [C64::real(0.0), C64::real(1.0)],
        ];
        let mut mp = ms;
        let n_layers = self.layers.len();
        for k in 0..n_layers {
            let layer = &self.layers[if reversed { n_layers - 1 - k } else { k }];
            let n = layer.index.at(lambda_nm);
            let yj = y(n);
            let delta = yj * C64::real(2.0 * std::f64::consts::PI * layer.thickness_nm / lambda_nm);
            let (c, s) = delta.cos_sin();
            for (m, eta) in [(&mut ms, yj), (&mut mp, n * n / nonzero(yj))] {
                let layer_m = [[c, I * s / nonzero(eta)], [I * eta * s, c]];
                *m = mul2(*m, layer_m);
            }
        }
        let solve = |m: [[C64; 2]; 2], e0: C64, em: C64| {
            let b = m[0][0] + m[0][1] * em;
            let c = m[1][0] + m[1][1] * em;
            let den = e0 * b + c;
            let r = (e0 * b - c) / nonzero(den);
            let tau = (e0 + e0) / nonzero(den);
            let t = 4.0 * e0.re * em.re / den.norm2().max(f64::MIN_POSITIVE);
            (r, r.norm2().min(1.0), t.clamp(0.0, 1.0), tau.arg())
        };
        let (rs, r_s, t_s, ph_s) = solve(ms, eta0.0, eta_m.0);
        let (rp, r_p, t_p, ph_p) = solve(mp, eta0.1, eta_m.1);
        // to the conventions of `polarisation::fresnel` (Born & Wolf's n + ik, time factor
        // e^{−iωt}): Macleod's n − ik conjugates every amplitude, and his p amplitude has the
        // opposite sign
        StackResponse {
            r: (rs.conj(), -rp.conj()),
            reflectance: (r_s, r_p),
            transmittance: (t_s, t_p),
            transmission_phase: (-ph_s, -ph_p),
        }
    }
}

fn nonzero(z: C64) -> C64 {
    if z.norm2() > 0.0 {
        z
    } else {
        C64::real(f64::MIN_POSITIVE)
    }
}

fn mul2(a: [[C64; 2]; 2], b: [[C64; 2]; 2]) -> [[C64; 2]; 2] {
    [
        [
            a[0][0] * b[0][0] + a[0][1] * b[1][0],
            a[0][0] * b[0][1] + a[0][1] * b[1][1],
        ],
        [
            a[1][0] * b[0][0] + a[1][1] * b[1][0],
            a[1][0] * b[0][1] + a[1][1] * b[1][1],
        ],
    ]
}
