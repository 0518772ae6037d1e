//! The bits of a backend's factors and states, computed by a `const fn`: the set-up of a
//! value (its gains, its start weights, its rest band) for a tuning known when the
//! firmware is built, so that an `I16F16` firmware converts no `f64` to a mantissa at run
//! time ([`Tuned`](crate::Tuned)).
//!
//! The run-time conversions ([`Scalar::factor`], [`Scalar::state_from_f64`]) and these
//! share their arithmetic: the fixed-point ones call [`encode_mantissa`] and
//! [`fixed_state`], and the float ones round as [`Repr::bits_of`] does, which `raw.rs`
//! checks against [`Scalar::from_f64`] bit for bit. So a value built from a `Tuned` is the
//! value `SpringValue::new` builds from the same tuning, to the bit
//! (`tuning::tuned::tests`).

use super::raw::{f32_bits, f64_bits};
use super::{Repr, Scalar};
use core::marker::PhantomData;

/// How a backend stores a factor (set-up only).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub enum FactorForm {
    /// The float of this representation.
    Float(Repr),
    /// A mantissa of `bits` bits, sign included, and a shift: `value ≈ mantissa/2^shift`
    /// ([`encode_mantissa`]).
    Mantissa {
        /// The mantissa's width.
        bits: u32,
    },
}

/// How a backend stores a state (set-up only).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub enum StateForm {
    /// The float of this representation.
    Float(Repr),
    /// An integer of `bits` bits with `frac` fractional bits ([`fixed_state`]).
    Fixed {
        /// The integer's width.
        bits: u32,
        /// Its fractional bits.
        frac: u32,
    },
}

/// `(mantissa, shift)` with `value ≈ mantissa/2^shift` and `2^(h−2) ≤ |mantissa| <
/// 2^(h−1)`, rounded half away from zero: `h − 1` significant bits for a mantissa of `h`
/// bits. `(0, 0)` for zero, NaN, infinities and magnitudes beyond what the shift range
/// (`−2h ..= 6h`) holds.
///
/// Never inlined: a run-time set-up calls it for each of its factors (two gains, four
/// start weights), and one copy of the loop serves them all.
#[inline(never)]
pub(crate) const fn encode_mantissa(value: f64, h: u32) -> (i64, i32) {
    if !value.is_finite() || value == 0.0 {
        return (0, 0);
    }
    let h = h as i32;
    // Below the type's largest value: the rounding may carry into the next power of two,
    // and the loop then takes one shift less.
    let limit = ((1u64 << (h - 1)) - 1) as f64;
    // 2^e ≤ |value| < 2^(e+1), from the exponent field (normal numbers).
    let e = ((value.abs().to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let mut shift = (h - 2) - e;
    loop {
        if shift < -2 * h || shift > 6 * h {
            return (0, 0);
        }
        let m = round_half_away(value * pow2(shift));
        if m.abs() < limit {
            return (m as i64, shift);
        }
        shift -= 1;
    }
}

/// `value` as a fixed-point integer of `bits` bits with `frac` fractional bits: rounded
/// half away from zero, saturated at the type's ends, 0 for NaN. Never inlined, as
/// [`encode_mantissa`].
#[inline(never)]
pub(crate) const fn fixed_state(value: f64, bits: u32, frac: u32) -> i128 {
    if value.is_nan() {
        return 0;
    }
    // In two factors of at most 2^32 each, as exact powers of two.
    let scaled = value * pow2(frac as i32 - 32) * 4_294_967_296.0;
    // From 2^52 up an `f64` is an integer already, and adding a half would round (to
    // even) instead: 2^52 + 1 became 2^52 + 2. Below, `± 0.5` is exact.
    let r = if scaled >= pow2(52) || scaled <= -pow2(52) {
        scaled
    } else if scaled >= 0.0 {
        scaled + 0.5
    } else {
        scaled - 0.5
    };
    // `as` truncates toward zero and saturates at the ends of `i128`; then the ends of
    // the state's own type.
    let wide = r as i128;
    let (min, max) = (i128::MIN >> (128 - bits), i128::MAX >> (128 - bits));
    if wide < min {
        min
    } else if wide > max {
        max
    } else {
        wide
    }
}

/// Rounds half away from zero (`f64::round` is not in `core`): exact for `|v| < 2^127`.
const fn round_half_away(v: f64) -> f64 {
    let t = v as i128 as f64;
    let frac = v - t;
    if frac >= 0.5 {
        t + 1.0
    } else if frac <= -0.5 {
        t - 1.0
    } else {
        t
    }
}

/// `2^k` as `f64`, for `k` in the normal range.
const fn pow2(k: i32) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// A factor of backend `S` ([`Scalar::Factor`]) as its bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RawFactor<S> {
    /// The float's bits, or the mantissa.
    mantissa: i64,
    /// The shift (0 for a float).
    shift: i32,
    backend: PhantomData<S>,
}

impl<S: Scalar> RawFactor<S> {
    /// What [`Scalar::factor`] gives for `value`.
    pub(crate) const fn new(value: f64) -> Self {
        let (mantissa, shift) = match S::FACTOR_FORM {
            FactorForm::Float(Repr::F32) => (f32_bits(value), 0),
            FactorForm::Float(_) => (f64_bits(value), 0),
            FactorForm::Mantissa { bits } => encode_mantissa(value, bits),
        };
        RawFactor {
            mantissa,
            shift,
            backend: PhantomData,
        }
    }

    /// The factor, as `f64`: exactly what it stores.
    pub(crate) const fn to_f64(self) -> f64 {
        match S::FACTOR_FORM {
            FactorForm::Float(Repr::F32) => f32::from_bits(self.mantissa as u32) as f64,
            FactorForm::Float(_) => f64::from_bits(self.mantissa as u64),
            FactorForm::Mantissa { .. } => self.mantissa as f64 * pow2(-self.shift),
        }
    }

    /// Whether it is zero.
    pub(crate) const fn is_zero(self) -> bool {
        self.to_f64() == 0.0
    }

    /// The factor.
    #[inline]
    pub(crate) fn get(self) -> S::Factor {
        S::factor_from_const(self.mantissa, self.shift)
    }
}

/// A state of backend `S` ([`Scalar::State`]) as its bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RawState<S> {
    bits: i128,
    backend: PhantomData<S>,
}

