//! A value that springs toward a target: the UI animation building block.
//!
//! The state is kept relative to the target, as the offset `x = position − target` and
//! the kept step velocity `ũ = (1 − C_d)·u` (`u = v·dt`), in the backend's state format,
//! so that one step is
//!
//! ```text
//! u ← ũ − C_k·x        x ← x + u        ũ ← u − C_d·u
//! ```
//!
//! Retargeting moves the offset by exactly the change of the target and keeps the
//! position and the velocity; with a tuning from the exact map, the value then follows
//! exactly the continuous spring whose target jumped at that instant (see
//! [`Oscillator::start_weights`](crate::Oscillator::start_weights)). When the motion left falls inside the rest band the value
//! snaps exactly to its target and stays there, [`SpringValue::step`] returning
//! [`Motion::Resting`], until something moves it again.

use crate::error::{Error, Parameter};
use crate::input::{check_position, gains_of, saturate};
use crate::motion::Motion;
use crate::rest::{RestBand, RestThreshold};
use crate::scalar::Scalar;
use crate::start::Start;
use crate::tuning::{Tuned, Tuning};
use core::mem::MaybeUninit;

/// A `D`-dimensional value springing toward a target, in backend `S`.
///
/// Its time step is its tuning's: there is no second `dt` to get wrong.
///
/// **The UI path cannot fail.** [`set_target`](SpringValue::set_target),
/// [`set_position`](SpringValue::set_position) and [`fling`](SpringValue::fling) take any
/// input: NaN is ignored, and what is out of range saturates (documented on each). Their
/// `try_` twins report the same cases as an [`Error`] and leave the value unchanged.
///
/// ```
/// use stiffspring::{Motion, SpringValue, Tuning};
///
/// let tuning = Tuning::from_frequency(2.0, 1.0, 1.0 / 60.0)?; // 2 Hz, critically damped
/// let mut card = SpringValue::<f32, 2>::new([0.0, 0.0], &tuning)?;
/// card.set_target([100.0, 40.0]);
/// let mut frames = 0;
/// while card.step() != Motion::Settled {
///     frames += 1;
/// }
/// assert_eq!(card.position(), [100.0, 40.0]); // snapped exactly
/// assert!(frames < 90);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
// `repr(C)`: the fields `step` reads come first and together (25 bytes of an 88-byte
// `f32` value), so that a loop over many values touches one cache line of each instead
// of the two the compiler's own order spread them over; the cold fields follow.
#[repr(C)]
pub struct SpringValue<S: Scalar, const D: usize = 1> {
    gains: S::Gains,
    offset: [S::State; D],
    step_velocity: [S::State; D],
    band: RestBand<S>,
    at_rest: bool,
    target: [S; D],
    start: Start<S>,
    threshold: RestThreshold,
    /// `√C_k` and `dt`, to rebuild the rest band for another threshold.
    rest_scales: (f64, f64),
}

