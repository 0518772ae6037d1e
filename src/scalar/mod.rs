//! The arithmetic the whole crate is generic over: see [`Scalar`], and the formats its
//! backends keep a spring's gains and factors in.

#[cfg(feature = "fixed")]
mod fast;
#[cfg(feature = "fixed")]
mod fixed_point;
mod float;
mod raw;
mod raw_state;
#[cfg(feature = "fixed")]
mod wide;
#[cfg(feature = "fixed")]
mod widening;

#[doc(hidden)]
pub use raw::Repr;
#[allow(unused_imports)]
pub(crate) use raw::{Raw, RawCoef};
pub use raw_state::{FactorForm, StateForm};
pub(crate) use raw_state::{RawFactor, RawGains, RawState};

#[cfg(feature = "fixed")]
pub use fixed_point::{FixedFactor, FixedGains};
pub use float::FloatGains;

use core::fmt::Debug;

/// Keeps [`Scalar`] implementable only inside this crate, so that methods can be added
/// without breaking anyone.
mod sealed {
    pub trait Sealed {}
}
pub(crate) use sealed::Sealed;

/// `defmt::Format` with the `defmt` feature, and nothing without it: a bound on the
/// backends' associated types that lets every generic type of the crate derive
/// `defmt::Format` exactly when the feature is on.
mod maybe_format {
    /// Implemented by every type; with the `defmt` feature, by every `defmt::Format`.
    #[cfg(feature = "defmt")]
    pub trait MaybeFormat: defmt::Format {}
    #[cfg(feature = "defmt")]
    impl<T: defmt::Format + ?Sized> MaybeFormat for T {}

    /// Implemented by every type; with the `defmt` feature, by every `defmt::Format`.
    #[cfg(not(feature = "defmt"))]
    pub trait MaybeFormat {}
    #[cfg(not(feature = "defmt"))]
    impl<T: ?Sized> MaybeFormat for T {}
}
pub(crate) use maybe_format::MaybeFormat;

