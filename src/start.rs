//! How a spring's step velocity `u` relates to the velocity of the continuous trajectory
//! it samples, in a backend's formats.
//!
//! The discrete state `(x, u)` is two samples, `x_n` and `x_{n−1} = x_n − u`. For a tuning
//! from the exact map, the continuous trajectory through the sample `x` with velocity `v`
//! has the backward sample `x(−dt)`, so that
//!
//! ```text
//! u = P·x + Q·v
//! ```
//!
//! with `P ≈ C_k/2` and `Q ≈ dt` for a well-sampled spring (see
//! [`Oscillator::start_weights`](crate::Oscillator::start_weights)). This linear relation
//! is what lets a value be flung (`u` from `v`), retargeted (`x` jumps by `Δ` with `v`
//! kept: `u += P·Δ`) and retuned (`v` from `u`, then `u` again) while staying on an exact
//! continuous trajectory. Raw coefficients use `P = 0`, `Q = dt`: the article's `u = v·dt`.
//!
//! Values keep `ũ = (1 − C_d)·u` (see [`Scalar`](crate::Scalar)), so everything here is
//! scaled by the retention: `ũ = P̃·x + Q̃·v` with `P̃ = (1 − C_d)·P`, `Q̃ = (1 − C_d)·Q`.

use crate::error::{Error, Parameter, Remedy};
use crate::scalar::{RawFactor, RawState, Scalar};
use crate::tuning::Tuning;

/// `P`, `Q` and `1/Q` in the backend's factor format, and the bound on the state.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Start<S: Scalar> {
    offset_weight: S::Factor,
    velocity_weight: S::Factor,
    /// `1/Q̃`, or 0 when `Q̃ = 0` (a spring with `C_d = 1` keeps no velocity).
    inverse_velocity_weight: S::Factor,
    /// `1/(1 − C_d)`, or 0 when `C_d = 1`: the step velocity from the kept one.
    inverse_retention: S::Factor,
    /// The largest `|x|` and `|u|` a setter may leave: `STATE_MAX / growth` for floats,
    /// so that no later step can overflow (see `Tuning::growth`); `STATE_MAX / 2` in fixed
    /// point, which saturates.
    pub(crate) limit: S::State,
}

impl<S: Scalar> Start<S> {
    /// The start data of `tuning` in backend `S`.
    ///
    /// # Errors
    ///
    /// [`Error::Unrepresentable`] when the tuning's transient growth leaves floats no room
    /// for the positions they accept.
    ///
    /// `#[inline]`, as `gains_of`: so that a caller that keeps only the error's kind does
    /// not build the rest of it.
    #[inline]
    pub(crate) fn new(tuning: &Tuning) -> Result<Self, Error> {
        match StartParts::new(tuning) {
            Ok(parts) => Ok(parts.get()),
            Err(e) => Err(e),
        }
    }

    /// The step velocity `P·x + Q·v` for offset `x` and velocity `v`, or the error that
    /// says it leaves the state's range.
    pub(crate) fn step_velocity(&self, offset: S::State, velocity: S) -> Result<S::State, Error> {
        self.check(
            self.step_velocity_unchecked(offset, velocity),
            Parameter::StepVelocity,
        )
    }

    /// `P·x + Q·v`, saturating in fixed point, unbounded in floats.
    pub(crate) fn step_velocity_unchecked(&self, offset: S::State, velocity: S) -> S::State {
        S::state_add(
            S::scale(offset, self.offset_weight),
            S::scale(velocity.widen(), self.velocity_weight),
        )
    }

    /// `u + P·Δ`: the step velocity after the offset jumped by `Δ` with the velocity
    /// kept.
    pub(crate) fn shifted(&self, step_velocity: S::State, delta: S::State) -> S::State {
        S::state_add(step_velocity, S::scale(delta, self.offset_weight))
    }

    /// The velocity (units per second) `(u − P·x)/Q` of the continuous trajectory through
    /// offset `x` with step velocity `u`.
    pub(crate) fn velocity(&self, offset: S::State, step_velocity: S::State) -> S {
        let u = S::state_sub(step_velocity, S::scale(offset, self.offset_weight));
        read(S::scale(u, self.inverse_velocity_weight))
    }

