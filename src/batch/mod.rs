//! Many values that share one tuning, stepped together: list items, grid cells, particles
//! of an effect.
//!
//! The state lives in plain arrays indexed by slot, and the tuning's gains are loaded
//! once per step for all of them. While every value is awake the step is one straight
//! loop over the arrays; once some have settled it visits only the awake ones, through a
//! list of their slots, so settled values cost nothing.

use crate::error::{Error, Parameter};
use crate::input::check_position;
use crate::rest::{RestBand, RestThreshold};
use crate::scalar::Scalar;
use crate::tuning::Tuning;
use core::mem::MaybeUninit;
use heapless::Vec;

mod index;
mod moved;
mod setters;
mod stagger;
mod step;
mod trail;
mod tunings;

pub use index::{BatchIndex, BatchMotion};
pub use moved::Moved;
pub use stagger::Stagger;
pub use trail::Trail;
use tunings::BatchTuning;
pub use tunings::TuningSlot;

/// Up to `N` values of `D` dimensions in backend `S`, sharing one [`Tuning`] (and so one
/// time step), or, with `T > 1`, each value one of up to `T` tunings of the same time step
/// ([`add_tuning`](SpringBatch::add_tuning)).
///
/// Like [`SpringValue`](crate::SpringValue), the UI path cannot fail: `set_target`,
/// `set_position` and `fling` ignore a stale index or NaN and saturate what is out of
/// range; their `try_` twins report it. The values are read by index
/// ([`position`](SpringBatch::position), [`velocity`](SpringBatch::velocity)) or all at
/// once ([`iter`](SpringBatch::iter)); there is no slice of positions, because the state
/// is kept relative to each target in the backend's wide state format (see
/// [`Scalar`]), and storing positions too would cost a store per value per step.
///
/// ```
/// use stiffspring::{SpringBatch, Tuning};
///
/// let tuning = Tuning::from_frequency(3.0, 0.8, 1.0 / 60.0)?;
/// let mut list = SpringBatch::<f32, 1, 200>::new(&tuning)?;
/// let rows: Vec<_> = (0..200).map(|i| list.push([i as f32 * 40.0])).collect::<Result<_, _>>()?;
/// for (i, row) in rows.iter().enumerate() {
///     list.set_target(*row, [i as f32 * 40.0 + 40.0]); // everything scrolls one row
/// }
/// while list.step().any() {}
/// assert_eq!(list.position(rows[3]), Some([160.0]));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpringBatch<S: Scalar, const D: usize, const N: usize, const T: usize = 1> {
    offset: [[S::State; D]; N],
    step_velocity: [[S::State; D]; N],
    target: [[S; D]; N],
    generation: [u16; N],
    live: [bool; N],
    is_awake: [bool; N],
    /// The slots of the awake values, in no order.
    awake: Vec<u16, N>,
    /// The slots that settled in the last step.
    settled: Vec<u16, N>,
    /// By slot: the position [`SpringBatch::moved`] last reported (at `push`, the pushed
    /// position). Written only there and at `push`: the step never touches it.
    reported: [[S; D]; N],
    /// The slots woken since `moved` last reported them at rest, in no order, and the
    /// same as flags by slot.
    unreported: Vec<u16, N>,
    is_unreported: [bool; N],
    /// Slots `0..used` have held a value; the rest never did.
    used: usize,
    len: usize,
    /// The tunings values can have; `tunings[..tuning_count]` are set, the first is the
    /// one `new` (or `set_tuning`) was given.
    tunings: [BatchTuning<S>; T],
    tuning_count: u8,
    /// By slot: which of `tunings` the value has (always below `tuning_count`).
    tuning_of: [u8; N],
    threshold: RestThreshold,
    check_every: u16,
    until_check: u16,
}

