//! A range a value may rest in: a scroll's smallest and largest offset.

use crate::error::{Bound, Error, Parameter};
use crate::input::{check_position, saturate};
use crate::scalar::Scalar;

/// The closed range `[min, max]` a value rests in (Android's `setMinValue` and
/// `setMaxValue`): a list's first and last scroll offsets.
///
/// A value may pass an end for a while (a throw that overshoots, a drag that pulls past
/// it); a [`Scroll`](crate::Scroll) then brings it back and rests inside.
///
/// ```
/// use stiffspring::Bounds;
///
/// let list = Bounds::<f32>::new(0.0, 4_000.0)?; // 200 rows of 24 px in a 160 px view… roughly
/// assert_eq!(list.clamp(-12.0), 0.0);
/// assert!(list.contains(100.0));
/// assert!(Bounds::<f32>::new(10.0, 0.0).is_err()); // min > max
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Bounds<S: Scalar> {
    min: S,
    max: S,
}

impl<S: Scalar> Bounds<S> {
    /// The range `[min, max]`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] with [`Parameter::Bounds`] for a NaN or infinite end;
    /// [`Error::OutOfRange`] with [`Parameter::Bounds`] for an end beyond [`Scalar::MAX`]
    /// (`Bound::MagnitudeAtMost`), or for `min > max` (the value `min`, `Bound::AtMost`
    /// `max`).
    ///
    /// ```
    /// use stiffspring::{Bound, Bounds, Error, Parameter};
    ///
    /// assert_eq!(
    ///     Bounds::<f64>::new(5.0, 1.0),
    ///     Err(Error::OutOfRange {
    ///         parameter: Parameter::Bounds,
    ///         value: 5.0,
    ///         bound: Bound::AtMost { max: 1.0 }
    ///     })
    /// );
    /// assert!(Bounds::<f64>::new(f64::NAN, 1.0).is_err());
    /// ```
    pub fn new(min: S, max: S) -> Result<Self, Error> {
        let min = check_position(min, Parameter::Bounds)?;
        let max = check_position(max, Parameter::Bounds)?;
        if min > max {
            return Err(Error::OutOfRange {
                parameter: Parameter::Bounds,
                value: min.to_f64(),
                bound: Bound::AtMost { max: max.to_f64() },
            });
        }
        Ok(Bounds { min, max })
    }

    /// The whole range of the backend, `[−MAX, MAX]`: no end a value can reach.
    ///
    /// ```
    /// use stiffspring::{Bounds, Scalar};
    /// let all = Bounds::<f32>::unbounded();
    /// assert_eq!(all.max() as f64, <f32 as Scalar>::MAX);
    /// ```
    pub fn unbounded() -> Self {
        let max = S::from_f64(S::MAX);
        Bounds {
            min: max.neg(),
            max,
        }
    }

    /// The UI path's reading of `(min, max)`: `None` when an end is NaN; ends beyond
    /// `±MAX` saturate there, and `min > max` becomes the single point `[min, min]` (a
    /// content shorter than its view scrolls nowhere).
    pub(crate) fn saturating(min: S, max: S) -> Option<Self> {
        let (min, max) = (saturate(min)?, saturate(max)?);
        Some(Bounds {
            min,
            max: if max < min { min } else { max },
        })
    }

    /// The smallest value.
    ///
    /// ```
    /// assert_eq!(stiffspring::Bounds::<f32>::new(-1.0, 2.0)?.min(), -1.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn min(&self) -> S {
        self.min
    }

    /// The largest value.
    ///
    /// ```
    /// assert_eq!(stiffspring::Bounds::<f32>::new(-1.0, 2.0)?.max(), 2.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn max(&self) -> S {
        self.max
    }

    /// `value` limited to the range (NaN stays NaN).
    ///
    /// ```
    /// let b = stiffspring::Bounds::<f32>::new(0.0, 10.0)?;
    /// assert_eq!((b.clamp(-3.0), b.clamp(4.0), b.clamp(12.0)), (0.0, 4.0, 10.0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn clamp(&self, value: S) -> S {
        if value < self.min {
            self.min
        } else if value > self.max {
            self.max
        } else {
            value
        }
    }

    /// True when `min ≤ value ≤ max`.
    ///
    /// ```
    /// let b = stiffspring::Bounds::<f32>::new(0.0, 10.0)?;
    /// assert!(b.contains(10.0) && !b.contains(10.5));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn contains(&self, value: S) -> bool {
        self.min <= value && value <= self.max
    }
}
