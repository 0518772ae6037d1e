//! The one error type of the crate.
//!
//! Every check happens at set-up (constructors, setters): the stepping functions never
//! fail, so they return nothing. Each variant names the argument that was wrong, so a
//! firmware log (or `defmt`) says exactly what to fix.

use core::fmt;

/// Which argument of a set-up call was rejected.
///
/// ```
/// use stiffspring::{Error, Parameter, Tuning};
///
/// let err = Tuning::from_coefficients(1.5, 0.2).unwrap_err();
/// assert_eq!(err, Error::OutOfRange(Parameter::Stiffness));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
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
    /// A duration, in seconds (SwiftUI's `duration`).
    Duration,
    /// SwiftUI's `bounce`.
    Bounce,
    /// A position, offset or target.
    Position,
    /// A velocity.
    Velocity,
    /// A rest threshold.
    Threshold,
    /// An index (or id) that names no live element.
    Index,
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
    /// A knob's encoder resolution (an angle per count).
    EncoderResolution,
}

/// Everything that can go wrong at set-up.
///
/// ```
/// use stiffspring::{Error, Parameter, Tuning};
///
/// assert_eq!(
///     Tuning::from_frequency(f64::NAN, 0.5, 1.0 / 60.0),
///     Err(Error::NotFinite(Parameter::Frequency))
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Error {
    /// The argument was NaN or infinite.
    NotFinite(Parameter),
    /// The argument must be strictly positive and was zero or negative.
    NotPositive(Parameter),
    /// The argument must not be negative.
    Negative(Parameter),
    /// The argument lies outside its documented range (for coefficients: outside
    /// `[0, 1]²`, or outside the exact stability region for the extended constructor; for
    /// positions: beyond the backend's safe magnitude, see [`Scalar::SAFE_MAGNITUDE`]).
    ///
    /// [`Scalar::SAFE_MAGNITUDE`]: crate::Scalar::SAFE_MAGNITUDE
    OutOfRange(Parameter),
    /// A fixed-capacity container is full; nothing was added.
    CapacityFull,
    /// A spring from a particle to itself.
    SameParticle,
    /// The operation needs a free particle and the particle is pinned (for example,
    /// giving a pinned particle a velocity or an impulse).
    Pinned,
    /// A spring's coefficient exceeds the network's safe limit for the number of springs
    /// its particles share (see [`network_limit`](crate::scene::network_limit)), and the
    /// scene's policy is to reject; nothing was changed.
    ExceedsNetworkLimit,
    /// An undamped oscillator whose frequency is a multiple of half the sample rate
    /// (`f·dt = k/2`): its sampled map has a double pole at `z = ±1`, which grows without
    /// bound from a general start, so no valid tuning reproduces it.
    Aliased,
    /// The tuning has no continuous damped oscillator behind it at this `dt`: its map has
    /// a pole on the negative real axis or at zero (for example [`Tuning::rigid`], or any
    /// `C_d ≥ 1`), or `C_k = 0`.
    ///
    /// [`Tuning::rigid`]: crate::Tuning::rigid
    NoContinuousEquivalent,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NotFinite(p) => write!(f, "{p:?} is NaN or infinite"),
            Error::NotPositive(p) => write!(f, "{p:?} must be greater than zero"),
            Error::Negative(p) => write!(f, "{p:?} must not be negative"),
            Error::OutOfRange(p) => write!(f, "{p:?} is outside its documented range"),
            Error::CapacityFull => f.write_str("capacity is full"),
            Error::SameParticle => f.write_str("a spring needs two different particles"),
            Error::Pinned => f.write_str("the particle is pinned"),
            Error::ExceedsNetworkLimit => f.write_str("coefficient above the network's safe limit"),
            Error::Aliased => f.write_str("undamped oscillator aliases onto z = ±1 at this dt"),
            Error::NoContinuousEquivalent => {
                f.write_str("tuning has no continuous oscillator equivalent")
            }
        }
    }
}

impl core::error::Error for Error {}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(value: f64, what: Parameter) -> Result<f64, Error> {
    if !value.is_finite() {
        Err(Error::NotFinite(what))
    } else if value <= 0.0 {
        Err(Error::NotPositive(what))
    } else {
        Ok(value)
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(value: f64, what: Parameter) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NotFinite(what))
    }
}

/// Checks that `value` is finite and not negative.
pub(crate) fn non_negative(value: f64, what: Parameter) -> Result<f64, Error> {
    if !value.is_finite() {
        Err(Error::NotFinite(what))
    } else if value < 0.0 {
        Err(Error::Negative(what))
    } else {
        Ok(value)
    }
}
