//! The knob's linear loop from the rotor's physics, for checking the library's analysis:
//! the state matrix of one control period and its eigenvalues (nalgebra, through
//! [`crate::linear`]).
//!
//! The state is `(θ, w, θ_prev, v, Δu_prev)` in step units (angles, and velocities times
//! `dt`): the controller reads `θ`, filters the backward difference `u = θ − θ_prev` as
//! `v ← (1 − α)·v + α·u`, and commands `Δu = −(C_k·θ + C_d·v)` (a torque `Δu·J/dt²`); the
//! previous command acts for `delay` of the period and the new one for the rest, each
//! integrated exactly (`θ'' = Δu` per step²). Nothing here uses the library.

use crate::linear::{Complex, Matrix};

/// One period of the loop on the state `x`, with `C_k`, `C_d`, the filter's `α` and the
/// delay as a fraction of the period (0 to 1).
pub fn period(x: [f64; 5], ck: f64, cd: f64, alpha: f64, delay: f64) -> [f64; 5] {
    let [theta, w, prev, v, du_prev] = x;
    let v = (1.0 - alpha) * v + alpha * (theta - prev);
    let du = -(ck * theta + cd * v);
    let (d1, d2) = (delay, 1.0 - delay);
    let theta1 = theta + w * d1 + 0.5 * du_prev * d1 * d1;
    let w1 = w + du_prev * d1;
    [
        theta1 + w1 * d2 + 0.5 * du * d2 * d2,
        w1 + du * d2,
        theta,
        v,
        du,
    ]
}

/// The 5×5 matrix of [`period`] (it is linear in the state): column `j` is the period
/// applied to the `j`-th unit vector.
pub fn state_matrix(ck: f64, cd: f64, alpha: f64, delay: f64) -> Matrix {
    let mut m = Matrix::zeros(5, 5);
    for j in 0..5 {
        let mut e = [0.0; 5];
        e[j] = 1.0;
        let col = period(e, ck, cd, alpha, delay);
        for (i, c) in col.iter().enumerate() {
            m[(i, j)] = *c;
        }
    }
    m
}

/// The loop's eigenvalues (the closed-loop poles), zeros included.
pub fn poles(ck: f64, cd: f64, alpha: f64, delay: f64) -> Vec<Complex> {
    crate::linear::eigenvalues(&state_matrix(ck, cd, alpha, delay))
}

/// `det(z·I − A)`, the characteristic polynomial of `a` evaluated at `z` (LU in complex
/// arithmetic).
pub fn characteristic_at(a: &Matrix, z: Complex) -> Complex {
    let n = a.nrows();
    let m = nalgebra::DMatrix::<Complex>::from_fn(n, n, |i, j| {
        let d = if i == j { z } else { Complex::new(0.0, 0.0) };
        d - Complex::new(a[(i, j)], 0.0)
    });
    m.determinant()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without the controller (`C_k = C_d = 0`) the rotor coasts: a double pole at 1 (θ, w)
    /// and the filter's pole at `1 − α`; with gains the product of the poles is the
    /// determinant.
    #[test]
    fn a_free_rotor_coasts() {
        let p = poles(0.0, 0.0, 0.3, 1.0);
        let ones = p
            .iter()
            .filter(|z| (z.re - 1.0).abs() < 1e-6 && z.im.abs() < 1e-6);
        assert_eq!(ones.count(), 2, "{p:?}");
        assert!(
            p.iter()
                .any(|z| (z.re - 0.7).abs() < 1e-9 && z.im.abs() < 1e-9)
        );
        let a = state_matrix(0.1, 0.3, 0.5, 0.0);
        let product = poles(0.1, 0.3, 0.5, 0.0)
            .iter()
            .fold(Complex::new(1.0, 0.0), |acc, z| acc * z);
        let det = characteristic_at(&a, Complex::new(0.0, 0.0)) * (-1.0f64).powi(5);
        assert!((product - det).norm() < 1e-12, "{product} {det}");
    }
}
