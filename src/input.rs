//! What set-up and the infallible setters accept from the caller, in the backend's own
//! arithmetic: a tuning's gains, positions and other bounded magnitudes, and the
//! saturation the UI path applies instead of an error. Shared by values, batches and
//! scenes, so that each refuses the same input with the same error.

use crate::error::{Bound, Error, Parameter, Remedy};
use crate::scalar::{RawGains, Scalar};
use crate::tuning::Tuning;

/// The gains of `tuning` in backend `S`, or the error that says why they do not exist:
/// which gain the backend cannot hold, and the smallest one it holds.
///
/// `#[inline]`: a caller that keeps only the error's kind (the C API's error codes, a
/// firmware's `let Ok(..) else`) then drops the error's construction with it (the halving
/// loop for the least gain the backend holds is most of this function). Out of line, as
/// LTO left it when two constructors of one backend call it, every caller paid for the
/// whole error: with `Start::new`'s, 1.4 KB of the C API's `f32` value firmware on the
/// Cortex-M4F (`scripts/capi-size`).
#[inline]
pub(crate) fn gains_of<S: Scalar>(tuning: &Tuning) -> Result<S::Gains, Error> {
    match RawGains::<S>::new(tuning.stiffness(), tuning.damping()) {
        Some(gains) => Ok(gains.get()),
        None => Err(gains_error::<S>(tuning)),
    }
}

/// Why backend `S` cannot hold the gains of `tuning` ([`gains_of`]): which gain, and the
/// smallest one it holds. A `const fn`, shared with [`Tuned::new`](crate::Tuned::new).
#[inline]
pub(crate) const fn gains_error<S: Scalar>(tuning: &Tuning) -> Error {
    let (k, d) = (tuning.stiffness(), tuning.damping());
    let stiffness = RawGains::<S>::new(k, 0.0).is_none();
    let (parameter, value) = if stiffness {
        (Parameter::Stiffness, k)
    } else {
        (Parameter::Damping, d)
    };
    // The smallest power of two the backend holds, found by halving: this runs only when
    // set-up fails (2⁻²⁴ for `C_k` in `I16F16`, 2⁻³² in `I32F32`).
    let mut least = 1.0;
    while least > f64::MIN_POSITIVE && held::<S>(0.5 * least, stiffness) {
        least *= 0.5;
    }
    Error::Unrepresentable {
        parameter,
        backend: S::NAME,
        value,
        limit: least,
        remedy: if S::RESOLUTION > 0.0 {
            Remedy::LowerRate
        } else {
            Remedy::WiderBackend
        },
    }
}

/// Whether backend `S` holds `v` as the stiffness (or as the damping) alone.
const fn held<S: Scalar>(v: f64, stiffness: bool) -> bool {
    if stiffness {
        RawGains::<S>::new(v, 0.0).is_some()
    } else {
        RawGains::<S>::new(0.0, v).is_some()
    }
}

/// [`Scalar::MAX`] in the backend's type (a constant: the conversion folds).
#[inline(always)]
fn max_position<S: Scalar>() -> S {
    S::from_f64(S::MAX)
}

/// `value` as a position, or why not: not finite, or beyond [`Scalar::MAX`].
pub(crate) fn check_position<S: Scalar>(value: S, parameter: Parameter) -> Result<S, Error> {
    // Fixed point always passes: its range is the bound.
    check_magnitude(value, S::MAX, parameter)
}

/// `value` if `|value| ≤ max`, or why not: not finite, or beyond `max`.
///
/// The test runs in the backend's own arithmetic (an `f32` firmware links no `f64`
/// comparison for it: `S::from_f64` of a constant folds); only the error is built in
/// `f64`.
#[inline(always)]
pub(crate) fn check_magnitude<S: Scalar>(
    value: S,
    max: f64,
    parameter: Parameter,
) -> Result<S, Error> {
    // NaN compares false, ±∞ is above the bound.
    if value.abs() <= S::from_f64(max) {
        return Ok(value);
    }
    let v = value.to_f64();
    Err(if !v.is_finite() {
        Error::NotFinite { parameter }
    } else {
        Error::OutOfRange {
            parameter,
            value: v,
            bound: Bound::MagnitudeAtMost { max },
        }
    })
}

/// `value` made usable by an infallible setter: `None` for NaN, else saturated to
/// [`Scalar::MAX`]. In the backend's arithmetic, as [`check_position`].
pub(crate) fn saturate<S: Scalar>(value: S) -> Option<S> {
    let max = max_position::<S>();
    if value.abs() <= max {
        Some(value)
    } else if value > S::ZERO {
        Some(max)
    } else if value < S::ZERO {
        Some(max.neg())
    } else {
        None // NaN
    }
}
