//! The one error type of the crate.
//!
//! Every check happens at set-up (constructors, `try_` setters): the stepping functions
//! never fail, so they return no `Result`. Each variant names the argument that was
//! wrong, the value it had and the bound it broke, so a firmware log (`Display` or
//! `defmt`) says what to change. Formatting code is only linked when it is used.

use core::fmt;

/// Which argument of a set-up call was rejected.
///
/// ```
/// use stiffspring::{Bound, Error, Parameter, Tuning};
///
/// let err = Tuning::from_coefficients(1.5, 0.2, 0.01).unwrap_err();
/// assert_eq!(err.parameter(), Some(Parameter::Stiffness));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Parameter {
    /// The stiffness coefficient `C_k`.
    Stiffness,
    /// The damping coefficient `C_d`.
    Damping,
    /// The time step `dt`, in seconds.
    TimeStep,
    /// A natural frequency, in hertz.
    Frequency,
    /// A damping ratio `ζ`.
    DampingRatio,
    /// A mass or a moment of inertia.
    Mass,
    /// A physical spring constant `k`.
    SpringConstant,
    /// A physical damping constant `c`.
    DampingConstant,
    /// A duration, in seconds (SwiftUI's `duration`, `response`).
    Duration,
    /// SwiftUI's `bounce`.
    Bounce,
    /// A position, offset or target.
    Position,
    /// A velocity.
    Velocity,
    /// The step velocity `u = v·dt` that a start, a fling or a retarget needs.
    StepVelocity,
    /// A rest threshold.
    Threshold,
    /// A batch index that names no live value.
    Index,
    /// A particle id that names no live particle.
    Particle,
    /// A spring id that names no live spring.
    Spring,
    /// A spring's rest length.
    RestLength,
    /// An external acceleration (gravity).
    Acceleration,
    /// An impulse.
    Impulse,
    /// A knob's rotor moment of inertia.
    Inertia,
    /// A knob's motor torque limit.
    TorqueLimit,
    /// A knob's stiffness (of detents, endstops, magnets, the return spring).
    KnobStiffness,
    /// A knob's damping.
    KnobDamping,
    /// A knob's strength (detents, endstops, magnets, return spring), or the sum of the
    /// strengths that act at once.
    Strength,
    /// A knob's detent width or detent count.
    DetentWidth,
    /// A knob's snap point (a fraction of the detent width).
    SnapPoint,
    /// A knob's hysteresis (an angle).
    Hysteresis,
    /// A knob's magnetic detent capture radius, or the spacing of its magnetic detents.
    CaptureRadius,
    /// A knob's encoder counts per turn (`KnobConfig::new`'s `counts_per_turn`).
    CountsPerTurn,
    /// A control loop rate, in hertz.
    LoopRate,
    /// A knob's detent stiffness, N·m/rad (`KnobConfig::detent_stiffness`).
    DetentStiffness,
    /// A knob's detent peak torque, N·m (`KnobConfig::detent_torque`).
    DetentTorque,
    /// A knob's number of detents between its endstops (`KnobConfig::detent_count`).
    DetentCount,
    /// A knob's detent origin, rad (`KnobConfig::detent_origin`).
    DetentOrigin,
    /// A knob's endstop angles, rad (`KnobConfig::endstops`).
    Endstops,
    /// A knob's endstop stiffness, N·m/rad (`KnobConfig::endstop_stiffness`).
    EndstopStiffness,
    /// A knob's return-to-centre stiffness, N·m/rad (`KnobConfig::return_to_centre`).
    ReturnStiffness,
    /// A knob's return-to-centre angle, rad (`KnobConfig::return_to_centre`).
    ReturnCentre,
    /// A knob's magnetic detent angles, rad (`KnobConfig::magnets`).
    Magnets,
    /// A knob's magnetic detent stiffness, N·m/rad (`KnobConfig::magnet_stiffness`).
    MagnetStiffness,
    /// A knob's maximum speed, rad/s.
    MaxSpeed,
    /// A friction: its rate (per second), a deceleration rate per millisecond (iOS) or a
    /// friction scalar (Android).
    Friction,
    /// A range's bounds (a scroll's minimum and maximum offset).
    Bounds,
    /// The spacing of snap points (items, pages).
    SnapSpacing,
    /// A rubber band's dimension (the viewport it stretches over).
    RubberBand,
    /// Snap points given as a slice (they must be finite and in ascending order).
    SnapPoints,
    /// A scene's linear damping rate `c` (per second: a free particle's velocity decays
    /// as `e^{−c·t}`).
    LinearDamping,
    /// An angular scene's angular damping rate `c` (per second: a free body's angular
    /// velocity decays as `e^{−c·t}`).
    AngularDamping,
    /// A rope's stretch under its own weight, as a fraction of its rest length
    /// ([`Tuning::from_rope_stretch`](crate::Tuning::from_rope_stretch)).
    Stretch,
    /// A number of particles (a rope's, for
    /// [`Tuning::from_rope_stretch`](crate::Tuning::from_rope_stretch)).
    ParticleCount,
}

