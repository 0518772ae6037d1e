//! `f32` and `f64`: plain IEEE arithmetic; the state and the gains in the same format.

use super::{FactorForm, RawGains, Repr, Scalar, Sealed, StateForm};

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
    (
        $F:ty, $Bits:ty, $name:literal, $max_exponent:literal, $state_exponent:literal,
        $network_exponent:literal, $min_gain:expr, $sqrt:path, $Remainder:ty,
        $carrying:ident
    ) => {
        impl Sealed for $F {}

        impl Scalar for $F {
            type State = $F;
            type Gains = FloatGains<$F>;
            type Factor = $F;
            type Coef = $F;
            type Remainder = $Remainder;
            type Band = $Bits;

            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const STATE_ZERO: Self = 0.0;
            const NAME: &'static str = $name;
            const RESOLUTION: f64 = 0.0;
            // 2^e, written out because `powi` is not in `core`.
            const MAX: f64 = f64::from_bits(((1023 + $max_exponent) as u64) << 52);
            const STATE_MAX: f64 = f64::from_bits(((1023 + $state_exponent) as u64) << 52);
            // Σ dᵢ² of three separations up to 2·bound must stay below MAX:
            // 3·(2^(e+1))² < 2^(2e+4) ≤ 2^127 (f32) or 2^1023 (f64).
            const NETWORK_MAX: f64 = f64::from_bits(((1023 + $network_exponent) as u64) << 52);

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
                // The one definition every backend shares, also evaluated at compile
                // time (`RawGains`).
                RawGains::<Self>::new(stiffness, damping).map(RawGains::get)
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
            fn spring_term(gains: &Self::Gains, x: Self) -> Self {
                gains.stiffness * x
            }
            #[inline(always)]
            fn damping_term(gains: &Self::Gains, u: Self) -> Self {
                gains.damping * u
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
            #[inline(always)]
            fn add_carrying(x: Self, r: $Remainder, u: Self) -> (Self, $Remainder) {
                $carrying::add(x, r, u)
            }
            #[inline(always)]
            fn difference_carrying(b: Self, rb: $Remainder, a: Self, ra: $Remainder) -> Self {
                $carrying::difference(b, rb, a, ra)
            }
            #[inline(always)]
            fn remainder_to_f64(r: $Remainder) -> f64 {
                $carrying::to_f64(r)
            }
            #[inline(always)]
            fn state_abs(state: Self) -> Self {
                <$F>::abs(state)
            }
            #[inline(always)]
            fn state_clamp(state: Self, bound: Self) -> Self {
                // Written so that NaN fails every comparison and lands on 0.
                if state.abs() <= bound {
                    state
                } else if state > 0.0 {
                    bound
                } else if state < 0.0 {
                    -bound
                } else {
                    0.0
                }
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
            const REPR: Repr = if <$F>::MANTISSA_DIGITS == 24 {
                Repr::F32
            } else {
                Repr::F64
            };
            const COEF_REPR: Repr = <Self as Scalar>::REPR;
            const FACTOR_FORM: FactorForm = FactorForm::Float(<Self as Scalar>::REPR);
            const STATE_FORM: StateForm = StateForm::Float(<Self as Scalar>::REPR);
            const LEAST_GAIN: f64 = $min_gain as f64;
            #[inline]
            fn factor_from_const(mantissa: i64, _shift: i32) -> Self::Factor {
                <$F>::from_bits(mantissa as $Bits)
            }
            #[inline]
            fn state_from_const(bits: i128) -> Self::State {
                <$F>::from_bits(bits as $Bits)
            }
            #[inline]
            fn gains_from_factors(stiffness: $F, damping: $F) -> Self::Gains {
                FloatGains { stiffness, damping }
            }
            #[inline]
            fn from_const_bits(bits: i64) -> Self {
                <$F>::from_bits(bits as $Bits)
            }
            #[inline]
            fn coef_from_const_bits(bits: i64) -> Self::Coef {
                <$F>::from_bits(bits as $Bits)
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
            #[inline(always)]
            fn state_mul_coef(state: Self, coef: Self) -> Self {
                state * coef
            }
            #[inline(always)]
            fn state_to_coef(state: Self, factor: Self) -> Self {
                state * factor
            }
            #[inline(always)]
            fn norm<const D: usize>(d: &[Self; D]) -> Self {
                $sqrt(Self::dot(d, d))
            }
            #[inline(always)]
            fn square_sum<const D: usize>(d: &[Self; D]) -> Self {
                Self::dot(d, d)
            }
            #[inline(always)]
            fn ratio(a: Self, b: Self) -> Self {
                // A comparison and a select, not `max` (a library call, `fmaxf`, on a
                // Cortex-M4F, which has no `vmax`).
                if b > 0.0 { a / b } else { 0.0 }
            }
            #[inline(always)]
            fn axis<const D: usize>(d: &[Self; D], length: Self) -> [Self; D] {
                // One division and D products instead of D divisions (a division is 14
                // cycles on a Cortex-M4F, a product 1).
                let inverse = if length > 0.0 { 1.0 / length } else { 0.0 };
                d.map(|d| d * inverse)
            }
        }
    };
}

// Positions up to 2^64 (f32) and 2^500 (f64); states up to 2^120 and 2^1000, which leaves
// 2^56 and 2^500 for the transient growth of a spring (see `Tuning::growth`).
/// `f32` positions in a scene carry their rounding remainder: `x + u` rounds to an ulp of
/// `x`, which grows as a network drifts from the origin, and that noise heats an undamped
/// network (measured: a free rope drifting to 10⁴ units gains 4 to 9 times its energy in
/// 10⁶ steps without the remainder, and stays within ±0.5 % with it; `tests/network_energy.rs`).
mod compensated {
    /// `(x, r) ← TwoSum(x, u + r)`: six additions, no branch, no condition on magnitudes.
    #[inline(always)]
    pub(super) fn add(x: f32, r: f32, u: f32) -> (f32, f32) {
        let y = u + r;
        let t = x + y;
        let z = t - x;
        (t, (x - (t - z)) + (y - z))
    }
    #[inline(always)]
    pub(super) fn difference(b: f32, rb: f32, a: f32, ra: f32) -> f32 {
        (b - a) + (rb - ra)
    }
    #[inline(always)]
    pub(super) fn to_f64(r: f32) -> f64 {
        r as f64
    }
}

/// `f64` positions carry nothing: an ulp of `2⁻⁵²·|x|` of noise stays far below anything
/// a network shows.
mod plain {
    #[inline(always)]
    pub(super) fn add(x: f64, _: (), u: f64) -> (f64, ()) {
        (x + u, ())
    }
    #[inline(always)]
    pub(super) fn difference(b: f64, _: (), a: f64, _: ()) -> f64 {
        b - a
    }
    #[inline(always)]
    pub(super) fn to_f64(_: ()) -> f64 {
        0.0
    }
}

float_backend!(
    f32,
    u32,
    "f32",
    64,
    120,
    60,
    f32::MIN_POSITIVE,
    libm::sqrtf,
    f32,
    compensated
);
float_backend!(
    f64,
    u64,
    "f64",
    500,
    1000,
    500,
    f64::MIN_POSITIVE,
    libm::sqrt,
    (),
    plain
);
