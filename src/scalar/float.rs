//! `f32` and `f64`: plain IEEE arithmetic; the state and the gains in the same format.

use super::{Scalar, Sealed};

/// The gains `(C_k, C_d)` of a spring in a float backend.
///
/// ```
/// use stiffspring::Scalar;
/// let g = f32::gains(0.5, 0.25).unwrap();
/// assert_eq!(f32::gains_to_f64(&g), (0.5, 0.25));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FloatGains<F> {
    pub(crate) stiffness: F,
    pub(crate) damping: F,
}

macro_rules! float_backend {
    ($F:ty, $Bits:ty, $name:literal, $max_exponent:literal, $state_exponent:literal, $min_gain:expr) => {
        impl Sealed for $F {}

        impl Scalar for $F {
            type State = $F;
            type Gains = FloatGains<$F>;
            type Factor = $F;
            type Coef = $F;
            type Band = $Bits;

            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const STATE_ZERO: Self = 0.0;
            const NAME: &'static str = $name;
            const RESOLUTION: f64 = 0.0;
            // 2^e, written out because `powi` is not in `core`.
            const MAX: f64 = f64::from_bits(((1023 + $max_exponent) as u64) << 52);
            const STATE_MAX: f64 = f64::from_bits(((1023 + $state_exponent) as u64) << 52);

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
            fn gains(stiffness: f64, damping: f64) -> Option<Self::Gains> {
                let (k, d) = (Self::from_f64(stiffness), Self::from_f64(damping));
                // A gain that becomes subnormal loses its relative precision, one that
                // becomes zero its effect: neither is the tuning that was asked for.
                let lost = |c: f64, g: $F| c != 0.0 && g.abs() < $min_gain;
                if lost(stiffness, k) || lost(damping, d) {
                    None
                } else {
                    Some(FloatGains {
                        stiffness: k,
                        damping: d,
                    })
                }
            }
            #[inline]
            fn gains_to_f64(gains: &Self::Gains) -> (f64, f64) {
                (gains.stiffness as f64, gains.damping as f64)
            }
            #[inline]
            fn factor(value: f64) -> Self::Factor {
                Self::from_f64(value)
            }
            #[inline(always)]
            fn widen(self) -> Self::State {
                self
            }
            #[inline(always)]
            fn narrow(state: Self::State) -> Self {
                state
            }
            #[inline]
            fn state_from_f64(value: f64) -> Self::State {
                Self::from_f64(value)
            }
            #[inline]
            fn state_to_f64(state: Self::State) -> f64 {
                state as f64
            }
            #[inline(always)]
            fn advance(gains: &Self::Gains, x: &mut Self, v: &mut Self) {
                let u = *v - gains.stiffness * *x;
                *x += u;
                *v = u - gains.damping * u;
            }
            #[inline(always)]
            fn state_add(a: Self, b: Self) -> Self {
                a + b
            }
            #[inline(always)]
            fn state_sub(a: Self, b: Self) -> Self {
                a - b
            }
            #[inline(always)]
            fn scale(state: Self, factor: Self) -> Self {
                state * factor
            }
            #[inline(always)]
            fn within(state: Self, bound: Self) -> bool {
                state.abs() <= bound
            }
            #[inline]
            fn band(bound: Self) -> $Bits {
                bound.to_bits() << 1
            }
            #[inline(always)]
            fn in_band(state: Self, band: $Bits) -> bool {
                // The sign shifted out, the bits of a magnitude order as the magnitude
                // (±0 is 0; NaN is above +∞, so never inside a finite or infinite band).
                (state.to_bits() << 1) <= band
            }
            #[inline]
            fn coef(value: f64) -> Self::Coef {
                Self::from_f64(value)
            }
            #[inline]
            fn coef_to_f64(coef: Self::Coef) -> f64 {
                coef as f64
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
            fn mul(self, rhs: Self) -> Self {
                self * rhs
            }
            #[inline(always)]
            fn mul_coef(self, coef: Self::Coef) -> Self {
                self * coef
            }
            #[inline(always)]
            fn mul_coef_diff(a: Self, ca: Self, b: Self, cb: Self) -> Self {
                a * ca - b * cb
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

// Positions up to 2^64 (f32) and 2^500 (f64); states up to 2^120 and 2^1000, which leaves
// 2^56 and 2^500 for the transient growth of a spring (see `Tuning::growth`).
float_backend!(f32, u32, "f32", 64, 120, f32::MIN_POSITIVE);
float_backend!(f64, u64, "f64", 500, 1000, f64::MIN_POSITIVE);