/// The range a rejected number had to lie in.
///
/// ```
/// use stiffspring::Bound;
///
/// assert!(Bound::Within { min: 0.0, max: 1.0 }.contains(1.0));
/// assert!(!Bound::Positive.contains(0.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Bound {
    /// Strictly greater than zero.
    Positive,
    /// Zero or more.
    NonNegative,
    /// In the closed interval `[min, max]`.
    Within {
        /// The smallest value accepted.
        min: f64,
        /// The largest value accepted.
        max: f64,
    },
    /// Strictly below `max`.
    Below {
        /// The first value rejected.
        max: f64,
    },
    /// At most `max` in magnitude.
    MagnitudeAtMost {
        /// The largest magnitude accepted.
        max: f64,
    },
    /// At least `min`.
    AtLeast {
        /// The smallest value accepted.
        min: f64,
    },
    /// At most `max`.
    AtMost {
        /// The largest value accepted.
        max: f64,
    },
}

impl Bound {
    /// True when `value` satisfies the bound (NaN never does).
    ///
    /// ```
    /// assert!(stiffspring::Bound::MagnitudeAtMost { max: 2.0 }.contains(-2.0));
    /// ```
    pub const fn contains(&self, value: f64) -> bool {
        match *self {
            Bound::Positive => value > 0.0,
            Bound::NonNegative => value >= 0.0,
            Bound::Within { min, max } => value >= min && value <= max,
            Bound::Below { max } => value < max,
            Bound::MagnitudeAtMost { max } => value >= -max && value <= max,
            Bound::AtLeast { min } => value >= min,
            Bound::AtMost { max } => value <= max,
        }
    }
}

/// What would make an unrepresentable set-up representable (see
/// [`Error::Unrepresentable`]).
///
/// ```
/// use stiffspring::Remedy;
/// assert_ne!(Remedy::WiderBackend, Remedy::LowerRate);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Remedy {
    /// Step less often (a larger `dt`): the coefficients grow as `dt²`.
    LowerRate,
    /// Step more often (a smaller `dt`): a heavily overdamped spring extrapolated one
    /// step back needs a step velocity that grows as `e^{2ζω·dt}`.
    HigherRate,
    /// Measure positions in a larger unit, so that the same motion takes fewer units.
    LargerUnit,
    /// A backend with more range or precision (`I32F32`, `f32`, `f64`).
    WiderBackend,
}

