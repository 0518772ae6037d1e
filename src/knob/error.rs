//! The knob's set-up errors: which parameter, what value, and which bound it broke.

use crate::error::{Bound, Error, Parameter};
use core::fmt;

/// Where a knob is, for its loop: inside the range and free of magnets, held by a magnetic
/// detent, or beyond an endstop. Each zone is one spring-damper loop with its own
/// stiffness (the sum of the layers acting there) and the knob's one damping.
///
/// ```
/// use stiffspring::knob::Zone;
/// assert_ne!(Zone::Free, Zone::Beyond);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Zone {
    /// Inside the range, not held by a magnet: detents and the return spring.
    Free,
    /// Held by a magnetic detent: detents, the magnet and the return spring.
    Magnet,
    /// Beyond an endstop: detents, the endstop and the return spring.
    Beyond,
}

/// The bound a rejected knob parameter broke. The offending value and the bound's limit
/// are in [`KnobError::value`] and [`KnobError::limit`].
///
/// ```
/// use stiffspring::knob::{Limit, Zone};
/// assert_ne!(Limit::LoopStiffness(Zone::Free), Limit::LoopStiffness(Zone::Beyond));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Limit {
    /// The value must be finite (`limit` is NaN).
    Finite,
    /// The value must be greater than zero (`limit` is 0).
    Positive,
    /// The value must not be negative (`limit` is 0).
    NotNegative,
    /// The value must be at least `limit`.
    AtLeast,
    /// The value must be at most `limit`.
    AtMost,
    /// The value must be below `limit`.
    Below,
    /// The zone fails the loop guarantee ([`knob::stability`](crate::knob::stability)):
    /// `value` is what the user set that makes it that stiff (a detent's stiffness or peak
    /// torque, an endstop's, a magnet's or the return spring's stiffness, named by the
    /// crate-wide error), `limit` the most of it with which the knob passes, everything
    /// else as configured (for a detent stiffness,
    /// [`KnobConfig::detent_stiffness_limit`](crate::KnobConfig::detent_stiffness_limit)).
    LoopStiffness(Zone),
    /// The damping (N·m·s/rad) is above `limit`, the most the loop takes at this rate and
    /// inertia (the damper on its own rings at twice the gain).
    LoopDamping,
    /// The peak torque of a detent (at its switching point) or a magnet (at its release
    /// radius) is above the torque limit: the clamp would make it a relay, which can
    /// limit-cycle. `value` is the stiffness the user set (or the detent's peak torque),
    /// `limit` the most of it whose peak the motor gives.
    PeakTorque,
    /// The number of magnets is above `limit` ([`MAX_MAGNETS`](crate::knob::MAX_MAGNETS)).
    Capacity,
    /// The value (an angle, a stiffness or a damping) exceeds what the backend holds,
    /// `limit`.
    BackendRange,
    /// A detent count needs endstops to spread over (`value` is the count, `limit` NaN;
    /// the crate-wide error is [`Error::NeedsEndstops`]).
    NeedsEndstops,
    /// One encoder count commands more torque through the zone's spring and filtered
    /// damper, `(K + B·α/dt)·count`, than [`COUNT_TORQUE_FRACTION`] of the torque limit: the
    /// knob would buzz at rest, toggling a count. `value` is the counts per turn, `limit`
    /// the counts per turn that would pass (a count's torque scales with the count); the
    /// crate-wide error names [`Parameter::CountsPerTurn`](crate::Parameter::CountsPerTurn).
    ///
    /// [`COUNT_TORQUE_FRACTION`]: crate::knob::stability::COUNT_TORQUE_FRACTION
    CountTorque(Zone),
}

/// Why [`Knob::new`](crate::Knob::new) refused a configuration: the crate-wide [`Error`]
/// (which parameter, what kind of problem; `?` into [`Error`] keeps it), the bound, the
/// offending value and the bound's limit, in the units of the argument the user set
/// (radians, N·m, N·m/rad, N·m·s/rad, kg·m², Hz, counts per turn).
///
/// ```
/// use stiffspring::knob::{KnobError, Limit, Zone};
/// use stiffspring::{Error, Knob, KnobConfig, Parameter};
///
/// // 1 kHz, 1e−5 kg·m², a 2 N·m motor, a 14-bit encoder; detents far too stiff for 1 kHz.
/// let config = KnobConfig::new(1_000.0, 1e-5, 2.0, 16384)
///     .detent_width(0.1)
///     .detent_stiffness(5.0);
/// let err: KnobError = Knob::<f32>::new(&config, 0.0).unwrap_err();
/// assert_eq!(err.error.parameter(), Some(Parameter::DetentStiffness));
/// assert_eq!(err.bound, Limit::LoopStiffness(Zone::Free));
/// assert_eq!(err.value, 5.0);
/// // The stiffest detent that passes.
/// assert_eq!(err.limit, config.detent_stiffness_limit::<f32>()?);
/// assert!(err.limit > 0.1 && err.limit < 1.0);
/// # Ok::<(), KnobError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct KnobError {
    /// The crate-wide error: the parameter and the kind of problem.
    pub error: Error,
    /// The bound that was broken.
    pub bound: Limit,
    /// The offending value.
    pub value: f64,
    /// The bound's limit (NaN for [`Limit::Finite`]).
    pub limit: f64,
}

