//! A tuning per value: a batch holds up to `T` tunings of one time step, and each value
//! has one of them (a highlighted row that bounces, the others critically damped).

use super::{BatchIndex, SpringBatch};
use crate::error::{Error, Parameter};
use crate::input::gains_of;
use crate::rest::{RestBand, RestThreshold};
use crate::scalar::Scalar;
use crate::start::Start;
use crate::tuning::Tuning;

/// One of a batch's tunings, by its place in the batch
/// ([`SpringBatch::add_tuning`]). [`TuningSlot::FIRST`] is the tuning the batch was made
/// with.
///
/// ```
/// use stiffspring::{SpringBatch, TuningSlot, Tuning};
/// let mut b = SpringBatch::<f32, 1, 8, 2>::new(&Tuning::rigid(0.01)?)?;
/// let i = b.push([0.0])?;
/// assert_eq!(b.tuning_of(i), Some(TuningSlot::FIRST));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TuningSlot(u8);

impl TuningSlot {
    /// The tuning the batch was made (or last [`set_tuning`](SpringBatch::set_tuning))
    /// with, which a pushed value has.
    ///
    /// ```
    /// assert_eq!(stiffspring::TuningSlot::FIRST.index(), 0);
    /// ```
    pub const FIRST: TuningSlot = TuningSlot(0);

    /// Its place among the batch's tunings, from 0.
    ///
    /// ```
    /// assert_eq!(stiffspring::TuningSlot::FIRST.index(), 0);
    /// ```
    pub const fn index(self) -> usize {
        self.0 as usize
    }
}

/// A tuning with what a value's step and setters need of it, computed at set-up.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(super) struct BatchTuning<S: Scalar> {
    pub(super) gains: S::Gains,
    pub(super) band: RestBand<S>,
    pub(super) start: Start<S>,
    pub(super) tuning: Tuning,
}

impl<S: Scalar> BatchTuning<S> {
    pub(super) fn new(tuning: &Tuning, threshold: &RestThreshold) -> Result<Self, Error> {
        Ok(BatchTuning {
            gains: gains_of::<S>(tuning)?,
            band: RestBand::new(threshold, tuning),
            start: Start::new(tuning)?,
            tuning: *tuning,
        })
    }
}

impl<S: Scalar, const D: usize, const N: usize, const T: usize> SpringBatch<S, D, N, T> {
    /// Adds a tuning that values can be given ([`set_tuning_of`](Self::set_tuning_of),
    /// [`push_with_tuning`](Self::push_with_tuning)), and returns its slot; a tuning the
    /// batch already has returns that one's slot. The batch's loop steps each value with
    /// its own tuning's gains; with `T = 1` (the default) it is the loop of one tuning.
    ///
    /// # Errors
    ///
    /// [`Error::TimeStepMismatch`] when its time step is not the batch's (every value
    /// steps together); [`Error::CapacityFull`] when the batch has `T` tunings; as
    /// [`SpringValue::new`](crate::SpringValue::new) for a tuning the backend cannot
    /// hold. Nothing changes then.
    ///
    /// ```
    /// use stiffspring::{Error, SpringBatch, Tuning};
    /// let calm = Tuning::from_frequency(3.0, 1.0, 1.0 / 60.0)?;
    /// let bouncy = Tuning::from_frequency(3.0, 0.3, 1.0 / 60.0)?;
    /// let mut rows = SpringBatch::<f32, 1, 200, 2>::new(&calm)?;
    /// let hot = rows.add_tuning(&bouncy)?;
    /// assert_eq!(rows.add_tuning(&bouncy), Ok(hot));
    /// assert!(matches!(
    ///     rows.add_tuning(&Tuning::from_frequency(3.0, 0.3, 1.0 / 120.0)?),
    ///     Err(Error::TimeStepMismatch { .. })
    /// ));
    /// assert_eq!(
    ///     rows.add_tuning(&Tuning::from_frequency(5.0, 0.3, 1.0 / 60.0)?),
    ///     Err(Error::CapacityFull { capacity: 2 })
    /// );
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn add_tuning(&mut self, tuning: &Tuning) -> Result<TuningSlot, Error> {
        let count = self.tuning_count as usize;
        if let Some(k) = self.tunings[..count]
            .iter()
            .position(|t| t.tuning == *tuning)
        {
            return Ok(TuningSlot(k as u8));
        }
        let dt = self.tunings[0].tuning.dt();
        if tuning.dt() != dt {
            return Err(Error::TimeStepMismatch {
                expected: dt,
                found: tuning.dt(),
            });
        }
        if count == T {
            return Err(Error::CapacityFull { capacity: T });
        }
        self.tunings[count] = BatchTuning::new(tuning, &self.threshold)?;
        self.tuning_count += 1;
        Ok(TuningSlot(count as u8))
    }

