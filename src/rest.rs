//! When a spring counts as settled: a threshold in the user's units.
//!
//! A value is at rest when the motion it has left is smaller than a change nobody would
//! see. At rest it snaps exactly to its target and stays there until it is moved: a batch,
//! a decay and a scene then skip it, and a `SpringValue` steps its zero state, which no
//! step changes (its moving path has no flag test; see `SpringValue::step`).

use crate::error::{Error, Parameter, positive};
use crate::scalar::{RawState, Scalar};
use crate::tuning::Tuning;

/// The smallest motion that still counts: a position threshold (the user's unit) and a
/// velocity threshold (units per second).
///
/// A spring settles when **the amplitude of the motion it has left** is below the
/// position threshold and it moves slower than the velocity threshold. The amplitude
/// matters, not just the offset: a slow spring passes its target fast and turns far from
/// it, and a test on the offset and the velocity alone (Android's, for one) lets a 1 Hz
/// spring with ζ = 0.1 snap while it still swings 8.5 times the position threshold.
/// Here the step-velocity band is also limited by `position·√C_k`: an undamped spring of
/// amplitude `A` crosses its target with step velocity `A·√C_k` exactly (`C_k = 4·sin²(θ/2)`),
/// so a spring that passes both tests has less than the threshold left (to a factor
/// `1 + θ/4`, measured in `tests/value_behaviour.rs`).
///
/// ```
/// use stiffspring::RestThreshold;
///
/// // Pixels: a quarter of a pixel and a few pixels per second.
/// let px = RestThreshold::new(0.25, 4.0)?;
/// assert_eq!((px.position(), px.velocity()), (0.25, 4.0));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RestThreshold {
    position: f64,
    velocity: f64,
}

impl RestThreshold {
    /// Android's thresholds for a minimum visible change of 1 (one pixel):
    /// `position = 0.75`, `velocity = 46.875` per second.
    ///
    /// ```
    /// use stiffspring::RestThreshold;
    /// assert_eq!(RestThreshold::PIXELS, RestThreshold::from_min_visible_change(1.0)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const PIXELS: RestThreshold = RestThreshold::from_visible_change(1.0);

    /// A threshold of `position` (the user's unit) and `velocity` (units per second).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for either argument `≤ 0`.
    ///
    /// ```
    /// assert!(stiffspring::RestThreshold::new(0.0, 1.0).is_err());
    /// ```
    pub const fn new(position: f64, velocity: f64) -> Result<Self, Error> {
        let position = match positive(position, Parameter::Threshold) {
            Ok(p) => p,
            Err(e) => return Err(e),
        };
        let velocity = match positive(velocity, Parameter::Threshold) {
            Ok(v) => v,
            Err(e) => return Err(e),
        };
        Ok(RestThreshold { position, velocity })
    }

    /// Android's rule: from the smallest change of the value a user can see,
    /// `position = 0.75·change` and `velocity = 62.5·position` per second
    /// (`SpringForce`'s `THRESHOLD_MULTIPLIER` and `VELOCITY_THRESHOLD_MULTIPLIER`).
    ///
    /// Android's constants for the change: 1 for pixels, 0.1 for degrees of rotation,
    /// 1/256 for alpha, 1/500 for scale.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a change `≤ 0`.
    ///
    /// ```
    /// let alpha = stiffspring::RestThreshold::from_min_visible_change(1.0 / 256.0)?;
    /// assert_eq!(alpha.position(), 0.75 / 256.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn from_min_visible_change(change: f64) -> Result<Self, Error> {
        match positive(change, Parameter::Threshold) {
            Ok(c) => Ok(Self::from_visible_change(c)),
            Err(e) => Err(e),
        }
    }

    /// [`RestThreshold::default`], as a constant for set-up computed at compile time.
    pub(crate) const DEFAULT: RestThreshold = RestThreshold::from_visible_change(1e-3);

    const fn from_visible_change(change: f64) -> Self {
        let position = 0.75 * change;
        RestThreshold {
            position,
            velocity: 62.5 * position,
        }
    }

    /// The position threshold, in the user's unit.
    ///
    /// ```
    /// assert_eq!(stiffspring::RestThreshold::PIXELS.position(), 0.75);
    /// ```
    pub const fn position(&self) -> f64 {
        self.position
    }

    /// The velocity threshold, in the user's unit per second.
    ///
    /// ```
    /// assert_eq!(stiffspring::RestThreshold::PIXELS.velocity(), 46.875);
    /// ```
    pub const fn velocity(&self) -> f64 {
        self.velocity
    }
}

impl Default for RestThreshold {
    /// A thousandth of a unit: fine enough for pixels and for values in `[0, 1]` alike.
    ///
    /// ```
    /// let t = stiffspring::RestThreshold::default();
    /// assert_eq!((t.position(), t.velocity()), (0.75e-3, 0.046875));
    /// ```
    fn default() -> Self {
        RestThreshold::DEFAULT
    }
}

/// A [`RestThreshold`] converted for one tuning and one backend at set-up: the offset
/// band and the step-velocity band, in the state format, prepared for one integer
/// comparison each ([`Scalar::in_band`]).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RestBand<S: Scalar> {
    pub(crate) offset: S::Band,
    pub(crate) step_velocity: S::Band,
}

impl<S: Scalar> RestBand<S> {
    pub(crate) fn new(threshold: &RestThreshold, tuning: &Tuning) -> Self {
        Self::scaled(threshold, tuning.root_stiffness(), tuning.dt())
    }

