//! `I16F16` and `I32F32`: saturating fixed point with a wide internal state.
//!
//! | backend | position | state | gains, factors | fractions (`Coef`) |
//! |---|---|---|---|---|
//! | `I16F16` | Q16.16 (`i32`) | Q24.40 (`i64`) | 30-bit mantissa, shift | `I3F29` |
//! | `I32F32` | Q32.32 (`i64`) | Q64.64 (`i128`) | 62-bit mantissa, shift | `I3F61` |
//!
//! The state keeps 24 (resp. 32) bits below a position's last bit and 8 (resp. 32) bits
//! of range above its top, so that a fling whose exact start needs a step velocity beyond
//! the position range (a heavily overdamped spring extrapolated one step back) still
//! fits. Positions are read by rounding the state to nearest and saturating.
//!
//! The `fixed` crate provides the types, the conversions and the saturating add; the
//! products are taken on the raw bits, with the rounding chosen in the parent module.

use super::fast::{FastGains, broad_step, narrow_step};
use super::raw_state::{encode_mantissa, fixed_state};
use super::wide::{broad, narrow};
use super::{FactorForm, RawGains, Repr, Scalar, Sealed, StateForm};
use fixed::types::{I3F29, I3F61, I16F16, I32F32};

/// The gains `(C_k, C_d)` of a spring in a fixed-point backend: each a mantissa and an
/// exponent, `C = mantissa / 2^shift`.
///
/// ```
/// use stiffspring::{I16F16, Scalar};
/// let g = I16F16::gains(3.9e-7, 1.26e-4).unwrap();
/// let (k, d) = I16F16::gains_to_f64(&g);
/// assert!((k / 3.9e-7 - 1.0).abs() < 1e-6 && (d / 1.26e-4 - 1.0).abs() < 1e-8);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedGains<M> {
    pub(crate) stiffness: FixedFactor<M>,
    pub(crate) damping: FixedFactor<M>,
    /// The same gains prepared for the step's fast path (see `wide::FastGains`).
    pub(crate) fast: FastGains<M>,
}

/// A factor of any magnitude in a fixed-point backend: `mantissa / 2^shift`.
///
/// ```
/// use stiffspring::{I16F16, Scalar};
/// let f = I16F16::factor(1e-4);
/// let one = I16F16::from_num(1).widen();
/// let scaled = I16F16::scale(one, f);
/// assert!((I16F16::state_to_f64(scaled) - 1e-4).abs() < 1e-11);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedFactor<M> {
    pub(crate) mantissa: M,
    pub(crate) shift: i32,
}

/// Rounds `p / 2^SHIFT` toward zero and saturates to the narrow type: the products of a
/// position and a fraction (`Coef`).
macro_rules! narrow_fn {
    ($name:ident, $Wide:ty, $WideU:ty, $Narrow:ty, $SHIFT:expr) => {
        #[inline(always)]
        const fn $name(p: $Wide) -> $Narrow {
            // `2^SHIFT − 1` when `p < 0`, else 0: the sign mask shifted down logically.
            let bias = ((p >> (<$Wide>::BITS - 1)) as $WideU >> (<$Wide>::BITS - $SHIFT)) as $Wide;
            let r = (p + bias) >> $SHIFT;
            let low = r as $Narrow;
            let high = (r >> <$Narrow>::BITS) as $Narrow;
            if high != low >> (<$Narrow>::BITS - 1) {
                (high >> (<$Narrow>::BITS - 1)) ^ <$Narrow>::MAX
            } else {
                low
            }
        }
    };
}

narrow_fn!(narrow_q29, i64, u64, i32, 29);
narrow_fn!(narrow_q61, i128, u128, i64, 61);
narrow_fn!(narrow_q16, i64, u64, i32, 16);
narrow_fn!(narrow_q32, i128, u128, i64, 32);

