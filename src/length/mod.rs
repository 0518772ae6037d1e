//! Length kernels: how a distance spring in two or three dimensions measures itself.
//!
//! A distance spring between particles `a` and `b` with rest length `L` acts along the
//! axis `n = d/|d|`, `d = p_b − p_a`, on the extension `x = |d| − L`. The square root and
//! the division in that formula are most of a spring's cost on a microcontroller, so the
//! kernel is chosen per scene, at compile time, as a type parameter:
//!
//! | kernel | extension | axis | cost | error | backends |
//! |---|---|---|---|---|---|
//! | [`Exact`] (the default) | `√(d·d) − L` | `d/|d|` | a root and a division | rounding | all |
//! | [`Linearised`] | `(d·d − L²)/(2L)` | `d/L` | no root, no division | second order in `x/L` | all |
//! | `Approximate` (`micromath`) | `(d·d)·r − L` | `d·r` | no root, no division | ~3.4 % in `r` | `f32` |
//! | `ApproximateNewton` (`micromath`) | as above, `r` refined by one Newton step | | 4 multiplies more | ~0.2 % | `f32` |
//! | `HardwareSqrt` (`hw-sqrt`, Cortex-M4F/M7/M33 only) | `vsqrt.f32` | `d/|d|` | one `vsqrt`, one `vdiv` | rounding | `f32` |
//!
//! where `r ≈ 1/√(d·d)` is micromath's inverse square root. The instruction counts are
//! measured by the firmware cost harness (see the README).
//!
//! **Coincident ends.** When `d = 0` the axis is undefined. Every kernel then returns a
//! zero axis, so the spring applies nothing that step (no NaN, no division by zero); it
//! acts again as soon as the ends separate. With a zero rest length (a drag handle: a
//! particle pulled to a point) that is exactly where the spring is satisfied.
//!
//! In fixed point, [`Exact`] takes the root of the exact double-width sum of squares of
//! the wide state, so it holds for separations across the whole range. [`Linearised`]
//! squares in the state format, so in `I16F16` it needs `|d|` below about 2 896 units
//! (it saturates, never wraps, beyond).

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
pub use linearised::{Linearised, LinearisedRest};

use crate::scalar::{MaybeFormat, Scalar};
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
    type Rest: Copy + Debug + Default + PartialEq + MaybeFormat;
    /// A short name for tables.
    const NAME: &'static str;
    /// True when the rest value may be negative (a rest *angle*); distance springs need
    /// a rest length of zero or more.
    const SIGNED_REST: bool = false;
    /// True when the kernel takes a rest length of exactly zero (a drag handle).
    const ZERO_REST: bool = true;
    /// Precomputes the per-spring data for rest length `length` (set-up only; the scene
    /// validates it first).
    fn rest(length: S) -> Self::Rest;
    /// The rest length back, for reporting.
    fn rest_length(rest: &Self::Rest) -> S;
    /// The rest data of the same spring with its ends swapped: the same for a distance,
    /// negated for a signed angle.
    fn flipped(rest: &Self::Rest) -> Self::Rest {
        *rest
    }
    /// How much stiffer and more damped than the exact spring this kernel acts at
    /// `stretch = |d|/L`: the factors `(a, b)` by which its largest stiffness eigenvalue
    /// exceeds `C_k` and its damping along the axis exceeds `C_d`, each at least 1. A
    /// scene checks `a·C_k` and `b·C_d` against the [network
    /// limit](crate::scene::network_limit) at the stretch a spring has when it is added
    /// or retuned. `(1, 1)` for the exact kernels (a stretched exact spring's transverse
    /// stiffness `C_k·(1 − L/|d|)` is below its axial one).
    ///
    /// ```
    /// use stiffspring::length::{Exact, LengthKernel};
    /// assert_eq!(<Exact as LengthKernel<f32>>::stiffening(1.5), (1.0, 1.0));
    /// ```
    fn stiffening(stretch: f64) -> (f64, f64) {
        let _ = stretch;
        (1.0, 1.0)
    }
    /// The extension (in the state format) and the unit (or approximately unit) axis for
    /// the separation `d`.
    fn measure<const D: usize>(d: &[S::State; D], rest: &Self::Rest) -> (S::State, [S::Coef; D]);
}
