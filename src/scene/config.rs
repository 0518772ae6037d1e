//! How a scene is set up: time step, gravity, drag, stepper, limit policy, sleeping.

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
/// **In your units.** The velocity is in the scene's unit per second: the default,
/// `10⁻³` for half a second, is 1 mm/s for a scene in metres and a thousandth of a pixel
/// per second for one in pixels (which then sleeps late). An island asleep stops where it
/// is; what it would have moved on is at most `velocity/c` under a drag `c`
/// ([`SceneConfig::linear_damping`]). So choose `velocity` about `c` times the smallest
/// change anyone can see: 1 cm/s under `c = 6` leaves at most 1.7 mm unmoved (0.17 px at
/// 100 px per metre), and `6` px/s under the same drag leaves at most a pixel for a scene
/// in pixels. Without drag nothing bounds it: an undamped swing may stay below the
/// threshold for the whole time and be cut off mid-swing.
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

/// How a scene is set up: its time step, gravity, drag, stepper, limit policy and
/// sleeping.
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
    /// The drag every particle gets when it is added: the rate `c` (per second), and
    /// `d = 1 − e^{−c·dt}`, its step form (see [`damping`](super::damping)).
    pub(crate) damping: (f64, f64),
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
            damping: (0.0, 0.0),
        })
    }

    /// The same configuration with a drag on the motion of every particle added to the
    /// scene: a free particle's velocity decays as `e^{−c·t}` (Box2D's `linearDamping`),
    /// sampled exactly (see [`Scene::set_linear_damping`](super::Scene::set_linear_damping),
    /// which sets it per particle). The springs damp only their stretching; this damps the
    /// swing of a whole rope about its pin, so a released network comes to rest and
    /// sleeps.
    ///
    /// **Choosing `c`.** Alone, a velocity keeps `e^{−c·t}` of itself after `t` seconds.
    /// A swing is an oscillator of frequency `ω`, and the drag damps it at `c/2` per
    /// second up to `c = 2ω` (critical); beyond that the swing creeps (at `ω²/c`) instead
    /// of stopping sooner. A rope of length `ℓ` hanging under gravity `g` swings slowest at
    /// `ω₁ ≈ 1.2·√(g/ℓ)` (a hanging chain's first mode), so `c ≈ 2.4·√(g/ℓ)` brings it to
    /// rest fastest: about 6 per second for a metre. Measured
    /// (`tests/scene_damping.rs`): a 20-particle rope of 0.95 m, dragged through a handle
    /// and let go, is asleep 2.3 s later with `c = 6` and
    /// [`SleepThreshold::new(0.01, 0.5)`](SleepThreshold::new) (in `f32` and `I16F16`);
    /// without drag it still swings at 0.8–1.3 m/s a minute later.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::LinearDamping`]
    /// outside `0 ≤ c ≤ ln 2/dt` (a step keeps at least half of the velocity: the drag
    /// within which every network at its [limit](super::network_limit) stays stable);
    /// [`Error::Unrepresentable`] for a drag so weak that the backend would not apply it
    /// (`c·dt` below `2⁻²⁴` in `f32` and `I16F16`, `2⁻³²` in `I32F32`).
    ///
    /// ```
    /// use stiffspring::scene::SceneConfig;
    /// use stiffspring::{Error, Parameter};
    ///
    /// let c = SceneConfig::<f32, 2>::new(1.0 / 60.0)?.linear_damping(2.5)?;
    /// assert_eq!(c.linear_damping_rate(), 2.5);
    /// assert!(matches!(
    ///     SceneConfig::<f32, 2>::new(1.0 / 60.0)?.linear_damping(-1.0),
    ///     Err(Error::OutOfRange { parameter: Parameter::LinearDamping, .. })
    /// ));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn linear_damping(self, rate: f64) -> Result<Self, Error> {
        self.with_damping(rate, Parameter::LinearDamping)
    }

    /// [`SceneConfig::linear_damping`] for an [`AngularScene`](super::AngularScene), whose
    /// particles are rotating bodies: every body's angular velocity decays as `e^{−c·t}`
    /// (Box2D's `angularDamping`). The same drag under another name; its errors name
    /// [`Parameter::AngularDamping`].
    ///
    /// # Errors
    ///
    /// As [`SceneConfig::linear_damping`], with [`Parameter::AngularDamping`].
    ///
    /// ```
    /// use stiffspring::scene::SceneConfig;
    /// let c = SceneConfig::<f64, 1>::new(1e-3)?.angular_damping(0.5)?;
    /// assert_eq!(c.linear_damping_rate(), 0.5);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn angular_damping(self, rate: f64) -> Result<Self, Error> {
        self.with_damping(rate, Parameter::AngularDamping)
    }

    fn with_damping(mut self, rate: f64, parameter: Parameter) -> Result<Self, Error> {
        let d = super::damping::step_fraction::<S>(rate, self.dt, parameter)?;
        self.damping = (rate, d);
        Ok(self)
    }

    /// The drag rate `c` (per second) every new particle gets; 0 without drag.
    ///
    /// ```
    /// assert_eq!(stiffspring::scene::SceneConfig::<f32, 1>::new(0.01)?.linear_damping_rate(), 0.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn linear_damping_rate(&self) -> f64 {
        self.damping.0
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
