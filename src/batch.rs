//! Many values stepped together, in fixed-capacity structure-of-arrays storage.
//!
//! A UI screen animates dozens of values, most of them at rest most of the time. The
//! batch keeps each field in its own `heapless::Vec` and a list of the awake values, so a
//! step touches only values that move: a value at rest costs nothing, not even a check.

use crate::error::{Error, Parameter, positive};
use crate::kernel::Coefficients;
use crate::rest::{RestBand, RestThreshold};
use crate::sampling::Sampling;
use crate::scalar::Scalar;
use crate::tuning::Tuning;
use crate::value::{advance, check_all, jump, offsets};
use heapless::Vec;

/// Up to `N` values of dimension `D` springing toward their targets, in backend `S`,
/// all stepped every `dt`.
///
/// ```
/// use stiffspring::{SpringBatch, Tuning};
///
/// let dt = 1.0 / 60.0;
/// let mut batch = SpringBatch::<f32, 16>::new(dt)?;
/// let t = Tuning::from_frequency(3.0, 1.0, dt)?;
/// let a = batch.push([0.0], t)?;
/// let b = batch.push([10.0], t)?;
/// batch.set_target(a, [5.0])?;
/// assert_eq!(batch.awake(), 1); // b is at rest and costs nothing
/// for _ in 0..120 {
///     batch.step();
/// }
/// assert_eq!(batch.position(a)?, [5.0]);
/// assert!(batch.is_at_rest(a)? && batch.awake() == 0);
/// # let _ = b;
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpringBatch<S: Scalar, const N: usize, const D: usize = 1> {
    offsets: Vec<[S; D], N>,
    step_velocities: Vec<[S; D], N>,
    targets: Vec<[S; D], N>,
    coefficients: Vec<Coefficients<S>, N>,
    samplings: Vec<Sampling<S>, N>,
    bands: Vec<RestBand<S>, N>,
    thresholds: Vec<RestThreshold, N>,
    /// Indices of the values that are not at rest, in no particular order.
    awake: Vec<usize, N>,
    dt: f64,
}