    /// The band for a spring with `√C_k = root_stiffness` stepped every `dt`.
    pub(crate) fn scaled(threshold: &RestThreshold, root_stiffness: f64, dt: f64) -> Self {
        RestBandParts::scaled(threshold, root_stiffness, dt).get()
    }

    /// The band of a [`Decay`](crate::Decay) (a friction with no stiffness), whose offset
    /// from its resting point is `−ũ/C_d`: at rest when the travel it has left,
    /// `|ũ|/C_d`, is within the position threshold and its velocity, `|ũ|·c/C_d`, within
    /// the velocity threshold. `damping` is `C_d`, `rate` the friction's `c`.
    ///
    /// Only the kept step velocity is tested: the offset is `−ũ/C_d` up to the rounding
    /// the steps add to it, and a test on it could fail for ever once `ũ` has reached zero
    /// (in `f32` that drift is at most `2⁻²⁴/C_d` of the throw, 7e−6 at 240 Hz with
    /// iOS's normal rate, above the default threshold for a long throw). In fixed point
    /// the band is at least the kept step velocity of one last bit of travel, `lsb·C_d`
    /// (rounded away from zero, the damping term brings `ũ` to zero, so the value always
    /// gets there).
    pub(crate) fn decay(threshold: &RestThreshold, damping: f64, rate: f64) -> Self {
        let p = threshold.position;
        let by_travel = p * damping;
        let by_speed = threshold.velocity * damping / rate;
        let u = if by_travel < by_speed {
            by_travel
        } else {
            by_speed
        };
        // Floats: at least 1e−30, far below anything visible. Below it a float `ũ`
        // reaches the subnormals, where `C_d·ũ` rounds to nothing and `ũ` stops
        // shrinking: a band of zero would never be reached.
        let least = if S::RESOLUTION > 0.0 {
            S::RESOLUTION * damping
        } else {
            1e-30
        };
        let clamp = |v: f64, least: f64| {
            let v = if v < least { least } else { v };
            let half = 0.5 * S::STATE_MAX;
            S::band(S::state_from_f64(if v > half { half } else { v }))
        };
        RestBand {
            // Every offset: half the state's range, the widest band `in_band` takes.
            offset: clamp(0.5 * S::STATE_MAX, 0.0),
            step_velocity: clamp(u, least),
        }
    }

    /// True when both the offset and the step velocity are inside the band. The step
    /// velocity is tested first: a moving spring is outside its band most of the time,
    /// and the test stops at the first comparison.
    #[inline(always)]
    pub(crate) fn contains(&self, offset: S::State, step_velocity: S::State) -> bool {
        S::in_band(step_velocity, self.step_velocity) && S::in_band(offset, self.offset)
    }

    /// [`RestBand::contains`] without a branch, for loops that a compiler vectorises.
    #[inline(always)]
    pub(crate) fn contains_all(&self, offset: S::State, step_velocity: S::State) -> bool {
        S::in_band(step_velocity, self.step_velocity) & S::in_band(offset, self.offset)
    }
}

/// [`RestBand`] as the bits of its two bounds, computed by a `const fn`: what
/// [`RestBand::scaled`] builds at run time, and what a [`Tuned`](crate::Tuned) carries
/// from the compiler.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RestBandParts<S> {
    offset: RawState<S>,
    step_velocity: RawState<S>,
}

impl<S: Scalar> RestBandParts<S> {
    /// The band of `threshold` for a spring of `√C_k = root_stiffness` at `dt`.
    pub(crate) const fn scaled(threshold: &RestThreshold, root_stiffness: f64, dt: f64) -> Self {
        // Box |x| ≤ p/√2, |u| ≤ p·√C_k/√2: an undamped spring inside it has an amplitude
        // below p·(1 + θ/4) (see `RestThreshold`).
        let p = threshold.position * core::f64::consts::FRAC_1_SQRT_2;
        let by_amplitude = p * root_stiffness;
        let by_speed = threshold.velocity * dt;
        let u = if by_amplitude < by_speed {
            by_amplitude
        } else {
            by_speed
        };
        // Fixed point: motion of about one last bit counts as rest, and never less. The
        // offset band is at least a position's last bit, so that rounding the state to a
        // position never hides motion the band would have caught (the spring's dead band
        // is below a last bit: set-up refuses C_k below the state's resolution). The
        // step-velocity band is at least `lsb·√C_k`, the kept step velocity of a swing of
        // one last bit: it holds the few-bit cycles of the state that a spring beyond the
        // square can end in (C_k ≥ 1.5, or C_d > 1), and no more. A whole last bit per
        // step would be a swing of `lsb/√C_k`, 32 times the default threshold for a 1 Hz
        // spring at 10 kHz in `I16F16`.
        let lsb = S::RESOLUTION;
        RestBandParts {
            offset: bound::<S>(p, lsb),
            step_velocity: bound::<S>(u, lsb * root_stiffness),
        }
    }

    /// The band.
    #[inline]
    pub(crate) fn get(&self) -> RestBand<S> {
        RestBand {
            offset: S::band(self.offset.get()),
            step_velocity: S::band(self.step_velocity.get()),
        }
    }
}

/// `v`, at least `least` and at most half the state's range (so that `Scalar::within`
/// cannot overflow), as a state.
const fn bound<S: Scalar>(v: f64, least: f64) -> RawState<S> {
    let v = if v < least { least } else { v };
    let half = 0.5 * S::STATE_MAX;
    RawState::new(if v > half { half } else { v })
}