macro_rules! fixed_backend {
    (
        $S:ty, $Bits:ty, $State:ty, $StateU:ty, $Half:ty, $Coef:ty, $Wide:ty,
        $arith:ident, $narrow:ident, $narrow_self:ident, $guard:expr, $name:literal,
        $fast:expr, $fast_step:expr, $off_fast_step:path, $mul:path
    ) => {
        impl Sealed for $S {}

        impl Scalar for $S {
            type State = $State;
            type Gains = FixedGains<$Half>;
            type Factor = FixedFactor<$Half>;
            type Coef = $Coef;
            type Remainder = ();
            type Band = ($State, $StateU);

            const ZERO: Self = <$S>::ZERO;
            const ONE: Self = <$S>::ONE;
            const STATE_ZERO: $State = 0;
            const NAME: &'static str = $name;
            const RESOLUTION: f64 = 1.0 / (1u64 << <$S>::FRAC_NBITS) as f64;
            const MAX: f64 = (1u64 << (<$S>::INT_NBITS - 1)) as f64;
            const NETWORK_MAX: f64 = <Self as Scalar>::MAX;
            const STATE_MAX: f64 = {
                // 2^(state integer bits − 1), written out: the state has
                // FRAC_NBITS + GUARD fractional bits.
                let int_bits = <$State>::BITS - <$S>::FRAC_NBITS - $guard;
                f64::from_bits(((1023 + int_bits - 1) as u64) << 52)
            };

            #[inline]
            fn from_f64(value: f64) -> Self {
                // `saturating_from_num` panics on NaN; the library never does.
                if value.is_nan() {
                    <$S>::ZERO
                } else {
                    <$S>::saturating_from_num(value)
                }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self.to_num::<f64>()
            }
            fn gains(stiffness: f64, damping: f64) -> Option<Self::Gains> {
                // The one definition every backend shares, also evaluated at compile
                // time (`RawGains`).
                RawGains::<Self>::new(stiffness, damping).map(RawGains::get)
            }
            fn gains_to_f64(gains: &Self::Gains) -> (f64, f64) {
                (
                    $arith::decode(gains.stiffness.mantissa, gains.stiffness.shift),
                    $arith::decode(gains.damping.mantissa, gains.damping.shift),
                )
            }
            fn factor(value: f64) -> Self::Factor {
                let (mantissa, shift) = encode_mantissa(value, <$Half>::BITS);
                FixedFactor {
                    mantissa: mantissa as $Half,
                    shift,
                }
            }
            #[inline(always)]
            fn widen(self) -> $State {
                (self.to_bits() as $State) << $guard
            }
            #[inline(always)]
            fn narrow(state: $State) -> Self {
                // Round to nearest (ties up), then saturate to the position's range.
                let r = state.saturating_add(1 << ($guard - 1)) >> $guard;
                <$S>::from_bits(r.clamp(<$Bits>::MIN as $State, <$Bits>::MAX as $State) as $Bits)
            }
            fn state_from_f64(value: f64) -> $State {
                fixed_state(value, <$State>::BITS, <$S>::FRAC_NBITS + $guard) as $State
            }
            fn state_to_f64(state: $State) -> f64 {
                state as f64 / (1u64 << (<$S>::FRAC_NBITS + $guard - 32)) as f64 / 4_294_967_296.0
            }
            #[inline(always)]
            fn spring_term(gains: &Self::Gains, x: $State) -> $State {
                let k = gains.stiffness;
                $arith::mul_shift::<false>(x, k.mantissa, k.shift)
            }
            #[inline(always)]
            fn damping_term(gains: &Self::Gains, u: $State) -> $State {
                let d = gains.damping;
                $arith::mul_shift::<true>(u, d.mantissa, d.shift)
            }
            #[inline(always)]
            fn advance(gains: &Self::Gains, x: &mut $State, v: &mut $State) {
                if !$fast_step(&gains.fast, x, v) {
                    $off_fast_step(gains, x, v);
                }
            }
            #[inline(always)]
            fn state_add(a: $State, b: $State) -> $State {
                a.saturating_add(b)
            }
            #[inline(always)]
            fn state_sub(a: $State, b: $State) -> $State {
                a.saturating_sub(b)
            }
            #[inline(always)]
            fn scale(state: $State, factor: Self::Factor) -> $State {
                $arith::mul_shift::<false>(state, factor.mantissa, factor.shift)
            }
            #[inline(always)]
            fn within(state: $State, bound: $State) -> bool {
                // −b ≤ x ≤ b ⟺ 0 ≤ x + b ≤ 2b, one unsigned comparison; the bound is at
                // most STATE_MAX/2 by construction, so 2b does not overflow.
                (state.wrapping_add(bound) as $StateU) <= (bound as $StateU).wrapping_mul(2)
            }
            #[inline(always)]
            fn add_carrying(x: $State, _: (), u: $State) -> ($State, ()) {
                (x.saturating_add(u), ())
            }
            #[inline(always)]
            fn difference_carrying(b: $State, _: (), a: $State, _: ()) -> $State {
                b.saturating_sub(a)
            }
            #[inline(always)]
            fn remainder_to_f64(_: ()) -> f64 {
                0.0
            }
            #[inline(always)]
            fn state_abs(state: $State) -> $State {
                state.saturating_abs()
            }
            #[inline(always)]
            fn state_clamp(state: $State, _bound: $State) -> $State {
                state
            }
            #[inline]
            fn band(bound: $State) -> ($State, $StateU) {
                (bound, (bound as $StateU).wrapping_mul(2))
            }
            #[inline(always)]
            fn in_band(state: $State, band: ($State, $StateU)) -> bool {
                // As `within`, with `2b` computed at set-up.
                (state.wrapping_add(band.0) as $StateU) <= band.1
            }
            #[inline]
            fn coef(value: f64) -> Self::Coef {
                // `saturating_from_num` panics on NaN; the library never does.
                if value.is_nan() {
                    <$Coef>::ZERO
                } else {
                    <$Coef>::saturating_from_num(value)
                }
            }
            #[inline]
            fn coef_to_f64(coef: Self::Coef) -> f64 {
                coef.to_num::<f64>()
            }
            const REPR: Repr = Repr::Fixed {
                bits: <$Bits>::BITS,
                frac: <$S>::FRAC_NBITS,
            };
            const COEF_REPR: Repr = Repr::Fixed {
                bits: <$Bits>::BITS,
                frac: <$Coef>::FRAC_NBITS,
            };
            #[inline]
            fn from_const_bits(bits: i64) -> Self {
                <$S>::from_bits(bits as $Bits)
            }
            const FACTOR_FORM: FactorForm = FactorForm::Mantissa {
                bits: <$Half>::BITS,
            };
            const STATE_FORM: StateForm = StateForm::Fixed {
                bits: <$State>::BITS,
                frac: <$S>::FRAC_NBITS + $guard,
            };
            // The state's last bit over a position's: 2^−guard.
            const LEAST_GAIN: f64 = Self::RESOLUTION / (1u64 << $guard) as f64 / Self::RESOLUTION;
            #[inline]
            fn factor_from_const(mantissa: i64, shift: i32) -> Self::Factor {
                FixedFactor {
                    mantissa: mantissa as $Half,
                    shift,
                }
            }
            #[inline]
            fn state_from_const(bits: i128) -> Self::State {
                bits as $State
            }
            #[inline]
            fn gains_from_factors(k: Self::Factor, d: Self::Factor) -> Self::Gains {
                FixedGains {
                    stiffness: k,
                    damping: d,
                    fast: $fast(k, d),
                }
            }
            #[inline]
            fn coef_from_const_bits(bits: i64) -> Self::Coef {
                <$Coef>::from_bits(bits as $Bits)
            }
            #[inline(always)]
            fn add(self, rhs: Self) -> Self {
                self.saturating_add(rhs)
            }
            #[inline(always)]
            fn sub(self, rhs: Self) -> Self {
                self.saturating_sub(rhs)
            }
            #[inline(always)]
            fn neg(self) -> Self {
                self.saturating_neg()
            }
            #[inline(always)]
            fn abs(self) -> Self {
                self.saturating_abs()
            }
            #[inline(always)]
            fn mul(self, rhs: Self) -> Self {
                <$S>::from_bits($narrow_self($mul(self.to_bits(), rhs.to_bits())))
            }
            #[inline(always)]
            fn mul_coef(self, coef: Self::Coef) -> Self {
                <$S>::from_bits($narrow($mul(self.to_bits(), coef.to_bits())))
            }
            #[inline(always)]
            fn mul_coef_diff(a: Self, ca: Self::Coef, b: Self, cb: Self::Coef) -> Self {
                let p = $mul(a.to_bits(), ca.to_bits()) - $mul(b.to_bits(), cb.to_bits());
                <$S>::from_bits($narrow(p))
            }
            #[inline(always)]
            fn dot<const D: usize>(a: &[Self; D], b: &[Self; D]) -> Self {
                // Exact in the double-width integer for D ≤ 2 (each product is below
                // 2^(2·BITS−2)); for larger D the sum saturates instead of wrapping.
                let mut sum: $Wide = 0;
                for k in 0..D {
                    sum = sum.saturating_add($mul(a[k].to_bits(), b[k].to_bits()));
                }
                <$S>::from_bits($narrow_self(sum))
            }
            #[inline(always)]
            fn state_mul_coef(state: $State, coef: Self::Coef) -> $State {
                $arith::mul_shift::<false>(state, coef.to_bits(), <$Coef>::FRAC_NBITS as i32)
            }
            #[inline(always)]
            fn state_to_coef(state: $State, factor: Self::Factor) -> Self::Coef {
                // The state's unit is 2^(FRAC + guard), a fraction's 2^(Coef FRAC).
                let shift =
                    factor.shift + (<$S>::FRAC_NBITS + $guard) as i32 - <$Coef>::FRAC_NBITS as i32;
                let v = $arith::mul_shift::<false>(state, factor.mantissa, shift);
                <$Coef>::from_bits(v.clamp(<$Half>::MIN as $State, <$Half>::MAX as $State) as $Half)
            }
            fn norm<const D: usize>(d: &[$State; D]) -> $State {
                <$State as WideGeometry>::norm(d)
            }
            #[inline(always)]
            fn square_sum<const D: usize>(d: &[$State; D]) -> $State {
                let mut sum: $State = 0;
                for v in d {
                    sum = sum.saturating_add(<$State as WideGeometry>::square(*v));
                }
                sum
            }
            fn ratio(a: $State, b: $State) -> Self::Coef {
                <$Coef>::from_bits(<$State as WideGeometry>::ratio(a, b))
            }
            #[inline(always)]
            fn axis<const D: usize>(d: &[$State; D], length: $State) -> [Self::Coef; D] {
                <$State as WideGeometry>::axis(d, length).map(<$Coef>::from_bits)
            }
        }
    };
}