impl<S: Scalar> RawState<S> {
    /// What [`Scalar::state_from_f64`] gives for `value`.
    pub(crate) const fn new(value: f64) -> Self {
        let bits = match S::STATE_FORM {
            StateForm::Float(Repr::F32) => f32_bits(value) as i128,
            StateForm::Float(_) => f64_bits(value) as i128,
            StateForm::Fixed { bits, frac } => fixed_state(value, bits, frac),
        };
        RawState {
            bits,
            backend: PhantomData,
        }
    }

    /// The state.
    #[inline]
    pub(crate) fn get(self) -> S::State {
        S::state_from_const(self.bits)
    }
}

/// The least `k` of a stiffness the lifted step takes: `C_k < 4 = 2^30/2^(32 − 4)`.
const NARROW_LEAST_STIFFNESS_K: i32 = -3;
/// The least `k` of a damping the lifted step takes: `C_d < 2`.
const NARROW_LEAST_DAMPING_K: i32 = -2;

/// Whether the `I16F16` step (`fast::narrow_step`) takes the gains `(mantissa, shift)`:
/// a stiffness below 4, a damping below 2, each zero or at least `2⁻³³`, neither
/// negative. `I16F16` refuses any other gains at set-up (`RawGains::new`), so that its
/// step needs no general product.
pub(crate) const fn narrow_takes(stiffness: (i64, i32), damping: (i64, i32)) -> bool {
    const fn takes((m, shift): (i64, i32), least_k: i32) -> bool {
        m == 0 || (m > 0 && shift - 32 >= least_k && shift - 32 <= 31)
    }
    takes(stiffness, NARROW_LEAST_STIFFNESS_K) && takes(damping, NARROW_LEAST_DAMPING_K)
}

/// A backend's gains ([`Scalar::Gains`]) as the bits of their two factors, accepted as
/// [`Scalar::gains`] accepts them: the run-time `gains` of every backend is this, so that
/// the two cannot differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RawGains<S> {
    stiffness: RawFactor<S>,
    damping: RawFactor<S>,
}

impl<S: Scalar> RawGains<S> {
    /// The gains of `C_k = stiffness` and `C_d = damping`, or `None` where the backend
    /// cannot hold one of them ([`Scalar::LEAST_GAIN`]).
    pub(crate) const fn new(stiffness: f64, damping: f64) -> Option<Self> {
        let (k, d) = (RawFactor::<S>::new(stiffness), RawFactor::<S>::new(damping));
        let lost = match S::FACTOR_FORM {
            // A gain that becomes subnormal loses its relative precision, one that
            // becomes zero its effect: neither is the tuning that was asked for.
            FactorForm::Float(_) => {
                (stiffness != 0.0 && k.to_f64().abs() < S::LEAST_GAIN)
                    || (damping != 0.0 && d.to_f64().abs() < S::LEAST_GAIN)
            }
            // The spring stops for good within |x| < 1/C_k last bits of the state: below
            // the least gain that dead band is wider than a position's last bit. A gain
            // beyond the mantissa's range encodes as zero.
            FactorForm::Mantissa { bits } => {
                (stiffness != 0.0 && (stiffness.abs() < S::LEAST_GAIN || k.is_zero()))
                    || (damping != 0.0 && d.is_zero())
                    || (bits == 32 && !narrow_takes((k.mantissa, k.shift), (d.mantissa, d.shift)))
            }
        };
        if lost {
            None
        } else {
            Some(RawGains {
                stiffness: k,
                damping: d,
            })
        }
    }

