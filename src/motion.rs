//! What a step reports: whether something moved, and what just came to rest.
//!
//! A display redraws what moved and can sleep when nothing did; react-spring calls its
//! `onRest`, Android its end listeners. Steps report it without allocating.

/// What one [`SpringValue::step`](crate::SpringValue::step) did.
///
/// ```
/// use stiffspring::{Motion, SpringValue, Tuning};
///
/// let mut v = SpringValue::<f32>::new([0.0], &Tuning::from_coefficients(0.5, 1.0, 0.01)?)?;
/// assert_eq!(v.step(), Motion::Resting); // nothing to do
/// v.set_target([1.0]);
/// assert_eq!(v.step(), Motion::Moving); // halfway
/// let mut steps = 1;
/// while v.step() == Motion::Moving {
///     steps += 1;
/// }
/// assert_eq!(v.position(), [1.0]); // settled: snapped onto the target
/// assert_eq!(v.step(), Motion::Resting);
/// assert!(steps < 30);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[must_use = "a step reports whether to redraw; `let _ =` discards it"]
pub enum Motion {
    /// The value was at rest and the step did nothing.
    Resting,
    /// The value moved and is still moving.
    Moving,
    /// The value moved and came to rest on its target in this step: draw it once more.
    Settled,
}

impl Motion {
    /// True when the value's position changed in this step (it is `Moving` or just
    /// `Settled`): what a dirty-rectangle redraw needs.
    ///
    /// ```
    /// use stiffspring::Motion;
    /// assert!(Motion::Settled.moved() && !Motion::Resting.moved());
    /// ```
    pub const fn moved(self) -> bool {
        !matches!(self, Motion::Resting)
    }
}