/// Lengths and ratios on the raw state integers, whose unit is `2^UNIT`.
trait WideGeometry: Sized {
    /// The fraction's raw type (`I3F29`'s `i32`, `I3F61`'s `i64`).
    type Fraction;
    /// `v²` in state units, rounded down, saturating.
    fn square(v: Self) -> Self;
    /// `√(Σ dᵢ²)`, rounded down, saturating.
    fn norm<const D: usize>(d: &[Self; D]) -> Self;
    /// `a/b` as a fraction (toward zero, saturating), 0 for `b ≤ 0`.
    fn ratio(a: Self, b: Self) -> Self::Fraction;
    /// `dᵢ/length` for `|dᵢ| ≤ length`, as fractions; zeros for `length ≤ 0`.
    fn axis<const D: usize>(d: &[Self; D], length: Self) -> [Self::Fraction; D]
    where
        Self: Copy,
    {
        d.map(|d| Self::ratio(d, length))
    }
}

impl WideGeometry for i64 {
    type Fraction = i32;
    fn axis<const D: usize>(d: &[i64; D], length: i64) -> [i32; D] {
        if length <= 0 {
            return [0; D];
        }
        // r = ⌊2^93/length⌋ once; dᵢ·r/2^64 is dᵢ/length in Q3.29, and |dᵢ| ≤ length keeps
        // the product below 2^93. Truncating r and the product rounds toward −∞ by at most
        // two Q3.29 last bits, which a unit axis does not notice.
        let r = (1u128 << 93) / length as u128;
        d.map(|v| {
            let q = (v as i128 * r as i128) >> 64;
            q.clamp(i32::MIN as i128, i32::MAX as i128) as i32
        })
    }
    fn square(v: i64) -> i64 {
        // Q24.40: v² has 80 fractional bits; the square of any i64 fits i128.
        let p = (v as i128 * v as i128) >> 40;
        p.min(i64::MAX as i128) as i64
    }
    fn norm<const D: usize>(d: &[i64; D]) -> i64 {
        // Σ dᵢ² of raw values is the squared length with 80 fractional bits, exact in
        // u128 for D ≤ 3 (each square is below 2^126); its root has 40, the state's.
        let mut sum = 0u128;
        for v in d {
            let r = v.unsigned_abs() as u128;
            sum = sum.saturating_add(r * r);
        }
        sum.isqrt().min(i64::MAX as u128) as i64
    }
    fn ratio(a: i64, b: i64) -> i32 {
        if b <= 0 {
            return 0;
        }
        // a·2^29/b, toward zero (integer division truncates), saturated to Q3.29.
        let q = ((a as i128) << 29) / b as i128;
        q.clamp(i32::MIN as i128, i32::MAX as i128) as i32
    }
}