impl<S: Scalar, const N: usize, const D: usize> SpringBatch<S, N, D> {
    /// An empty batch stepped every `dt` seconds.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::NotPositive`] for `dt`.
    ///
    /// ```
    /// let batch = stiffspring::SpringBatch::<f32, 8, 2>::new(0.01)?;
    /// assert!(batch.is_empty());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(dt: f64) -> Result<Self, Error> {
        Ok(SpringBatch {
            offsets: Vec::new(),
            step_velocities: Vec::new(),
            targets: Vec::new(),
            coefficients: Vec::new(),
            samplings: Vec::new(),
            bands: Vec::new(),
            thresholds: Vec::new(),
            awake: Vec::new(),
            dt: positive(dt, Parameter::TimeStep)?,
        })
    }

    /// Adds a value at rest at `position` with the default [`RestThreshold`], and returns
    /// its index.
    ///
    /// # Errors
    ///
    /// [`Error::CapacityFull`] when `N` values are already in; [`Error::NotFinite`] or
    /// [`Error::OutOfRange`] for the position. Nothing is added then.
    ///
    /// ```
    /// use stiffspring::{Error, SpringBatch, Tuning};
    ///
    /// let mut batch = SpringBatch::<f32, 1>::new(0.01)?;
    /// assert_eq!(batch.push([1.0], Tuning::rigid())?, 0);
    /// assert_eq!(batch.push([2.0], Tuning::rigid()), Err(Error::CapacityFull));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn push(&mut self, position: [S; D], tuning: Tuning) -> Result<usize, Error> {
        self.push_with_threshold(position, tuning, RestThreshold::default())
    }

    /// Adds a value at rest at `position` with its own rest thresholds, and returns its
    /// index.
    ///
    /// # Errors
    ///
    /// As [`SpringBatch::push`].
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringBatch, Tuning};
    ///
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push_with_threshold([0.0], Tuning::rigid(), RestThreshold::PIXELS)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn push_with_threshold(
        &mut self,
        position: [S; D],
        tuning: Tuning,
        threshold: RestThreshold,
    ) -> Result<usize, Error> {
        check_all(&position, Parameter::Position)?;
        if self.offsets.is_full() {
            return Err(Error::CapacityFull);
        }
        let coefficients = Coefficients::new(&tuning);
        let band = RestBand::new(&threshold, &coefficients, self.dt);
        // All vectors have the same length and the check above found room in each, so
        // none of these pushes can fail; the results are still not ignored silently.
        let pushed = self.offsets.push([S::ZERO; D]).is_ok()
            & self.step_velocities.push([S::ZERO; D]).is_ok()
            & self.targets.push(position).is_ok()
            & self.coefficients.push(coefficients).is_ok()
            & self
                .samplings
                .push(Sampling::new(&tuning, &coefficients, self.dt))
                .is_ok()
            & self.bands.push(band).is_ok()
            & self.thresholds.push(threshold).is_ok();
        if pushed {
            Ok(self.offsets.len() - 1)
        } else {
            Err(Error::CapacityFull)
        }
    }

    /// Moves the target of value `index`; it keeps its position and velocity and wakes
    /// up, as [`SpringValue::set_target`](crate::SpringValue::set_target) does.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown index; otherwise as
    /// [`SpringValue::set_target`](crate::SpringValue::set_target).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push([0.0], Tuning::rigid())?;
    /// batch.set_target(i, [3.0])?;
    /// assert_eq!(batch.target(i)?, [3.0]);
    /// assert!(batch.set_target(7, [3.0]).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_target(&mut self, index: usize, target: [S; D]) -> Result<(), Error> {
        self.check_index(index)?;
        check_all(&target, Parameter::Position)?;
        let offset = offsets(&self.position(index)?, &target)?;
        let sampling = self.samplings[index];
        let mut moved = false;
        let state = self.offsets[index]
            .iter_mut()
            .zip(&mut self.step_velocities[index]);
        for ((x, u), to) in state.zip(offset) {
            moved |= jump(x, u, &sampling, to);
        }
        self.targets[index] = target;
        if moved {
            self.wake(index);
        }
        Ok(())
    }

    /// Gives value `index` a velocity in units per second, on its continuous trajectory
    /// as [`SpringValue::fling`](crate::SpringValue::fling) does.
    ///
    /// # Errors
    ///
    /// As [`SpringBatch::set_target`], and [`Error::OutOfRange`] when the step velocity
    /// leaves the backend's range.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push([0.0], Tuning::from_frequency(1.0, 0.5, 0.01)?)?;
    /// batch.fling(i, [100.0])?;
    /// batch.step();
    /// assert!(batch.position(i)?[0] > 0.9);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn fling(&mut self, index: usize, velocity: [S; D]) -> Result<(), Error> {
        self.check_index(index)?;
        check_all(&velocity, Parameter::Velocity)?;
        let mut u = [S::ZERO; D];
        for k in 0..D {
            u[k] = self.samplings[index].step_velocity(self.offsets[index][k], velocity[k])?;
        }
        self.step_velocities[index] = u;
        self.wake(index);
        Ok(())
    }

    /// Retunes value `index`; its position and velocity are kept.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown index, or for the
    /// velocity when the new tuning needs a step velocity outside the backend's range.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push([1.0], Tuning::rigid())?;
    /// batch.set_tuning(i, Tuning::from_coefficients(0.1, 0.3)?)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_tuning(&mut self, index: usize, tuning: Tuning) -> Result<(), Error> {
        self.check_index(index)?;
        let coefficients = Coefficients::new(&tuning);
        let sampling = Sampling::new(&tuning, &coefficients, self.dt);
        let old = self.samplings[index];
        let mut u = [S::ZERO; D];
        for (k, x) in self.offsets[index].iter().enumerate() {
            let velocity = old.velocity(*x, self.step_velocities[index][k]);
            u[k] = sampling.step_velocity(*x, velocity)?;
        }
        self.step_velocities[index] = u;
        self.bands[index] = RestBand::new(&self.thresholds[index], &coefficients, self.dt);
        self.coefficients[index] = coefficients;
        self.samplings[index] = sampling;
        Ok(())
    }

    /// Advances every awake value by one step; values that come to rest snap to their
    /// targets and leave the awake list.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push([0.0], Tuning::rigid())?;
    /// batch.set_target(i, [1.0])?;
    /// batch.step();
    /// batch.step();
    /// assert_eq!(batch.awake(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step(&mut self) {
        // Every per-value vector has the same length; slicing them to it once lets the
        // compiler check each awake index against the bound once instead of four times.
        let n = self.offsets.len();
        let offsets = &mut self.offsets[..n];
        let step_velocities = &mut self.step_velocities[..n];
        let all_coefficients = &self.coefficients[..n];
        let bands = &self.bands[..n];
        let mut slot = 0;
        while slot < self.awake.len() {
            let i = self.awake[slot];
            let mut inside = true;
            let coefficients = &all_coefficients[i];
            let band = &bands[i];
            let offset = &mut offsets[i];
            let step_velocity = &mut step_velocities[i];
            for k in 0..D {
                inside &= advance(&mut offset[k], &mut step_velocity[k], coefficients, band);
            }
            if inside {
                *offset = [S::ZERO; D];
                *step_velocity = [S::ZERO; D];
                // `slot < len` here, so this cannot panic; the last awake index moves
                // into `slot` and is stepped next.
                self.awake.swap_remove(slot);
            } else {
                slot += 1;
            }
        }
    }

    /// The position of value `index`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4, 2>::new(0.01)?;
    /// let i = batch.push([1.0, 2.0], Tuning::rigid())?;
    /// assert_eq!(batch.position(i)?, [1.0, 2.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self, index: usize) -> Result<[S; D], Error> {
        self.check_index(index)?;
        let mut p = self.targets[index];
        for (p, x) in p.iter_mut().zip(self.offsets[index].iter()) {
            *p = p.add(*x);
        }
        Ok(p)
    }

    /// The target of value `index`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push([1.0], Tuning::rigid())?;
    /// assert_eq!(batch.target(i)?, [1.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn target(&self, index: usize) -> Result<[S; D], Error> {
        self.check_index(index)?;
        Ok(self.targets[index])
    }

    /// The step velocity `u = v·dt` of value `index`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push([1.0], Tuning::rigid())?;
    /// assert_eq!(batch.step_velocity(i)?, [0.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step_velocity(&self, index: usize) -> Result<[S; D], Error> {
        self.check_index(index)?;
        Ok(self.step_velocities[index])
    }

    /// True when value `index` is at rest on its target.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] for an unknown index.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 4>::new(0.01)?;
    /// let i = batch.push([1.0], Tuning::rigid())?;
    /// assert!(batch.is_at_rest(i)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_at_rest(&self, index: usize) -> Result<bool, Error> {
        self.check_index(index)?;
        Ok(!self.awake.contains(&index))
    }

    /// The number of values that are not at rest: the work one step does.
    ///
    /// ```
    /// let batch = stiffspring::SpringBatch::<f32, 4>::new(0.01)?;
    /// assert_eq!(batch.awake(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn awake(&self) -> usize {
        self.awake.len()
    }

    /// The number of values in the batch.
    ///
    /// ```
    /// let batch = stiffspring::SpringBatch::<f32, 4>::new(0.01)?;
    /// assert_eq!(batch.len(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// True when the batch holds no value.
    ///
    /// ```
    /// let batch = stiffspring::SpringBatch::<f32, 4>::new(0.01)?;
    /// assert!(batch.is_empty());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }

    fn check_index(&self, index: usize) -> Result<(), Error> {
        if index < self.offsets.len() {
            Ok(())
        } else {
            Err(Error::OutOfRange(Parameter::Index))
        }
    }

    fn wake(&mut self, index: usize) {
        if !self.awake.contains(&index) {
            // The awake list has the same capacity as the batch and holds distinct
            // indices, so there is always room.
            let _ = self.awake.push(index);
        }
    }
}
