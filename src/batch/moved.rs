//! What moved since the last redraw: each value's previous and new position, for a
//! display that erases and redraws only the dirty rectangles.

use super::{BatchIndex, SpringBatch};
use crate::scalar::Scalar;

/// A value that moved since the last [`SpringBatch::moved`]: where it was drawn then and
/// where it is now. Erase `from`, draw `to`.
///
/// ```
/// use stiffspring::{Moved, SpringBatch, Tuning};
/// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::from_coefficients(0.5, 0.5, 0.01)?)?;
/// let i = b.push([0.0])?;
/// b.set_target(i, [1.0]);
/// let _ = b.step();
/// let m: Vec<Moved<f32, 1>> = b.moved().collect();
/// assert_eq!(m, [Moved { index: i, from: [0.0], to: [0.5] }]);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Moved<S: Scalar, const D: usize> {
    /// The value.
    pub index: BatchIndex,
    /// Its position at the last [`SpringBatch::moved`] that reported it, or where it was
    /// pushed: what the display shows.
    pub from: [S; D],
    /// Its position now.
    pub to: [S; D],
}

impl<S: Scalar, const D: usize, const N: usize, const T: usize> SpringBatch<S, D, N, T> {
    /// Every value whose position changed since the last call, with the position that
    /// call reported (or where the value was pushed) and its position now; the new
    /// positions become the reported ones. Call it once per frame, after the steps, and
    /// redraw what it yields: however many steps ran in between, the positions a display
    /// shows stay those it was last given, and nothing that moved is missed (a value that
    /// woke and settled between two calls is reported once, at its resting position).
    ///
    /// Only the values woken since they were last reported at rest are visited: a
    /// settled list costs nothing, and [`SpringBatch::step`] pays nothing for this. A
    /// value that woke but has not moved (a new target, no step yet) is not yielded.
    /// Values are yielded in no particular order. Dropping the iterator early leaves the
    /// rest for the next call. `push` and `remove` are the caller's own to draw and
    /// erase: a pushed value is reported from where it was pushed, a removed one never.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let tuning = Tuning::from_frequency(3.0, 0.8, 1.0 / 60.0)?;
    /// let mut list = SpringBatch::<f32, 1, 200>::new(&tuning)?;
    /// let rows: Vec<_> = (0..200).map(|i| list.push([i as f32 * 40.0])).collect::<Result<_, _>>()?;
    /// list.set_target(rows[7], [0.0]); // one row flies to the top
    /// let mut drawn = [0.0f32; 200];
    /// for (i, r) in rows.iter().enumerate() {
    ///     drawn[i] = list.position(*r).unwrap()[0];
    /// }
    /// while list.step().any() {
    ///     for m in list.moved() {
    ///         assert_eq!(drawn[m.index.slot()], m.from[0]); // erase where it was drawn
    ///         drawn[m.index.slot()] = m.to[0]; // draw it where it is
    ///     }
    /// }
    /// assert_eq!(drawn[7], 0.0);
    /// assert_eq!(list.moved().count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn moved(&mut self) -> impl Iterator<Item = Moved<S, D>> + '_ {
        let mut next = 0;
        core::iter::from_fn(move || {
            while let Some(&slot) = self.unreported.get(next) {
                let slot = slot as usize;
                let to = self.position_of(slot);
                let from = core::mem::replace(&mut self.reported[slot], to);
                if self.is_awake[slot] {
                    next += 1; // still moving: reported again next time
                } else {
                    // At rest where it is now reported: off the list (the last slot
                    // takes its place, visited next).
                    self.is_unreported[slot] = false;
                    self.unreported.swap_remove(next);
                }
                if from != to {
                    return Some(Moved {
                        index: self.index_of(slot),
                        from,
                        to,
                    });
                }
            }
            None
        })
    }

    /// Takes `slot` off the list of values `moved` has to report.
    pub(super) fn forget_report(&mut self, slot: usize) {
        if self.is_unreported[slot] {
            self.is_unreported[slot] = false;
            if let Some(i) = self.unreported.iter().position(|&s| s as usize == slot) {
                self.unreported.swap_remove(i);
            }
        }
    }
}