impl WideGeometry for i128 {
    type Fraction = i64;
    fn square(v: i128) -> i128 {
        // Q64.64: v²/2^64 with v = h·2^64 + l is h²·2^64 + 2hl + ⌊l²/2^64⌋.
        let m = v.unsigned_abs();
        let (h, l) = (m >> 64, m & u64::MAX as u128);
        let l2 = (l * l) >> 64;
        let sum = h
            .checked_mul(h)
            .and_then(|hh| hh.checked_mul(1 << 64))
            .and_then(|hh| (2 * h).checked_mul(l).and_then(|hl| hh.checked_add(hl)))
            .and_then(|s| s.checked_add(l2));
        match sum {
            Some(s) if s <= i128::MAX as u128 => s as i128,
            _ => i128::MAX,
        }
    }
    fn norm<const D: usize>(d: &[i128; D]) -> i128 {
        // Shift every component down until the largest is below 2^62, so that the sum of
        // squares fits u128; the root shifts back up. Exact for separations below 2^62
        // raw (2^−2 units), 62 significant bits beyond.
        let largest = d.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
        let shift = (128 - largest.leading_zeros()).saturating_sub(62);
        let mut sum = 0u128;
        for v in d {
            let r = v.unsigned_abs() >> shift;
            sum = sum.saturating_add(r * r);
        }
        let root = sum.isqrt();
        if root.leading_zeros() <= shift {
            i128::MAX
        } else {
            (root << shift).min(i128::MAX as u128) as i128
        }
    }
    fn ratio(a: i128, b: i128) -> i64 {
        if b <= 0 {
            return 0;
        }
        // Scale both down until b < 2^64; |a| ≥ 4b saturates, else (a << 61)/b fits.
        let shift = (128 - b.leading_zeros()).saturating_sub(64);
        let (a, b) = (a >> shift, b >> shift);
        if b == 0 {
            return 0;
        }
        if a.unsigned_abs() >= 4 * b.unsigned_abs() {
            return if a > 0 { i64::MAX } else { i64::MIN };
        }
        (((a << 61) / b) as i64).clamp(i64::MIN, i64::MAX)
    }
}

