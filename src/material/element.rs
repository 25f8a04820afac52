//! Thin polarising optical elements that light crosses undeviated: Mitsuba 3's `polarizer` and
//! `retarder`. In an unpolarised render they are grey filters (a polariser passes half of
//! unpolarised light, a retarder all of it); in a polarised render they are Mueller matrices
//! ([`Element::mueller`]), as Mitsuba's `scalar_spectral_polarized` defines them.

use glam::Vec3;

use crate::polarisation::{Mueller, elements, rotate_stokes_basis, rotated_element, stokes_basis};

/// A thin optical element in the plane of a surface, oriented by its shading frame (the
/// frame's first tangent follows ∂p/∂u, as Mitsuba's does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Element {
    /// An ideal linear polariser whose absorption axis is the local +y turned by `theta`
    /// (radians) toward +x in the surface's plane, so that at normal incidence it passes light
    /// polarised along the local x axis turned by −`theta` about the normal (see
    /// [`Element::mueller`]), times `transmittance` (in [0, 1]). Mitsuba 3.9.1's `polarizer`.
    /// Not `polarizing`: a grey filter of ½·transmittance that keeps the light's polarisation
    /// (Mitsuba's `polarizing = false`).
    Polariser {
        theta: f32,
        transmittance: f32,
        polarizing: bool,
    },
    /// An ideal linear retarder, fast axis turned by `theta` (radians) from the local first
    /// tangent (clockwise seen against the light), retardance `delta` (radians) at normal
    /// incidence, scaled by |cos θ| at oblique incidence (Mitsuba 3.9.1's `retarder`: "a cosine
    /// falloff").
    Retarder { theta: f32, delta: f32 },
}

impl Element {
    /// The fraction of unpolarised light the element passes (dimensionless): the weight of its
    /// straight-through sample in an unpolarised render.
    #[inline]
    pub fn transmittance(&self) -> f32 {
        match self {
            Element::Polariser { transmittance, .. } => 0.5 * transmittance,
            Element::Retarder { .. } => 1.0,
        }
    }

    /// The element's Mueller matrix for light travelling along `forward` (local shading frame,
    /// unit), and the Stokes basis vector (local) it acts in, on both sides; as Mitsuba 3.9.1
    /// computes them (measured against its `scalar_spectral_polarized` BSDFs to 10⁻⁷ at oblique
    /// incidence). The polariser: the ideal polariser in the basis `forward × a`, with `a` the
    /// absorption axis (sin θ, cos θ, 0) projected perpendicular to `forward` (the tilted
    /// polariser of Korger et al. 2013), times the transmittance. The retarder: the ideal
    /// retarder of retardance δ·|cos θᵢ| turned by −θ about `forward`, in the basis of the local
    /// +x as it stands (a frame change by the angle between +x and the target basis, as
    /// Mitsuba's `rotate_stokes_basis` takes it, exact at normal incidence).
    pub fn mueller(&self, forward: Vec3) -> (Mueller, Vec3) {
        match *self {
            Element::Polariser {
                theta,
                transmittance,
                polarizing,
            } => {
                // Mitsuba's `absorber`: a grey filter that keeps the polarisation
                if !polarizing {
                    return (
                        Mueller::IDENTITY.scale(0.5 * transmittance),
                        perpendicular(Vec3::X, forward),
                    );
                }
                let (sin, cos) = theta.sin_cos();
                let a = perpendicular(Vec3::new(sin, cos, 0.0), forward);
                let basis = forward.cross(a);
                (elements::linear_polariser().scale(transmittance), basis)
            }
            Element::Retarder { theta, delta } => {
                let m =
                    rotated_element(-theta, &elements::linear_retarder(delta * forward.z.abs()));
                // Mitsuba turns the basis from +x to the local implicit basis first, an angle
                // between vectors that are not both perpendicular to the beam at oblique
                // incidence; the same two steps give its matrix
                let b = stokes_basis(forward);
                let r = rotate_stokes_basis(forward, Vec3::X, b);
                (r * m * r.transpose(), b)
            }
        }
    }

    /// [`Element::mueller`] re-expressed in the basis `target` (unit, perpendicular to
    /// `forward`) on both sides.
    pub fn mueller_in(&self, forward: Vec3, target: Vec3) -> Mueller {
        let (m, basis) = self.mueller(forward);
        let r = rotate_stokes_basis(forward, basis, target);
        r * m * r.transpose()
    }
}

impl super::Material {
    /// Whether the material holds a polarising element (a polariser that polarises, a
    /// retarder) or Mitsuba's polarising plastic, which an unpolarised render would
    /// misrepresent: such a scene renders polarised.
    pub fn polarises(&self) -> bool {
        use super::Material as M;
        match self {
            M::Element(Element::Polariser { polarizing, .. }) => *polarizing,
            M::Element(Element::Retarder { .. }) => true,
            // Mitsuba's polarising plastic exists for polarised renders
            M::PPlastic(_) => true,
            // a measured pBRDF exists for polarised renders, as Mitsuba's
            M::MeasuredPolarized(_) => true,
            M::Mask(m) => m.inner.polarises(),
            M::Blend(m) => m.a.polarises() || m.b.polarises(),
            M::NormalMap(m) => m.inner.polarises(),
            M::BumpMap(m) => m.inner.polarises(),
            M::Textured(m) => m.inner.polarises(),
            M::Diffuse(_)
            | M::Principled(_)
            | M::Hair(_)
            | M::Layered(_)
            | M::DiffuseTransmission(_)
            | M::Phong(_)
            | M::Dielectric(_)
            | M::RoughDielectric(_)
            | M::Conductor(_)
            | M::RoughConductor(_)
            | M::Plastic(_)
            | M::Measured(_)
            | M::ThinDielectric { .. }
            | M::ThinFilm(_)
            | M::Null => false,
        }
    }
}

/// `v` projected perpendicular to the unit vector `forward` and normalised (another
/// perpendicular axis when `v` is parallel to it).
fn perpendicular(v: Vec3, forward: Vec3) -> Vec3 {
    let p = v - forward * forward.dot(v);
    if p.length_squared() > 1e-12 {
        p.normalize()
    } else {
        crate::geometry::Frame::from_normal(forward).s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polarisation::Stokes;

    /// Unpolarised light leaves a polariser with half its power, and a second polariser
    /// crossed with it passes nothing.
    #[test]
    fn crossed_polarisers_pass_nothing() {
        let f = Vec3::Z;
        let p0 = Element::Polariser {
            theta: 0.0,
            transmittance: 1.0,
            polarizing: true,
        };
        let p90 = Element::Polariser {
            theta: std::f32::consts::FRAC_PI_2,
            transmittance: 1.0,
            polarizing: true,
        };
        let b = Vec3::X;
        let s = p0.mueller_in(f, b) * Stokes::unpolarised(1.0);
        assert!((s.0[0] - 0.5).abs() < 1e-6);
        let s2 = p90.mueller_in(f, b) * s;
        assert!(s2.0[0].abs() < 1e-6, "{s2:?}");
        assert_eq!(p0.transmittance(), 0.5);
    }

    /// A quarter-wave retarder at 45° turns linear light along its basis into circular light.
    #[test]
    fn quarter_wave_plate_makes_circular_light() {
        let r = Element::Retarder {
            theta: std::f32::consts::FRAC_PI_4,
            delta: std::f32::consts::FRAC_PI_2,
        };
        let s = r.mueller_in(Vec3::Z, Vec3::X) * Stokes([1.0, 1.0, 0.0, 0.0]);
        assert!((s.0[3].abs() - 1.0).abs() < 1e-5, "{s:?}");
    }
}
