//! The linearised extension: no root, no division.

use super::{LengthKernel, Sealed, scaled};
use crate::scalar::Scalar;

/// `x ≈ (d·d − L²)/(2L)` along `n ≈ d/L`.
///
/// With `|d| = L + x`, `d·d − L² = 2Lx + x²`, so the extension is off by `x²/(2L)`: a
/// relative error of `x/(2L)`, 1 % at 2 % stretch. The axis has length `|d|/L = 1 + x/L`.
/// Good for stiff networks that stay near their rest lengths (ropes, jelly); wrong for
/// large stretches. `1/L`, `1/(2L)` and `L²` are precomputed.
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

/// `L²`, `1/(2L)` and `1/L` for one spring, in the position format.
///
/// ```
/// use stiffspring::length::{LengthKernel, Linearised};
/// let rest = <Linearised as LengthKernel<f32>>::rest(2.0);
/// assert_eq!(<Linearised as LengthKernel<f32>>::rest_length(&rest), 2.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LinearisedRest<S> {
    length: S,
    square: S,
    inverse_twice: S,
    inverse: S,
}

impl<S: Scalar> LengthKernel<S> for Linearised {
    type Rest = LinearisedRest<S>;
    const NAME: &'static str = "linearised";

    fn rest(length: f64) -> Self::Rest {
        LinearisedRest {
            length: S::from_f64(length),
            square: S::from_f64(length * length),
            inverse_twice: S::from_f64(0.5 / length),
            inverse: S::from_f64(1.0 / length),
        }
    }

    fn rest_length(rest: &Self::Rest) -> f64 {
        rest.length.to_f64()
    }

    #[inline(always)]
    fn measure<const D: usize>(d: &[S; D], rest: &Self::Rest) -> (S, [S; D]) {
        let excess = S::dot(d, d).sub(rest.square);
        (excess.mul(rest.inverse_twice), scaled(d, rest.inverse))
    }
}