/// The `I16F16` step off its fast path: gains of `C ≥ 2⁻³` (the damping of a UI spring
/// at 60 Hz), and states beyond the fast path's headroom of `2^16` units, which it
/// scales into it. It takes every gain `I16F16` accepts, so the step links no general
/// product. Cold, so that the fast path around its call stays as short as without it.
#[cold]
#[inline(never)]
fn narrow_lifted_step(gains: &FixedGains<i32>, x: &mut i64, v: &mut i64) {
    let shifts = (gains.stiffness.shift, gains.damping.shift);
    narrow_step::advance_lifted(&gains.fast, shifts, x, v);
}

/// The `I32F32` step off its fast path: any gains, any state, with the wide products
/// and saturating sums.
#[cold]
#[inline(never)]
fn broad_general_step(gains: &FixedGains<i64>, x: &mut i128, v: &mut i128) {
    /// One copy of the saturating product for both of the step's roundings.
    #[inline(never)]
    fn product(x: i128, m: i64, shift: i32, away: bool) -> i128 {
        broad::mul_shift_rounding(x, m, shift, away)
    }
    let (k, d) = (gains.stiffness, gains.damping);
    let u = v.saturating_sub(product(*x, k.mantissa, k.shift, false));
    *x = x.saturating_add(u);
    *v = u.saturating_sub(product(u, d.mantissa, d.shift, true));
}