impl KnobError {
    pub(crate) const fn new(error: Error, bound: Limit, value: f64, limit: f64) -> Self {
        KnobError {
            error,
            bound,
            value,
            limit,
        }
    }

    /// A finite, strictly positive value, or the error for `parameter`.
    pub(crate) const fn positive(value: f64, parameter: Parameter) -> Result<f64, Self> {
        Self::checked(value, parameter, Bound::Positive, Limit::Positive)
    }

    /// A finite, non-negative value, or the error for `parameter`.
    pub(crate) const fn non_negative(value: f64, parameter: Parameter) -> Result<f64, Self> {
        Self::checked(value, parameter, Bound::NonNegative, Limit::NotNegative)
    }

    /// A finite value, or the error for `parameter`.
    pub(crate) const fn finite(value: f64, parameter: Parameter) -> Result<f64, Self> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(Self::new(
                Error::NotFinite { parameter },
                Limit::Finite,
                value,
                f64::NAN,
            ))
        }
    }

    /// The crate's [`check`](crate::error::check) of `value` against a bound whose limit is
    /// 0, with the knob's name for that bound.
    const fn checked(
        value: f64,
        parameter: Parameter,
        bound: Bound,
        limit: Limit,
    ) -> Result<f64, Self> {
        match crate::error::check(value, parameter, bound) {
            Ok(v) => Ok(v),
            Err(error @ Error::NotFinite { .. }) => {
                Err(Self::new(error, Limit::Finite, value, f64::NAN))
            }
            Err(error) => Err(Self::new(error, limit, value, 0.0)),
        }
    }

    /// `value` of `parameter` against `limit` under `bound`, with the crate-wide error that
    /// says the same in its terms.
    pub(crate) const fn range(parameter: Parameter, bound: Limit, value: f64, limit: f64) -> Self {
        let range = match bound {
            Limit::Finite => return Self::new(Error::NotFinite { parameter }, bound, value, limit),
            Limit::Positive => Bound::Positive,
            Limit::NotNegative => Bound::NonNegative,
            Limit::AtLeast => Bound::AtLeast { min: limit },
            Limit::Below => Bound::Below { max: limit },
            Limit::NeedsEndstops => {
                return Self::new(Error::NeedsEndstops, bound, value, limit);
            }
            Limit::Capacity => {
                return Self::new(
                    Error::CapacityFull {
                        capacity: limit as usize,
                    },
                    bound,
                    value,
                    limit,
                );
            }
            Limit::AtMost
            | Limit::LoopStiffness(_)
            | Limit::LoopDamping
            | Limit::PeakTorque
            | Limit::BackendRange
            | Limit::CountTorque(_) => Bound::AtMost { max: limit },
        };
        Self::new(
            Error::OutOfRange {
                parameter,
                value,
                bound: range,
            },
            bound,
            value,
            limit,
        )
    }
}

/// `limit`, or the largest number below `value` where rounding made them meet: an error
/// never gives a limit equal to the value it refuses.
pub(crate) const fn below(value: f64, limit: f64) -> f64 {
    if limit < value || !value.is_finite() || value <= 0.0 {
        limit
    } else {
        value * (1.0 - f64::EPSILON)
    }
}

impl From<KnobError> for Error {
    fn from(e: KnobError) -> Error {
        e.error
    }
}

impl fmt::Display for KnobError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (v, l) = (self.value, self.limit);
        write!(f, "{}: ", self.error)?;
        match self.bound {
            Limit::Finite => write!(f, "{v} is not finite"),
            Limit::Positive => write!(f, "{v} must be greater than 0"),
            Limit::NotNegative => write!(f, "{v} must not be negative"),
            Limit::AtLeast => write!(f, "{v} is below the least allowed, {l}"),
            Limit::AtMost => write!(f, "{v} is above the most allowed, {l}"),
            Limit::Below => write!(f, "{v} must be below {l}"),
            Limit::LoopStiffness(zone) => write!(
                f,
                "{v} is above {l}, the most with which the {zone:?} zone meets the loop \
                 guarantee with everything else as configured (by {:.3}×)",
                v / l
            ),
            Limit::LoopDamping => write!(
                f,
                "the damping {v} N·m·s/rad is above {l} N·m·s/rad, the most the loop takes at \
                 this rate and inertia"
            ),
            Limit::PeakTorque => write!(
                f,
                "{v} is above {l}, the stiffest whose peak torque the motor gives (at the \
                 detent's switching point or the magnet's release radius; by {:.3}×)",
                v / l
            ),
            Limit::Capacity => write!(f, "{v} magnets, above the capacity {l}"),
            Limit::BackendRange => write!(f, "{v} is beyond what the backend holds, {l}"),
            Limit::NeedsEndstops => write!(f, "a count of {v} detents needs endstops"),
            Limit::CountTorque(zone) => write!(
                f,
                "with {v} counts per turn one count commands more than 1/8 of the torque \
                 limit in the {zone:?} zone (the knob would buzz at rest): at least {l} counts \
                 per turn, a softer spring or less damping"
            ),
        }
    }
}

impl core::error::Error for KnobError {}
