//! `I16F16` and `I32F32`: saturating fixed point with high-precision coefficients.
//!
//! | backend  | position   | coefficient | product        |
//! |----------|------------|-------------|----------------|
//! | `I16F16` | `i32`, Q16.16 | `I3F29` (`i32`) | `i64`, exact |
//! | `I32F32` | `i64`, Q32.32 | `I3F61` (`i64`) | `i128`, exact |
//!
//! Three integer bits in the coefficient cover `C_k < 4`, the top of the single-spring
//! stability region (`C_k + 2·C_d < 4`), and `1 − C_d ∈ (−1, 1]`. The difference of two
//! products cannot overflow the double-width integer: each factor is at most `2³¹`
//! (resp. `2⁶³`) in magnitude, so each product is at most `2⁶²` (resp. `2¹²⁶`), and the
//! two extremes cannot both be reached with opposite signs because the positive end of
//! each signed format is one LSB short of the negative end.
//!
//! The `fixed` crate provides the types, the conversions and the saturating add, but its
//! products round toward −∞ (which leaves limit cycles) and it has no "sum of two products, rounded once". The
//! products here are therefore taken on the raw bits, with the rounding chosen in the
//! [parent module](super).

use super::{Scalar, Sealed};
use fixed::types::{I3F29, I3F61, I16F16, I32F32};

/// Rounds `p / 2^SHIFT` toward zero and saturates to the narrow type.
///
/// The arithmetic shift floors; adding `2^SHIFT − 1` to a negative `p` first (the mask is
/// all ones exactly when `p < 0`) turns that into truncation toward zero on both sides.
///
/// The range test works on the two halves of `r`: it fits the narrow type exactly when
/// its high half is the sign extension of its low half, and the saturated value,
/// `MAX` or `MIN` by the sign of the high half, is `(high >> (N − 1)) ^ MAX`. On a
/// 32-bit core this is a compare and two conditional instructions, where the two
/// double-width comparisons against `MAX` and `MIN` took a dozen.
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
    ($S:ty, $Coef:ty, $Wide:ty, $narrow:ident, $narrow_self:ident, $name:literal) => {
        impl Sealed for $S {}

        impl Scalar for $S {
            type Coef = $Coef;

            const ZERO: Self = <$S>::ZERO;
            const ONE: Self = <$S>::ONE;
            const NAME: &'static str = $name;
            const RESOLUTION: f64 = 1.0 / (1u64 << <$S>::FRAC_NBITS) as f64;
            const NETWORK_MAGNITUDE: f64 = Self::SAFE_MAGNITUDE;
            const SAFE_MAGNITUDE: f64 = (1u64 << <$S>::INT_NBITS - 1) as f64;

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
            #[inline]
            fn is_valid(self) -> bool {
                true
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
            fn mul_coef(self, coef: Self::Coef) -> Self {
                <$S>::from_bits($narrow(self.to_bits() as $Wide * coef.to_bits() as $Wide))
            }
            #[inline(always)]
            fn mul_coef_diff(a: Self, ca: Self::Coef, b: Self, cb: Self::Coef) -> Self {
                let p = a.to_bits() as $Wide * ca.to_bits() as $Wide
                    - b.to_bits() as $Wide * cb.to_bits() as $Wide;
                <$S>::from_bits($narrow(p))
            }
            #[inline(always)]
            fn mul(self, rhs: Self) -> Self {
                <$S>::from_bits($narrow_self(
                    self.to_bits() as $Wide * rhs.to_bits() as $Wide,
                ))
            }
            #[inline(always)]
            fn clamp_magnitude(self, _bound: Self) -> Self {
                self
            }
            #[inline(always)]
            fn dot<const D: usize>(a: &[Self; D], b: &[Self; D]) -> Self {
                // Exact in the double-width integer for D ≤ 2 (each product is below
                // 2^(2·BITS−2)); for larger D the sum saturates instead of wrapping.
                let mut sum: $Wide = 0;
                for k in 0..D {
                    sum = sum.saturating_add(a[k].to_bits() as $Wide * b[k].to_bits() as $Wide);
                }
                <$S>::from_bits($narrow_self(sum))
            }
        }
    };
}

