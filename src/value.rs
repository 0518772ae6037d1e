//! A value that springs toward a target: the UI animation building block.
//!
//! The state is kept relative to the target, as the offset `x = position − target` and
//! the step velocity `u = v·dt`, so that one step is exactly the kernel's response
//! followed by one add per dimension:
//!
//! ```text
//! u ← (1 − C_d)·u − C_k·x        x ← x + u
//! ```
//!
//! Retargeting moves the offset and keeps the position and the velocity; with a tuning
//! from the exact map, the value then follows exactly the continuous spring whose target
//! jumped at that instant (see the `sampling` module). When both the offset and the step
//! velocity fall inside the rest band, the value snaps exactly to its target and
//! [`SpringValue::step`] returns at once until something moves it again.

use crate::error::{Error, Parameter, positive};
use crate::kernel::Coefficients;
use crate::rest::{RestBand, RestThreshold};
use crate::sampling::Sampling;
use crate::scalar::Scalar;
use crate::tuning::Tuning;

/// A `D`-dimensional value springing toward a target, in backend `S`.
///
/// ```
/// use stiffspring::{SpringValue, Tuning};
///
/// let dt = 1.0 / 60.0;
/// let tuning = Tuning::from_frequency(2.0, 1.0, dt)?; // 2 Hz, critically damped
/// let mut x = SpringValue::<f32, 2>::new([0.0, 0.0], tuning, dt)?;
/// x.set_target([100.0, 40.0])?;
/// let mut frames = 0;
/// while !x.is_at_rest() {
///     x.step();
///     frames += 1;
/// }
/// assert_eq!(x.position(), [100.0, 40.0]); // snapped exactly
/// assert!(frames < 90);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpringValue<S: Scalar, const D: usize> {
    offset: [S; D],
    step_velocity: [S; D],
    target: [S; D],
    coefficients: Coefficients<S>,
    sampling: Sampling<S>,
    threshold: RestThreshold,
    band: RestBand<S>,
    dt: f64,
    at_rest: bool,
}

/// A one-dimensional [`SpringValue`].
///
/// ```
/// use stiffspring::{SpringValue1, Tuning};
/// let v = SpringValue1::<f32>::new([0.0], Tuning::rigid(), 0.01)?;
/// assert_eq!(v.position(), [0.0]);
/// # Ok::<(), stiffspring::Error>(())
/// ```
pub type SpringValue1<S> = SpringValue<S, 1>;

/// Advances one component of a spring toward its target by one step and reports whether
/// it is inside its rest band. The single place where a value (or a batch member) steps.
#[inline(always)]
pub(crate) fn advance<S: Scalar>(
    offset: &mut S,
    step_velocity: &mut S,
    coefficients: &Coefficients<S>,
    band: &RestBand<S>,
) -> bool {
    let u = coefficients.respond(*offset, *step_velocity);
    // A spring with (almost) no pull and no damping drifts for ever: bound the offset at
    // the backend's safe magnitude so that a float never reaches infinity (the identity
    // in fixed point, which saturates anyway).
    let x = offset.add(u).clamp_magnitude(band.limit);
    *step_velocity = u;
    *offset = x;
    band.contains(x, u)
}

/// Moves one component's offset to `to` with its velocity kept (`u += P·Δx`, see the
/// `sampling` module) and reports whether it moved. Shared by values and batches.
pub(crate) fn jump<S: Scalar>(
    offset: &mut S,
    step_velocity: &mut S,
    sampling: &Sampling<S>,
    to: S,
) -> bool {
    let delta = to.sub(*offset);
    *step_velocity = sampling.shift(*step_velocity, delta);
    *offset = to;
    delta != S::ZERO
}

/// The offsets `position − target`, each of which must stay within the backend's safe
/// magnitude (in fixed point: not saturate).
pub(crate) fn offsets<S: Scalar, const D: usize>(
    position: &[S; D],
    target: &[S; D],
) -> Result<[S; D], Error> {
    let mut out = [S::ZERO; D];
    for ((o, p), t) in out.iter_mut().zip(position).zip(target) {
        if (p.to_f64() - t.to_f64()).abs() > S::SAFE_MAGNITUDE - S::RESOLUTION {
            return Err(Error::OutOfRange(Parameter::Position));
        }
        *o = p.sub(*t);
    }
    Ok(out)
}

/// Values must be finite and within the backend's safe magnitude.
pub(crate) fn check_all<S: Scalar, const D: usize>(
    values: &[S; D],
    what: Parameter,
) -> Result<(), Error> {
    check_within(values, S::SAFE_MAGNITUDE, what)
}

