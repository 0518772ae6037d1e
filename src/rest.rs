//! When a spring counts as settled: thresholds in the user's units.
//!
//! In the spirit of Android's `DynamicAnimation` "minimum visible change": a value is at
//! rest when it is closer to its target than a change nobody would see, and moves slower
//! than that. At rest it snaps exactly to the target and costs nothing until it is
//! retargeted.

use crate::error::{Error, Parameter, positive};
use crate::kernel::Coefficients;
use crate::scalar::Scalar;

/// Position and velocity thresholds below which a spring is at rest.
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
    /// [`Error::NotFinite`] or [`Error::NotPositive`] for either argument.
    ///
    /// ```
    /// assert!(stiffspring::RestThreshold::new(0.0, 1.0).is_err());
    /// ```
    pub fn new(position: f64, velocity: f64) -> Result<Self, Error> {
        Ok(RestThreshold {
            position: positive(position, Parameter::Threshold)?,
            velocity: positive(velocity, Parameter::Threshold)?,
        })
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
    /// [`Error::NotFinite`] or [`Error::NotPositive`].
    ///
    /// ```
    /// let alpha = stiffspring::RestThreshold::from_min_visible_change(1.0 / 256.0)?;
    /// assert_eq!(alpha.position(), 0.75 / 256.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn from_min_visible_change(change: f64) -> Result<Self, Error> {
        Ok(Self::from_visible_change(positive(
            change,
            Parameter::Threshold,
        )?))
    }

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
    fn default() -> Self {
        RestThreshold::from_visible_change(1e-3)
    }
}

/// A [`RestThreshold`] converted for one spring and one backend at set-up: the offset
/// threshold and the *step* velocity threshold (`velocity·dt`), both widened to cover
/// the fixed-point dead band so that every trajectory reaches it.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct RestBand<S: Scalar> {
    pub(crate) offset: S,
    pub(crate) step_velocity: S,
    /// [`Scalar::SAFE_MAGNITUDE`] in the backend: the bound on a value's offset.
    pub(crate) limit: S,
    /// The lower ends of the band for fixed point (see [`RestBand::contains`]).
    offset_low: S,
    step_velocity_low: S,
}

impl<S: Scalar> RestBand<S> {
    pub(crate) fn new(threshold: &RestThreshold, coefficients: &Coefficients<S>, dt: f64) -> Self {
        let lsb = S::RESOLUTION;
        let ck = S::coef_to_f64(coefficients.stiffness());
        // Products are truncated toward zero, so with u = 0 and |C_k·x| < 1 LSB the
        // response is 0: the spring stops for good anywhere in |x| < 1/C_k LSB
        // (tests/fixed_rounding.rs measures it). One LSB more covers the rounding of the
        // threshold itself. A spring with C_k = 0 has no pull toward its target, so
        // nothing is widened.
        // Floats have no dead band (`RESOLUTION` is 0): testing the constant first lets
        // the compiler drop the division, and with it the soft-float `f64` division
        // routine (0.9 KiB) from an `f32` firmware (scripts/size-report).
        let dead_band = if lsb > 0.0 && ck > 0.0 {
            (1.0 / ck + 1.0) * lsb
        } else {
            0.0
        };
        // Beyond the article's square (C_k > 1: an undersampled exact map, or the extended
        // constructor) truncation no longer always stops dead: it can end in a limit
        // cycle, measured at a few LSB with moderate damping and near 1/C_d LSB with very
        // light damping (tests/fixed_point_limits.rs). Cover 4/C_d LSB of offset, and
        // twice that of step velocity (a cycle's |u| is at most 2·|x|). An undamped spring
        // (C_d = 0) never settles, as in floats.
        let cd = 1.0 - S::coef_to_f64(coefficients.retention());
        let cycle = if lsb > 0.0 && ck > 1.0 && cd > 0.0 {
            (4.0 / cd + 4.0) * lsb
        } else {
            0.0
        };
        let offset = S::from_f64(threshold.position.max(dead_band).max(cycle));
        let step_velocity = S::from_f64((threshold.velocity * dt).max(lsb).max(2.0 * cycle));
        RestBand {
            offset,
            step_velocity,
            limit: S::from_f64(S::SAFE_MAGNITUDE),
            offset_low: lower_end(offset),
            step_velocity_low: lower_end(step_velocity),
        }
    }

    /// True when both the offset and the step velocity are inside the band.
    ///
    /// Floats test `|x| ≤ band` (an `abs` is one instruction). Fixed point tests
    /// `low ≤ x ≤ band` instead: its saturating `abs` costs five instructions on a
    /// Cortex-M, two comparisons cost none more, and `low` is chosen so that the answer is
    /// the same for every `x`.
    #[inline(always)]
    pub(crate) fn contains(&self, offset: S, step_velocity: S) -> bool {
        if S::RESOLUTION > 0.0 {
            self.offset_low <= offset
                && offset <= self.offset
                && self.step_velocity_low <= step_velocity
                && step_velocity <= self.step_velocity
        } else {
            offset.abs() <= self.offset && step_velocity.abs() <= self.step_velocity
        }
    }
}

/// The `low` of `low ≤ x ≤ band` that accepts exactly the `x` with
/// `saturating_abs(x) ≤ band`: `−band`, except that a band at the top of the range also
/// accepts the bottom of the range (whose saturated magnitude is the top).
fn lower_end<S: Scalar>(band: S) -> S {
    let top = S::from_f64(f64::MAX);
    if band == top {
        S::from_f64(-f64::MAX)
    } else {
        band.neg()
    }
}
