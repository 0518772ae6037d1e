//! How a scene is set up: time step, gravity, stepper, limit policy, sleeping.

use crate::error::{Error, Parameter, positive};

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
    /// [`Error::NotFinite`] or [`Error::NotPositive`] with [`Parameter::Threshold`].
    ///
    /// ```
    /// assert!(stiffspring::scene::SleepThreshold::new(0.0, 1.0).is_err());
    /// ```
    pub fn new(velocity: f64, time: f64) -> Result<Self, Error> {
        Ok(SleepThreshold {
            velocity: positive(velocity, Parameter::Threshold)?,
            time: positive(time, Parameter::Threshold)?,
        })
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
    fn default() -> Self {
        SleepThreshold {
            velocity: 1e-3,
            time: 0.5,
        }
    }
}

/// Everything a [`Scene`](super::Scene) is built from.
///
/// ```
/// use stiffspring::scene::{SceneConfig, Stepper};
///
/// let config = SceneConfig::<2>::new(1.0 / 120.0)?
///     .gravity([0.0, -9.81])?
///     .stepper(Stepper::Jacobi)
///     .no_sleep();
/// assert_eq!(config.dt(), 1.0 / 120.0);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SceneConfig<const D: usize> {
    pub(crate) dt: f64,
    pub(crate) gravity: [f64; D],
    pub(crate) stepper: Stepper,
    pub(crate) policy: LimitPolicy,
    pub(crate) sleep: Option<SleepThreshold>,
}

impl<const D: usize> SceneConfig<D> {
    /// A scene stepped every `dt` seconds, without gravity, with the Gauss-Seidel
    /// stepper, the reject policy and the default sleep threshold.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::NotPositive`] for `dt`.
    ///
    /// ```
    /// assert!(stiffspring::scene::SceneConfig::<2>::new(-1.0).is_err());
    /// ```
    pub fn new(dt: f64) -> Result<Self, Error> {
        Ok(SceneConfig {
            dt: positive(dt, Parameter::TimeStep)?,
            gravity: [0.0; D],
            stepper: Stepper::GaussSeidel,
            policy: LimitPolicy::Reject,
            sleep: Some(SleepThreshold::default()),
        })
    }

    /// An external acceleration on every free particle, in units per second squared.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] with [`Parameter::Acceleration`].
    ///
    /// ```
    /// # use stiffspring::scene::SceneConfig;
    /// assert!(SceneConfig::<2>::new(0.01)?.gravity([0.0, f64::NAN]).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn gravity(mut self, acceleration: [f64; D]) -> Result<Self, Error> {
        if acceleration.iter().any(|a| !a.is_finite()) {
            return Err(Error::NotFinite(Parameter::Acceleration));
        }
        self.gravity = acceleration;
        Ok(self)
    }

    /// The stepper.
    ///
    /// ```
    /// # use stiffspring::scene::{SceneConfig, Stepper};
    /// let c = SceneConfig::<1>::new(0.01)?.stepper(Stepper::Jacobi);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn stepper(mut self, stepper: Stepper) -> Self {
        self.stepper = stepper;
        self
    }

    /// The policy for coefficients above the network limit.
    ///
    /// ```
    /// # use stiffspring::scene::{LimitPolicy, SceneConfig};
    /// let c = SceneConfig::<1>::new(0.01)?.limit_policy(LimitPolicy::Clamp);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn limit_policy(mut self, policy: LimitPolicy) -> Self {
        self.policy = policy;
        self
    }

    /// The sleep threshold.
    ///
    /// ```
    /// # use stiffspring::scene::{SceneConfig, SleepThreshold};
    /// let c = SceneConfig::<1>::new(0.01)?.sleep(SleepThreshold::new(0.1, 1.0)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn sleep(mut self, threshold: SleepThreshold) -> Self {
        self.sleep = Some(threshold);
        self
    }

    /// Never put anything to sleep.
    ///
    /// ```
    /// # use stiffspring::scene::SceneConfig;
    /// let c = SceneConfig::<1>::new(0.01)?.no_sleep();
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn no_sleep(mut self) -> Self {
        self.sleep = None;
        self
    }

    /// The time step, in seconds.
    ///
    /// ```
    /// # use stiffspring::scene::SceneConfig;
    /// assert_eq!(SceneConfig::<1>::new(0.01)?.dt(), 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn dt(&self) -> f64 {
        self.dt
    }
}