/// Values must be finite and at most `bound` in magnitude (`SAFE_MAGNITUDE` for values,
/// `NETWORK_MAGNITUDE` for scenes).
pub(crate) fn check_within<S: Scalar, const D: usize>(
    values: &[S; D],
    bound: f64,
    what: Parameter,
) -> Result<(), Error> {
    for v in values.iter().map(|v| v.to_f64()) {
        if !v.is_finite() {
            return Err(Error::NotFinite(what));
        }
        if v.abs() > bound {
            return Err(Error::OutOfRange(what));
        }
    }
    Ok(())
}

impl<S: Scalar, const D: usize> SpringValue<S, D> {
    /// A value at rest at `position`, tuned by `tuning`, stepped every `dt` seconds, with
    /// the default [`RestThreshold`] (a thousandth of a unit).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a position; [`Error::NotFinite`]
    /// or [`Error::NotPositive`] for `dt`.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let v = SpringValue::<f64, 1>::new([3.0], Tuning::rigid(), 0.001)?;
    /// assert!(v.is_at_rest());
    /// assert!(SpringValue::<f32, 1>::new([f32::NAN], Tuning::rigid(), 0.001).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(position: [S; D], tuning: Tuning, dt: f64) -> Result<Self, Error> {
        check_all(&position, Parameter::Position)?;
        let dt = positive(dt, Parameter::TimeStep)?;
        let coefficients = Coefficients::new(&tuning);
        let threshold = RestThreshold::default();
        Ok(SpringValue {
            offset: [S::ZERO; D],
            step_velocity: [S::ZERO; D],
            target: position,
            coefficients,
            sampling: Sampling::new(&tuning, &coefficients, dt),
            threshold,
            band: RestBand::new(&threshold, &coefficients, dt),
            dt,
            at_rest: true,
        })
    }

    /// The same value with other rest thresholds.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringValue, Tuning};
    ///
    /// let v = SpringValue::<f32, 1>::new([0.0], Tuning::rigid(), 0.01)?
    ///     .with_rest_threshold(RestThreshold::PIXELS);
    /// assert_eq!(v.rest_threshold(), RestThreshold::PIXELS);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_rest_threshold(mut self, threshold: RestThreshold) -> Self {
        self.threshold = threshold;
        self.band = RestBand::new(&threshold, &self.coefficients, self.dt);
        self
    }

    /// Moves the target. The value keeps its position (exactly in fixed point, to a
    /// rounding in floats) and its velocity, and springs toward the new target from
    /// there; a value at rest wakes up unless the target did not change.
    ///
    /// With raw coefficients the step velocity `u` is kept as it is. With a tuning from
    /// the exact map the value then samples exactly the continuous spring whose target
    /// jumped at this instant: the step velocity changes by `P·Δx` (see
    /// [`Oscillator::start_weights`]), which also makes a value released from rest start
    /// on the continuous trajectory instead of one step behind it.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the target, and
    /// [`Error::OutOfRange`] when the offset `position − target` leaves
    /// [`Scalar::SAFE_MAGNITUDE`] (in fixed point: when the value would have to cross more
    /// than half the range); the value is then unchanged.
    ///
    /// [`Oscillator::start_weights`]: crate::Oscillator::start_weights
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let dt = 0.01;
    /// let mut v = SpringValue::<f64, 1>::new([0.0], Tuning::from_frequency(2.0, 0.2, dt)?, dt)?;
    /// v.set_target([1.0])?;
    /// v.step();
    /// let (p, vel) = (v.position(), v.velocity());
    /// v.set_target([-1.0])?; // mid-flight
    /// assert_eq!(v.position(), p);
    /// assert!((v.velocity()[0] - vel[0]).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_target(&mut self, target: [S; D]) -> Result<(), Error> {
        check_all(&target, Parameter::Position)?;
        let offset = offsets(&self.position(), &target)?;
        self.target = target;
        self.move_offset(offset);
        Ok(())
    }

    /// Moves the value to `position` at once (its target stays), keeping its velocity.
    ///
    /// # Errors
    ///
    /// As [`SpringValue::set_target`].
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f64, 1>::new([0.0], Tuning::rigid(), 0.01)?;
    /// v.set_position([2.0])?;
    /// assert_eq!((v.position(), v.target()), ([2.0], [0.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_position(&mut self, position: [S; D]) -> Result<(), Error> {
        check_all(&position, Parameter::Position)?;
        let offset = offsets(&position, &self.target)?;
        self.move_offset(offset);
        Ok(())
    }

    /// Gives the value a velocity (units per second), as a finger releasing a fling does.
    ///
    /// With a tuning from the exact map, the step velocity is set to `u₀ = x(0) − x(−dt)`
    /// of the continuous oscillator the tuning samples (see
    /// [`Oscillator::start_step_velocity`]), so that every later sample lies exactly on
    /// the continuous trajectory. Raw coefficients get `u₀ = velocity·dt`. No
    /// transcendental function runs here: the weights were computed at set-up.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the velocity, or when `u₀`
    /// leaves the backend's range; the value is then unchanged.
    ///
    /// [`Oscillator::start_step_velocity`]: crate::Oscillator::start_step_velocity
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let dt = 1.0 / 120.0;
    /// let mut v = SpringValue::<f32, 1>::new([0.0], Tuning::from_frequency(1.0, 0.5, dt)?, dt)?;
    /// v.fling([2000.0])?;
    /// v.step();
    /// assert!(v.position()[0] > 15.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn fling(&mut self, velocity: [S; D]) -> Result<(), Error> {
        check_all(&velocity, Parameter::Velocity)?;
        let mut u = [S::ZERO; D];
        for i in 0..D {
            u[i] = self.sampling.step_velocity(self.offset[i], velocity[i])?;
        }
        self.step_velocity = u;
        self.at_rest = false;
        Ok(())
    }

    /// Retunes the value; its position and velocity are kept.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] for the velocity when the new tuning would need a step
    /// velocity outside the backend's range; the value is then unchanged.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f32, 1>::new([0.0], Tuning::rigid(), 0.01)?;
    /// v.set_tuning(Tuning::from_coefficients(0.1, 0.2)?)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_tuning(&mut self, tuning: Tuning) -> Result<(), Error> {
        self.resample(tuning, self.dt)
    }

    /// Changes the time step, for a display that switches between 60 and 120 Hz.
    ///
    /// Position and velocity (in units per second) are kept. If the tuning samples a
    /// continuous oscillator ([`Tuning::samples_oscillator`]), the coefficients are
    /// recomputed so that the same oscillator is sampled at the new rate; raw coefficients
    /// are kept, which the article says keeps the same behaviour per step.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::NotPositive`] for `dt`, an error of the exact map
    /// at the new rate ([`Error::Aliased`]), or [`Error::OutOfRange`] for the velocity;
    /// the value is then unchanged.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let dt = 1.0 / 60.0;
    /// let mut v = SpringValue::<f64, 1>::new([0.0], Tuning::from_frequency(2.0, 0.5, dt)?, dt)?;
    /// v.set_dt(1.0 / 120.0)?;
    /// let f = v.tuning().oscillator(1.0 / 120.0)?.frequency();
    /// assert!((f - 2.0).abs() < 1e-9);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_dt(&mut self, dt: f64) -> Result<(), Error> {
        let dt = positive(dt, Parameter::TimeStep)?;
        let tuning = self.tuning();
        #[cfg(feature = "libm")]
        if tuning.samples_oscillator() {
            let resampled = tuning.oscillator(self.dt)?.tuning(dt)?;
            return self.resample(resampled, dt);
        }
        self.resample(tuning, dt)
    }

    /// Installs `tuning` at `dt`, keeping position and velocity: the velocity is read
    /// through the old sampling weights and written through the new ones.
    fn resample(&mut self, tuning: Tuning, dt: f64) -> Result<(), Error> {
        let velocity = self.velocity();
        let coefficients = Coefficients::new(&tuning);
        let sampling = Sampling::new(&tuning, &coefficients, dt);
        let mut u = [S::ZERO; D];
        for i in 0..D {
            u[i] = sampling.step_velocity(self.offset[i], velocity[i])?;
        }
        self.step_velocity = u;
        self.coefficients = coefficients;
        self.sampling = sampling;
        self.dt = dt;
        self.band = RestBand::new(&self.threshold, &coefficients, dt);
        Ok(())
    }

    /// Advances the value by one time step. Does nothing when the value is at rest.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f32, 1>::new([0.0], Tuning::from_coefficients(0.5, 0.5)?, 0.01)?;
    /// v.set_target([1.0])?;
    /// v.step();
    /// assert_eq!(v.position(), [0.5]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline]
    pub fn step(&mut self) {
        if self.at_rest {
            return;
        }
        let mut inside = true;
        for i in 0..D {
            inside &= advance(
                &mut self.offset[i],
                &mut self.step_velocity[i],
                &self.coefficients,
                &self.band,
            );
        }
        if inside {
            self.settle();
        }
    }

    /// The current position.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f32, 3>::new([1.0, 2.0, 3.0], Tuning::rigid(), 0.01)?;
    /// assert_eq!(v.position(), [1.0, 2.0, 3.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self) -> [S; D] {
        let mut p = self.target;
        for (p, x) in p.iter_mut().zip(self.offset.iter()) {
            *p = p.add(*x);
        }
        p
    }

    /// The target the value springs toward.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f32, 1>::new([4.0], Tuning::rigid(), 0.01)?;
    /// assert_eq!(v.target(), [4.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn target(&self) -> [S; D] {
        self.target
    }

    /// The offset from the target, `position − target`.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let mut v = SpringValue::<f32, 1>::new([4.0], Tuning::rigid(), 0.01)?;
    /// v.set_target([1.0])?;
    /// assert_eq!(v.offset(), [3.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn offset(&self) -> [S; D] {
        self.offset
    }

    /// The step velocity `u = v·dt`: the distance moved in the last step.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f32, 1>::new([4.0], Tuning::rigid(), 0.01)?;
    /// assert_eq!(v.step_velocity(), [0.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step_velocity(&self) -> [S; D] {
        self.step_velocity
    }

    /// The velocity in units per second.
    ///
    /// For a tuning from the exact map it is the velocity of the continuous trajectory
    /// the value samples, exactly (see [`SpringValue::fling`], whose inverse it is); for
    /// raw coefficients the backward difference `u/dt`.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f64, 1>::new([0.0], Tuning::rigid(), 0.5)?;
    /// v.set_target([1.0])?;
    /// v.step();
    /// assert_eq!(v.velocity(), [2.0]);
    ///
    /// let dt = 0.01;
    /// let mut w = SpringValue::<f64, 1>::new([0.0], Tuning::from_frequency(1.0, 0.1, dt)?, dt)?;
    /// w.fling([3.0])?;
    /// assert!((w.velocity()[0] - 3.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self) -> [S; D] {
        let mut v = [S::ZERO; D];
        for ((v, x), u) in v.iter_mut().zip(&self.offset).zip(&self.step_velocity) {
            *v = self.sampling.velocity(*x, *u);
        }
        v
    }

    /// The time step, in seconds.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f32, 1>::new([0.0], Tuning::rigid(), 0.01)?;
    /// assert_eq!(v.dt(), 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The tuning in effect, after rounding to the backend's coefficient format.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f64, 1>::new([0.0], Tuning::rigid(), 0.01)?;
    /// assert_eq!(v.tuning(), Tuning::rigid());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn tuning(&self) -> Tuning {
        let t = self.coefficients.tuning();
        Tuning::from_parts(t.stiffness(), t.retention(), self.sampling.is_continuous())
    }

    /// The rest thresholds as given by the user.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringValue, Tuning};
    /// let v = SpringValue::<f32, 1>::new([0.0], Tuning::rigid(), 0.01)?;
    /// assert_eq!(v.rest_threshold(), RestThreshold::default());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_threshold(&self) -> RestThreshold {
        self.threshold
    }

    /// The offset below which the value snaps to its target when it is slow enough: the
    /// position threshold, widened in fixed point to cover the dead band
    /// `1/C_k` LSB in which the rounded spring stops moving.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringValue, Tuning};
    ///
    /// let v = SpringValue::<f32, 1>::new([0.0], Tuning::rigid(), 0.01)?
    ///     .with_rest_threshold(RestThreshold::new(0.5, 1.0)?);
    /// assert_eq!(v.rest_offset(), 0.5);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_offset(&self) -> S {
        self.band.offset
    }

    /// True when the value sits exactly on its target with zero velocity, and stepping it
    /// costs nothing.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let mut v = SpringValue::<f32, 1>::new([0.0], Tuning::rigid(), 0.01)?;
    /// v.set_target([1.0])?;
    /// assert!(!v.is_at_rest());
    /// v.step();
    /// v.step();
    /// assert!(v.is_at_rest());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_at_rest(&self) -> bool {
        self.at_rest
    }

    /// Snaps exactly onto the target: at rest, stepping costs nothing until moved.
    fn settle(&mut self) {
        // Zeroed element by element, with the flag in between: two whole-array stores
        // of zero merge into one memset in `f64`, and a memset stops the compiler from
        // keeping the state in registers across a caller's loop of steps (every step
        // then pays a store-to-load round trip through memory).
        for x in self.offset.iter_mut() {
            *x = S::ZERO;
        }
        self.at_rest = true;
        for u in self.step_velocity.iter_mut() {
            *u = S::ZERO;
        }
    }

    /// Jumps the offset to `offset` with the velocity kept (`u += P·Δx`). A value at rest
    /// stays at rest only if nothing moved; anything else wakes it and the next step
    /// decides.
    fn move_offset(&mut self, offset: [S; D]) {
        let mut moved = false;
        for ((x, u), to) in self
            .offset
            .iter_mut()
            .zip(&mut self.step_velocity)
            .zip(offset)
        {
            moved |= jump(x, u, &self.sampling, to);
        }
        self.at_rest &= !moved;
    }
}