/// Everything that can go wrong at set-up.
///
/// ```
/// use stiffspring::{Bound, Error, Parameter, Tuning};
///
/// assert_eq!(
///     Tuning::from_frequency(f64::NAN, 0.5, 1.0 / 60.0),
///     Err(Error::NotFinite { parameter: Parameter::Frequency })
/// );
/// let err = Tuning::from_coefficients(0.5, -0.1, 0.01).unwrap_err();
/// assert_eq!(
///     err,
///     Error::OutOfRange {
///         parameter: Parameter::Damping,
///         value: -0.1,
///         bound: Bound::Within { min: 0.0, max: 1.0 },
///     }
/// );
/// assert_eq!(err.to_string(), "Damping = -0.1 is outside [0, 1]");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// The argument was NaN or infinite.
    NotFinite {
        /// Which argument.
        parameter: Parameter,
    },
    /// The argument lies outside the range the call accepts.
    OutOfRange {
        /// Which argument.
        parameter: Parameter,
        /// The value it had.
        value: f64,
        /// The range it must lie in.
        bound: Bound,
    },
    /// The backend cannot hold the value at its resolution or in its range: a
    /// coefficient below its resolution, or a start velocity beyond its range. Nothing
    /// was changed; `remedy` says what would work.
    Unrepresentable {
        /// Which quantity.
        parameter: Parameter,
        /// The backend's name (`"I16F16"`, ...).
        backend: &'static str,
        /// The value that was needed.
        value: f64,
        /// The smallest (for a resolution) or largest (for a range) value the backend
        /// holds.
        limit: f64,
        /// What would make it representable.
        remedy: Remedy,
    },
    /// A fixed-capacity container is full; nothing was added.
    CapacityFull {
        /// The container's capacity.
        capacity: usize,
    },
    /// An id or index that names nothing live: removed, or naming a slot the container
    /// does not hold. (Ids carry a slot and its generation, not their container: an id of
    /// another container whose slot and generation are live here is not detected.)
    Stale {
        /// [`Parameter::Particle`], [`Parameter::Spring`] or [`Parameter::Index`].
        parameter: Parameter,
    },
    /// A spring from a particle to itself.
    SameParticle,
    /// A knob given a number of detents and no endstops to spread them over: give
    /// endstops, or a detent width instead of a count.
    NeedsEndstops,
    /// The operation needs a free particle and the particle is pinned (giving a pinned
    /// particle a velocity or an impulse).
    Pinned,
    /// A spring's coefficient exceeds the network's safe limit for the number of springs
    /// its particles share (see [`network_limit`](crate::scene::network_limit)), and the
    /// scene's policy is to reject; nothing was changed.
    ExceedsNetworkLimit {
        /// The largest coefficient of the spring (`C_k` or `C_d`).
        coefficient: f64,
        /// The limit for its particles.
        limit: f64,
    },
    /// An undamped oscillator whose frequency is a multiple of half the sample rate
    /// (`f·dt = k/2`): its sampled map has a double pole at `z = ±1`, which grows without
    /// bound from a general start, so no valid tuning reproduces it.
    Aliased {
        /// `f·dt` of the oscillator.
        frequency_times_dt: f64,
    },
    /// The tuning has no continuous damped oscillator behind it: its map has a pole on
    /// the negative real axis or at zero (for example [`Tuning::rigid`], or any
    /// `C_d ≥ 1`), or `C_k = 0`.
    ///
    /// [`Tuning::rigid`]: crate::Tuning::rigid
    NoContinuousEquivalent,
    /// A spring tuned for one time step was added to a scene stepped at another.
    TimeStepMismatch {
        /// The scene's `dt`.
        expected: f64,
        /// The tuning's `dt`.
        found: f64,
    },
}

impl Error {
    /// The argument the error is about, where there is one.
    ///
    /// ```
    /// use stiffspring::{Error, Parameter};
    /// assert_eq!(Error::SameParticle.parameter(), None);
    /// assert_eq!(
    ///     Error::NotFinite { parameter: Parameter::Mass }.parameter(),
    ///     Some(Parameter::Mass)
    /// );
    /// ```
    pub const fn parameter(&self) -> Option<Parameter> {
        match *self {
            Error::NotFinite { parameter }
            | Error::OutOfRange { parameter, .. }
            | Error::Unrepresentable { parameter, .. }
            | Error::Stale { parameter } => Some(parameter),
            Error::Aliased { .. } => Some(Parameter::Frequency),
            Error::TimeStepMismatch { .. } => Some(Parameter::TimeStep),
            Error::NeedsEndstops => Some(Parameter::DetentCount),
            _ => None,
        }
    }
}

