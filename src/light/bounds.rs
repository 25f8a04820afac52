//! What the light tree knows of a light or a cluster of lights: where it is, which way it
//! faces, how much it emits, and from that an importance at a shading point (Conty Estevez &
//! Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting", §4; pbrt-v4
//! §12.6.3, `LightBounds`).
//!
//! Contract: the importance is an estimate, not a density; it must only be **zero where the
//! light cannot contribute** (every direction from the bounds toward the point lies outside
//! the emission cone, or on the point's shading horizon), since the tree never picks a light of
//! zero importance. Every bound here is therefore conservative.

use glam::Vec3;
use std::f32::consts::PI;

/// A cone of unit directions: axis `w` and the cosine of its half-angle (−1: all directions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionCone {
    pub w: Vec3,
    pub cos_theta: f32,
}

impl DirectionCone {
    /// Every direction.
    pub const ALL: DirectionCone = DirectionCone {
        w: Vec3::Z,
        cos_theta: -1.0,
    };

    /// The single direction `w` (unit).
    pub fn of(w: Vec3) -> DirectionCone {
        DirectionCone { w, cos_theta: 1.0 }
    }

    /// The smallest cone holding both (pbrt-v4 §3.9.4, `Union(DirectionCone, DirectionCone)`).
    pub fn union(a: DirectionCone, b: DirectionCone) -> DirectionCone {
        if a.cos_theta <= -1.0 || b.cos_theta <= -1.0 {
            return DirectionCone::ALL;
        }
        let theta_a = a.cos_theta.clamp(-1.0, 1.0).acos();
        let theta_b = b.cos_theta.clamp(-1.0, 1.0).acos();
        let theta_d = angle_between(a.w, b.w);
        if (theta_d + theta_b).min(PI) <= theta_a {
            return a;
        }
        if (theta_d + theta_a).min(PI) <= theta_b {
            return b;
        }
        let theta_o = 0.5 * (theta_a + theta_d + theta_b);
        if theta_o >= PI {
            return DirectionCone::ALL;
        }
        // turn a's axis toward b's by θo − θa about their common normal (Rodrigues)
        let k = a.w.cross(b.w);
        if k.length_squared() < 1e-12 {
            return DirectionCone::ALL;
        }
        let k = k.normalize();
        let (s, c) = (theta_o - theta_a).sin_cos();
        let w = a.w * c + k.cross(a.w) * s + k * k.dot(a.w) * (1.0 - c);
        // a little wider than θo, so that rounding never leaves a member direction outside
        DirectionCone {
            w: w.normalize(),
            cos_theta: (theta_o + 1e-4).min(PI).cos(),
        }
    }
}

/// The angle between unit vectors, accurate near 0 and π, rad.
fn angle_between(a: Vec3, b: Vec3) -> f32 {
    if a.dot(b) < 0.0 {
        PI - 2.0 * ((a + b).length() * 0.5).min(1.0).asin()
    } else {
        2.0 * ((b - a).length() * 0.5).min(1.0).asin()
    }
}

/// cos(max(0, θa − θb)) from the sines and cosines.
#[inline]
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}

/// sin(max(0, θa − θb)) from the sines and cosines.
#[inline]
fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        0.0
    } else {
        sin_a * cos_b - cos_a * sin_b
    }
}

/// Bounds of a light's (or a cluster's) emission.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    /// Axis-aligned box of the emitting points, m.
    pub lo: Vec3,
    pub hi: Vec3,
    /// 4π times the emitter's largest radiant intensity over directions, W: the power of an
    /// isotropic emitter as bright as this one in its brightest direction (a sum for a
    /// cluster). The importance scales by it, so that φ·cos θ'/d² is in proportion to the
    /// irradiance the light can deliver whatever its kind: for a point light or a sphere it is
    /// the power; for a one-sided flat emitter, whose intensity peaks at power/π along its
    /// normal, four times the power. pbrt-v4's `LightBounds` takes the power for area lights
    /// and 4π·I for point lights, which picks a point light four times too often beside a
    /// flat lamp of the same contribution (measured in BENCHMARKS.md, issue 25).
    pub phi: f32,
    /// Cone of the emitters' normals (a spot's axis, a surface's normal), θo.
    pub normals: DirectionCone,
    /// cos θe: light leaves within θe of some normal of the cone (π/2 for a Lambertian
    /// surface, the cut-off beyond the normal cone for a spot).
    pub cos_e: f32,
    /// Whether the surfaces emit on both sides (the normal cone then also holds its mirror).
    pub two_sided: bool,
}

impl LightBounds {
    /// An emitter at `p` emitting in every direction, `phi` as in [`LightBounds::phi`], W (for
    /// an isotropic point light, its power).
    pub fn point(p: Vec3, phi: f32) -> LightBounds {
        LightBounds {
            lo: p,
            hi: p,
            phi,
            normals: DirectionCone::ALL,
            cos_e: 0.0,
            two_sided: false,
        }
    }

