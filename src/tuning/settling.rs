//! How long a tuning takes to come to rest: the layouts' and timelines' question (Core
//! Animation's `settlingDuration`), answered in the steps a value takes.

use super::Tuning;
use crate::motion::Motion;
use crate::rest::RestThreshold;
use crate::value::SpringValue;

/// The most steps [`Tuning::settling_steps`] runs before it gives up: 2²⁴, four and a
/// half hours at 1 kHz. A tuning that needs more (an undamped spring never settles) gets
/// `None`.
pub const MAX_SETTLING_STEPS: u32 = 1 << 24;

impl Tuning {
    /// The steps a value with this tuning takes, released `offset` from its target (the
    /// user's unit) moving at `velocity` (units per second), until [`SpringValue::step`]
    /// reports [`Motion::Resting`] with the rest `threshold`: the frame on which the value
    /// lands on its target and stops. `Some(0)` for a value that starts at rest.
    ///
    /// It runs the value, in `f64`, step by step (set-up only: the time grows with the
    /// answer); `None` when the value has not settled within [`MAX_SETTLING_STEPS`], or
    /// for a non-finite start. A value in `f32` or fixed point settles within a step or two
    /// of it: its rounding moves where it crosses the threshold by a last bit.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, Tuning, presets};
    ///
    /// // SwiftUI's `.smooth` (0.5 s, no bounce) at 60 Hz, released 300 px from its target.
    /// let smooth = presets::swiftui::SMOOTH.tuning(1.0 / 60.0)?;
    /// let frames = smooth.settling_steps(300.0, 0.0, RestThreshold::PIXELS).unwrap();
    /// assert!((40..60).contains(&frames), "{frames}");
    /// // A fling toward the target settles sooner than one away from it.
    /// let toward = smooth.settling_steps(300.0, -2000.0, RestThreshold::PIXELS).unwrap();
    /// let away = smooth.settling_steps(300.0, 2000.0, RestThreshold::PIXELS).unwrap();
    /// assert!(toward < away);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn settling_steps(
        &self,
        offset: f64,
        velocity: f64,
        threshold: RestThreshold,
    ) -> Option<u32> {
        if !offset.is_finite() || !velocity.is_finite() {
            return None;
        }
        if offset == 0.0 && velocity == 0.0 {
            return Some(0);
        }
        let mut value = SpringValue::<f64, 1>::new([offset], self)
            .ok()?
            .with_rest_threshold(threshold);
        value.set_target([0.0]);
        value.fling([velocity]);
        (1..=MAX_SETTLING_STEPS).find(|_| value.step() == Motion::Resting)
    }

    /// [`Self::settling_steps`] in seconds: the steps times [`Tuning::dt`].
    ///
    /// ```
    /// use stiffspring::{RestThreshold, Tuning};
    ///
    /// let t = Tuning::from_frequency(2.0, 1.0, 1.0 / 120.0)?;
    /// let s = t.settling_time(100.0, 0.0, RestThreshold::PIXELS).unwrap();
    /// // Critically damped: x(t) = 100·(1 + ωt)·e^(−ωt) falls under 0.75 px near t = 0.65 s.
    /// assert!((0.55..0.8).contains(&s), "{s}");
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn settling_time(
        &self,
        offset: f64,
        velocity: f64,
        threshold: RestThreshold,
    ) -> Option<f64> {
        self.settling_steps(offset, velocity, threshold)
            .map(|n| f64::from(n) * self.dt())
    }
}
