//! The last step of the set-up: a designed knob, for one backend, ready to run.
//!
//! [`KnobDesign::new`] runs the validation and the loop design as a `const fn`, so that a
//! configuration known when the firmware is built is designed by the compiler
//! ([`knob!`](crate::knob!)), and the firmware carries neither the stability analysis nor
//! the `f64` arithmetic of the design; [`Knob::from_design`](crate::Knob::from_design)
//! starts a knob from it.

use super::config::KnobConfig;
use super::design::{Design, design, design_or_reason};
use super::error::{KnobError, Limit};
use super::parts::KnobParts;
use crate::error::Parameter;
use crate::scalar::Scalar;

/// A knob designed for backend `S`: a [`KnobConfig`] validated, its loop designed and
/// checked against the guarantee of [`stability`](super::stability). Build it in a `const`
/// ([`knob!`](crate::knob!)) to do all of that when the firmware is built, then start
/// knobs from it with [`Knob::from_design`](crate::Knob::from_design).
///
/// ```
/// use stiffspring::knob::KnobDesign;
/// use stiffspring::{Knob, KnobConfig};
///
/// const CONFIG: KnobConfig = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
///     .endstops(0.0, 3.0)
///     .detent_count(16)
///     .detent_stiffness(0.05);
/// const DESIGN: KnobDesign<f32> = match KnobDesign::new(&CONFIG) {
///     Ok(d) => d,
///     Err(_) => panic!("the knob's configuration is refused"),
/// };
/// let mut knob = Knob::from_design(&DESIGN, 0.0)?;
/// assert_eq!(knob.update(0.0).torque, 0.0);
/// # Ok::<(), stiffspring::knob::KnobError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct KnobDesign<S: Scalar> {
    pub(crate) design: Design,
    /// The backend's numbers, computed with the design.
    pub(crate) parts: KnobParts<S>,
}

impl<S: Scalar> KnobDesign<S> {
    /// Validates `config` and designs its loop for backend `S`: everything
    /// [`Knob::new`](crate::Knob::new) checks except the initial angle.
    ///
    /// # Errors
    ///
    /// The [`KnobError`] of [`Knob::new`](crate::Knob::new), naming the argument the user
    /// set, its value and the value that would pass.
    ///
    /// ```
    /// use stiffspring::knob::KnobDesign;
    /// use stiffspring::{KnobConfig, Parameter};
    ///
    /// let too_stiff = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1).detent_stiffness(0.45);
    /// let e = KnobDesign::<f32>::new(&too_stiff).unwrap_err();
    /// assert_eq!(e.error.parameter(), Some(Parameter::DetentStiffness));
    /// assert_eq!(e.limit, too_stiff.detent_stiffness_limit::<f32>()?);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub const fn new(config: &KnobConfig) -> Result<Self, KnobError> {
        match design::<S>(config) {
            Ok(design) => Ok(KnobDesign {
                parts: KnobParts::new(&design),
                design,
            }),
            Err(e) => Err(e),
        }
    }

    /// [`Self::new`] without the search for the values that would pass: on a refusal, the
    /// parameter and the bound only. What [`knob!`](crate::knob!) calls, so that a refused
    /// configuration fails to compile quickly.
    ///
    /// ```
    /// use stiffspring::knob::{KnobDesign, Limit, Zone};
    /// use stiffspring::{KnobConfig, Parameter};
    ///
    /// let too_stiff = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1).detent_stiffness(0.45);
    /// let (p, l) = KnobDesign::<f32>::new_or_reason(&too_stiff).unwrap_err();
    /// assert_eq!((p, l), (Some(Parameter::DetentStiffness), Limit::LoopStiffness(Zone::Free)));
    /// ```
    pub const fn new_or_reason(config: &KnobConfig) -> Result<Self, (Option<Parameter>, Limit)> {
        match design_or_reason::<S>(config) {
            Ok(design) => Ok(KnobDesign {
                parts: KnobParts::new(&design),
                design,
            }),
            Err(e) => Err(e),
        }
    }
}