    /// [`LightBounds::phi`] of an emitter of power `power` (W) whose peak intensity is
    /// `power / omega` (`omega` in sr: 4π for an isotropic emitter, π for a one-sided flat
    /// one): 4π·power/omega. The power itself where `omega` is not a positive finite number.
    pub fn phi_of(power: f32, omega: f32) -> f32 {
        if omega > 0.0 && omega.is_finite() {
            power * (4.0 * std::f32::consts::PI / omega)
        } else {
            power
        }
    }

    pub fn centroid(&self) -> Vec3 {
        0.5 * (self.lo + self.hi)
    }

    /// Both bounds in one: boxes and normal cones joined, powers added, the wider emission.
    pub fn union(&self, o: &LightBounds) -> LightBounds {
        LightBounds {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
            phi: self.phi + o.phi,
            normals: DirectionCone::union(self.normals, o.normals),
            cos_e: self.cos_e.min(o.cos_e),
            two_sided: self.two_sided || o.two_sided,
        }
    }

    /// Importance at the shading point `p` with unit shading normal `n` (zero vector: a point
    /// in a medium or with no preferred side); see [`Importance::at`].
    pub fn importance(&self, p: Vec3, n: Vec3) -> f32 {
        Importance::from(self).at(p, n)
    }
}

/// [`LightBounds`] as the importance reads them, with what it derives computed once (the
/// light tree's nodes hold these).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Importance {
    /// Box centre, m, and a quarter of the squared diagonal (the bounding sphere's r²), m².
    centre: Vec3,
    radius2: f32,
    /// Normal cone axis, its cos θo and sin θo.
    w: Vec3,
    cos_o: f32,
    sin_o: f32,
    cos_e: f32,
    phi: f32,
    two_sided: bool,
}

impl From<&LightBounds> for Importance {
    fn from(b: &LightBounds) -> Importance {
        let cos_o = b.normals.cos_theta;
        Importance {
            centre: b.centroid(),
            radius2: (b.hi - b.lo).length_squared() * 0.25,
            w: b.normals.w,
            cos_o,
            sin_o: (1.0 - cos_o * cos_o).max(0.0).sqrt(),
            cos_e: b.cos_e,
            phi: b.phi,
            two_sided: b.two_sided,
        }
    }
}

impl Importance {
    /// φ · cos θ' / d², times cos θ'ᵢ for a surface (pbrt-v4 `LightBounds::Importance`). θ' is
    /// the smallest angle between the normal cone and the directions from the box toward `p`,
    /// θ'ᵢ the smallest angle between ±`n` and the directions toward the box, d the distance to
    /// the box's centre (at least half its diagonal, so a point inside a cluster does not
    /// favour it without bound). Zero where no light in the bounds reaches `p` (see the module
    /// doc). Unitless but proportional to W/m².
    #[inline]
    pub fn at(&self, p: Vec3, n: Vec3) -> f32 {
        let v = p - self.centre;
        let d2p = v.length_squared();
        let d2 = d2p.max(self.radius2);
        let wi = if d2p > 0.0 {
            v * d2p.sqrt().recip()
        } else {
            Vec3::Z
        };
        // the cone of directions from p that the box's bounding sphere subtends
        let (sin_b, cos_b) = if d2p <= self.radius2 {
            (0.0, -1.0)
        } else {
            let s2 = self.radius2 / d2p;
            (s2.sqrt(), (1.0 - s2).max(0.0).sqrt())
        };
        let cos_p = if self.cos_o <= -1.0 {
            // a normal cone of every direction holds the direction toward p: θ' = 0 (what the
            // general case gives exactly, without its square roots; points and spheres)
            1.0
        } else {
            let mut cos_w = self.w.dot(wi);
            if self.two_sided {
                cos_w = cos_w.abs();
            }
            let sin_w = (1.0 - cos_w * cos_w).max(0.0).sqrt();
            let (cos_o, sin_o) = (self.cos_o, self.sin_o);
            let cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_o);
            let sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_o);
            cos_sub_clamped(sin_x, cos_x, sin_b, cos_b)
        };
        if cos_p <= self.cos_e {
            return 0.0;
        }
        let mut imp = self.phi * cos_p / d2;
        if n != Vec3::ZERO {
            let cos_i = wi.dot(n).abs();
            let sin_i = (1.0 - cos_i * cos_i).max(0.0).sqrt();
            imp *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
        }
        imp.max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phi_is_four_pi_times_the_peak_intensity() {
        use std::f32::consts::PI;
        // isotropic: the power; a one-sided Lambertian plate, Φ = π·I_peak: four times it
        assert!((LightBounds::phi_of(10.0, 4.0 * PI) - 10.0).abs() < 1e-5);
        assert!((LightBounds::phi_of(10.0, PI) - 40.0).abs() < 1e-4);
        assert_eq!(LightBounds::phi_of(10.0, 0.0), 10.0);
        assert_eq!(LightBounds::phi_of(10.0, f32::NAN), 10.0);
    }

    #[test]
    fn cone_union_holds_both_cones() {
        let a = DirectionCone::of(Vec3::Z);
        let b = DirectionCone::of(Vec3::X);
        let u = DirectionCone::union(a, b);
        for d in [Vec3::Z, Vec3::X] {
            assert!(u.w.dot(d) >= u.cos_theta - 1e-6, "{u:?} misses {d}");
        }
        assert!((u.cos_theta - (PI / 4.0).cos()).abs() < 1e-3);
        let opposite = DirectionCone::union(a, DirectionCone::of(-Vec3::Z));
        assert!(opposite.cos_theta <= -0.999);
    }

    #[test]
    fn one_sided_emitter_has_no_importance_behind_it() {
        let b = LightBounds {
            lo: Vec3::new(-1.0, -1.0, 0.0),
            hi: Vec3::new(1.0, 1.0, 0.0),
            phi: 10.0,
            normals: DirectionCone::of(Vec3::Z),
            cos_e: 0.0,
            two_sided: false,
        };
        assert!(b.importance(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO) > 0.0);
        assert_eq!(b.importance(Vec3::new(0.0, 0.0, -3.0), Vec3::ZERO), 0.0);
        let two = LightBounds {
            two_sided: true,
            ..b
        };
        assert!(two.importance(Vec3::new(0.0, 0.0, -3.0), Vec3::ZERO) > 0.0);
        // a point whose normal is perpendicular to every direction toward a point light
        let p = LightBounds::point(Vec3::ZERO, 1.0);
        assert_eq!(p.importance(Vec3::new(5.0, 0.0, 0.0), Vec3::Z), 0.0);
        assert!(p.importance(Vec3::new(5.0, 0.0, 0.0), Vec3::X) > 0.0);
    }
}

