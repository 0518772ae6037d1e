//! A stagger: targets that reach a batch's values one after the other, a delay apart
//! (react-spring's `trail` delay, a list whose rows move in turn).

use super::{BatchIndex, BatchMotion, SpringBatch};
use crate::scalar::Scalar;

/// Targets scheduled for the values of a [`SpringBatch`], each a number of steps from
/// now: [`Stagger::step`] hands each to the batch on its step, then steps the batch. The
/// batch itself is untouched: its hot loop pays nothing for a stagger it does not have.
///
/// A value's target arrives on the step it is due, exactly as a
/// [`SpringBatch::set_target`] before that step would: the `k`-th row of a list
/// staggered by `d` steps moves as the first one does, `k·d` steps later, to the bit
/// (`tests/batch_choreography.rs`).
///
/// ```
/// use stiffspring::{SpringBatch, Stagger, Tuning};
///
/// let tuning = Tuning::from_frequency(3.0, 0.8, 1.0 / 60.0)?;
/// let mut list = SpringBatch::<f32, 1, 200>::new(&tuning)?;
/// let rows: Vec<_> = (0..200).map(|i| list.push([i as f32 * 40.0])).collect::<Result<_, _>>()?;
/// // Every row scrolls up by one row, each two frames after the one above it.
/// let mut stagger = Stagger::<f32, 1, 200>::new();
/// stagger.schedule_all(rows.iter().map(|&r| (r, [list.position(r).unwrap()[0] - 40.0])), 0, 2);
/// assert_eq!(stagger.pending(), 200);
/// while stagger.step(&mut list).any() || stagger.pending() > 0 {}
/// assert_eq!(list.position(rows[199]), Some([198.0 * 40.0]));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stagger<S: Scalar, const D: usize, const N: usize> {
    /// By slot: the value, its target and the steps until it is due.
    due: [Option<(BatchIndex, [S; D], u32)>; N],
    pending: usize,
}

impl<S: Scalar, const D: usize, const N: usize> Default for Stagger<S, D, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, const D: usize, const N: usize> Stagger<S, D, N> {
    /// Nothing scheduled.
    ///
    /// ```
    /// assert_eq!(stiffspring::Stagger::<f32, 2, 8>::new().pending(), 0);
    /// ```
    pub const fn new() -> Self {
        Stagger {
            due: [None; N],
            pending: 0,
        }
    }

    /// Schedules `target` for `index`, handed to the batch `delay` steps from now (0: on
    /// the next [`Stagger::step`]). A value already scheduled gets the new target and
    /// delay instead. An index beyond the capacity is ignored (a batch of capacity `N`
    /// has no such slot).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Stagger, Tuning};
    ///
    /// let mut b = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([0.0])?;
    /// let mut s = Stagger::new();
    /// s.schedule(i, [1.0], 3);
    /// for _ in 0..3 {
    ///     let _ = s.step(&mut b);
    ///     assert_eq!(b.target(i), Some([0.0])); // not yet
    /// }
    /// let _ = s.step(&mut b);
    /// assert_eq!(b.target(i), Some([1.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn schedule(&mut self, index: BatchIndex, target: [S; D], delay: u32) {
        let Some(entry) = self.due.get_mut(index.slot()) else {
            return;
        };
        if entry.is_none() {
            self.pending += 1;
        }
        *entry = Some((index, target, delay));
    }

    /// Schedules each `(index, target)` in turn, the first `first` steps from now and each
    /// next one `spacing` steps after the one before: a stagger by position in the
    /// sequence.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Stagger, Tuning};
    ///
    /// let mut b = SpringBatch::<f32, 1, 3>::new(&Tuning::rigid(0.01)?)?;
    /// let rows = [b.push([0.0])?, b.push([0.0])?, b.push([0.0])?];
    /// let mut s = Stagger::new();
    /// s.schedule_all(rows.iter().map(|&r| (r, [1.0])), 1, 2); // due in 1, 3 and 5 steps
    /// let mut started = [0; 3];
    /// for n in 1..=6 {
    ///     let _ = s.step(&mut b);
    ///     for (k, &r) in rows.iter().enumerate() {
    ///         if started[k] == 0 && b.target(r) == Some([1.0]) {
    ///             started[k] = n;
    ///         }
    ///     }
    /// }
    /// assert_eq!(started, [2, 4, 6]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn schedule_all(
        &mut self,
        targets: impl IntoIterator<Item = (BatchIndex, [S; D])>,
        first: u32,
        spacing: u32,
    ) {
        let mut delay = first;
        for (index, target) in targets {
            self.schedule(index, target, delay);
            delay = delay.saturating_add(spacing);
        }
    }

    /// Targets still to be handed over.
    ///
    /// ```
    /// assert_eq!(stiffspring::Stagger::<f32, 1, 4>::default().pending(), 0);
    /// ```
    pub const fn pending(&self) -> usize {
        self.pending
    }

    /// Drops what is scheduled (the batch keeps the targets it already has).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Stagger, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([0.0])?;
    /// let mut s = Stagger::<f32, 1, 2>::new();
    /// s.schedule(i, [1.0], 10);
    /// s.clear();
    /// assert_eq!(s.pending(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn clear(&mut self) {
        self.due = [None; N];
        self.pending = 0;
    }

    /// One frame: hands the targets due now to `batch` (a stale index is ignored, as
    /// [`SpringBatch::set_target`] ignores it), counts the others down, then steps the
    /// batch and returns what it reports.
    pub fn step<const T: usize>(&mut self, batch: &mut SpringBatch<S, D, N, T>) -> BatchMotion {
        if self.pending > 0 {
            for entry in self.due.iter_mut() {
                match entry {
                    Some((index, target, 0)) => {
                        batch.set_target(*index, *target);
                        *entry = None;
                        self.pending -= 1;
                    }
                    Some((_, _, delay)) => *delay -= 1,
                    None => {}
                }
            }
        }
        batch.step()
    }
}
