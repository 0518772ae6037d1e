//! Backend numbers computed by the compiler: what a `const` set-up writes.
//!
//! A `const fn` cannot call [`Scalar::from_f64`] (a trait method), so a set-up that runs
//! at compile time computes each number's bits with [`Raw::new`], a `const fn` over the
//! backend's [`Repr`], and the firmware turns the bits into the number with [`Raw::get`]:
//! a bit cast, with no `f64` arithmetic and no float-to-fixed conversion linked.
//! [`Raw::new`] rounds exactly as [`Scalar::from_f64`] does, bit for bit (the tests
//! below compare them on every kind of input, ties included).

use super::Scalar;
use core::marker::PhantomData;

/// How a backend stores a number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub enum Repr {
    /// IEEE single precision.
    F32,
    /// IEEE double precision.
    F64,
    /// Two's complement fixed point of `bits` bits, `frac` of them fractional.
    Fixed {
        /// All the bits, sign included (at most 64).
        bits: u32,
        /// The fractional bits.
        frac: u32,
    },
}

impl Repr {
    /// The bits of `value` in this format, converted as [`Scalar::from_f64`] converts it:
    /// NaN to zero; a float clamped to its finite range, then rounded to nearest; fixed
    /// point saturated to its range and rounded to nearest with ties to even (as the
    /// `fixed` crate's `saturating_from_num`).
    pub const fn bits_of(self, value: f64) -> i64 {
        if value.is_nan() {
            return 0;
        }
        match self {
            Repr::F32 => f32_bits(value),
            Repr::F64 => f64_bits(value),
            Repr::Fixed { bits, frac } => {
                // 2^(bits − 1) and 2^frac are powers of two: exact in f64.
                let top = pow2(bits - 1);
                let scaled = value * pow2(frac);
                let max = (i64::MAX >> (64 - bits), i64::MIN >> (64 - bits));
                if scaled >= top {
                    max.0
                } else if scaled <= -top {
                    max.1
                } else {
                    let r = round_ties_even(scaled);
                    if r > max.0 { max.0 } else { r }
                }
            }
        }
    }
}

/// The bits of `value` as an `f32` ([`Repr::bits_of`] for [`Repr::F32`]), for the set-up
/// of a float factor or state, which knows its representation: a call of `bits_of` there
/// links all of its arms (776 bytes on the Cortex-M4F for a run-time `f32` value).
#[inline]
pub(crate) const fn f32_bits(value: f64) -> i64 {
    if value.is_nan() {
        return 0;
    }
    (clamp(value, f32::MAX as f64) as f32).to_bits() as i64
}

/// The bits of `value` as an `f64` ([`Repr::bits_of`] for [`Repr::F64`]).
#[inline]
pub(crate) const fn f64_bits(value: f64) -> i64 {
    if value.is_nan() {
        return 0;
    }
    clamp(value, f64::MAX).to_bits() as i64
}

/// `value` within `[−max, max]`: a float backend keeps a finite input finite.
const fn clamp(value: f64, max: f64) -> f64 {
    if value > max {
        max
    } else if value < -max {
        -max
    } else {
        value
    }
}

/// `x` rounded to the nearest integer, ties to even, for `|x| < 2^63` (`core` has no
/// `f64::round_ties_even` without `std`). Every step is exact: the truncation of an `f64`
/// below 2^63, and the difference of two `f64` that close.
const fn round_ties_even(x: f64) -> i64 {
    let t = x as i64;
    let rest = x - t as f64;
    if rest > 0.5 || (rest == 0.5 && t % 2 != 0) {
        t + 1
    } else if rest < -0.5 || (rest == -0.5 && t % 2 != 0) {
        t - 1
    } else {
        t
    }
}

/// `2^n` for `n ≤ 1023`, exactly.
const fn pow2(n: u32) -> f64 {
    f64::from_bits(((1023 + n) as u64) << 52)
}

