//! Moving a batch's values: targets, positions, flings. Infallible, with `try_` twins.

use super::{BatchIndex, SpringBatch};
use crate::error::{Error, Parameter};
use crate::input::{check_position, saturate};
use crate::scalar::Scalar;

impl<S: Scalar, const D: usize, const N: usize, const T: usize> SpringBatch<S, D, N, T> {
    /// Moves a value's target; see [`SpringValue::set_target`](crate::SpringValue::set_target).
    /// A stale index or a NaN component is ignored; out-of-range input saturates.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.set_target(i, [5.0]);
    /// assert_eq!(b.target(i), Some([5.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_target(&mut self, index: BatchIndex, target: [S; D]) {
        let Some(slot) = self.slot(index) else {
            return;
        };
        let start = self.tuned(slot).start;
        let mut t = target;
        for v in t.iter_mut() {
            match saturate(*v) {
                Some(s) => *v = s,
                None => return,
            }
        }
        let mut moved = false;
        for k in 0..D {
            let delta = S::state_sub(self.target[slot][k].widen(), t[k].widen());
            let x = S::state_add(self.offset[slot][k], delta);
            let u = start.shifted(self.step_velocity[slot][k], delta);
            moved |= x != self.offset[slot][k];
            self.offset[slot][k] = start.clamp(x);
            self.step_velocity[slot][k] = start.clamp(u);
        }
        self.target[slot] = t;
        if moved {
            self.wake(slot);
        }
    }

    /// [`SpringBatch::set_target`], reporting instead of ignoring or saturating.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for an index that names no live value; otherwise as
    /// [`SpringValue::try_set_target`](crate::SpringValue::try_set_target). The batch is
    /// then unchanged.
    ///
    /// ```
    /// use stiffspring::{Error, Parameter, SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.remove(i);
    /// assert_eq!(
    ///     b.try_set_target(i, [1.0]),
    ///     Err(Error::Stale { parameter: Parameter::Index })
    /// );
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_set_target(&mut self, index: BatchIndex, target: [S; D]) -> Result<(), Error> {
        let slot = self.live_slot(index)?;
        let start = self.tuned(slot).start;
        let mut x = self.offset[slot];
        let mut u = self.step_velocity[slot];
        for k in 0..D {
            check_position(target[k], Parameter::Position)?;
            let delta = S::state_sub(self.target[slot][k].widen(), target[k].widen());
            x[k] = start.check(S::state_add(x[k], delta), Parameter::Position)?;
            u[k] = start.check(start.shifted(u[k], delta), Parameter::StepVelocity)?;
        }
        let moved = x != self.offset[slot];
        self.offset[slot] = x;
        self.step_velocity[slot] = u;
        self.target[slot] = target;
        if moved {
            self.wake(slot);
        }
        Ok(())
    }

    /// Moves a value to `position` at once, keeping its velocity and target; see
    /// [`SpringValue::set_position`](crate::SpringValue::set_position). A stale index or
    /// NaN is ignored; out-of-range input saturates.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.set_position(i, [2.0]);
    /// assert_eq!(b.position(i), Some([2.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_position(&mut self, index: BatchIndex, position: [S; D]) {
        let Some(slot) = self.slot(index) else {
            return;
        };
        let start = self.tuned(slot).start;
        let mut p = position;
        for v in p.iter_mut() {
            match saturate(*v) {
                Some(s) => *v = s,
                None => return,
            }
        }
        let mut moved = false;
        for k in 0..D {
            let to = S::state_sub(p[k].widen(), self.target[slot][k].widen());
            let delta = S::state_sub(to, self.offset[slot][k]);
            moved |= delta != S::STATE_ZERO;
            let u = start.shifted(self.step_velocity[slot][k], delta);
            self.offset[slot][k] = start.clamp(to);
            self.step_velocity[slot][k] = start.clamp(u);
        }
        if moved {
            self.wake(slot);
        }
    }

    /// Gives a value a velocity (units per second); see
    /// [`SpringValue::fling`](crate::SpringValue::fling). A stale index or NaN is
    /// ignored; a step velocity out of range saturates.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f64, 1, 2>::new(&Tuning::from_frequency(1.0, 0.1, 0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.fling(i, [3.0]);
    /// assert!((b.velocity(i).unwrap()[0] - 3.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn fling(&mut self, index: BatchIndex, velocity: [S; D]) {
        let Some(slot) = self.slot(index) else {
            return;
        };
        let start = self.tuned(slot).start;
        let mut u = self.step_velocity[slot];
        for k in 0..D {
            let Some(v) = saturate(velocity[k]) else {
                return;
            };
            u[k] = start.clamp(start.step_velocity_unchecked(self.offset[slot][k], v));
        }
        self.step_velocity[slot] = u;
        self.wake(slot);
    }

    /// [`SpringBatch::fling`], reporting instead of ignoring or saturating.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`] for a stale index; otherwise as
    /// [`SpringValue::try_fling`](crate::SpringValue::try_fling).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// let i = b.push([0.0])?;
    /// assert!(b.try_fling(i, [f32::NAN]).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_fling(&mut self, index: BatchIndex, velocity: [S; D]) -> Result<(), Error> {
        let slot = self.live_slot(index)?;
        let start = self.tuned(slot).start;
        let mut u = self.step_velocity[slot];
        for k in 0..D {
            let v = check_position(velocity[k], Parameter::Velocity)?;
            u[k] = start.step_velocity(self.offset[slot][k], v)?;
        }
        self.step_velocity[slot] = u;
        self.wake(slot);
        Ok(())
    }
}