/// A number format the springs run in: `f32`, `f64`, `I16F16` or `I32F32`.
///
/// Positions, targets, velocities, masses and lengths are `Self`. Inside, each backend
/// keeps the spring's state in the format that lets the discrete spring follow the
/// continuous one at every rate from 60 Hz to 10 kHz:
///
/// | backend | positions | state (offset, step velocity) | gains `C_k`, `C_d` | rounding |
/// |---|---|---|---|---|
/// | `f32` | `f32` | `f32` | `f32` | IEEE |
/// | `f64` | `f64` | `f64` | `f64` | IEEE |
/// | `I16F16` | Q16.16 | `i64`, Q24.40: 24 guard bits, ±2²³ units | 30-bit mantissas, one shared exponent | toward zero |
/// | `I32F32` | Q32.32 | `i128`, Q64.64: 32 guard bits, ±2⁶³ units | 62-bit mantissas, one shared exponent | toward zero |
///
/// Every step is the article's impulse (eq. 27/28 with `u = v·dt`) in the order
///
/// ```text
/// u ← ũ − C_k·x        x ← x + u        ũ ← u − C_d·u
/// ```
///
/// where `ũ = (1 − C_d)·u` is the step velocity the spring carries into the next step,
/// already damped. It is algebraically the article's `u ← (1 − C_d)·u − C_k·x`, and each
/// of its products is accurate where the other forms lose the spring:
///
/// - `C_d·u` rather than `(1 − C_d)·u`: at high rates `C_d` is small (a 1 Hz spring with
///   ζ = 0.1 at 10 kHz has `C_d = 1.26e−4`) and `1 − C_d` keeps only the absolute
///   precision of numbers near 1, 5e−4 of `C_d` in `f32`;
/// - `ũ` stored rather than `u`: a heavily damped spring (`C_d → 1`) cancels `u − C_d·u`,
///   and its exact start extrapolates one step back to a step velocity `u₀` that grows
///   as `e^{2ζω·dt}` (7·10¹⁰ times the offset for ζ = 10 at 12 Hz and 60 Hz), beyond the
///   range of fixed point and the precision of `f32`. `ũ₀ = (1 − C_d)·u₀` stays within
///   the offset's magnitude. Measured through the public API, `f32` goes from an error of
///   5.9e−2 of the amplitude to 3.6e−8 there (`tests/exact_map.rs`).
///
/// **Why guard bits.** Fixed point rounds the increment `a` to the state's last bit
/// each step. Rounded toward zero (the only rounding whose spring always comes to rest,
/// measured in `tests/fixed_rounding.rs`) it drags a lightly damped spring by `2/C_k`
/// last bits of amplitude per cycle and stops it anywhere within `1/C_k` last bits of its
/// target; `C_k` shrinks as `(ω·dt)²`, so at 10 kHz a 1 Hz spring (`C_k = 3.9e−7`) loses
/// 5·10⁶ last bits per cycle. With the state's last bit 2⁻²⁴ of a position's, that is 0.3
/// of a position's last bit. Run `cargo run --release -p stiffspring-lab --bin precision`
/// for the whole study (every candidate representation, every rate).
///
/// **Why mantissas.** A 1 Hz spring at 10 kHz needs `C_k = 3.9e−7` to about 30
/// significant bits (an undamped spring's phase drifts by `tan(θ/2)·ε` per step for a
/// relative error `ε`); a fixed `Q3.29` fraction holds it to 210 last bits. Both gains
/// share the exponent of the larger, so one shift finishes the sum of the two products.
///
/// Every fixed-point operation saturates; none wraps. The `I16F16` step of a value, a
/// batch or a decay ([`Scalar::advance`]) keeps its state within `[−2¹⁶, 2¹⁶)` units,
/// twice the positions' range, so that it multiplies by every gain `I16F16` accepts
/// (`C_k < 4`, `C_d < 2`, each zero or at least `2⁻³³`) with two long multiplies and no
/// saturation test: a state beyond it (an offset between positions never is; a spring
/// tuned beyond the article's square, started near an end of the range, can grow past
/// it) is halved, offset and step velocity together, until it is inside. That is the
/// same spring from a smaller start, in the same direction, so it still comes to rest. Float ↔ fixed conversion happens
/// at set-up only; the stepping code never touches a float when the backend is fixed
/// point.
///
/// ```
/// use stiffspring::Scalar;
///
/// // One step of a spring with C_k = 0.25, C_d = 0.5 from x = 1, ũ = 2:
/// // u = 2 − 0.25·1 = 1.75, x = 2.75, ũ = 1.75 − 0.5·1.75 = 0.875.
/// let g = f32::gains(0.25, 0.5).unwrap();
/// let (mut x, mut v) = (1.0f32, 2.0f32);
/// f32::advance(&g, &mut x, &mut v);
/// assert_eq!((x, v), (2.75, 0.875));
/// ```
pub trait Scalar:
    Sealed + MaybeFormat + Copy + PartialOrd + Debug + Default + Send + Sync + 'static
{
    /// The spring's internal state format (offsets and step velocities).
    type State: MaybeFormat
        + Copy
        + PartialEq
        + PartialOrd
        + Debug
        + Default
        + Send
        + Sync
        + 'static;
    /// The pair `(C_k, C_d)` in the format the step multiplies by.
    type Gains: MaybeFormat + Copy + PartialEq + Debug + Default + Send + Sync + 'static;
    /// A factor of any magnitude, applied at set-up and on retargets (the start weights,
    /// two-body weights).
    type Factor: MaybeFormat + Copy + PartialEq + Debug + Default + Send + Sync + 'static;
    /// What a scene carries beside each position to add step velocities without losing
    /// them: the rounding remainder in `f32` (compensated summation), nothing (`()`) in
    /// `f64`, whose rounding is far below what a network shows, and in fixed point, whose
    /// additions are exact.
    type Remainder: MaybeFormat + Copy + PartialEq + Debug + Default + Send + Sync + 'static;

    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// Zero in the state format.
    const STATE_ZERO: Self::State;
    /// A short name for tables and errors: `"f32"`, `"I16F16"`, ...
    const NAME: &'static str;
    /// One last bit of a position, as `f64`; `0.0` for floats.
    const RESOLUTION: f64;
    /// The largest magnitude of positions, targets and velocities accepted at set-up.
    ///
    /// For floats it leaves headroom (`2⁶⁴` for `f32`, `2⁵⁰⁰` for `f64`) for the transient
    /// growth of a stable spring, so that no state ever becomes infinite (see
    /// [`Tuning::growth`](crate::Tuning::growth)). Fixed point accepts its whole range.
    const MAX: f64;
    /// The largest magnitude the internal state holds (fixed point saturates there).
    const STATE_MAX: f64;
    /// The largest magnitude of positions and step velocities in a
    /// [`Scene`](crate::scene::Scene): small enough that a distance spring's squared
    /// length stays finite (`2⁶⁰` for `f32`, `2⁵⁰⁰` for `f64`); [`Scalar::MAX`] in fixed
    /// point, which saturates anyway.
    const NETWORK_MAX: f64;

    /// Converts from `f64`, rounding to nearest and saturating at the ends of the range
    /// (NaN becomes zero). Set-up only.
    fn from_f64(value: f64) -> Self;
    /// Converts to `f64` (rounded to nearest for `I32F32` beyond 53 significant bits).
    fn to_f64(self) -> f64;
    /// The gains `(C_k, C_d)` in the step's format, rounded to nearest; `None` when a
    /// non-zero gain would round to zero or below the state's resolution, and in
    /// `I16F16` outside the single-spring region's bounds (`C_k ≥ 4`, `C_d ≥ 2`, a
    /// negative gain) or for a damping below `2⁻³³`, which its step does not take.
    ///
    /// ```
    /// use stiffspring::{I16F16, Scalar};
    ///
    /// assert!(I16F16::gains(3.9, 0.05).is_some());
    /// assert!(I16F16::gains(4.0, 0.05).is_none());
    /// ```
    fn gains(stiffness: f64, damping: f64) -> Option<Self::Gains>;
    /// The gains back as `(C_k, C_d)`.
    fn gains_to_f64(gains: &Self::Gains) -> (f64, f64);
    /// A factor from `f64` (saturating far beyond any use; NaN becomes zero).
    fn factor(value: f64) -> Self::Factor;

    /// A position as state, exactly.
    fn widen(self) -> Self::State;
    /// A state as a position: rounded to nearest, saturated to the backend's range.
    fn narrow(state: Self::State) -> Self;
    /// A state from `f64`, rounded to nearest, saturated (set-up only).
    fn state_from_f64(value: f64) -> Self::State;
    /// A state as `f64`.
    fn state_to_f64(state: Self::State) -> f64;

    /// `a + b` (saturating in fixed point).
    fn state_add(a: Self::State, b: Self::State) -> Self::State;
    /// `a − b` (saturating in fixed point).
    fn state_sub(a: Self::State, b: Self::State) -> Self::State;
    /// `s·f`, rounded toward zero in fixed point (saturating).
    fn scale(state: Self::State, factor: Self::Factor) -> Self::State;
    /// `|state| ≤ bound` for a non-negative `bound` (in fixed point one add and one
    /// unsigned comparison).
    fn within(state: Self::State, bound: Self::State) -> bool;
    /// `x + u` carrying the remainder `r`: the new position and remainder, so that
    /// `x + r` moves by `u` to the rounding of `u + r`, not of `x + u` (Knuth's TwoSum in
    /// `f32`; a plain add elsewhere).
    fn add_carrying(
        x: Self::State,
        r: Self::Remainder,
        u: Self::State,
    ) -> (Self::State, Self::Remainder);
    /// `(b + r_b) − (a + r_a)`: a separation rounded to its own size, not to the
    /// positions'.
    fn difference_carrying(
        b: Self::State,
        rb: Self::Remainder,
        a: Self::State,
        ra: Self::Remainder,
    ) -> Self::State;
    /// A remainder as `f64` (0 where there is none).
    fn remainder_to_f64(r: Self::Remainder) -> f64;
    /// `|state|` (saturating in fixed point; one `vabs` in `f32` on a Cortex-M4F).
    fn state_abs(state: Self::State) -> Self::State;
    /// `state` limited to `[−bound, bound]`, NaN mapped to 0: the safety net that keeps
    /// an unstable float network finite. The identity in fixed point, whose arithmetic
    /// saturates.
    fn state_clamp(state: Self::State, bound: Self::State) -> Self::State;

    /// The spring term `C_k·x`, rounded toward zero in fixed point (a slightly weaker
    /// spring, which conserves an undamped spring's energy: each half of a step is a
    /// shear, a bijection of the integer lattice).
    fn spring_term(gains: &Self::Gains, x: Self::State) -> Self::State;
    /// The damping term `C_d·u`, rounded away from zero in fixed point (damping that
    /// never vanishes while `u ≠ 0`, so a damped spring always comes to rest).
    fn damping_term(gains: &Self::Gains, u: Self::State) -> Self::State;

    /// A rest bound `b ≥ 0` prepared for [`Scalar::in_band`] (set-up only): for floats
    /// the bits of `b` shifted left by one, for fixed point `b` and `2b`.
    #[doc(hidden)]
    type Band: MaybeFormat + Copy + PartialEq + Debug + Default + Send + Sync + 'static;
    /// `bound` (`0 ≤ bound ≤ STATE_MAX/2`, not NaN) prepared for [`Scalar::in_band`].
    #[doc(hidden)]
    fn band(bound: Self::State) -> Self::Band;
    /// `|state| ≤ bound` for a band from [`Scalar::band`], exactly as
    /// [`Scalar::within`]: one integer comparison (floats compare the magnitudes' bits,
    /// which order like the magnitudes; NaN is never inside).
    #[doc(hidden)]
    fn in_band(state: Self::State, band: Self::Band) -> bool;

    /// One step of a spring toward zero, from offset `x` and kept step velocity
    /// `v = ũ`: `u = ũ − C_k·x; x += u; ũ = u − C_d·u`.
    #[inline(always)]
    fn advance(gains: &Self::Gains, x: &mut Self::State, v: &mut Self::State) {
        let u = Self::state_sub(*v, Self::spring_term(gains, *x));
        *x = Self::state_add(*x, u);
        *v = Self::state_sub(u, Self::damping_term(gains, u));
    }

    /// The format of fractions applied to positions (`C_k`, `C_d` and weights in a
    /// network, a knob's shares): a signed fraction in `[−4, 4)`, with more fractional
    /// bits than positions in fixed point (`Q3.29`, `Q3.61`).
    type Coef: MaybeFormat + Copy + PartialEq + Debug + Default + Send + Sync + 'static;
    /// A fraction from `f64`, rounded to nearest, saturated to `[−4, 4)`. Set-up only.
    fn coef(value: f64) -> Self::Coef;
    /// A fraction back as `f64`.
    fn coef_to_f64(coef: Self::Coef) -> f64;

    /// How `Self` stores a number, for a set-up that runs at compile time (`Raw`).
    #[doc(hidden)]
    const REPR: Repr;
    /// How [`Self::Coef`] stores a fraction.
    #[doc(hidden)]
    const COEF_REPR: Repr;
    /// The number whose bits `Repr::bits_of` gave. Set-up only.
    #[doc(hidden)]
    fn from_const_bits(bits: i64) -> Self;
    /// The fraction whose bits `Repr::bits_of` gave. Set-up only.
    #[doc(hidden)]
    fn coef_from_const_bits(bits: i64) -> Self::Coef;
    /// How [`Self::Factor`] stores a number (set-up only).
    #[doc(hidden)]
    const FACTOR_FORM: FactorForm;
    /// How [`Self::State`] stores a number (set-up only).
    #[doc(hidden)]
    const STATE_FORM: StateForm;
    /// The smallest gain the backend holds: in a float the smallest normal number (a
    /// subnormal gain loses its relative precision); in fixed point the state's last bit
    /// over a position's (below it, the spring's dead band is wider than a position's
    /// last bit).
    #[doc(hidden)]
    const LEAST_GAIN: f64;
    /// The factor whose bits `RawFactor::new` gave. Set-up only.
    #[doc(hidden)]
    fn factor_from_const(mantissa: i64, shift: i32) -> Self::Factor;
    /// The state whose bits `RawState::new` gave. Set-up only.
    #[doc(hidden)]
    fn state_from_const(bits: i128) -> Self::State;
    /// The gains of two factors that [`Self::gains`] accepted (no `f64`). Set-up only.
    #[doc(hidden)]
    fn gains_from_factors(stiffness: Self::Factor, damping: Self::Factor) -> Self::Gains;

    /// `self + rhs` (saturating in fixed point).
    fn add(self, rhs: Self) -> Self;
    /// `self − rhs` (saturating in fixed point).
    fn sub(self, rhs: Self) -> Self;
    /// `−self` (saturating in fixed point).
    fn neg(self) -> Self;
    /// `|self|` (saturating in fixed point).
    fn abs(self) -> Self;
    /// `self · rhs`, rounded once toward zero (saturating in fixed point).
    fn mul(self, rhs: Self) -> Self;
    /// `self · coef`, rounded once toward zero.
    fn mul_coef(self, coef: Self::Coef) -> Self;
    /// `a·ca − b·cb`, rounded once toward zero.
    fn mul_coef_diff(a: Self, ca: Self::Coef, b: Self, cb: Self::Coef) -> Self;
    /// `Σ aᵢ·bᵢ`, rounded once toward zero (saturating in fixed point).
    fn dot<const D: usize>(a: &[Self; D], b: &[Self; D]) -> Self;

    /// `s·c`: a state times a fraction, rounded toward zero (saturating).
    fn state_mul_coef(state: Self::State, coef: Self::Coef) -> Self::State;
    /// `s·f` rounded toward zero and saturated to a fraction in `[−4, 4)`: an axis
    /// component `dᵢ/L` from a separation and the factor `1/L`.
    fn state_to_coef(state: Self::State, factor: Self::Factor) -> Self::Coef;
    /// `√(Σ dᵢ²)` of a state vector: the exact length of a separation (rounded down in
    /// fixed point, saturating).
    fn norm<const D: usize>(d: &[Self::State; D]) -> Self::State;
    /// `Σ dᵢ²` in the state format (saturating in fixed point): the squared length the
    /// linearised kernel needs.
    fn square_sum<const D: usize>(d: &[Self::State; D]) -> Self::State;
    /// `a/b` as a fraction in `[−4, 4)` for `b > 0` (rounded toward zero, saturating);
    /// 0 when `b ≤ 0`: the components of a unit axis.
    fn ratio(a: Self::State, b: Self::State) -> Self::Coef;
    /// The unit axis `dᵢ/length` of a separation whose length is `length ≥ |dᵢ|` (a zero
    /// axis for a zero length): one reciprocal and `D` products where the backend can, the
    /// division `D` times otherwise.
    #[inline(always)]
    fn axis<const D: usize>(d: &[Self::State; D], length: Self::State) -> [Self::Coef; D] {
        d.map(|d| Self::ratio(d, length))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip<S: Scalar>() {
        for v in [0.0, 1.0, -1.0, 0.5, 123.25, -7.75] {
            assert_eq!(S::from_f64(v).to_f64(), v, "{}", S::NAME);
            assert_eq!(S::state_to_f64(S::from_f64(v).widen()), v, "{}", S::NAME);
            assert_eq!(S::narrow(S::from_f64(v).widen()).to_f64(), v, "{}", S::NAME);
        }
        for (k, d) in [(1.0, 0.5), (0.25, 0.0), (3.5, 0.25), (1e-6, 0.125)] {
            let g = S::gains(k, d).unwrap();
            let (k2, d2) = S::gains_to_f64(&g);
            // One shared exponent: each gain is exact to 2^−29 of the larger one.
            let tolerance = k.max(d) * 2f64.powi(-29);
            assert!(
                (k2 - k).abs() <= tolerance && (d2 - d).abs() <= tolerance,
                "{}",
                S::NAME
            );
        }
        assert_eq!(S::from_f64(f64::NAN).to_f64(), 0.0);
    }

    #[test]
    fn conversions_round_trip_exact_values() {
        round_trip::<f32>();
        round_trip::<f64>();
        #[cfg(feature = "fixed")]
        {
            round_trip::<fixed::types::I16F16>();
            round_trip::<fixed::types::I32F32>();
        }
    }
}