fixed_backend!(I16F16, I3F29, i64, narrow_q29, narrow_q16, "I16F16");
fixed_backend!(I32F32, I3F61, i128, narrow_q61, narrow_q32, "I32F32");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_of_positions_truncate_and_saturate() {
        let a = I16F16::from_num(1.5);
        let b = I16F16::from_num(-2.25);
        assert_eq!(a.mul(b), I16F16::from_num(-3.375));
        // −1 LSB · 0.5 = −0.5 LSB truncates to 0, not to −1.
        assert_eq!(
            I16F16::from_bits(-1).mul(I16F16::from_num(0.5)),
            I16F16::ZERO
        );
        assert_eq!(I16F16::MAX.mul(I16F16::MAX), I16F16::MAX);
        assert_eq!(I16F16::MIN.mul(I16F16::MAX), I16F16::MIN);
        let d = [I16F16::from_num(3), I16F16::from_num(4)];
        assert_eq!(I16F16::dot(&d, &d), I16F16::from_num(25));
        let big = [I16F16::MAX; 3];
        assert_eq!(I16F16::dot(&big, &big), I16F16::MAX);
        let d = [I32F32::from_num(-3), I32F32::from_num(4)];
        assert_eq!(I32F32::dot(&d, &d), I32F32::from_num(25));
        assert_eq!(I32F32::MIN.mul(I32F32::MIN), I32F32::MAX);
    }

    #[test]
    fn narrowing_truncates_toward_zero() {
        let one = 1i64 << 29;
        assert_eq!(narrow_q29(one - 1), 0);
        assert_eq!(narrow_q29(-one + 1), 0);
        assert_eq!(narrow_q29(one), 1);
        assert_eq!(narrow_q29(-one), -1);
        assert_eq!(narrow_q29(5 * one + 1), 5);
        assert_eq!(narrow_q29(-5 * one - 1), -5);
        assert_eq!(narrow_q29(-5 * one + 1), -4);
        assert_eq!(narrow_q29(i64::MAX / 2), i32::MAX);
        assert_eq!(narrow_q29(i64::MIN / 2), i32::MIN);
        assert_eq!(narrow_q61((3i128 << 61) - 1), 2);
        assert_eq!(narrow_q61(-(3i128 << 61) + 1), -2);
    }

    #[test]
    fn extreme_products_saturate_instead_of_wrapping() {
        // The corners of both formats: every sign combination of the extreme factors,
        // against exact i128 arithmetic, whose `/` truncates toward zero.
        let expected_q29 = |p: i128| (p / (1 << 29)).clamp(i32::MIN as i128, i32::MAX as i128);
        for c in [I3F29::MIN, I3F29::MAX] {
            for d in [I3F29::MIN, I3F29::MAX] {
                for a in [I16F16::MIN, I16F16::MAX] {
                    for b in [I16F16::MIN, I16F16::MAX] {
                        let p = a.to_bits() as i128 * c.to_bits() as i128
                            - b.to_bits() as i128 * d.to_bits() as i128;
                        let got = I16F16::mul_coef_diff(a, c, b, d).to_bits() as i128;
                        assert_eq!(got, expected_q29(p));
                    }
                }
            }
        }
        for c in [I3F61::MIN, I3F61::MAX] {
            for a in [I32F32::MIN, I32F32::MAX] {
                let p = a.to_bits() as i128 * c.to_bits() as i128;
                let expected = (p / (1 << 61)).clamp(i64::MIN as i128, i64::MAX as i128);
                assert_eq!(a.mul_coef(c).to_bits() as i128, expected);
            }
        }
        assert_eq!(I16F16::coef(-9.0), I3F29::MIN);
        assert_eq!(I16F16::coef(9.0), I3F29::MAX);
    }
}
