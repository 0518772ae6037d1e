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
    /// The zone's stiffness (N·m/rad) is above `limit`, the stiffest that meets the loop
    /// guarantee with the knob's damping, inertia, rate and latency
    /// ([`knob::stability`](crate::knob::stability)).
    LoopStiffness(Zone),
    /// The damping (N·m·s/rad) is above `limit`, the most the loop takes at this rate and
    /// inertia (the damper on its own rings at twice the gain).
    LoopDamping,
    /// The peak torque of a detent (at its switching point) or a magnet (at its release
    /// radius), in N·m, is above the torque limit: the clamp would make it a relay, which
    /// can limit-cycle.
    PeakTorque,
    /// The number of magnets is above `limit` ([`MAX_MAGNETS`](crate::knob::MAX_MAGNETS)).
    Capacity,
    /// The value (an angle, or a gain in angle⁻¹) exceeds what the backend holds, `limit`.
    BackendRange,
    /// A detent count needs endstops to spread over (`value` is the count, `limit` NaN;
    /// the crate-wide error is [`Error::NeedsEndstops`]).
    NeedsEndstops,
    /// One encoder count commands more torque (N·m, `value`) through the zone's spring and
    /// filtered damper, `(K + B·α/dt)·count`, than `limit` ([`COUNT_TORQUE_FRACTION`] of the
    /// torque limit): the knob would buzz at rest, toggling a count. The crate-wide error
    /// names the encoder resolution, with the counts per turn that would pass.
    ///
    /// [`COUNT_TORQUE_FRACTION`]: crate::knob::stability::COUNT_TORQUE_FRACTION
    CountTorque(Zone),
}

/// Why [`Knob::new`](crate::Knob::new) refused a configuration: the crate-wide [`Error`]
/// (which parameter, what kind of problem; `?` into [`Error`] keeps it), the bound, the
/// offending value and the bound's limit, in SI units (radians, N·m, N·m/rad, N·m·s/rad,
/// kg·m², Hz).
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
/// assert_eq!(err.error.parameter(), Some(Parameter::SpringConstant));
/// assert_eq!(err.bound, Limit::LoopStiffness(Zone::Free));
/// assert_eq!(err.value, 5.0);
/// assert!(err.limit > 0.1 && err.limit < 1.0);
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
    pub(crate) fn new(error: Error, bound: Limit, value: f64, limit: f64) -> Self {
        KnobError {
            error,
            bound,
            value,
            limit,
        }
    }

    /// A finite, strictly positive value, or the error for `parameter`.
    pub(crate) fn positive(value: f64, parameter: Parameter) -> Result<f64, Self> {
        Self::checked(value, parameter, Bound::Positive, Limit::Positive)
    }

    /// A finite, non-negative value, or the error for `parameter`.
    pub(crate) fn non_negative(value: f64, parameter: Parameter) -> Result<f64, Self> {
        Self::checked(value, parameter, Bound::NonNegative, Limit::NotNegative)
    }

    /// A finite value, or the error for `parameter`.
    pub(crate) fn finite(value: f64, parameter: Parameter) -> Result<f64, Self> {
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
    fn checked(value: f64, parameter: Parameter, bound: Bound, limit: Limit) -> Result<f64, Self> {
        crate::error::check(value, parameter, bound).map_err(|error| match error {
            Error::NotFinite { .. } => Self::new(error, Limit::Finite, value, f64::NAN),
            _ => Self::new(error, limit, value, 0.0),
        })
    }

    /// `value` of `parameter` against `limit` under `bound`, with the crate-wide error that
    /// says the same in its terms.
    pub(crate) fn range(parameter: Parameter, bound: Limit, value: f64, limit: f64) -> Self {
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
                "the {zone:?} zone's stiffness {v} N·m/rad is above {l} N·m/rad, the stiffest \
                 the loop guarantees with this damping, inertia, rate and latency (by {:.3}×)",
                v / l
            ),
            Limit::LoopDamping => write!(
                f,
                "the damping {v} N·m·s/rad is above {l} N·m·s/rad, the most the loop takes at \
                 this rate and inertia"
            ),
            Limit::PeakTorque => write!(
                f,
                "the peak torque {v} N·m is above the torque limit {l} N·m (by {:.3}×)",
                v / l
            ),
            Limit::Capacity => write!(f, "{v} magnets, above the capacity {l}"),
            Limit::BackendRange => write!(f, "{v} is beyond what the backend holds, {l}"),
            Limit::NeedsEndstops => write!(f, "a count of {v} detents needs endstops"),
            Limit::CountTorque(zone) => write!(
                f,
                "in the {zone:?} zone one encoder count commands {v} N·m, above {l} N·m (by \
                 {:.3}×): a finer encoder, a softer spring or less damping",
                v / l
            ),
        }
    }
}

impl core::error::Error for KnobError {}