impl fmt::Display for Bound {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Bound::Positive => f.write_str("(0, ∞)"),
            Bound::NonNegative => f.write_str("[0, ∞)"),
            Bound::Within { min, max } => write!(f, "[{min}, {max}]"),
            Bound::Below { max } => write!(f, "(−∞, {max})"),
            Bound::MagnitudeAtMost { max } => write!(f, "[−{max}, {max}]"),
            Bound::AtLeast { min } => write!(f, "[{min}, ∞)"),
            Bound::AtMost { max } => write!(f, "(−∞, {max}]"),
        }
    }
}

impl fmt::Display for Remedy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Remedy::LowerRate => "step at a lower rate",
            Remedy::HigherRate => "step at a higher rate",
            Remedy::LargerUnit => "measure positions in a larger unit",
            Remedy::WiderBackend => "use a wider backend (I32F32, f32 or f64)",
        })
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NotFinite { parameter } => write!(f, "{parameter:?} is NaN or infinite"),
            Error::OutOfRange {
                parameter,
                value,
                bound,
            } => write!(f, "{parameter:?} = {value} is outside {bound}"),
            Error::Unrepresentable {
                parameter,
                backend,
                value,
                limit,
                remedy,
            } => write!(
                f,
                "{parameter:?} = {value} is beyond what {backend} holds ({limit}): {remedy}"
            ),
            Error::CapacityFull { capacity } => write!(f, "capacity {capacity} is full"),
            Error::Stale { parameter } => write!(f, "the {parameter:?} id names nothing live"),
            Error::SameParticle => f.write_str("a spring needs two different particles"),
            Error::NeedsEndstops => f.write_str(
                "a count of detents needs endstops to spread over: give endstops, or a detent width",
            ),
            Error::Pinned => f.write_str("the particle is pinned"),
            Error::ExceedsNetworkLimit { coefficient, limit } => write!(
                f,
                "coefficient {coefficient} is above the network's safe limit {limit}"
            ),
            Error::Aliased { frequency_times_dt } => write!(
                f,
                "an undamped oscillator at f·dt = {frequency_times_dt} aliases onto z = ±1"
            ),
            Error::NoContinuousEquivalent => {
                f.write_str("the tuning has no continuous oscillator equivalent")
            }
            Error::TimeStepMismatch { expected, found } => write!(
                f,
                "the tuning is sampled at dt = {found}, the scene steps at dt = {expected}"
            ),
        }
    }
}

impl core::error::Error for Error {}

/// `value`, if it is finite and satisfies `bound`.
pub(crate) const fn check(value: f64, parameter: Parameter, bound: Bound) -> Result<f64, Error> {
    if !value.is_finite() {
        Err(Error::NotFinite { parameter })
    } else if !bound.contains(value) {
        Err(Error::OutOfRange {
            parameter,
            value,
            bound,
        })
    } else {
        Ok(value)
    }
}

/// `value`, if it is finite and strictly positive.
pub(crate) const fn positive(value: f64, parameter: Parameter) -> Result<f64, Error> {
    check(value, parameter, Bound::Positive)
}

/// `value`, if it is finite and not negative.
pub(crate) const fn non_negative(value: f64, parameter: Parameter) -> Result<f64, Error> {
    check(value, parameter, Bound::NonNegative)
}

/// `?` for `const fn`, where the `Try` trait is not available.
macro_rules! tri {
    ($e:expr) => {
        match $e {
            Ok(v) => v,
            Err(e) => return Err(e),
        }
    };
}
pub(crate) use tri;
