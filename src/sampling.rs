//! How a spring's step velocity `u` relates to the velocity of the continuous trajectory
//! it samples.
//!
//! The discrete state `(x, u)` is two samples, `x_n` and `x_{n−1} = x_n − u`. For a tuning
//! from the exact map, the continuous trajectory through the sample `x` with velocity `v`
//! has the backward sample `x(−dt)`, so that (see [`Oscillator::start_weights`])
//!
//! ```text
//! u = P·x + Q·v
//! ```
//!
//! with `P ≈ C_k/2` and `Q ≈ dt` for a well-sampled spring. This linear relation is what
//! lets a value be flung (`u` from `v`), retargeted or teleported (`x` jumps by `Δ` with
//! `v` kept: `u += P·Δ`), retimed or retuned (`v` from `u`, then `u` again) while staying
//! on an exact continuous trajectory. Starting a value from rest with `u = 0` instead
//! would put it on a trajectory that was already moving, a first-order error of about
//! `C_k/2` of the offset per step.
//!
//! A tuning from raw coefficients keeps the article's discrete meaning and uses `P = 0`,
//! `Q = dt`: the step velocity is the velocity times `dt`. So does a tuning whose
//! oscillator cannot be sampled this way in the backend (a heavily overdamped,
//! undersampled spring whose `P` leaves the coefficient range).
//!
//! [`Oscillator::start_weights`]: crate::Oscillator::start_weights

use crate::error::{Error, Parameter};
use crate::kernel::Coefficients;
use crate::scalar::Scalar;
use crate::tuning::Tuning;

/// `P` and `Q` for one spring at one `dt`.
///
/// Both stay in `f64`: they are used only on retargets, flings and retunes, never in a
/// step, and `P` spans many decades (about `C_k/2` for a well-sampled spring, above 4 for
/// an undersampled one, `e^{2ζω·dt}` for a heavily overdamped one), more than any
/// fixed-point coefficient format holds.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Sampling<S: Scalar> {
    offset_weight: f64,
    velocity_weight: f64,
    continuous: bool,
    backend: core::marker::PhantomData<S>,
}

impl<S: Scalar> Sampling<S> {
    /// The weights for `tuning`, converted to `coefficients`, stepped every `dt`
    /// (set-up only).
    pub(crate) fn new(tuning: &Tuning, coefficients: &Coefficients<S>, dt: f64) -> Self {
        #[cfg(feature = "libm")]
        if !tuning.samples_oscillator() {
            // Raw coefficients: the article's discrete velocity.
        } else if let Ok(osc) = coefficients.tuning().oscillator(dt) {
            let (p, q) = osc.start_weights(dt);
            // Only a backward extrapolation that overflows f64 (ζω·dt in the hundreds)
            // falls back to the discrete meaning.
            if p.is_finite() && q.is_finite() && q > 0.0 {
                return Sampling {
                    offset_weight: p,
                    velocity_weight: q,
                    continuous: true,
                    backend: core::marker::PhantomData,
                };
            }
        }
        #[cfg(not(feature = "libm"))]
        let _ = (tuning, coefficients);
        Sampling {
            offset_weight: 0.0,
            velocity_weight: dt,
            continuous: false,
            backend: core::marker::PhantomData,
        }
    }

    /// True when the weights follow a continuous oscillator (else `P = 0`, `Q = dt`).
    pub(crate) fn is_continuous(&self) -> bool {
        self.continuous
    }

    /// The step velocity after the offset jumped by `delta` with the velocity kept:
    /// `u + P·Δ`, rounded once and saturated to the backend's range (a heavily overdamped,
    /// undersampled spring in fixed point can ask for more than the range holds; the
    /// stable map still brings it to rest).
    pub(crate) fn shift(&self, step_velocity: S, delta: S) -> S {
        if delta == S::ZERO || !self.continuous {
            return step_velocity;
        }
        let u = step_velocity.to_f64() + self.offset_weight * delta.to_f64();
        S::from_f64(u.clamp(-S::SAFE_MAGNITUDE, S::SAFE_MAGNITUDE))
    }

    /// The step velocity `P·x + Q·v` for offset `x` and velocity `v` (units per second).
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] for the velocity when the result leaves the backend's range.
    pub(crate) fn step_velocity(&self, offset: S, velocity: S) -> Result<S, Error> {
        let u = self.offset_weight * offset.to_f64() + self.velocity_weight * velocity.to_f64();
        if u.is_finite() && u.abs() <= S::SAFE_MAGNITUDE {
            Ok(S::from_f64(u))
        } else {
            Err(Error::OutOfRange(Parameter::Velocity))
        }
    }

    /// The velocity (units per second) `(u − P·x)/Q` of the continuous trajectory through
    /// offset `x` with step velocity `u`.
    pub(crate) fn velocity(&self, offset: S, step_velocity: S) -> S {
        let u = step_velocity.to_f64() - self.offset_weight * offset.to_f64();
        S::from_f64(u / self.velocity_weight)
    }
}