    /// The gains.
    #[inline]
    pub(crate) fn get(self) -> S::Gains {
        S::gains_from_factors(self.stiffness.get(), self.damping.get())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixed::types::{I16F16, I32F32};

    /// The values the conversions are checked on: ends, ties and 2,000 of every sign and
    /// magnitude from 1e−20 to 1e20.
    fn values() -> impl Iterator<Item = f64> {
        let listed = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            0.3,
            1.0 / 60.0,
            0.999_999_9,
            1e-12,
            -1e-12,
            3.0e9,
            -3.0e9,
            1e300,
            -1e300,
            f64::MIN_POSITIVE,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            // Halves of a fixed state's last bit (I16F16: 2^−40), rounded away from zero.
            2.5 * pow2(-40),
            -2.5 * pow2(-40),
            // A mantissa that rounds up into the next power of two.
            1.0 - pow2(-40),
        ];
        let mut x = 0.123_456_789_f64;
        let spread = core::iter::repeat_with(move || {
            x = (x * 7.3 + 0.1) % 1.0;
            (x - 0.5) * libm::pow(10.0, libm::floor(x * 40.0) - 20.0)
        })
        .take(2000);
        listed.into_iter().chain(spread)
    }

    /// A float backend's factor and state are [`Scalar::from_f64`] of the value (its own
    /// conversion: a clamp and a cast), bit for bit.
    fn floats_agree<S: Scalar>() {
        for v in values() {
            let expected = S::from_f64(v);
            assert_eq!(
                S::factor_from_const(RawFactor::<S>::new(v).mantissa, 0),
                S::factor(v)
            );
            assert_eq!(RawState::<S>::new(v).get(), S::state_from_f64(v));
            assert_eq!(S::state_from_f64(v), expected.widen(), "{} {v:e}", S::NAME);
        }
    }

    #[test]
    fn a_float_factor_and_state_are_the_floats_conversion() {
        floats_agree::<f32>();
        floats_agree::<f64>();
    }

    /// A fixed-point state is the value rounded half away from zero to the state's last
    /// bit and saturated at the type's ends, from the definition (`libm::round`), for
    /// both fixed backends' state formats.
    #[test]
    fn a_fixed_state_is_the_value_rounded_to_its_last_bit() {
        for (bits, frac) in [(64, 40), (128, 64)] {
            let (min, max) = (i128::MIN >> (128 - bits), i128::MAX >> (128 - bits));
            for v in values() {
                let want = if v.is_nan() {
                    0
                } else {
                    let r = libm::round(v * pow2(frac as i32));
                    if r >= pow2(bits as i32 - 1) {
                        max
                    } else if r < -pow2(bits as i32 - 1) {
                        min
                    } else {
                        r as i128
                    }
                };
                assert_eq!(fixed_state(v, bits, frac), want, "{v:e}, Q{bits}.{frac}");
            }
        }
        assert_eq!(RawState::<I16F16>::new(1.0).get(), 1i64 << 40);
        // An integer from 2^52 up is itself (a half added to it rounded to even).
        assert_eq!(fixed_state(pow2(52) + 1.0, 64, 0), (1 << 52) + 1);
        assert_eq!(fixed_state(-(pow2(52) + 1.0), 64, 0), -(1 << 52) - 1);
        assert_eq!(RawState::<I32F32>::new(-1.0).get(), -(1i128 << 64));
    }

    /// A mantissa is the value rounded half away from zero to `h − 1` significant bits,
    /// from the definition: `2^(h−2) ≤ |m| < 2^(h−1)` and `|m/2^s − v| ≤ 2^(−s−1)`.
    #[test]
    fn a_mantissa_is_the_value_rounded_to_its_bits() {
        let mut x = 0.314_159_f64;
        for _ in 0..5000 {
            x = (x * 9.7 + 0.3) % 1.0;
            let v = (x - 0.5) * libm::pow(10.0, libm::floor(x * 24.0) - 12.0);
            for h in [32, 64] {
                let (m, s) = encode_mantissa(v, h);
                let (lo, hi) = (pow2(h as i32 - 2), pow2(h as i32 - 1));
                let size = (m as f64).abs();
                assert!(size >= lo && size < hi, "{v:e}, h {h}: {m}");
                let step = pow2(-s);
                // In exact arithmetic: m − v·2^s is computed exactly for h = 32.
                if h == 32 {
                    assert!((m as f64 - v * pow2(s)).abs() <= 0.5, "{v:e}: {m}, {s}");
                }
                assert!(
                    (m as f64 * step - v).abs() <= 0.5 * step * (1.0 + 1e-12),
                    "{v:e}"
                );
            }
        }
        assert_eq!(encode_mantissa(0.0, 32), (0, 0));
        assert_eq!(encode_mantissa(f64::NAN, 32), (0, 0));
        assert_eq!(encode_mantissa(1e300, 32), (0, 0));
    }
}
