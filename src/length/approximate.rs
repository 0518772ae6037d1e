//! micromath's approximate inverse square root: no root, no division.

use super::{LengthKernel, Sealed};
use crate::scalar::Scalar;
use micromath::F32Ext;

/// `r ≈ 1/√(d·d)` from micromath's bit trick (`0x5f37_5a86 − bits/2`, no refinement), then
/// `x = (d·d)·r − L` and `n = d·r`. Relative error of `r`: 3.4 % at worst (the bit
/// trick's error over every `f32`, which two binades cover; Lomont, "Fast Inverse Square
/// Root", 2003), which scales the stiffness of a stretched spring by up to that much:
/// fast, and a different spring. `f32` only.
///
/// ```
/// use stiffspring::length::{Approximate, LengthKernel};
///
/// let rest = <Approximate as LengthKernel<f32>>::rest(1.0);
/// let (x, n) = <Approximate as LengthKernel<f32>>::measure(&[3.0, 4.0], &rest);
/// assert!((x - 4.0).abs() < 0.2 && (n[0] - 0.6).abs() < 0.03);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Approximate;

/// [`Approximate`] with one Newton step on the inverse root,
/// `r ← r·(1.5 − 0.5·s·r²)`, which squares the relative error: about 0.2 % from 3.4 %.
///
/// ```
/// use stiffspring::length::{ApproximateNewton, LengthKernel};
///
/// let rest = <ApproximateNewton as LengthKernel<f32>>::rest(1.0);
/// let (x, _) = <ApproximateNewton as LengthKernel<f32>>::measure(&[3.0, 4.0], &rest);
/// assert!((x - 4.0).abs() < 0.02);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ApproximateNewton;

impl Sealed for Approximate {}
impl Sealed for ApproximateNewton {}

/// Shared body: `NEWTON` selects the refined variant at compile time.
#[inline(always)]
fn measure<const D: usize, const NEWTON: bool>(d: &[f32; D], rest: f32) -> (f32, [f32; D]) {
    let s = <f32 as Scalar>::dot(d, d);
    // micromath's invsqrt(0) is a large finite number and d = 0 there, so the axis is
    // zero and nothing is NaN.
    let mut r = s.invsqrt();
    if NEWTON {
        r *= 1.5 - 0.5 * s * r * r;
    }
    (s * r - rest, d.map(|d| d * r))
}

macro_rules! approximate_kernel {
    ($K:ty, $name:literal, $newton:literal) => {
        impl LengthKernel<f32> for $K {
            type Rest = f32;
            const NAME: &'static str = $name;

            fn rest(length: f32) -> Self::Rest {
                length
            }

            fn rest_length(rest: &Self::Rest) -> f32 {
                *rest
            }

            #[inline(always)]
            fn measure<const D: usize>(d: &[f32; D], rest: &Self::Rest) -> (f32, [f32; D]) {
                measure::<D, $newton>(d, *rest)
            }
        }
    };
}

approximate_kernel!(Approximate, "micromath", false);
approximate_kernel!(ApproximateNewton, "micromath+newton", true);