impl<S: Scalar, const D: usize> SpringValue<S, D> {
    /// A value at rest at `position`, tuned by `tuning` (which also sets its time step),
    /// with the default [`RestThreshold`].
    ///
    /// # Errors
    ///
    /// - [`Error::NotFinite`] or [`Error::OutOfRange`] for a position;
    /// - [`Error::Unrepresentable`] when the backend cannot hold the tuning: in fixed
    ///   point a `C_k` whose dead band would be wider than a position's last bit
    ///   (`C_k < 2⁻²⁴` in `I16F16`, `2⁻³²` in `I32F32`: step less often, or use `I32F32`);
    ///   in floats a gain that rounds to zero.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning, I16F16};
    ///
    /// let v = SpringValue::<f64>::new([3.0], &Tuning::rigid(0.001)?)?;
    /// assert!(v.is_at_rest());
    /// assert!(SpringValue::<f32>::new([f32::NAN], &Tuning::rigid(0.001)?).is_err());
    /// // A 0.1 Hz spring at 10 kHz: C_k = 3.9e−9 is below I16F16's resolution.
    /// let slow = Tuning::from_frequency(0.1, 0.5, 1e-4)?;
    /// assert!(SpringValue::<I16F16>::new([I16F16::ZERO], &slow).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(position: [S; D], tuning: &Tuning) -> Result<Self, Error> {
        for p in position {
            check_position(p, Parameter::Position)?;
        }
        // The conversions of `Tuned::new`, each inlined here (as `gains_of` and
        // `Start::new` are), so that a caller keeping only the error's kind drops its
        // construction (the C API: `scripts/capi-size`).
        let gains = gains_of::<S>(tuning)?;
        let start = Start::new(tuning)?;
        let band = RestBand::new(&RestThreshold::DEFAULT, tuning);
        Ok(Self::at_rest_with(position, tuning, (gains, start, band)))
    }

    /// A value at rest at `position`, tuned by a tuning converted to this backend when the
    /// firmware was built ([`Tuned`], from [`tuning!`](crate::tuning!) with the backend):
    /// [`Self::new`]'s value, to the bit, without the run-time conversion (in fixed point
    /// an `f64` conversion of the gains to mantissas; `docs/firmware.md`, the flash
    /// table).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a position.
    ///
    /// ```
    /// use stiffspring::{I16F16, SpringValue, Tuned, Tuning, tuning};
    ///
    /// const T: Tuned<I16F16> = tuning!(Tuning::from_frequency(2.0, 0.7, 1.0 / 120.0), I16F16);
    /// let v = SpringValue::from_tuned([I16F16::from_num(3)], &T)?;
    /// assert!(v.is_at_rest());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn from_tuned(position: [S; D], tuned: &Tuned<S>) -> Result<Self, Error> {
        for p in position {
            check_position(p, Parameter::Position)?;
        }
        Ok(Self::at_rest_with(position, tuned.tuning(), tuned.parts()))
    }

    /// [`Self::from_tuned`], built in `slot` instead of returned: for storage the firmware
    /// keeps (a `static`, say). An `I16F16` value is 192 bytes, and moving one out of a
    /// `Result` into its storage copies all of it with the compiler's `memcpy` (742 bytes
    /// of flash on the Cortex-M4F, `scripts/size-report`); built in place, it is written
    /// where it lies. `slot` is written only when this returns `Ok`.
    ///
    /// # Errors
    ///
    /// As [`Self::from_tuned`].
    ///
    /// ```
    /// use core::mem::MaybeUninit;
    /// use stiffspring::{I16F16, SpringValue, Tuned, Tuning, tuning};
    ///
    /// const T: Tuned<I16F16> = tuning!(Tuning::rigid(0.01), I16F16);
    /// let mut slot = MaybeUninit::uninit();
    /// let v = SpringValue::<I16F16>::from_tuned_in(&mut slot, [I16F16::ZERO], &T)?;
    /// assert!(v.is_at_rest());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn from_tuned_in<'a>(
        slot: &'a mut MaybeUninit<Self>,
        position: [S; D],
        tuned: &Tuned<S>,
    ) -> Result<&'a mut Self, Error> {
        for p in position {
            check_position(p, Parameter::Position)?;
        }
        Ok(slot.write(Self::at_rest_with(position, tuned.tuning(), tuned.parts())))
    }

    /// The value at rest at `position` (checked) with `tuning`'s numbers in this backend
    /// and the default rest threshold.
    #[inline(always)]
    fn at_rest_with(
        position: [S; D],
        tuning: &Tuning,
        (gains, start, band): (S::Gains, Start<S>, RestBand<S>),
    ) -> Self {
        SpringValue {
            offset: [S::STATE_ZERO; D],
            step_velocity: [S::STATE_ZERO; D],
            gains,
            target: position,
            band,
            at_rest: true,
            start,
            threshold: RestThreshold::DEFAULT,
            rest_scales: (tuning.root_stiffness(), tuning.dt()),
        }
    }

    /// The same value with another rest threshold.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringValue, Tuning};
    ///
    /// let v = SpringValue::<f32>::new([0.0], &Tuning::rigid(0.01)?)?
    ///     .with_rest_threshold(RestThreshold::PIXELS);
    /// assert_eq!(v.rest_threshold(), RestThreshold::PIXELS);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_rest_threshold(mut self, threshold: RestThreshold) -> Self {
        self.threshold = threshold;
        let (root, dt) = self.rest_scales;
        self.band = RestBand::scaled(&threshold, root, dt);
        self
    }

    /// Moves the target. The value keeps its position and its velocity, and springs
    /// toward the new target from there; a value at rest wakes up unless the target did
    /// not change.
    ///
    /// The offset moves by exactly the change of the target (in floats, the change
    /// rounded once), so a value far from the origin keeps its position to the bit. With
    /// a tuning from the exact map the step velocity changes by `P·Δx` (see
    /// [`Oscillator::start_weights`](crate::Oscillator::start_weights)): the value then
    /// samples the continuous spring whose
    /// target jumped at this instant, and one released from rest starts on the
    /// continuous trajectory instead of one step behind it.
    ///
    /// A NaN component is ignored (the whole call does nothing); a target beyond
    /// [`Scalar::MAX`] saturates there, and an offset or a step velocity beyond the
    /// state's range saturates at its end. [`SpringValue::try_set_target`] reports these.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let dt = 0.01;
    /// let mut v = SpringValue::<f64>::new([0.0], &Tuning::from_frequency(2.0, 0.2, dt)?)?;
    /// v.set_target([1.0]);
    /// v.advance();
    /// let (p, vel) = (v.position(), v.velocity());
    /// v.set_target([-1.0]); // mid-flight
    /// assert_eq!(v.position(), p);
    /// assert!((v.velocity()[0] - vel[0]).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_target(&mut self, target: [S; D]) {
        let mut t = target;
        for v in t.iter_mut() {
            match saturate(*v) {
                Some(s) => *v = s,
                None => return,
            }
        }
        let (offset, velocity) = self.retargeted(&t);
        let moved = offset != self.offset;
        self.target = t;
        for i in 0..D {
            self.offset[i] = self.start.clamp(offset[i]);
            self.step_velocity[i] = self.start.clamp(velocity[i]);
        }
        self.wake_if(moved);
    }

    /// [`SpringValue::set_target`], reporting instead of saturating.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the target;
    /// [`Error::Unrepresentable`] when the offset or the step velocity leaves the state's
    /// range. The value is then unchanged.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let mut v = SpringValue::<f32>::new([0.0], &Tuning::rigid(0.01)?)?;
    /// assert!(v.try_set_target([f32::INFINITY]).is_err());
    /// assert!(v.try_set_target([2.0]).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_set_target(&mut self, target: [S; D]) -> Result<(), Error> {
        for v in target {
            check_position(v, Parameter::Position)?;
        }
        let (offset, velocity) = self.retargeted(&target);
        for i in 0..D {
            self.start.check(offset[i], Parameter::Position)?;
            self.start.check(velocity[i], Parameter::StepVelocity)?;
        }
        let moved = offset != self.offset;
        self.target = target;
        self.offset = offset;
        self.step_velocity = velocity;
        self.wake_if(moved);
        Ok(())
    }

    /// The offset and step velocity after moving the target to `target`, unchecked.
    fn retargeted(&self, target: &[S; D]) -> ([S::State; D], [S::State; D]) {
        let mut offset = self.offset;
        let mut velocity = self.step_velocity;
        for i in 0..D {
            // x + (old target − new target): exact in fixed point, one rounding in floats.
            let delta = S::state_sub(self.target[i].widen(), target[i].widen());
            offset[i] = S::state_add(offset[i], delta);
            velocity[i] = self.start.shifted(velocity[i], delta);
        }
        (offset, velocity)
    }

    /// Puts the value at `offset` from `target` with `velocity` (`f64`, rounded once to the
    /// state and the velocity formats, saturated), awake: a hand-over from another motion
    /// that keeps the offset finer than a position.
    pub(crate) fn start_at(&mut self, target: [S; D], offset: [f64; D], velocity: [f64; D]) {
        self.target = target;
        for i in 0..D {
            let x = self.start.clamp(S::state_from_f64(offset[i]));
            let v = saturate(S::from_f64(velocity[i])).unwrap_or(S::ZERO);
            self.offset[i] = x;
            self.step_velocity[i] = self.start.clamp(self.start.step_velocity_unchecked(x, v));
        }
        self.at_rest = false;
    }

    /// Moves the value to `position` at once (its target stays), keeping its velocity.
    ///
    /// NaN is ignored; out-of-range input saturates, as for [`SpringValue::set_target`].
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f64>::new([0.0], &Tuning::rigid(0.01)?)?;
    /// v.set_position([2.0]);
    /// assert_eq!((v.position(), v.target()), ([2.0], [0.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_position(&mut self, position: [S; D]) {
        let mut p = position;
        for v in p.iter_mut() {
            match saturate(*v) {
                Some(s) => *v = s,
                None => return,
            }
        }
        let (offset, velocity) = self.moved_to(&p);
        let moved = offset != self.offset;
        for i in 0..D {
            self.offset[i] = self.start.clamp(offset[i]);
            self.step_velocity[i] = self.start.clamp(velocity[i]);
        }
        self.wake_if(moved);
    }

    /// [`SpringValue::set_position`], reporting instead of saturating.
    ///
    /// # Errors
    ///
    /// As [`SpringValue::try_set_target`]; the value is then unchanged.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let mut v = SpringValue::<f32>::new([0.0], &Tuning::rigid(0.01)?)?;
    /// assert!(v.try_set_position([f32::NAN]).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_set_position(&mut self, position: [S; D]) -> Result<(), Error> {
        for v in position {
            check_position(v, Parameter::Position)?;
        }
        let (offset, velocity) = self.moved_to(&position);
        for i in 0..D {
            self.start.check(offset[i], Parameter::Position)?;
            self.start.check(velocity[i], Parameter::StepVelocity)?;
        }
        let moved = offset != self.offset;
        self.offset = offset;
        self.step_velocity = velocity;
        self.wake_if(moved);
        Ok(())
    }

    /// The offset and step velocity after a jump to `position`, unchecked.
    fn moved_to(&self, position: &[S; D]) -> ([S::State; D], [S::State; D]) {
        let mut offset = self.offset;
        let mut velocity = self.step_velocity;
        for i in 0..D {
            let to = S::state_sub(position[i].widen(), self.target[i].widen());
            let delta = S::state_sub(to, offset[i]);
            offset[i] = to;
            velocity[i] = self.start.shifted(velocity[i], delta);
        }
        (offset, velocity)
    }

    /// Gives the value a velocity (units per second), as a finger releasing a fling does.
    ///
    /// With a tuning from the exact map, the step velocity is set to `u₀ = x(0) − x(−dt)`
    /// of the continuous oscillator the tuning samples (see
    /// [`Oscillator::start_weights`](crate::Oscillator::start_weights)), so that every
    /// later sample lies exactly on the continuous trajectory. Raw coefficients get `u₀ = velocity·dt`. No
    /// transcendental function runs here: the weights were computed at set-up.
    ///
    /// NaN is ignored; a step velocity beyond the state's range saturates.
    /// [`SpringValue::try_fling`] reports these.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let tuning = Tuning::from_frequency(1.0, 0.5, 1.0 / 120.0)?;
    /// let mut v = SpringValue::<f32>::new([0.0], &tuning)?;
    /// v.fling([2000.0]);
    /// v.advance();
    /// assert!(v.position()[0] > 15.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn fling(&mut self, velocity: [S; D]) {
        let mut u = self.step_velocity;
        for i in 0..D {
            let Some(v) = saturate(velocity[i]) else {
                return;
            };
            u[i] = self
                .start
                .clamp(self.start.step_velocity_unchecked(self.offset[i], v));
        }
        self.step_velocity = u;
        self.at_rest = false;
    }

    /// [`SpringValue::fling`], reporting instead of saturating.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the velocity;
    /// [`Error::Unrepresentable`] when the step velocity leaves the state's range (say, a
    /// heavily overdamped spring whose exact start extrapolates one step back to a huge
    /// offset). The value is then unchanged.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let mut v = SpringValue::<f32>::new([0.0], &Tuning::rigid(0.01)?)?;
    /// assert!(v.try_fling([f32::NAN]).is_err());
    /// assert!(v.try_fling([10.0]).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_fling(&mut self, velocity: [S; D]) -> Result<(), Error> {
        let mut u = self.step_velocity;
        for i in 0..D {
            let v = check_position(velocity[i], Parameter::Velocity)?;
            u[i] = self.start.step_velocity(self.offset[i], v)?;
        }
        self.step_velocity = u;
        self.at_rest = false;
        Ok(())
    }

    /// Retunes the value (a new spring, a new time step, or both); its position and
    /// velocity are kept.
    ///
    /// # Errors
    ///
    /// As [`SpringValue::new`] for the tuning, and [`Error::Unrepresentable`] when the
    /// velocity needs a step velocity beyond the state's range at the new tuning. The
    /// value is then unchanged.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let t60 = Tuning::from_frequency(2.0, 0.5, 1.0 / 60.0)?;
    /// let mut v = SpringValue::<f64>::new([0.0], &t60)?;
    /// v.set_target([1.0]);
    /// v.advance();
    /// let (p, vel) = (v.position(), v.velocity());
    /// v.set_tuning(&t60.with_dt(1.0 / 120.0)?)?; // the display switched to 120 Hz
    /// assert_eq!(v.position(), p);
    /// assert!((v.velocity()[0] - vel[0]).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_tuning(&mut self, tuning: &Tuning) -> Result<(), Error> {
        let gains = gains_of::<S>(tuning)?;
        let start = Start::<S>::new(tuning)?;
        let mut u = self.step_velocity;
        for i in 0..D {
            let v = self.start.velocity(self.offset[i], self.step_velocity[i]);
            u[i] = start.step_velocity(self.offset[i], v)?;
        }
        self.gains = gains;
        self.start = start;
        self.step_velocity = u;
        self.rest_scales = (tuning.root_stiffness(), tuning.dt());
        self.band = RestBand::new(&self.threshold, tuning);
        Ok(())
    }

    /// Advances the value by one time step and reports what happened: it settles (snaps
    /// exactly onto its target, and stays there) when the motion it has left is inside
    /// its [`RestThreshold`].
    ///
    /// **Cost.** The moving path is the spring ([`SpringValue::advance`]) and one
    /// comparison of the step velocity with its band; the position's band is compared
    /// only when that one passes. A value at rest is stepped the same way, not skipped:
    /// its state is zero, which a step leaves unchanged to the bit, and it returns
    /// [`Motion::Resting`] from the branch where the flag is read. So a resting value
    /// costs what a moving one does (on the Cortex-M4F, the moving step's 15
    /// instructions instead of the 3 of a flag test), and a moving one 3 instructions
    /// less than a step that tests the flag first (`scripts/cost`, whose tables
    /// docs/firmware.md includes). Many values that rest most of the
    /// time belong in a [`SpringBatch`](crate::SpringBatch), which skips its settled ones.
    ///
    /// ```
    /// use stiffspring::{Motion, SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f32>::new([0.0], &Tuning::from_coefficients(0.5, 0.5, 0.01)?)?;
    /// v.set_target([1.0]);
    /// assert_eq!(v.step(), Motion::Moving);
    /// assert_eq!(v.position(), [0.5]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline]
    pub fn step(&mut self) -> Motion {
        // No test of the at-rest flag on the way in: at rest the state is zero, which
        // every backend's step leaves unchanged (see `advance`), and zero is inside every
        // band. A value at rest is stepped as a moving one is and lands in the branch of
        // the band test that a moving value takes once, where the flag is read. The
        // moving path is the spring and one band comparison.
        for i in 0..D {
            S::advance(&self.gains, &mut self.offset[i], &mut self.step_velocity[i]);
        }
        // Every component inside its band; the first one outside ends the test.
        let band = &self.band;
        if (0..D).all(|i| band.contains(self.offset[i], self.step_velocity[i])) {
            self.inside_band()
        } else {
            Motion::Moving
        }
    }

    /// The rest test passed: a value already at rest stays so, a moving one settles.
    #[inline]
    fn inside_band(&mut self) -> Motion {
        if self.at_rest {
            Motion::Resting
        } else {
            self.settle();
            Motion::Settled
        }
    }

    /// Advances the value by one time step and nothing else: no rest test, no flag. The
    /// cheapest step, for a loop that runs the spring continuously (a haptic output) or
    /// tests rest itself. A value advanced this way never settles; [`SpringValue::step`]
    /// afterwards picks up where it is. A value at rest sits on its target with no
    /// velocity, which a step leaves unchanged, so it stays at rest (and `advance`
    /// touches no flag: its cost is the spring's and nothing else).
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f32>::new([0.0], &Tuning::from_coefficients(0.5, 0.5, 0.01)?)?;
    /// v.set_target([1.0]);
    /// v.advance();
    /// assert_eq!(v.position(), [0.5]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline]
    pub fn advance(&mut self) {
        for i in 0..D {
            S::advance(&self.gains, &mut self.offset[i], &mut self.step_velocity[i]);
        }
        // No `at_rest = false`: at rest the state is zero (see `settle` and `wake_if`),
        // and zero is a fixed point of every backend's step.
        debug_assert!(
            !self.at_rest
                || (self.offset == [S::STATE_ZERO; D] && self.step_velocity == [S::STATE_ZERO; D])
        );
    }

    /// The current position.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f32, 3>::new([1.0, 2.0, 3.0], &Tuning::rigid(0.01)?)?;
    /// assert_eq!(v.position(), [1.0, 2.0, 3.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self) -> [S; D] {
        let mut p = self.target;
        for (p, x) in p.iter_mut().zip(self.offset.iter()) {
            // Summed in the state format, which holds offsets beyond the position range
            // (a retarget across the whole range), then rounded once.
            *p = S::narrow(S::state_add(p.widen(), *x));
        }
        p
    }

    /// The target the value springs toward.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f32>::new([4.0], &Tuning::rigid(0.01)?)?;
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
    /// let mut v = SpringValue::<f32>::new([4.0], &Tuning::rigid(0.01)?)?;
    /// v.set_target([1.0]);
    /// assert_eq!(v.offset(), [3.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn offset(&self) -> [S; D] {
        self.offset.map(S::narrow)
    }

    /// The step velocity `u = x_n − x_{n−1}`: the distance moved in the last step (rounded
    /// to a position in fixed point, whose state keeps more bits). A spring with `C_d = 1`
    /// keeps no velocity from one step to the next, and reads 0 here. It saturates at
    /// `±Scalar::MAX`: the exact start of a heavily overdamped spring extrapolates one step
    /// back to a step velocity beyond any format (see [`Scalar`]), which the value never
    /// stores (it keeps `(1 − C_d)·u`).
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let v = SpringValue::<f32>::new([4.0], &Tuning::rigid(0.01)?)?;
    /// assert_eq!(v.step_velocity(), [0.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step_velocity(&self) -> [S; D] {
        self.step_velocity.map(|v| self.start.step_velocity_of(v))
    }

    /// The velocity in units per second.
    ///
    /// For a tuning from the exact map it is the velocity of the continuous trajectory
    /// the value samples (see [`SpringValue::fling`], whose inverse it is); for raw
    /// coefficients the backward difference `u/dt`. It saturates at `±Scalar::MAX`.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f64>::new([0.0], &Tuning::from_coefficients(0.5, 0.5, 0.5)?)?;
    /// v.set_target([1.0]);
    /// v.advance(); // moves by 0.5 in 0.5 s
    /// assert_eq!(v.velocity(), [1.0]);
    ///
    /// let dt = 0.01;
    /// let mut w = SpringValue::<f64>::new([0.0], &Tuning::from_frequency(1.0, 0.1, dt)?)?;
    /// w.fling([3.0]);
    /// assert!((w.velocity()[0] - 3.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self) -> [S; D] {
        let mut v = [S::ZERO; D];
        for (v, (x, u)) in v
            .iter_mut()
            .zip(self.offset.iter().zip(&self.step_velocity))
        {
            *v = self.start.velocity(*x, *u);
        }
        v
    }

    /// The rest threshold.
    ///
    /// ```
    /// use stiffspring::{RestThreshold, SpringValue, Tuning};
    /// let v = SpringValue::<f32>::new([0.0], &Tuning::rigid(0.01)?)?;
    /// assert_eq!(v.rest_threshold(), RestThreshold::default());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_threshold(&self) -> RestThreshold {
        self.threshold
    }

    /// True when the value sits exactly on its target with zero velocity: stepping it
    /// leaves it there and returns [`Motion::Resting`].
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    /// let mut v = SpringValue::<f32>::new([0.0], &Tuning::rigid(0.01)?)?;
    /// v.set_target([1.0]);
    /// assert!(!v.is_at_rest());
    /// let _ = (v.step(), v.step());
    /// assert!(v.is_at_rest());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_at_rest(&self) -> bool {
        self.at_rest
    }

    /// Snaps exactly onto the target: at rest, stepping leaves the value there until it
    /// is moved.
    fn settle(&mut self) {
        // Element by element with the flag in between: two whole-array stores merge into
        // one wide store (a 16-byte `movups` for an `f64` value), which overlaps both
        // fields, and LLVM then reloads the state from memory on every step of a caller's
        // loop instead of keeping it in registers (`f64` value step 1.8× slower; see
        // docs/benchmarks.md).
        for x in self.offset.iter_mut() {
            *x = S::STATE_ZERO;
        }
        self.at_rest = true;
        for u in self.step_velocity.iter_mut() {
            *u = S::STATE_ZERO;
        }
    }

    /// A value at rest stays at rest only if nothing moved.
    fn wake_if(&mut self, moved: bool) {
        self.at_rest &= !moved;
    }
}
