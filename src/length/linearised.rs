//! The linearised extension: no root, no division.

use super::{LengthKernel, Sealed};
use crate::scalar::Scalar;

/// `x ≈ (d·d − L²)/(2L)` along `n ≈ d/L`.
///
/// With `|d| = L + x`, `d·d − L² = 2Lx + x²`, so the extension is off by `x²/(2L)`: a
/// relative error of `x/(2L)`, 1 % at 2 % stretch. The axis has length `|d|/L = 1 + x/L`.
/// Good for stiff networks that stay near their rest lengths (ropes, jelly); wrong for
/// large stretches. `1/L`, `1/(2L)` and `L²` are precomputed, so it needs `L > 0`.
///
/// **A hardening spring.** The stiffness impulse `−C_k·x·n = −C_k·(|d|² − L²)·d/(2L²)`
/// is the gradient of `C_k·(|d|² − L²)²/(8L²)` (so it conserves energy), whose Hessian at
/// stretch `s = |d|/L` is `C_k/2·((s² − 1)·I + 2s²·n̂n̂ᵀ)`: axial stiffness
/// `C_k·(3s² − 1)/2`, transverse `C_k·(s² − 1)/2`, against `C_k` and `C_k·(1 − 1/s)` for
/// the exact kernel. The damping impulse `−C_d·(n·u)·n` is `C_d·s²` along the axis. At
/// `s = 1.5` (a mesh pre-stretched by half) that is `2.875·C_k` and `2.25·C_d`, which
/// takes a network at its limit far past it; a scene applies
/// [`LengthKernel::stiffening`] at set-up (`tests/linearised_stretch.rs`).
///
/// ```
/// use stiffspring::length::{LengthKernel, Linearised};
///
/// let rest = <Linearised as LengthKernel<f64>>::rest(10.0);
/// let (x, n) = <Linearised as LengthKernel<f64>>::measure(&[10.2, 0.0], &rest);
/// assert!((x - 0.202).abs() < 1e-12); // the exact extension is 0.2
/// assert!((n[0] - 1.02).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Linearised;

impl Sealed for Linearised {}

/// `L`, `L²`, `1/(2L)` and `1/L` for one spring.
///
/// ```
/// use stiffspring::length::{LengthKernel, Linearised};
/// let rest = <Linearised as LengthKernel<f32>>::rest(2.0);
/// assert_eq!(<Linearised as LengthKernel<f32>>::rest_length(&rest), 2.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LinearisedRest<S: Scalar> {
    length: S,
    square: S::State,
    inverse_twice: S::Factor,
    inverse: S::Factor,
}

impl<S: Scalar> LengthKernel<S> for Linearised {
    type Rest = LinearisedRest<S>;
    const NAME: &'static str = "linearised";
    const ZERO_REST: bool = false;

    fn rest(length: S) -> Self::Rest {
        let l = length.to_f64();
        let inverse = |v: f64| if v > 0.0 { 1.0 / v } else { 0.0 };
        LinearisedRest {
            length,
            square: S::square_sum(&[length.widen()]),
            inverse_twice: S::factor(inverse(2.0 * l)),
            inverse: S::factor(inverse(l)),
        }
    }

    fn rest_length(rest: &Self::Rest) -> S {
        rest.length
    }

    /// `(max(1, (3s² − 1)/2), max(1, s²))`: see the [type docs](Linearised).
    ///
    /// ```
    /// use stiffspring::length::{LengthKernel, Linearised};
    /// assert_eq!(<Linearised as LengthKernel<f64>>::stiffening(1.5), (2.875, 2.25));
    /// assert_eq!(<Linearised as LengthKernel<f64>>::stiffening(0.9), (1.0, 1.0));
    /// ```
    fn stiffening(stretch: f64) -> (f64, f64) {
        let square = stretch * stretch;
        // NaN (never from a scene) fails `max` toward 1.
        ((1.5 * square - 0.5).max(1.0), square.max(1.0))
    }

    #[inline(always)]
    fn measure<const D: usize>(d: &[S::State; D], rest: &Self::Rest) -> (S::State, [S::Coef; D]) {
        let excess = S::state_sub(S::square_sum(d), rest.square);
        let mut n = [S::coef(0.0); D];
        for (n, d) in n.iter_mut().zip(d) {
            *n = S::state_to_coef(*d, rest.inverse);
        }
        (S::scale(excess, rest.inverse_twice), n)
    }
}
