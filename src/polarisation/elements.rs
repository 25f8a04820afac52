//! Ideal optical elements as Mueller matrices (Goldstein, *Polarized Light*, 3rd ed., ch. 6;
//! the forms of Mitsuba 3's `polarizer` and `retarder` plugins), and the test of whether a
//! Mueller matrix is physically realisable (Cloude 1986).

use super::Mueller;

/// An ideal linear polariser passing light polarised along the basis vector (0°): ½ on the
/// top-left 2 × 2 block. Turn it with [`super::rotated_element`].
pub fn linear_polariser() -> Mueller {
    Mueller([
        [0.5, 0.5, 0.0, 0.0],
        [0.5, 0.5, 0.0, 0.0],
        [0.0; 4],
        [0.0; 4],
    ])
}

/// An ideal linear retarder with its fast axis along the basis vector, delaying the slow
/// component by `phase` radians (π/2: a quarter-wave plate, π: a half-wave plate).
pub fn linear_retarder(phase: f32) -> Mueller {
    let (s, c) = phase.sin_cos();
    Mueller([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, c, s],
        [0.0, 0.0, -s, c],
    ])
}

/// An ideal depolariser of transmittance `value`: only (0, 0) is non-zero.
pub fn depolariser(value: f32) -> Mueller {
    let mut m = [[0.0; 4]; 4];
    m[0][0] = value;
    Mueller(m)
}

/// Whether `m` is the Mueller matrix of a physical (passive, possibly depolarising) element:
/// Cloude's criterion, that its coherency matrix H = ¼ Σᵢⱼ mᵢⱼ (σᵢ ⊗ σⱼ*) (σ the identity and
/// the Pauli matrices in Stokes order: σ_z, σ_x, σ_y) has no eigenvalue below −`tol`·m₀₀.
/// H is Hermitian 4 × 4; its eigenvalues are found as those of the real symmetric 8 × 8
/// [[Re H, −Im H], [Im H, Re H]] (each appears twice) by Jacobi rotations.
pub fn realisable(m: &Mueller, tol: f32) -> bool {
    let h = coherency(m);
    let mut a = [[0.0f64; 8]; 8];
    for i in 0..4 {
        for j in 0..4 {
            let (re, im) = h[i][j];
            a[i][j] = re;
            a[i + 4][j + 4] = re;
            a[i][j + 4] = -im;
            a[i + 4][j] = im;
        }
    }
    let eig = jacobi_eigenvalues(a);
    let scale = f64::from(m.0[0][0]).abs().max(1e-12);
    eig.iter().all(|&l| l >= -f64::from(tol) * scale)
}

/// The coherency matrix of `m`, as (re, im) pairs.
fn coherency(m: &Mueller) -> [[(f64, f64); 4]; 4] {
    // Pauli matrices as 2 × 2 of (re, im): identity, σ_z (S1), σ_x (S2), σ_y (S3)
    let z = (0.0, 0.0);
    let pauli: [[[(f64, f64); 2]; 2]; 4] = [
        [[(1.0, 0.0), z], [z, (1.0, 0.0)]],
        [[(1.0, 0.0), z], [z, (-1.0, 0.0)]],
        [[z, (1.0, 0.0)], [(1.0, 0.0), z]],
        [[z, (0.0, -1.0)], [(0.0, 1.0), z]],
    ];
    let mut h = [[(0.0, 0.0); 4]; 4];
    for (i, si) in pauli.iter().enumerate() {
        for (j, sj) in pauli.iter().enumerate() {
            let w = 0.25 * f64::from(m.0[i][j]);
            // Kronecker product σᵢ ⊗ conj(σⱼ)
            for r in 0..4 {
                for c in 0..4 {
                    let a = si[r / 2][c / 2];
                    let b = sj[r % 2][c % 2];
                    let b = (b.0, -b.1);
                    h[r][c].0 += w * (a.0 * b.0 - a.1 * b.1);
                    h[r][c].1 += w * (a.0 * b.1 + a.1 * b.0);
                }
            }
        }
    }
    h
}

/// The eigenvalues of a real symmetric matrix by cyclic Jacobi rotations.
fn jacobi_eigenvalues<const K: usize>(mut a: [[f64; K]; K]) -> [f64; K] {
    for _ in 0..100 {
        let off: f64 = (0..K)
            .flat_map(|i| (0..K).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        if off < 1e-24 {
            break;
        }
        for p in 0..K {
            for q in p + 1..K {
                if a[p][q].abs() < 1e-300 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in a.iter_mut() {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (row_p, row_q) = (a[p], a[q]);
                for (k, (apk, aqk)) in row_p.into_iter().zip(row_q).enumerate() {
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
            }
        }
    }
    std::array::from_fn(|i| a[i][i])
}

#[cfg(test)]
mod tests {
    use super::super::{Complex, Stokes, fresnel, rotated_element};
    use super::*;

    #[test]
    fn physical_elements_are_realisable_and_others_are_not() {
        let good = [
            Mueller::IDENTITY,
            linear_polariser(),
            rotated_element(0.7, &linear_polariser()),
            linear_retarder(1.1),
            depolariser(0.5),
            fresnel::reflection(0.3, Complex::new(1.5, 0.0)),
            fresnel::reflection(0.3, Complex::new(1.0 / 1.5, 0.0)),
            fresnel::reflection(0.6, Complex::new(0.2, 3.0)),
            fresnel::transmission(0.45, 1.5),
        ];
        for m in good {
            assert!(realisable(&m, 1e-5), "{m:?}");
        }
        // a handedness flip alone, and more polarised light out than light
        let mut flip = Mueller::IDENTITY;
        flip.0[3][3] = -1.0;
        let mut gain = Mueller::IDENTITY;
        gain.0[0][1] = 2.0;
        for m in [flip, gain] {
            assert!(!realisable(&m, 1e-5), "{m:?}");
        }
    }

    #[test]
    fn a_quarter_wave_plate_at_45_degrees_makes_horizontal_light_circular() {
        let q = rotated_element(
            std::f32::consts::FRAC_PI_4,
            &linear_retarder(0.5 * std::f32::consts::PI),
        );
        let s = q * Stokes([1.0, 1.0, 0.0, 0.0]);
        assert!(
            (s.0[3].abs() - 1.0).abs() < 1e-6 && s.0[1].abs() < 1e-6,
            "{s:?}"
        );
    }
}
