//! The exact extension and axis: one square root and one division per spring.

use super::{LengthKernel, Sealed};
use crate::scalar::Scalar;

/// `x = |d| − L` along `n = d/|d|`, to the backend's rounding.
///
/// - `f32`, `f64`: `libm`'s correctly rounded `sqrtf`/`sqrt` and one division per axis
///   component.
/// - `I16F16`, `I32F32`: the sum of squares of the wide state exactly in a double-width
///   integer, its integer root (rounded down), and one integer division per component.
///
/// ```
/// use stiffspring::length::{Exact, LengthKernel};
///
/// let rest = <Exact as LengthKernel<f64>>::rest(1.0);
/// let (x, n) = <Exact as LengthKernel<f64>>::measure(&[0.0, 0.0, 3.0], &rest);
/// assert_eq!((x, n), (2.0, [0.0, 0.0, 1.0]));
/// // Coincident ends: no axis, no force, no NaN.
/// let (_, n) = <Exact as LengthKernel<f64>>::measure(&[0.0, 0.0, 0.0], &rest);
/// assert_eq!(n, [0.0; 3]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Exact;

impl Sealed for Exact {}

impl<S: Scalar> LengthKernel<S> for Exact {
    type Rest = S::State;
    const NAME: &'static str = "exact";

    fn rest(length: S) -> Self::Rest {
        length.widen()
    }

    fn rest_length(rest: &Self::Rest) -> S {
        S::narrow(*rest)
    }

    #[inline(always)]
    fn measure<const D: usize>(d: &[S::State; D], rest: &Self::Rest) -> (S::State, [S::Coef; D]) {
        let length = S::norm(d);
        (S::state_sub(length, *rest), S::axis(d, length))
    }
}