/// A number of backend `S`, computed in a `const` set-up: [`Raw::new`] at compile
/// time, [`Raw::get`] at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Raw<S> {
    bits: i64,
    backend: PhantomData<S>,
}

impl<S: Scalar> Raw<S> {
    /// `S::from_f64(value)`, as bits.
    pub(crate) const fn new(value: f64) -> Self {
        Raw {
            bits: S::REPR.bits_of(value),
            backend: PhantomData,
        }
    }

    /// The number.
    #[inline]
    pub(crate) fn get(self) -> S {
        S::from_const_bits(self.bits)
    }

    /// `a + b·c` in a float backend's own arithmetic (the product rounded, then the sum),
    /// as `a.add(b.mul(c))` computes it at run time; zero in fixed point, which has no use
    /// for it.
    pub(crate) const fn float_mul_add(a: Self, b: Self, c: Self) -> Self {
        let bits = match S::REPR {
            Repr::F32 => {
                let (a, b, c) = (
                    f32::from_bits(a.bits as u32),
                    f32::from_bits(b.bits as u32),
                    f32::from_bits(c.bits as u32),
                );
                (a + b * c).to_bits() as i64
            }
            Repr::F64 => {
                let (a, b, c) = (
                    f64::from_bits(a.bits as u64),
                    f64::from_bits(b.bits as u64),
                    f64::from_bits(c.bits as u64),
                );
                (a + b * c).to_bits() as i64
            }
            Repr::Fixed { .. } => 0,
        };
        Raw {
            bits,
            backend: PhantomData,
        }
    }
}

/// A coefficient of backend `S` (its [`Scalar::Coef`]), computed in a `const` set-up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RawCoef<S> {
    bits: i64,
    backend: PhantomData<S>,
}

impl<S: Scalar> RawCoef<S> {
    /// `S::coef(value)`, as bits.
    pub(crate) const fn new(value: f64) -> Self {
        RawCoef {
            bits: S::COEF_REPR.bits_of(value),
            backend: PhantomData,
        }
    }

    /// The coefficient.
    #[inline]
    pub(crate) fn get(self) -> S::Coef {
        S::coef_from_const_bits(self.bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inputs of every kind: zero, signs, the ranges' ends and beyond, infinities, NaN.
    const INPUTS: [f64; 28] = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        -0.1,
        1e-9,
        -1e-9,
        3.7,
        -3.7,
        1e6,
        -1e6,
        32767.99999,
        -32768.0,
        -32768.5,
        32768.0,
        4.0,
        -4.0,
        3.999999999,
        f64::MAX,
        -f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        3.5e38,
        -3.5e38,
        1e300,
        f64::MIN_POSITIVE,
    ];

    fn check<S: Scalar + PartialEq + core::fmt::Debug>(x: f64) {
        assert_eq!(Raw::<S>::new(x).get(), S::from_f64(x), "{} {x:e}", S::NAME);
        assert_eq!(
            RawCoef::<S>::new(x).get(),
            S::coef(x),
            "{} coef {x:e}",
            S::NAME
        );
    }

    /// Every input, and ties at the last bit of Q16.16, Q3.29, Q32.32 and Q3.61 (and
    /// values just either side of them).
    fn same<S: Scalar + PartialEq + core::fmt::Debug>() {
        for x in INPUTS {
            check::<S>(x);
        }
        for k in -40i32..40 {
            for frac in [16, 29, 32, 61] {
                let lsb = 1.0 / (1u64 << frac) as f64;
                let tie = (f64::from(k) + 0.5) * lsb;
                for x in [tie, tie + lsb * 1e-3, tie - lsb * 1e-3, f64::from(k) * lsb] {
                    check::<S>(x);
                    check::<S>(x * 1e5);
                }
            }
        }
    }

    #[test]
    fn floats_convert_as_from_f64() {
        same::<f32>();
        same::<f64>();
    }

    #[cfg(feature = "fixed")]
    #[test]
    fn fixed_point_converts_as_from_f64() {
        same::<crate::I16F16>();
        same::<crate::I32F32>();
    }
}
