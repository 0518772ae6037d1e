//! The arithmetic the whole crate is generic over: see [`Scalar`].

#[cfg(feature = "fixed")]
mod fixed_point;
mod float;

use core::fmt::Debug;

/// Keeps [`Scalar`] implementable only inside this crate, so that methods can be added
/// without breaking anyone.
mod sealed {
    pub trait Sealed {}
}
pub(crate) use sealed::Sealed;

/// `defmt::Format` with the `defmt` feature, and nothing without it: a bound on the
/// backends (and the length kernels' per-spring data) that lets every generic type of
/// the crate derive `defmt::Format` exactly when the feature is on.
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

/// A number format the springs can run in: `f32`, `f64`, `I16F16` or `I32F32`.
///
/// The methods are the complete arithmetic of the hot loops. Floats use plain IEEE
/// arithmetic; fixed point saturates at the ends of its range and truncates products
/// toward zero, as measured below.
///
/// [`Scalar`] is implemented for `f32` (Cortex-M4F/M7/M33, which have a single-precision
/// FPU), `f64` (host tools and tests) and, with the `fixed` feature, for
/// `fixed::types::I16F16` and `fixed::types::I32F32` (Cortex-M0/M0+, which have no
/// FPU at all).
///
/// Two formats per backend:
///
/// - **Positions and per-step velocities** (`u = v·dt`) are `Self`.
/// - **Coefficients** (`C_k`, `C_d`, the two-body weights `w_a`, `w_b`) are
///   [`Scalar::Coef`]. In fixed point they keep many more fractional bits than
///   positions: a 1 Hz spring stepped at 1 kHz has `C_k ≈ 3.9e−5`, which is only 3 LSB in
///   Q16.16 (a 16 % error in stiffness) but 21 000 LSB in Q3.29.
///
/// Every fixed-point operation saturates; none wraps. Float ↔ fixed conversion happens
/// at set-up only ([`Scalar::from_f64`], [`Scalar::coef`]); the stepping code never
/// touches a float when the backend is fixed point.
///
/// # Rounding in fixed point
///
/// Products of a position and a coefficient are computed exactly in a double-width
/// integer, summed there, and rounded **once**, toward zero. The choice comes from the
/// measurements in `tests/fixed_rounding.rs` (run
/// `cargo test --release --test fixed_rounding -- --nocapture` for the table): 324
/// trajectories, over exact-map tunings and lightly damped raw ones, each run until its
/// state repeats.
///
/// | rounding | ends at rest | limit cycles | worst rest offset | worst cycle |
/// |---|---|---|---|---|
/// | toward −∞ (the `fixed` crate's) | 228 | 96 | `1/C_k` LSB | 144 half-bands, 322 LSB/step |
/// | to nearest (any tie rule) | 192 | 132 | `0.5/C_k` LSB | 1795 half-bands, 1004 LSB/step |
/// | **toward zero** | **324** | **0** | **`1/C_k` LSB** | none |
///
/// (A half-band is `0.5/C_k` LSB.) Round-to-nearest stops closer to the target but lets a
/// lightly damped spring ring forever in a limit cycle hundreds of LSB wide, which no rest
/// threshold can tell from motion. With truncation toward zero, every measured trajectory
/// in the article's square `[0, 1]²` ended on a fixed point with `u = 0` inside the dead
/// band `|x| < 1/C_k` LSB (600 more runs in `tests/fixed_point_limits.rs`). Beyond the
/// square (`C_k > 1`, from an undersampled exact map) it can end in a limit cycle of a few
/// LSB, near `1/C_d` LSB when very lightly damped. It is also symmetric, so a trajectory
/// started from `−x₀` is exactly the negation of the one from `x₀`, and two equal masses
/// get exactly opposite velocity changes (their momentum is conserved to the bit).
///
/// The price is a small drag: truncation shortens `u` by half an LSB per step on
/// average, a Coulomb friction that costs a lightly damped spring `2/C_k` LSB of amplitude
/// per cycle (bounded in `tests/exact_map.rs`). Even an undamped spring (`C_d = 0`) feels
/// it, because the sum `u − C_k·x` is truncated, not `C_k·x` alone: over 10⁶ steps an
/// `I16F16` spring of amplitude 100 loses 85 % of its energy at `C_k = 0.001` and 3 % at
/// `C_k = 2.5`; `I32F32` at most 4·10⁻⁵ (`tests/long_runs.rs`).
///
/// The rest detection of [`SpringValue`](crate::SpringValue) widens its thresholds to cover
/// the dead band, and beyond the square the limit cycles (`4/C_d` LSB), so a damped
/// fixed-point value always settles.
///
/// ```
/// use stiffspring::Scalar;
///
/// // The spring's velocity response (1 − C_d)·u − C_k·x for u = 2, x = 1,
/// // C_d = 0.5, C_k = 0.25, rounded once.
/// let u_next = f32::mul_coef_diff(2.0, f32::coef(0.5), 1.0, f32::coef(0.25));
/// assert_eq!(u_next, 0.75);
/// ```
pub trait Scalar:
    Sealed + MaybeFormat + Copy + PartialOrd + Debug + Default + Send + Sync + 'static
{
    /// The format of coefficients (`C_k`, `1 − C_d`, weights): a signed fraction in
    /// `[−4, 4)`, with more precision than positions in fixed point.
    type Coef: MaybeFormat + Copy + PartialEq + Debug + Default + Send + Sync + 'static;

    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// A short name for tables: `"f32"`, `"I16F16"`, ...
    const NAME: &'static str;
    /// The smallest step between two values near zero, as `f64`; `0.0` for floats.
    const RESOLUTION: f64;
    /// The largest magnitude accepted at set-up for positions, targets and velocities.
    ///
    /// For floats it leaves headroom (`2¹⁰⁰` for `f32`, `2¹⁰⁰⁰` for `f64`) so that the
    /// transient growth of a stable spring can never reach infinity. Fixed point accepts
    /// its whole range and saturates.
    const SAFE_MAGNITUDE: f64;

    /// The largest magnitude of positions and step velocities in a
    /// [`Scene`](crate::scene::Scene): small enough that a distance spring's squared
    /// length stays finite (`2⁶⁰` for `f32`, `2⁵⁰⁰` for `f64`); the whole range in fixed
    /// point, which saturates anyway.
    const NETWORK_MAGNITUDE: f64;

    /// Converts from `f64`, rounding to nearest and saturating at the ends of the range
    /// (NaN becomes zero). Set-up only.
    fn from_f64(value: f64) -> Self;
    /// Converts to `f64`: exact for `f32` and `I16F16`, rounded to nearest for `I32F32`
    /// values beyond 53 significant bits.
    fn to_f64(self) -> f64;
    /// Converts a coefficient from `f64`, rounding to nearest and saturating to
    /// `[−4, 4)` in fixed point. Set-up only.
    fn coef(value: f64) -> Self::Coef;
    /// Converts a coefficient back to `f64`.
    fn coef_to_f64(coef: Self::Coef) -> f64;
    /// True when the value is finite and within [`Scalar::SAFE_MAGNITUDE`].
    fn is_valid(self) -> bool;

    /// `self + rhs` (saturating in fixed point).
    fn add(self, rhs: Self) -> Self;
    /// `self − rhs` (saturating in fixed point).
    fn sub(self, rhs: Self) -> Self;
    /// `−self` (saturating in fixed point).
    fn neg(self) -> Self;
    /// `|self|` (saturating in fixed point).
    fn abs(self) -> Self;
    /// `self · coef`, rounded once.
    fn mul_coef(self, coef: Self::Coef) -> Self;
    /// `a · ca − b · cb`, rounded once: the spring's velocity response
    /// `(1 − C_d)·u − C_k·x`.
    fn mul_coef_diff(a: Self, ca: Self::Coef, b: Self, cb: Self::Coef) -> Self;
    /// `self · rhs`, rounded once (saturating in fixed point).
    fn mul(self, rhs: Self) -> Self;
    /// `Σ aᵢ·bᵢ`, rounded once (saturating in fixed point): projections onto a spring's
    /// axis.
    fn dot<const D: usize>(a: &[Self; D], b: &[Self; D]) -> Self;
    /// `self` limited to `[−bound, bound]`, with NaN mapped to zero: the safety net that
    /// keeps an unstable network finite. The identity in fixed point, whose arithmetic
    /// already saturates.
    fn clamp_magnitude(self, bound: Self) -> Self;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip<S: Scalar>() {
        for v in [0.0, 1.0, -1.0, 0.5, 123.25, -7.75] {
            assert_eq!(S::from_f64(v).to_f64(), v, "{}", S::NAME);
        }
        for c in [0.0, 1.0, 0.5, 0.25, 3.5, -0.75] {
            assert_eq!(S::coef_to_f64(S::coef(c)), c, "{}", S::NAME);
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
