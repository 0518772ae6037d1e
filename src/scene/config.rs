//! How a scene is set up: time step, gravity, stepper, limit policy, sleeping.

use crate::error::{Error, Parameter, positive, tri};
use crate::input::check_position;
use crate::scalar::Scalar;

/// The order in which a scene applies its springs; see the [scene docs](super).
///
/// ```
/// use stiffspring::scene::Stepper;
/// assert_eq!(Stepper::default(), Stepper::GaussSeidel);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Stepper {
    /// The impulse form, spring by spring, in place: each spring sees the velocities the
    /// springs before it produced this step. Converges faster and tolerates stiffer
    /// networks; the result depends on the order springs were added.
    #[default]
    GaussSeidel,
    /// The force form: every spring's impulse from the same state, summed, then applied.
    /// Independent of order (and parallel in principle), but each particle gets the sum of
    /// all its springs at once, so the safe coefficient is lower.
    Jacobi,
}

/// What a scene does with a spring whose coefficients exceed the safe limit for its
/// place in the network ([`network_limit`](super::network_limit)).
///
/// ```
/// use stiffspring::scene::LimitPolicy;
/// assert_eq!(LimitPolicy::default(), LimitPolicy::Reject);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LimitPolicy {
    /// Refuse the change with [`Error::ExceedsNetworkLimit`]; nothing changes.
    #[default]
    Reject,
    /// Lower `C_k` and `C_d` to the limit (for the new spring and for any neighbour whose
    /// limit the change lowered) and report how many springs were clamped.
    Clamp,
}

/// When a group of connected particles goes to sleep: every particle slower than
/// `velocity` (units per second) for `time` seconds in a row.
///
/// ```
/// use stiffspring::scene::SleepThreshold;
///
/// let t = SleepThreshold::new(0.01, 0.5)?;
/// assert_eq!((t.velocity(), t.time()), (0.01, 0.5));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SleepThreshold {
    velocity: f64,
    time: f64,
}

impl SleepThreshold {
    /// A threshold of `velocity` (units per second) held for `time` seconds.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::Threshold`].
    ///
    /// ```
    /// assert!(stiffspring::scene::SleepThreshold::new(0.0, 1.0).is_err());
    /// ```
    pub const fn new(velocity: f64, time: f64) -> Result<Self, Error> {
        let velocity = tri!(positive(velocity, Parameter::Threshold));
        let time = tri!(positive(time, Parameter::Threshold));
        Ok(SleepThreshold { velocity, time })
    }

    /// The velocity threshold, in units per second.
    ///
    /// ```
    /// # let t = stiffspring::scene::SleepThreshold::new(0.01, 0.5)?;
    /// assert_eq!(t.velocity(), 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self) -> f64 {
        self.velocity
    }

    /// How long every particle must stay below it, in seconds.
    ///
    /// ```
    /// # let t = stiffspring::scene::SleepThreshold::new(0.01, 0.5)?;
    /// assert_eq!(t.time(), 0.5);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn time(&self) -> f64 {
        self.time
    }
}

impl Default for SleepThreshold {
    /// A thousandth of a unit per second for half a second (Box2D sleeps after 0.5 s too).
    ///
    /// ```
    /// let t = stiffspring::scene::SleepThreshold::default();
    /// assert_eq!((t.velocity(), t.time()), (1e-3, 0.5));
    /// ```
    fn default() -> Self {
        SleepThreshold {
            velocity: 1e-3,
            time: 0.5,
        }
    }
}

/// How a scene is set up: its time step, gravity, stepper, limit policy and sleeping.
///
/// The scene owns the only `dt`: every spring's [`Tuning`](crate::Tuning) must be sampled
/// at it ([`Error::TimeStepMismatch`] otherwise). Gravity is in the scene's number type,
/// like everything that has the unit of its positions.
///
/// ```
/// use stiffspring::scene::{SceneConfig, Stepper};
///
/// let config = SceneConfig::<f32, 2>::new(1.0 / 120.0)?
///     .gravity([0.0, -9.81])?
///     .stepper(Stepper::Jacobi);
/// assert_eq!(config.dt(), 1.0 / 120.0);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SceneConfig<S: Scalar, const D: usize> {
    pub(crate) dt: f64,
    pub(crate) gravity: [S; D],
    pub(crate) stepper: Stepper,
    pub(crate) policy: LimitPolicy,
    pub(crate) sleep: Option<SleepThreshold>,
}

impl<S: Scalar, const D: usize> SceneConfig<S, D> {
    /// A scene stepped every `dt` seconds, without gravity, Gauss-Seidel, rejecting
    /// springs above the network limit, sleeping by [`SleepThreshold::default`].
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for `dt ≤ 0`.
    ///
    /// ```
    /// assert!(stiffspring::scene::SceneConfig::<f32, 2>::new(0.0).is_err());
    /// ```
    pub fn new(dt: f64) -> Result<Self, Error> {
        Ok(SceneConfig {
            dt: positive(dt, Parameter::TimeStep)?,
            gravity: [S::ZERO; D],
            stepper: Stepper::GaussSeidel,
            policy: LimitPolicy::Reject,
            sleep: Some(SleepThreshold::default()),
        })
    }

    /// The same configuration with a constant acceleration on every free particle, in
    /// units per second².
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::Acceleration`].
    ///
    /// ```
    /// use stiffspring::scene::SceneConfig;
    /// assert!(SceneConfig::<f32, 2>::new(0.01)?.gravity([0.0, f32::NAN]).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn gravity(mut self, acceleration: [S; D]) -> Result<Self, Error> {
        for a in acceleration {
            check_position(a, Parameter::Acceleration)?;
        }
        self.gravity = acceleration;
        Ok(self)
    }

    /// The same configuration with another stepper.
    ///
    /// ```
    /// use stiffspring::scene::{SceneConfig, Stepper};
    /// let c = SceneConfig::<f32, 1>::new(0.01)?.stepper(Stepper::Jacobi);
    /// # let _ = c;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn stepper(mut self, stepper: Stepper) -> Self {
        self.stepper = stepper;
        self
    }

    /// The same configuration with another limit policy.
    ///
    /// ```
    /// use stiffspring::scene::{LimitPolicy, SceneConfig};
    /// let c = SceneConfig::<f32, 1>::new(0.01)?.limit_policy(LimitPolicy::Clamp);
    /// # let _ = c;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn limit_policy(mut self, policy: LimitPolicy) -> Self {
        self.policy = policy;
        self
    }

    /// The same configuration with another sleep threshold.
    ///
    /// ```
    /// use stiffspring::scene::{SceneConfig, SleepThreshold};
    /// let c = SceneConfig::<f32, 1>::new(0.01)?.sleep(SleepThreshold::new(0.1, 1.0)?);
    /// # let _ = c;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn sleep(mut self, threshold: SleepThreshold) -> Self {
        self.sleep = Some(threshold);
        self
    }

    /// The same configuration without sleeping: every island is stepped every step.
    ///
    /// ```
    /// use stiffspring::scene::SceneConfig;
    /// let c = SceneConfig::<f32, 1>::new(0.01)?.no_sleep();
    /// # let _ = c;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn no_sleep(mut self) -> Self {
        self.sleep = None;
        self
    }

    /// The time step, in seconds.
    ///
    /// ```
    /// assert_eq!(stiffspring::scene::SceneConfig::<f32, 1>::new(0.01)?.dt(), 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn dt(&self) -> f64 {
        self.dt
    }
}