/// A message naming `parameter`, for a compile-time refusal (a `const` panic prints a
/// string, not a number).
#[doc(hidden)]
pub const fn refusal(parameter: Option<Parameter>, limit: Limit) -> &'static str {
    use Parameter as P;
    match (parameter, limit) {
        (Some(P::CountsPerTurn), Limit::CountTorque(_)) => {
            "knob!: one encoder count commands more than 1/8 of the torque limit: more counts_per_turn (Knob::new at run time says how many), a softer spring or less damping"
        }
        (Some(P::DetentStiffness), Limit::PeakTorque) => {
            "knob!: the detent_stiffness gives a peak torque above the torque limit"
        }
        (Some(P::DetentStiffness), _) => {
            "knob!: detent_stiffness is beyond the loop guarantee: at most KnobConfig::detent_stiffness_limit"
        }
        (Some(P::DetentTorque), _) => {
            "knob!: detent_torque is refused (peak torque or loop guarantee)"
        }
        (Some(P::EndstopStiffness), _) => "knob!: endstop_stiffness is beyond the loop guarantee",
        (Some(P::MagnetStiffness), _) => {
            "knob!: magnet_stiffness is refused (peak torque or loop guarantee)"
        }
        (Some(P::ReturnStiffness), _) => "knob!: the return_to_centre stiffness is refused",
        (Some(P::ReturnCentre), _) => "knob!: the return_to_centre centre is refused",
        (Some(P::DampingConstant), _) => "knob!: damping is refused",
        (Some(P::DampingRatio), _) => "knob!: damping_ratio is outside [0.2, 2]",
        (Some(P::LoopRate), _) => {
            "knob!: the loop rate is refused (at least 100 Hz, and high enough for the springs)"
        }
        (Some(P::Inertia), _) => "knob!: the inertia must be finite and positive",
        (Some(P::TorqueLimit), _) => "knob!: the torque limit must be finite and positive",
        (Some(P::CountsPerTurn), _) => {
            "knob!: counts_per_turn is refused (zero, or finer than the backend resolves)"
        }
        (Some(P::Endstops), _) => {
            "knob!: the endstops are refused (not finite, min >= max, or beyond the backend's range)"
        }
        (Some(P::DetentCount), _) => {
            "knob!: detent_count is refused (below 2, without endstops, or detents narrower than four counts)"
        }
        (Some(P::DetentWidth), _) => {
            "knob!: detent_width is refused (not positive, or under four counts)"
        }
        (Some(P::DetentOrigin), _) => "knob!: detent_origin is refused",
        (Some(P::SnapPoint), _) => "knob!: snap_point is outside [0.5, 1)",
        (Some(P::Hysteresis), _) => {
            "knob!: hysteresis is refused (negative, or the detent cannot switch)"
        }
        (Some(P::Magnets), _) => {
            "knob!: the magnets are refused (more than MAX_MAGNETS, not finite, or outside the endstops)"
        }
        (Some(P::CaptureRadius), _) => "knob!: magnet_radius is refused",
        _ => "knob!: the knob's configuration is refused",
    }
}

/// A [`KnobDesign`] made when the firmware is built: `knob!(CONFIG)` for `f32`, or
/// `knob!(CONFIG, I16F16)` for another backend, with `CONFIG` a `const`
/// [`KnobConfig`]. A refused configuration is a compile error naming the argument.
///
/// ```
/// use stiffspring::knob::KnobDesign;
/// use stiffspring::{I16F16, Knob, KnobConfig, knob};
///
/// const CONFIG: KnobConfig = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
///     .endstops(0.0, 3.0)
///     .detent_count(16)
///     .detent_stiffness(0.05);
/// const DESIGN: KnobDesign<I16F16> = knob!(CONFIG, I16F16);
/// let mut knob = Knob::from_design(&DESIGN, I16F16::ZERO)?;
/// assert_eq!(knob.update(I16F16::ZERO).torque, I16F16::ZERO);
/// # Ok::<(), stiffspring::knob::KnobError>(())
/// ```
///
/// ```compile_fail
/// use stiffspring::{knob, knob::KnobDesign, KnobConfig};
/// // Far too stiff for 1 kHz: "knob!: detent_stiffness is beyond the loop guarantee".
/// const D: KnobDesign<f32> =
///     knob!(KnobConfig::new(1_000.0, 1e-5, 2.0, 16384).detent_width(0.1).detent_stiffness(5.0));
/// ```
#[macro_export]
macro_rules! knob {
    ($config:expr) => {
        $crate::knob!($config, f32)
    };
    ($config:expr, $backend:ty) => {{
        // A design runs a few hundred stability checks: more than the evaluator's
        // default patience on a slow machine.
        #[allow(long_running_const_eval)]
        const DESIGN: $crate::knob::KnobDesign<$backend> =
            match $crate::knob::KnobDesign::<$backend>::new_or_reason(&$config) {
                Ok(d) => d,
                Err((parameter, limit)) => {
                    panic!("{}", $crate::knob::refusal(parameter, limit))
                }
            };
        DESIGN
    }};
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, Knob};

    /// `Knob::loop_coefficients` derives the report from what the knob keeps; it must be
    /// the design's own, to the bit, in every zone that occurs and in none that does not.
    #[test]
    fn a_knobs_loop_report_is_its_designs_to_the_bit() {
        // The knob of issue 17 (4 kHz, 24 detents between endstops at ±135°), and the docs'.
        let base = KnobConfig::new(4_000.0, 1e-5, 0.02, 16384).detent_count(24);
        let docs = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_stiffness(0.05);
        let configs = [
            base.endstops(-2.356, 2.356).detent_torque(0.01),
            docs.detent_width(0.2),
            docs.endstops(0.0, 3.0).detent_count(16),
            docs.detent_width(0.2)
                .magnets(&[0.0, 1.0])
                .magnet_stiffness(0.02),
            docs.endstops(0.0, 3.0)
                .detent_count(16)
                .magnets(&[1.0, 2.0])
                .magnet_stiffness(0.02)
                .damping_ratio(1.0),
        ];
        let mut seen = [false; 3];
        for (i, config) in configs.iter().enumerate() {
            let design = KnobDesign::<f32>::new(config);
            let design = design.unwrap_or_else(|e| panic!("configuration {i}: {e:?}"));
            let knob = Knob::from_design(&design, 0.0).expect("a good angle");
            assert_eq!(
                knob.loop_coefficients(),
                design.design.zones,
                "configuration {i}"
            );
            for (z, zone) in design.design.zones.iter().enumerate() {
                seen[z] |= zone.is_some();
            }
            let fixed = KnobDesign::<I16F16>::new(config).expect("accepted in I16F16");
            let knob = Knob::from_design(&fixed, I16F16::ZERO).expect("a good angle");
            assert_eq!(
                knob.loop_coefficients(),
                fixed.design.zones,
                "configuration {i}"
            );
        }
        assert_eq!(seen, [true; 3], "every zone occurs in some configuration");
    }
}