    /// The step velocity `u = ũ/(1 − C_d)` of the last step (0 for `C_d = 1`).
    pub(crate) fn step_velocity_of(&self, kept: S::State) -> S {
        read(S::scale(kept, self.inverse_retention))
    }

    /// `state` if it lies within the limit, else the error naming `parameter`.
    pub(crate) fn check(&self, state: S::State, parameter: Parameter) -> Result<S::State, Error> {
        bounded::<S>(state, self.limit, parameter)
    }

    /// `state` limited to the bound (saturating), for the infallible setters.
    pub(crate) fn clamp(&self, state: S::State) -> S::State {
        if S::within(state, self.limit) {
            state
        } else if state > S::STATE_ZERO {
            self.limit
        } else {
            S::state_sub(S::STATE_ZERO, self.limit)
        }
    }
}

/// [`Start`] as the bits of its factors and limit, computed by a `const fn`: what
/// [`Start::new`] builds at run time, and what a [`Tuned`](crate::Tuned) carries from the
/// compiler.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct StartParts<S> {
    offset_weight: RawFactor<S>,
    velocity_weight: RawFactor<S>,
    inverse_velocity_weight: RawFactor<S>,
    inverse_retention: RawFactor<S>,
    limit: RawState<S>,
}

impl<S: Scalar> StartParts<S> {
    /// The start data of `tuning` in backend `S` ([`Start::new`]). `#[inline]`, as
    /// `Start::new`.
    #[inline]
    pub(crate) const fn new(tuning: &Tuning) -> Result<Self, Error> {
        let (p, q) = tuning.start_weights();
        let limit = if S::RESOLUTION > 0.0 {
            // Half the range: a product that saturated at the end of the state is then
            // seen to be beyond the limit, never taken for a value inside it.
            0.5 * S::STATE_MAX
        } else {
            // Twice the growth: rounding each step adds to the state a little more than
            // the exact map would.
            let limit = S::STATE_MAX / (2.0 * tuning.growth());
            if limit.is_nan() || limit < 2.0 * S::MAX {
                return Err(Error::Unrepresentable {
                    parameter: Parameter::Stiffness,
                    backend: S::NAME,
                    value: tuning.growth(),
                    limit: S::STATE_MAX / (4.0 * S::MAX),
                    remedy: Remedy::WiderBackend,
                });
            }
            limit
        };
        Ok(StartParts {
            offset_weight: RawFactor::new(p),
            velocity_weight: RawFactor::new(q),
            inverse_velocity_weight: RawFactor::new(inverse(q)),
            inverse_retention: RawFactor::new(inverse(tuning.retention())),
            limit: RawState::new(limit),
        })
    }

    /// The start data.
    #[inline]
    pub(crate) fn get(&self) -> Start<S> {
        Start {
            offset_weight: self.offset_weight.get(),
            velocity_weight: self.velocity_weight.get(),
            inverse_velocity_weight: self.inverse_velocity_weight.get(),
            inverse_retention: self.inverse_retention.get(),
            limit: self.limit.get(),
        }
    }
}

/// `1/v`, and 0 for 0 (a weight of 0 has no inverse to apply).
const fn inverse(v: f64) -> f64 {
    if v != 0.0 { 1.0 / v } else { 0.0 }
}

/// `state` if `|state| ≤ limit`, else the error that names
/// `parameter`, the value and the limit, and says what would hold it: a larger unit, which
/// holds the same motion in fewer units in every backend.
pub(crate) fn bounded<S: Scalar>(
    state: S::State,
    limit: S::State,
    parameter: Parameter,
) -> Result<S::State, Error> {
    if S::within(state, limit) {
        Ok(state)
    } else {
        Err(Error::Unrepresentable {
            parameter,
            backend: S::NAME,
            value: S::state_to_f64(state),
            limit: S::state_to_f64(limit),
            remedy: Remedy::LargerUnit,
        })
    }
}

/// A derived quantity as a position-format number, saturated at `±Scalar::MAX`: in floats a
/// heavily overdamped spring's step velocity `ũ/(1 − C_d)` (its exact start extrapolated one
/// step back) can lie beyond the format, which must read as the largest value, never as
/// infinity; fixed point saturates in `narrow`.
fn read<S: Scalar>(state: S::State) -> S {
    S::narrow(S::state_clamp(state, S::state_from_f64(S::MAX)))
}
