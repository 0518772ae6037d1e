//! `f32` and `f64`: plain IEEE arithmetic, coefficients in the same format.

use super::{Scalar, Sealed};

macro_rules! float_backend {
    ($F:ty, $name:literal, $safe_exponent:literal, $network_exponent:literal) => {
        impl Sealed for $F {}

        impl Scalar for $F {
            type Coef = $F;

            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const NAME: &'static str = $name;
            const RESOLUTION: f64 = 0.0;
            // 2^e, written out because `powi` is not in `core`: the headroom below
            // `MAX` absorbs the transient growth of any stable 2×2 map (see `SAFE_MAGNITUDE`).
            const SAFE_MAGNITUDE: f64 = f64::from_bits(((1023 + $safe_exponent) as u64) << 52);
            // Σ dᵢ² of three separations up to 2·bound must stay below MAX:
            // 3·(2^(e+1))² < 2^(2e+4) ≤ 2^127 (f32) or 2^1023 (f64).
            const NETWORK_MAGNITUDE: f64 =
                f64::from_bits(((1023 + $network_exponent) as u64) << 52);

            #[inline]
            fn from_f64(value: f64) -> Self {
                if value.is_nan() {
                    0.0
                } else {
                    // `as` saturates to ±INF; clamp first so that a finite input stays finite.
                    value.clamp(-(<$F>::MAX as f64), <$F>::MAX as f64) as $F
                }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn coef(value: f64) -> Self::Coef {
                Self::from_f64(value)
            }
            #[inline]
            fn coef_to_f64(coef: Self::Coef) -> f64 {
                coef as f64
            }
            #[inline]
            fn is_valid(self) -> bool {
                // NaN fails the comparison, infinities exceed the bound.
                (self as f64).abs() <= Self::SAFE_MAGNITUDE
            }
            #[inline(always)]
            fn add(self, rhs: Self) -> Self {
                self + rhs
            }
            #[inline(always)]
            fn sub(self, rhs: Self) -> Self {
                self - rhs
            }
            #[inline(always)]
            fn neg(self) -> Self {
                -self
            }
            #[inline(always)]
            fn abs(self) -> Self {
                // `f32::abs` is in `core` since Rust 1.85.
                <$F>::abs(self)
            }
            #[inline(always)]
            fn mul_coef(self, coef: Self::Coef) -> Self {
                self * coef
            }
            #[inline(always)]
            fn mul_coef_diff(a: Self, ca: Self::Coef, b: Self, cb: Self::Coef) -> Self {
                a * ca - b * cb
            }
            #[inline(always)]
            fn mul(self, rhs: Self) -> Self {
                self * rhs
            }
            #[inline(always)]
            fn clamp_magnitude(self, bound: Self) -> Self {
                // Written so that NaN fails every comparison and lands on 0.
                if self.abs() <= bound {
                    self
                } else if self > 0.0 {
                    bound
                } else if self < 0.0 {
                    -bound
                } else {
                    0.0
                }
            }
            #[inline(always)]
            fn dot<const D: usize>(a: &[Self; D], b: &[Self; D]) -> Self {
                let mut sum = 0.0;
                for k in 0..D {
                    sum += a[k] * b[k];
                }
                sum
            }
        }
    };
}

float_backend!(f32, "f32", 100, 60);
float_backend!(f64, "f64", 1000, 500);