    /// The tuning in `slot`, or `None` for a slot the batch does not have (a slot from
    /// before a [`set_tuning`](Self::set_tuning), or from another batch).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, TuningSlot, Tuning};
    /// let t = Tuning::rigid(0.01)?;
    /// let b = SpringBatch::<f32, 1, 8, 2>::new(&t)?;
    /// assert_eq!(b.tuning_in(TuningSlot::FIRST), Some(t));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn tuning_in(&self, slot: TuningSlot) -> Option<Tuning> {
        self.tunings[..self.tuning_count as usize]
            .get(slot.index())
            .map(|t| t.tuning)
    }

    /// Which tuning a value has, or `None` for a stale index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 8, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let bouncy = b.add_tuning(&Tuning::from_frequency(3.0, 0.3, 0.01)?)?;
    /// let i = b.push_with_tuning([0.0], bouncy)?;
    /// assert_eq!(b.tuning_of(i), Some(bouncy));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn tuning_of(&self, index: BatchIndex) -> Option<TuningSlot> {
        self.slot(index).map(|s| TuningSlot(self.tuning_of[s]))
    }

    /// [`push`](Self::push) a value with the tuning in `slot`.
    ///
    /// # Errors
    ///
    /// As `push`, and [`Error::Stale`] (for [`Parameter::Index`]) for a slot the batch
    /// does not have. Nothing is added then.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 8, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let slow = b.add_tuning(&Tuning::from_frequency(1.0, 1.0, 0.01)?)?;
    /// let i = b.push_with_tuning([0.0], slow)?;
    /// b.set_target(i, [1.0]);
    /// let _ = b.step();
    /// assert!(b.position(i).unwrap()[0] < 0.1); // the slow spring, not the rigid one
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn push_with_tuning(
        &mut self,
        position: [S; D],
        slot: TuningSlot,
    ) -> Result<BatchIndex, Error> {
        let tuning = self.tuning_slot(slot)?;
        let index = self.push(position)?;
        // At rest on its target, a zero state: nothing to convert.
        self.tuning_of[index.slot()] = tuning;
        Ok(index)
    }

    /// Gives a value the tuning in `slot`, keeping its position and velocity: it goes on
    /// from where it is, at the speed it has, on the new spring. A stale index or a slot
    /// the batch does not have changes nothing; a velocity the new tuning's step cannot
    /// hold saturates (see [`try_set_tuning_of`](Self::try_set_tuning_of)).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, TuningSlot, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 8, 2>::new(&Tuning::from_frequency(3.0, 1.0, 0.01)?)?;
    /// let bouncy = b.add_tuning(&Tuning::from_frequency(3.0, 0.2, 0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.set_target(i, [100.0]);
    /// let _ = b.step();
    /// let (p, v) = (b.position(i), b.velocity(i).unwrap()[0]);
    /// b.set_tuning_of(i, bouncy); // the highlighted row bounces
    /// assert_eq!(b.position(i), p);
    /// assert!((b.velocity(i).unwrap()[0] - v).abs() < 1e-3 * v.abs());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_tuning_of(&mut self, index: BatchIndex, slot: TuningSlot) {
        let (Some(s), Ok(to)) = (self.slot(index), self.tuning_slot(slot)) else {
            return;
        };
        let (old, new) = (self.tuned(s).start, self.tunings[to as usize].start);
        for k in 0..D {
            let (x, u) = (self.offset[s][k], self.step_velocity[s][k]);
            self.step_velocity[s][k] =
                new.clamp(new.step_velocity_unchecked(x, old.velocity(x, u)));
        }
        self.tuning_of[s] = to;
    }

    /// [`set_tuning_of`](Self::set_tuning_of), reporting what it would ignore or saturate.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] (for [`Parameter::Index`]) for a stale index or a slot the batch
    /// does not have; [`Error::OutOfRange`] for a velocity the new tuning cannot hold.
    /// Nothing changes then.
    ///
    /// ```
    /// use stiffspring::{Error, SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 8, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let slow = b.add_tuning(&Tuning::from_frequency(1.0, 1.0, 0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.try_set_tuning_of(i, slow)?;
    /// b.set_tuning(&Tuning::rigid(0.01)?)?; // one tuning again: `slow` is gone
    /// assert!(matches!(b.try_set_tuning_of(i, slow), Err(Error::Stale { .. })));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_set_tuning_of(&mut self, index: BatchIndex, slot: TuningSlot) -> Result<(), Error> {
        let s = self.live_slot(index)?;
        let to = self.tuning_slot(slot)?;
        let (old, new) = (self.tuned(s).start, self.tunings[to as usize].start);
        let mut u = self.step_velocity[s];
        for k in 0..D {
            let x = self.offset[s][k];
            u[k] = new.step_velocity(x, old.velocity(x, u[k]))?;
        }
        self.step_velocity[s] = u;
        self.tuning_of[s] = to;
        Ok(())
    }

    /// What a value's setters and its step use of its tuning.
    #[inline(always)]
    pub(super) fn tuned(&self, slot: usize) -> &BatchTuning<S> {
        if T == 1 {
            &self.tunings[0]
        } else {
            // `tuning_of` holds only slots below `tuning_count ≤ T`: never the fallback.
            let k = self.tuning_of.get(slot).copied().unwrap_or(0) as usize;
            self.tunings.get(k).unwrap_or(&self.tunings[0])
        }
    }

    /// The index in `tunings` of a slot the batch has.
    fn tuning_slot(&self, slot: TuningSlot) -> Result<u8, Error> {
        if slot.index() < self.tuning_count as usize {
            Ok(slot.0)
        } else {
            Err(Error::Stale {
                parameter: Parameter::Index,
            })
        }
    }
}