fixed_backend!(
    I16F16,
    i32,
    i64,
    u64,
    i32,
    I3F29,
    i64,
    narrow,
    narrow_q29,
    narrow_q16,
    24,
    "I16F16",
    |k: FixedFactor<i32>, d: FixedFactor<i32>| {
        FastGains::narrow((k.mantissa, k.shift), (d.mantissa, d.shift))
    },
    narrow_step::advance,
    narrow_lifted_step,
    super::widening::mul_i32
);
fixed_backend!(
    I32F32,
    i64,
    i128,
    u128,
    i64,
    I3F61,
    i128,
    broad,
    narrow_q61,
    narrow_q32,
    32,
    "I32F32",
    |k: FixedFactor<i64>, d: FixedFactor<i64>| {
        FastGains::broad((k.mantissa, k.shift), (d.mantissa, d.shift))
    },
    broad_step::advance,
    broad_general_step,
    super::widening::mul_i64
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn state_has_guard_bits_and_headroom() {
        assert_eq!(I16F16::STATE_MAX, 8_388_608.0); // 2^23 units
        assert_eq!(I32F32::STATE_MAX, 9_223_372_036_854_775_808.0); // 2^63 units
        let lsb = I16F16::from_bits(1).widen();
        assert_eq!(lsb, 1 << 24);
        assert_eq!(I16F16::narrow(lsb / 2), I16F16::from_bits(1)); // ties up
        assert_eq!(I16F16::narrow(lsb / 2 - 1), I16F16::ZERO);
        assert_eq!(I16F16::narrow(i64::MAX), I16F16::MAX);
        assert_eq!(I16F16::narrow(i64::MIN), I16F16::MIN);
        assert_eq!(I32F32::narrow(i128::MIN), I32F32::MIN);
        assert_eq!(
            I16F16::state_to_f64(I16F16::state_from_f64(-1234.5)),
            -1234.5
        );
        assert_eq!(I32F32::state_to_f64(I32F32::state_from_f64(1e9)), 1e9);
    }

    #[test]
    fn a_step_rounds_the_spring_toward_zero_and_the_damping_away() {
        // C_k = 0.5, C_d = 0.5 from x = 3 state LSB, ũ = 0: the spring term 1.5 truncates
        // to 1 (u = −1, x = 2), the damping term 0.5 rounds away to 1 (ũ = 0).
        let g = I16F16::gains(0.5, 0.5).unwrap();
        let (mut x, mut v) = (3i64, 0i64);
        I16F16::advance(&g, &mut x, &mut v);
        assert_eq!((x, v), (2, 0));
        let (mut x, mut v) = (-3i64, 0i64);
        I16F16::advance(&g, &mut x, &mut v);
        assert_eq!((x, v), (-2, 0));
        let g = I32F32::gains(0.5, 0.5).unwrap();
        let (mut x, mut v) = (-3i128, 0i128);
        I32F32::advance(&g, &mut x, &mut v);
        assert_eq!((x, v), (-2, 0));
    }

    #[test]
    fn gains_below_the_state_resolution_are_refused() {
        assert!(I16F16::gains(1e-8, 0.1).is_none()); // C_k < 2^−24
        assert!(I16F16::gains(1e-7, 0.1).is_some());
        assert!(I32F32::gains(1e-10, 0.1).is_none()); // C_k < 2^−32
        assert!(I32F32::gains(1e-9, 0.1).is_some());
        assert!(I16F16::gains(0.0, 0.0).is_some());
    }

    #[test]
    fn i16f16_takes_the_single_spring_region_and_no_more() {
        // The lifted step takes C_k < 4 and C_d < 2 (the exact region's bounds,
        // `Tuning::from_coefficients_extended`), each zero or at least 2^−33.
        for (k, d, taken) in [
            (3.999, 0.0, true),
            (4.0, 0.0, false),
            (0.5, 1.999, true),
            (0.5, 2.0, false),
            (0.05, 0.3, true),
            (0.01, 2e-10, true),
            (0.01, 1e-10, false), // C_d < 2^−33
            (-0.1, 0.3, false),
        ] {
            assert_eq!(I16F16::gains(k, d).is_some(), taken, "{k} {d}");
        }
        // I32F32 keeps its general step: any magnitude.
        assert!(I32F32::gains(4.0, 2.0).is_some());
    }

    #[test]
    fn a_ui_spring_steps_as_the_saturating_arithmetic_does() {
        // C_k = 0.05, C_d = 0.3 (a UI spring at 60 Hz) takes the lifted step; it agrees
        // with the saturating products of `spring_term` and `damping_term`.
        let g = I16F16::gains(0.05, 0.3).unwrap();
        assert_eq!(g.fast.headroom, 0);
        let (mut x, mut v) = (-(37i64 << 40) + 12_345, 5i64 << 38);
        for _ in 0..500 {
            let u = I16F16::state_sub(v, I16F16::spring_term(&g, x));
            let (ex, ev) = (
                I16F16::state_add(x, u),
                I16F16::state_sub(u, I16F16::damping_term(&g, u)),
            );
            I16F16::advance(&g, &mut x, &mut v);
            assert_eq!((x, v), (ex, ev));
        }
        assert!(x.abs() < 1 << 24, "{x}"); // at rest within one position bit
    }

    #[test]
    fn products_of_positions_truncate_and_saturate() {
        let a = I16F16::from_num(1.5);
        let b = I16F16::from_num(-2.25);
        assert_eq!(a.mul(b), I16F16::from_num(-3.375));
        assert_eq!(
            I16F16::from_bits(-1).mul(I16F16::from_num(0.5)),
            I16F16::ZERO
        );
        assert_eq!(I16F16::MAX.mul(I16F16::MAX), I16F16::MAX);
        let d = [I16F16::from_num(3), I16F16::from_num(4)];
        assert_eq!(I16F16::dot(&d, &d), I16F16::from_num(25));
        assert_eq!(I32F32::MIN.mul(I32F32::MIN), I32F32::MAX);
        assert_eq!(narrow_q29((1i64 << 29) - 1), 0);
        assert_eq!(narrow_q29(-(1i64 << 29) + 1), 0);
        assert_eq!(narrow_q61(-(3i128 << 61) + 1), -2);
    }
}