#[cfg(test)]
mod conservative {
    use super::*;

    /// A tiny deterministic generator for the tests.
    fn rng(state: &mut u64) -> f32 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*state >> 40) as f32) / (1u64 << 24) as f32
    }

    /// Wherever some point of a one-sided square emitter sends light to `p` and `p`'s normal
    /// does not make it graze, the importance is positive (the tree never drops a light that
    /// contributes); checked on random points, normals and emitter orientations.
    #[test]
    fn importance_is_positive_wherever_a_square_emitter_contributes() {
        let mut s = 7u64;
        let mut u = || rng(&mut s);
        for _ in 0..20_000 {
            let normal = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize();
            let frame = crate::geometry::Frame::from_normal(normal);
            let corner = |a: f32, b: f32| frame.to_world(Vec3::new(a, b, 0.0));
            let pts: Vec<Vec3> = (0..25)
                .map(|k| corner((k % 5) as f32 / 4.0 - 0.5, (k / 5) as f32 / 4.0 - 0.5))
                .collect();
            let (lo, hi) = pts
                .iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), &q| {
                    (l.min(q), h.max(q))
                });
            let b = LightBounds {
                lo,
                hi,
                phi: 1.0,
                normals: DirectionCone::of(normal),
                cos_e: 0.0,
                two_sided: false,
            };
            // near and far (up to 60 edge lengths), where the box's angle no longer hides
            // the emission cone's edge
            let p = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize() * (0.3 + 60.0 * u());
            let n = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize();
            let contributes = pts.iter().any(|&q| {
                let d = (p - q).normalize();
                d.dot(normal) > 1e-3 && d.dot(n).abs() > 1e-3
            });
            if contributes {
                assert!(b.importance(p, n) > 0.0, "{b:?} at {p} (n {n})");
            }
        }
    }

    /// The same for a spot: positive importance inside its cone (hard-edged or with falloff).
    #[test]
    fn importance_is_positive_inside_a_spot_cone() {
        let mut s = 11u64;
        let mut u = || rng(&mut s);
        for _ in 0..20_000 {
            let axis = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize();
            let total = 0.05 + 1.4 * u();
            let start = total * u();
            let theta_e = (total - start).max(1e-3);
            let b = LightBounds {
                normals: DirectionCone {
                    w: axis,
                    cos_theta: start.cos(),
                },
                cos_e: theta_e.cos(),
                ..LightBounds::point(Vec3::ZERO, 1.0)
            };
            let p = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * 6.0;
            let inside = p.normalize().dot(axis) > (total - 1e-3).cos();
            if inside {
                assert!(b.importance(p, Vec3::ZERO) > 0.0, "{b:?} at {p}");
            }
        }
    }
}
