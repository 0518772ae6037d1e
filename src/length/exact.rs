//! The exact extension and axis: one square root and one reciprocal per spring.

#[cfg(any(feature = "libm", feature = "fixed"))]
use super::LengthKernel;
use super::Sealed;
#[cfg(feature = "libm")]
use super::scaled;
#[cfg(any(feature = "libm", feature = "fixed"))]
use crate::scalar::Scalar;

/// `x = |d| − L` along `n = d/|d|`, to the backend's rounding.
///
/// - `f32`, `f64` (with the `libm` feature): `libm`'s correctly rounded `sqrtf`/`sqrt`, one
///   division for `1/|d|`, then multiplies.
/// - `I16F16`, `I32F32`: the sum of squares exactly in the double-width integer, its root
///   by the `fixed` crate's `sqrt` (rounded down), and one integer division for `1/|d|`.
///
/// Without `libm` the float backends have no exact root: use [`Linearised`](super::Linearised)
/// or the `micromath` kernels there.
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

#[cfg(feature = "libm")]
macro_rules! float_exact {
    ($F:ty, $sqrt:path) => {
        impl LengthKernel<$F> for Exact {
            type Rest = $F;
            const NAME: &'static str = "exact";

            fn rest(length: f64) -> Self::Rest {
                <$F as Scalar>::from_f64(length)
            }

            fn rest_length(rest: &Self::Rest) -> f64 {
                *rest as f64
            }

            #[inline(always)]
            fn measure<const D: usize>(d: &[$F; D], rest: &Self::Rest) -> ($F, [$F; D]) {
                let length = $sqrt(<$F as Scalar>::dot(d, d));
                let inverse = super::reciprocal_or_zero!(length, $F);
                (length - rest, scaled(d, inverse))
            }
        }
    };
}

#[cfg(feature = "libm")]
float_exact!(f32, libm::sqrtf);
#[cfg(feature = "libm")]
float_exact!(f64, libm::sqrt);

#[cfg(feature = "fixed")]
mod fixed_point {
    use super::*;
    use fixed::types::{I16F16, I32F32, U32F32, U64F64};

    impl LengthKernel<I16F16> for Exact {
        type Rest = I16F16;
        const NAME: &'static str = "exact";

        fn rest(length: f64) -> Self::Rest {
            I16F16::from_f64(length)
        }

        fn rest_length(rest: &Self::Rest) -> f64 {
            rest.to_f64()
        }

        #[inline(always)]
        fn measure<const D: usize>(d: &[I16F16; D], rest: &Self::Rest) -> (I16F16, [I16F16; D]) {
            // Σ dᵢ² of Q16.16 raw values is a Q32.32 number, exact in u64 for D ≤ 3; its
            // root, as U32F32, has the length's Q16.16 bits 16 places up.
            let mut sum = 0u64;
            for v in d {
                let r = v.to_bits().unsigned_abs() as u64;
                sum = sum.saturating_add(r * r);
            }
            let length_bits = (U32F32::from_bits(sum).sqrt().to_bits() >> 16) as i64;
            let length = I16F16::from_bits(length_bits.min(i32::MAX as i64) as i32);
            // 1/|d| as 2^64/raw: dᵢ_raw·2^64/|d|_raw is the axis component's Q16.16 bits
            // shifted up by 48, and |dᵢ|/|d| ≤ 1 keeps it in range. Zero length: zero axis.
            let inverse = if length_bits > 0 {
                (u64::MAX / length_bits as u64) as i128
            } else {
                0
            };
            let mut n = [I16F16::ZERO; D];
            for (n, v) in n.iter_mut().zip(d) {
                let bits = (v.to_bits() as i128 * inverse) >> 48;
                *n = I16F16::from_bits(bits.clamp(i32::MIN as i128, i32::MAX as i128) as i32);
            }
            (length.sub(*rest), n)
        }
    }

    impl LengthKernel<I32F32> for Exact {
        type Rest = I32F32;
        const NAME: &'static str = "exact";

        fn rest(length: f64) -> Self::Rest {
            I32F32::from_f64(length)
        }

        fn rest_length(rest: &Self::Rest) -> f64 {
            rest.to_f64()
        }

        #[inline(always)]
        fn measure<const D: usize>(d: &[I32F32; D], rest: &Self::Rest) -> (I32F32, [I32F32; D]) {
            // As for I16F16, one size up: Q64.64 sum of squares in u128, U64F64 root.
            let mut sum = 0u128;
            for v in d {
                let r = v.to_bits().unsigned_abs() as u128;
                sum = sum.saturating_add(r * r);
            }
            let length_bits = (U64F64::from_bits(sum).sqrt().to_bits() >> 32) as i128;
            let length = I32F32::from_bits(length_bits.min(i64::MAX as i128) as i64);
            // 1/|d| in Q32.64 (2^96 / raw would overflow u128 only for raw < 2^-32: never,
            // raw ≥ 1 here); the axis component dᵢ·(1/|d|) >> 64.
            let inverse = if length_bits > 0 {
                (1u128 << 96) / length_bits as u128
            } else {
                0
            };
            let mut n = [I32F32::ZERO; D];
            for (n, v) in n.iter_mut().zip(d) {
                // |raw| < 2^63 and inverse ≤ 2^96: the product needs up to 159 bits, so
                // split the multiplier into 64-bit halves to stay in i128.
                let r = v.to_bits() as i128;
                let high = r * (inverse >> 64) as i128;
                let low = (r * (inverse & u64::MAX as u128) as i128) >> 64;
                let bits = high.saturating_add(low);
                *n = I32F32::from_bits(bits.clamp(i64::MIN as i128, i64::MAX as i128) as i64);
            }
            (length.sub(*rest), n)
        }
    }
}
