//! Length kernels: how a distance spring in two or three dimensions measures itself.
//!
//! A distance spring between particles `a` and `b` with rest length `L` acts along the
//! axis `n = d/|d|`, `d = p_b − p_a`, on the extension `x = |d| − L`. The square root and
//! the division in that formula are most of a spring's cost on a microcontroller, so the
//! kernel is chosen per scene, at compile time, as a type parameter:
//!
//! | kernel | extension | axis | cost | error |
//! |---|---|---|---|---|
//! | [`Exact`] | `√(d·d) − L` | `d/|d|` | a root and a division | rounding |
//! | `Approximate` (`micromath`, f32) | `(d·d)·r − L` | `d·r` | no root, no division | ~3.4 % in `r` |
//! | `ApproximateNewton` (`micromath`, f32) | as above, `r` refined by one Newton step | | 4 multiplies more | ~0.2 % |
//! | `HardwareSqrt` (`hw-sqrt`, Cortex-M4F/M7/M33 only) | `vsqrt.f32` | `d/|d|` | one `vsqrt`, one `vdiv` | rounding |
//! | [`Linearised`] | `(d·d − L²)/(2L)` | `d/L` | no root, no division | second order in `x/L` |
//!
//! where `r ≈ 1/√(d·d)` is micromath's inverse square root. Measure the trade in
//! `cargo bench` and the firmware `cost` harness rather than guessing.
//!
//! **Coincident ends.** When `d = 0` the axis is undefined. Every kernel then returns a
//! zero axis, so the spring applies nothing that step (no NaN, no division by zero); it
//! acts again as soon as the ends separate.
//!
//! In fixed point, [`Exact`] takes the root of the exact double-width sum of squares with
//! the `fixed` crate's `sqrt`, so it holds for separations across the whole range.
//! [`Linearised`] squares in the position format, so in `I16F16` it needs `|d|` below
//! about 181 units (it saturates, never wraps, beyond).

#[cfg(feature = "micromath")]
mod approximate;
mod exact;
#[cfg(all(feature = "hw-sqrt", target_arch = "arm", target_abi = "eabihf"))]
mod hardware;
mod linearised;

#[cfg(feature = "micromath")]
pub use approximate::{Approximate, ApproximateNewton};
pub use exact::Exact;
#[cfg(all(feature = "hw-sqrt", target_arch = "arm", target_abi = "eabihf"))]
pub use hardware::HardwareSqrt;
pub use linearised::Linearised;

use crate::scalar::Scalar;
use core::fmt::Debug;

mod sealed {
    pub trait Sealed {}
}
pub(crate) use sealed::Sealed;

/// How a distance spring measures its extension and axis; see the [module docs](self).
///
/// ```
/// use stiffspring::length::{Exact, LengthKernel};
///
/// let rest = <Exact as LengthKernel<f32>>::rest(5.0);
/// let (extension, axis) = <Exact as LengthKernel<f32>>::measure(&[6.0, 8.0], &rest);
/// assert_eq!(extension, 5.0); // |(6, 8)| − 5
/// assert_eq!(axis, [0.6, 0.8]);
/// ```
pub trait LengthKernel<S: Scalar>: Sealed + Copy + Debug + Default + 'static {
    /// What the kernel precomputes from a spring's rest length at set-up.
    type Rest: Copy + Debug + Default + PartialEq + crate::scalar::MaybeFormat;
    /// A short name for tables.
    const NAME: &'static str;
    /// True when the rest value may be zero or negative (a rest *angle*); distance
    /// springs need a positive rest length.
    const SIGNED_REST: bool = false;
    /// Precomputes the per-spring data for rest length `length` (set-up only; the scene
    /// validates that `length` is finite and positive).
    fn rest(length: f64) -> Self::Rest;
    /// The rest length back, for reporting.
    fn rest_length(rest: &Self::Rest) -> f64;
    /// The extension and the (unit, or approximately unit) axis for the separation `d`.
    fn measure<const D: usize>(d: &[S; D], rest: &Self::Rest) -> (S, [S; D]);
}

/// `1/length`, or 0 when the length is 0: coincident ends, or ends so close that `d·d`
/// underflowed, get a zero axis (the spring applies nothing) instead of `0·∞ = NaN` or a
/// huge `d/MIN_POSITIVE`. A comparison and a select, not `max` (a library call,
/// `fmaxf`, on a Cortex-M4F, which has no `vmax`).
#[cfg(any(
    feature = "libm",
    all(feature = "hw-sqrt", target_arch = "arm", target_abi = "eabihf")
))]
macro_rules! reciprocal_or_zero {
    ($length:expr, $F:ty) => {{
        let length: $F = $length;
        if length > 0.0 { 1.0 / length } else { 0.0 }
    }};
}
#[cfg(any(
    feature = "libm",
    all(feature = "hw-sqrt", target_arch = "arm", target_abi = "eabihf")
))]
pub(crate) use reciprocal_or_zero;

/// `d·s` for every component: the axis from the separation and a reciprocal length.
#[inline(always)]
pub(crate) fn scaled<S: Scalar, const D: usize>(d: &[S; D], s: S) -> [S; D] {
    let mut n = [S::ZERO; D];
    for (n, d) in n.iter_mut().zip(d) {
        *n = d.mul(s);
    }
    n
}