impl<S: Scalar, const D: usize, const N: usize, const T: usize> SpringBatch<S, D, N, T> {
    /// An empty batch of values tuned by `tuning` (which also sets the time step), with
    /// the default [`RestThreshold`], testing rest every step.
    ///
    /// # Errors
    ///
    /// As [`SpringValue::new`](crate::SpringValue::new) for the tuning. Capacities above
    /// 65 535, and a number of tunings `T` of 0 or above 255, do not compile.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let batch = SpringBatch::<f32, 2, 16>::new(&Tuning::rigid(0.01)?)?;
    /// assert!(batch.is_empty());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(tuning: &Tuning) -> Result<Self, Error> {
        const { assert!(N <= u16::MAX as usize) };
        const { assert!(T >= 1 && T <= u8::MAX as usize) };
        let threshold = RestThreshold::default();
        let tuned = BatchTuning::new(tuning, &threshold)?;
        Ok(Self::with_parts(tuned, threshold))
    }

    /// [`SpringBatch::new`], built in `slot` instead of returned: for storage its owner
    /// keeps (the C API's). A batch is large (about 800 bytes for 16 `f32` values), and
    /// moving one out of a `Result` into such storage copies all of it (a `memcpy` that
    /// the C API's `init` paid for); built in place, its arrays are cleared where they
    /// lie. `slot` is written only when this returns `Ok`, and then whole: on an error it
    /// is as it was.
    ///
    /// # Errors
    ///
    /// As [`SpringBatch::new`].
    ///
    /// ```
    /// use core::mem::MaybeUninit;
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut slot = MaybeUninit::uninit();
    /// let batch = SpringBatch::<f32, 1, 16>::new_in(&mut slot, &Tuning::rigid(0.01)?)?;
    /// assert!(batch.is_empty());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new_in<'a>(
        slot: &'a mut MaybeUninit<Self>,
        tuning: &Tuning,
    ) -> Result<&'a mut Self, Error> {
        // Every check first, so that nothing is written on an error. The tuning's parts
        // are built before the literal, so that the batch is built where it lies (its
        // arrays cleared in place): copied inside the literal, the tuning made LLVM build
        // the literal on the stack and copy it into `slot` (376 bytes, a `memcpy`).
        let threshold = RestThreshold::default();
        let tuned = BatchTuning::new(tuning, &threshold)?;
        Ok(slot.write(Self::with_parts(tuned, threshold)))
    }

    /// An empty batch of the one tuning `tuned`, which [`SpringBatch::new`] checks.
    #[inline(always)]
    fn with_parts(tuned: BatchTuning<S>, threshold: RestThreshold) -> Self {
        const { assert!(N <= u16::MAX as usize) };
        const { assert!(T >= 1 && T <= u8::MAX as usize) };
        SpringBatch {
            offset: [[S::STATE_ZERO; D]; N],
            step_velocity: [[S::STATE_ZERO; D]; N],
            target: [[S::ZERO; D]; N],
            generation: [0; N],
            live: [false; N],
            is_awake: [false; N],
            awake: Vec::new(),
            settled: Vec::new(),
            reported: [[S::ZERO; D]; N],
            unreported: Vec::new(),
            is_unreported: [false; N],
            used: 0,
            len: 0,
            tunings: [tuned; T],
            tuning_count: 1,
            tuning_of: [0; N],
            threshold,
            check_every: 1,
            until_check: 0,
        }
    }

    /// The same batch with another rest threshold.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringBatch, Tuning};
    /// let b = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?
    ///     .with_rest_threshold(RestThreshold::PIXELS);
    /// assert_eq!(b.rest_threshold(), RestThreshold::PIXELS);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_rest_threshold(mut self, threshold: RestThreshold) -> Self {
        self.threshold = threshold;
        for t in self.tunings.iter_mut() {
            t.band = RestBand::new(&threshold, &t.tuning);
        }
        self
    }

    /// The same batch testing rest only every `period` steps (1 tests every step; 0 is
    /// taken as 1).
    ///
    /// The steps in between are the bare recurrence, with no test and no branch per
    /// value: the rest test costs `1/period` of itself per step. The price: a value settles
    /// up to `period − 1` steps after it entered the rest band (it keeps converging
    /// meanwhile), and [`SpringBatch::step`] reports it then.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?.with_rest_check_every(4);
    /// let i = b.push([0.0])?;
    /// b.set_target(i, [1.0]);
    /// let mut steps = 1;
    /// while b.step().settled == 0 {
    ///     steps += 1;
    /// }
    /// assert_eq!(steps, 4); // at rest after 1, reported at the 4th
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_rest_check_every(mut self, period: u16) -> Self {
        self.check_every = period.max(1);
        self.until_check = self.check_every - 1;
        self
    }

    /// Adds a value at rest at `position`.
    ///
    /// # Errors
    ///
    /// [`Error::CapacityFull`] when the batch holds `N` values; [`Error::NotFinite`] or
    /// [`Error::OutOfRange`] for the position. Nothing is added then.
    ///
    /// ```
    /// use stiffspring::{Error, SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 1>::new(&Tuning::rigid(0.01)?)?;
    /// b.push([0.0])?;
    /// assert_eq!(b.push([1.0]), Err(Error::CapacityFull { capacity: 1 }));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn push(&mut self, position: [S; D]) -> Result<BatchIndex, Error> {
        for p in position {
            check_position(p, Parameter::Position)?;
        }
        // A freed slot first, so that the used slots stay few and the straight loop short.
        let slot = match self.live[..self.used].iter().position(|l| !l) {
            Some(slot) => slot,
            None if self.used < N => {
                self.used += 1;
                self.used - 1
            }
            None => return Err(Error::CapacityFull { capacity: N }),
        };
        self.live[slot] = true;
        self.target[slot] = position;
        self.reported[slot] = position;
        self.tuning_of[slot] = 0;
        self.offset[slot] = [S::STATE_ZERO; D];
        self.step_velocity[slot] = [S::STATE_ZERO; D];
        self.len += 1;
        Ok(BatchIndex {
            slot: slot as u16,
            generation: self.generation[slot],
        })
    }

    /// Removes a value; returns its position, or `None` for a stale index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([3.0])?;
    /// assert_eq!(b.remove(i), Some([3.0]));
    /// assert_eq!(b.remove(i), None);
    /// assert!(b.is_empty());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn remove(&mut self, index: BatchIndex) -> Option<[S; D]> {
        let slot = self.slot(index)?;
        let position = self.position_of(slot);
        self.sleep(slot);
        self.forget_report(slot);
        self.live[slot] = false;
        self.generation[slot] = self.generation[slot].wrapping_add(1);
        self.offset[slot] = [S::STATE_ZERO; D];
        self.step_velocity[slot] = [S::STATE_ZERO; D];
        self.len -= 1;
        Some(position)
    }

    /// Retunes every value (a new spring, a new time step, or both), keeping positions
    /// and velocities. With `T > 1` every value then has this tuning, and the slots that
    /// [`add_tuning`](Self::add_tuning) gave are stale.
    ///
    /// # Errors
    ///
    /// As [`SpringValue::set_tuning`](crate::SpringValue::set_tuning); the batch is then
    /// unchanged.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// b.set_tuning(&Tuning::from_frequency(2.0, 0.5, 1.0 / 120.0)?)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_tuning(&mut self, tuning: &Tuning) -> Result<(), Error> {
        let tuned = BatchTuning::new(tuning, &self.threshold)?;
        let mut velocities = self.step_velocity;
        for &slot in self.awake.iter() {
            let slot = slot as usize;
            let old = self.tuned(slot).start;
            for k in 0..D {
                let (x, u) = (self.offset[slot][k], self.step_velocity[slot][k]);
                velocities[slot][k] = tuned.start.step_velocity(x, old.velocity(x, u))?;
            }
        }
        self.step_velocity = velocities;
        self.tunings = [tuned; T];
        self.tuning_count = 1;
        self.tuning_of = [0; N];
        Ok(())
    }

    /// Every value and its position, in slot order.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?;
    /// b.push([1.0])?;
    /// b.push([2.0])?;
    /// let sum: f32 = b.iter().map(|(_, p)| p[0]).sum();
    /// assert_eq!(sum, 3.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = (BatchIndex, [S; D])> + '_ {
        (0..self.used)
            .filter(|&s| self.live[s])
            .map(|s| (self.index_of(s), self.position_of(s)))
    }

    /// Whether `index` names a live value of this batch: false for a removed value's index
    /// and for one no push gave. The setters ignore an index for which this is false.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([1.0])?;
    /// assert!(b.contains(i));
    /// b.remove(i);
    /// assert!(!b.contains(i));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn contains(&self, index: BatchIndex) -> bool {
        self.slot(index).is_some()
    }

    /// A value's position, or `None` for a stale index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 2, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([1.0, 2.0])?;
    /// assert_eq!(b.position(i), Some([1.0, 2.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self, index: BatchIndex) -> Option<[S; D]> {
        self.slot(index).map(|s| self.position_of(s))
    }

    /// A value's target, or `None` for a stale index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([1.0])?;
    /// assert_eq!(b.target(i), Some([1.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn target(&self, index: BatchIndex) -> Option<[S; D]> {
        self.slot(index).map(|s| self.target[s])
    }

    /// A value's velocity in units per second (see
    /// [`SpringValue::velocity`](crate::SpringValue::velocity)), or `None` for a stale
    /// index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([1.0])?;
    /// assert_eq!(b.velocity(i), Some([0.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self, index: BatchIndex) -> Option<[S; D]> {
        let s = self.slot(index)?;
        let start = self.tuned(s).start;
        let mut v = [S::ZERO; D];
        for (k, v) in v.iter_mut().enumerate() {
            *v = start.velocity(self.offset[s][k], self.step_velocity[s][k]);
        }
        Some(v)
    }

    /// Whether a value is at rest, or `None` for a stale index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([1.0])?;
    /// assert_eq!(b.is_at_rest(i), Some(true));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_at_rest(&self, index: BatchIndex) -> Option<bool> {
        self.slot(index).map(|s| !self.is_awake[s])
    }

    /// How many values are awake.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// assert_eq!(b.awake(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn awake(&self) -> usize {
        self.awake.len()
    }

    /// How many values the batch holds.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// b.push([0.0])?;
    /// assert_eq!(b.len(), 1);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the batch holds no value.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// assert!(SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?.is_empty());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The tuning all values share: the one [`new`](Self::new) or
    /// [`set_tuning`](Self::set_tuning) was given (with `T > 1`, the tuning of the values
    /// given no other; [`tuning_of`](Self::tuning_of) tells a value's).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let t = Tuning::rigid(0.01)?;
    /// assert_eq!(SpringBatch::<f32, 1, 2>::new(&t)?.tuning(), t);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn tuning(&self) -> Tuning {
        self.tunings[0].tuning
    }

    /// The rest threshold.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringBatch, Tuning};
    /// let b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// assert_eq!(b.rest_threshold(), RestThreshold::default());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_threshold(&self) -> RestThreshold {
        self.threshold
    }

    /// The live slot an index names.
    fn slot(&self, index: BatchIndex) -> Option<usize> {
        let s = index.slot as usize;
        (s < N && self.live[s] && self.generation[s] == index.generation).then_some(s)
    }

    fn live_slot(&self, index: BatchIndex) -> Result<usize, Error> {
        self.slot(index).ok_or(Error::Stale {
            parameter: Parameter::Index,
        })
    }

    fn index_of(&self, slot: usize) -> BatchIndex {
        BatchIndex {
            slot: slot as u16,
            generation: self.generation[slot],
        }
    }

    fn position_of(&self, slot: usize) -> [S; D] {
        let mut p = self.target[slot];
        for (p, x) in p.iter_mut().zip(self.offset[slot].iter()) {
            // In the state format, which holds any offset (see `SpringValue::position`).
            *p = S::narrow(S::state_add(p.widen(), *x));
        }
        p
    }

    fn wake(&mut self, slot: usize) {
        if !self.is_awake[slot] {
            self.is_awake[slot] = true;
            // Cannot fail: a slot is in the list at most once.
            let _ = self.awake.push(slot as u16);
            if !self.is_unreported[slot] {
                self.is_unreported[slot] = true;
                // Cannot fail: as above.
                let _ = self.unreported.push(slot as u16);
            }
        }
    }

    fn sleep(&mut self, slot: usize) {
        if self.is_awake[slot] {
            self.is_awake[slot] = false;
            if let Some(i) = self.awake.iter().position(|&s| s as usize == slot) {
                self.awake.swap_remove(i);
            }
        }
    }
}
