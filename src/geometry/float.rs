//! Floating-point error analysis helpers (pbrt-v4 §6.8, Higham 2002 §3.1).
//!
//! With correctly rounded `f32` arithmetic, every operation has a relative error of at most
//! `ε = 2⁻²⁴` (half an ulp). A chain of `n` operations is bounded by `γ(n) = nε / (1 − nε)`.

use glam::Vec3;

/// Unit roundoff of `f32`: half the distance from 1.0 to the next float, 2⁻²⁴.
pub const MACHINE_EPSILON: f32 = f32::EPSILON * 0.5;

/// Higham's bound γ(n) = nε / (1 − nε) on the relative error of `n` rounded operations.
#[inline]
pub const fn gamma(n: u32) -> f32 {
    let ne = n as f32 * MACHINE_EPSILON;
    ne / (1.0 - ne)
}

/// Moves `x` to the next representable float in the direction of `sign` (`> 0` up, `< 0` down,
/// `0` unchanged).
#[inline]
pub fn next_float_toward(x: f32, sign: f32) -> f32 {
    if sign > 0.0 {
        x.next_up()
    } else if sign < 0.0 {
        x.next_down()
    } else {
        x
    }
}

/// Componentwise [`next_float_toward`].
#[inline]
pub fn next_float_toward3(v: Vec3, sign: Vec3) -> Vec3 {
    Vec3::new(
        next_float_toward(v.x, sign.x),
        next_float_toward(v.y, sign.y),
        next_float_toward(v.z, sign.z),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gamma_is_about_n_epsilon() {
        assert!((gamma(3) / (3.0 * MACHINE_EPSILON) - 1.0).abs() < 1e-5);
        assert!(gamma(1) > MACHINE_EPSILON);
    }

    #[test]
    fn next_float_moves_one_ulp() {
        assert!(next_float_toward(1.0, 1.0) > 1.0);
        assert!(next_float_toward(1.0, -1.0) < 1.0);
        assert_eq!(next_float_toward(1.0, 0.0), 1.0);
        assert!(next_float_toward(0.0, -1.0) < 0.0);
    }
}
