//! The knob's configuration, in physical units: set once, validated when the knob is built.

use super::detents::MAX_MAGNETS;
use super::error::{KnobError, Limit, Zone};
use super::stability::{
    COUNT_TORQUE_FRACTION, DAMPING_RATIO_RANGE, DECAY_FRACTION, FILTER_LADDER, Latency,
    LoopCoefficients, Plant, decay_radius, slowest_decay, sqrt,
};
use crate::error::Parameter;
use crate::scalar::Scalar;
use core::f64::consts::TAU;

/// How a knob feels and what it drives: everything a [`Knob`](crate::Knob) is built from,
/// in SI units: the loop rate in Hz, the rotor's moment of inertia in kg·m², torques in
/// N·m, angles in radians, stiffnesses in N·m/rad, damping in N·m·s/rad.
///
/// The builder methods only record their arguments; [`Knob::new`](crate::Knob::new)
/// checks everything at once and reports the first bad argument as a
/// [`KnobError`](crate::knob::KnobError): the parameter, its value and the bound it broke.
///
/// # The same feel at every rate
///
/// A stiffness is a stiffness: `detent_stiffness(0.1)` is 0.1 N·m/rad at 1, 4 and 10 kHz,
/// and the damping (given as a ratio or in N·m·s/rad) is the same physical damping too.
/// What the rate changes is how stiff a spring the sampled loop can hold: about
/// `0.38·J·rate²` N·m/rad at damping ratio 0.7 with one period of delay, so a configuration
/// accepted at 1 kHz is accepted at 10 kHz.
///
/// # Layers and zones
///
/// Detents, a return spring, magnetic detents and endstops are springs that add where they
/// act. Inside the range the detents and the return spring act (zone
/// [`Free`](crate::knob::Zone::Free)); a magnet adds its spring within its capture radius
/// ([`Magnet`](crate::knob::Zone::Magnet)); beyond an endstop the endstop's spring adds to
/// the detent field, which continues past the stop, so that the force is continuous there
/// ([`Beyond`](crate::knob::Zone::Beyond)). The damping is one and the same everywhere.
/// Each zone's total stiffness must meet the loop guarantee
/// ([`knob::stability`](crate::knob::stability)).
///
/// ```
/// use stiffspring::{Knob, KnobConfig};
///
/// let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384) // 1 kHz, 1e−5 kg·m², 50 mN·m, 14 bits
///     .endstops(0.0, 3.0)
///     .detent_count(16)
///     .detent_stiffness(0.05); // N·m/rad
/// let knob = Knob::<f32>::new(&config, 0.0)?;
/// assert_eq!(knob.detent(), 0);
/// # Ok::<(), stiffspring::knob::KnobError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct KnobConfig {
    pub(crate) rate: f64,
    pub(crate) inertia: f64,
    pub(crate) torque_limit: f64,
    pub(crate) counts_per_turn: u32,
    pub(crate) latency: Latency,
    pub(crate) damping: Damping,
    pub(crate) endstops: Option<(f64, f64)>,
    pub(crate) endstop_stiffness: Option<f64>,
    pub(crate) detents: DetentSpacing,
    pub(crate) detent_origin: f64,
    pub(crate) detent_spring: DetentSpring,
    pub(crate) snap_point: f64,
    pub(crate) hysteresis: Option<f64>,
    pub(crate) return_centre: f64,
    pub(crate) return_stiffness: f64,
    pub(crate) magnets: [f64; MAX_MAGNETS],
    pub(crate) magnet_count: usize,
    pub(crate) magnets_asked: usize,
    pub(crate) magnet_stiffness: f64,
    pub(crate) magnet_radius: Option<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum DetentSpacing {
    None,
    Width(f64),
    Count(u32),
}

#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum DetentSpring {
    Stiffness(f64),
    PeakTorque(f64),
}

#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum Damping {
    Ratio(f64),
    Coefficient(f64),
}

impl KnobConfig {
    /// The damping ratio unless set otherwise: a crisp detent that overshoots by about 5%
    /// after a flick.
    ///
    /// ```
    /// assert_eq!(stiffspring::KnobConfig::DEFAULT_DAMPING_RATIO, 0.7);
    /// ```
    pub const DEFAULT_DAMPING_RATIO: f64 = 0.7;

    /// The default snap point: switch at 55% of the width, SmartKnob's usual value.
    ///
    /// ```
    /// assert_eq!(stiffspring::KnobConfig::DEFAULT_SNAP_POINT, 0.55);
    /// ```
    pub const DEFAULT_SNAP_POINT: f64 = 0.55;

    /// The default hysteresis, in encoder counts.
    ///
    /// ```
    /// assert_eq!(stiffspring::KnobConfig::DEFAULT_HYSTERESIS_COUNTS, 2.0);
    /// ```
    pub const DEFAULT_HYSTERESIS_COUNTS: f64 = 2.0;

    /// A knob run at `rate` hertz, driving a rotor of moment of inertia `inertia` (kg·m²)
    /// with a motor that gives at most `torque_limit` (N·m), read by an encoder of
    /// `counts_per_turn`; no detents, endstops or springs yet, damping ratio
    /// [`Self::DEFAULT_DAMPING_RATIO`], [`Latency::OneStep`], a hysteresis of two counts.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(10_000.0, 2e-5, 0.1, 4096);
    /// assert_eq!(c.dt(), 1e-4);
    /// ```
    pub const fn new(rate: f64, inertia: f64, torque_limit: f64, counts_per_turn: u32) -> Self {
        KnobConfig {
            rate,
            inertia,
            torque_limit,
            counts_per_turn,
            latency: Latency::OneStep,
            damping: Damping::Ratio(Self::DEFAULT_DAMPING_RATIO),
            endstops: None,
            endstop_stiffness: None,
            detents: DetentSpacing::None,
            detent_origin: 0.0,
            detent_spring: DetentSpring::Stiffness(0.0),
            snap_point: Self::DEFAULT_SNAP_POINT,
            hysteresis: None,
            return_centre: 0.0,
            return_stiffness: 0.0,
            magnets: [0.0; MAX_MAGNETS],
            magnet_count: 0,
            magnets_asked: 0,
            magnet_stiffness: 0.0,
            magnet_radius: None,
        }
    }

    /// The loop rate, in hertz.
    ///
    /// ```
    /// assert_eq!(stiffspring::KnobConfig::new(4_000.0, 1e-5, 0.05, 16384).rate(), 4_000.0);
    /// ```
    pub const fn rate(&self) -> f64 {
        self.rate
    }

    /// The control period `1/rate`, in seconds.
    ///
    /// ```
    /// assert_eq!(stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).dt(), 1e-3);
    /// ```
    pub fn dt(&self) -> f64 {
        1.0 / self.rate
    }

    /// One encoder count, in radians.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384);
    /// assert_eq!(c.count(), core::f64::consts::TAU / 16384.0);
    /// ```
    pub fn count(&self) -> f64 {
        TAU / f64::from(self.counts_per_turn)
    }

    /// When the torque reaches the rotor (default [`Latency::OneStep`], which is also
    /// checked without the delay).
    ///
    /// ```
    /// use stiffspring::{knob::Latency, Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).latency(Latency::SameStep);
    /// assert!(Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn latency(mut self, latency: Latency) -> Self {
        self.latency = latency;
        self
    }

    /// The damping as a ratio `ζ` in [`DAMPING_RATIO_RANGE`] (default 0.7) of the
    /// stiffest spring inside the range (detents, return spring and, held by a magnet, the
    /// magnet; if there is none, the endstops): `B = 2ζ·√(K·J)`. Softer zones are damped
    /// more than `ζ`, stiffer ones (the endstops) less.
    ///
    /// [`DAMPING_RATIO_RANGE`]: crate::knob::DAMPING_RATIO_RANGE
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.2).detent_stiffness(0.1);
    /// let knob = Knob::<f32>::new(&c.damping_ratio(1.0), 0.0)?;
    /// assert!((knob.damping() - 2.0 * (0.1f64 * 1e-5).sqrt()).abs() < 1e-12);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    #[must_use]
    pub const fn damping_ratio(mut self, zeta: f64) -> Self {
        self.damping = Damping::Ratio(zeta);
        self
    }

    /// The damping in N·m·s/rad, the same in every zone (replaces the damping ratio).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.2).detent_stiffness(0.1);
    /// assert_eq!(Knob::<f32>::new(&c.damping(1e-3), 0.0)?.damping(), 1e-3);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    #[must_use]
    pub const fn damping(mut self, damping: f64) -> Self {
        self.damping = Damping::Coefficient(damping);
        self
    }

    /// Endstops at `min` and `max` (radians). Beyond them the endstop's spring adds to the
    /// detent field.
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(1.0, -1.0);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err().error.parameter(), Some(Parameter::Position));
    /// ```
    #[must_use]
    pub const fn endstops(mut self, min: f64, max: f64) -> Self {
        self.endstops = Some((min, max));
        self
    }

    /// The endstops' stiffness in N·m/rad, added to the detent field beyond the stops
    /// (default: the stiffest of 4, 2, 1, ½ and ¼ times the stiffness inside the range
    /// that meets the loop guarantee without a shorter velocity filter than the range
    /// needs; at 4× the endstop zone keeps a damping ratio of `ζ/√5`). A stiffer stop
    /// needs more damping ([`damping`](Self::damping)).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(0.0, 1.0).endstop_stiffness(0.2);
    /// assert!(Knob::<f32>::new(&c, 0.5).is_ok());
    /// ```
    #[must_use]
    pub const fn endstop_stiffness(mut self, stiffness: f64) -> Self {
        self.endstop_stiffness = Some(stiffness);
        self
    }

    /// `count` detents spread over the endstops' range, the first at `min` and the last at
    /// `max` (needs [`endstops`](Self::endstops) and `count ≥ 2`).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(0.0, 1.0).detent_count(11);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn detent_count(mut self, count: u32) -> Self {
        self.detents = DetentSpacing::Count(count);
        self
    }

    /// Detents every `width` radians, from `min` when there are endstops (up to `max`),
    /// else from the [`detent_origin`](Self::detent_origin), without end.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn detent_width(mut self, width: f64) -> Self {
        self.detents = DetentSpacing::Width(width);
        self
    }

    /// Where the detent grid is anchored when there are no endstops (default 0).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1).detent_origin(0.05);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn detent_origin(mut self, origin: f64) -> Self {
        self.detent_origin = origin;
        self
    }

    /// The detents' stiffness, in N·m/rad (default 0).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1).detent_stiffness(0.05);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn detent_stiffness(mut self, stiffness: f64) -> Self {
        self.detent_spring = DetentSpring::Stiffness(stiffness);
        self
    }

    /// The detents' peak torque in N·m: the torque just before the index switches, at
    /// `max(snap·width, width/2 + hysteresis)` from the centre (sets the stiffness).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.2).detent_torque(0.011);
    /// // 11 mN·m at the switching point, 0.55 of the width: 0.1 N·m/rad.
    /// let k = Knob::<f64>::new(&c, 0.0)?;
    /// assert!((k.zone_stiffness()[0] - 0.011 / (0.2 * 0.55)).abs() < 1e-12);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    #[must_use]
    pub const fn detent_torque(mut self, peak: f64) -> Self {
        self.detent_spring = DetentSpring::PeakTorque(peak);
        self
    }

    /// How far from the current detent's centre the rotor must go before the index
    /// switches, as a fraction of the width in `[0.5, 1)` (default
    /// [`Self::DEFAULT_SNAP_POINT`]). Above 0.5 the detent holds the rotor past the
    /// midpoint and then snaps it into the next one; the drop in the spring's energy at
    /// the switch is what makes switching dissipative.
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1).snap_point(0.4);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err().error.parameter(), Some(Parameter::SnapPoint));
    /// ```
    #[must_use]
    pub const fn snap_point(mut self, fraction: f64) -> Self {
        self.snap_point = fraction;
        self
    }

    /// The least distance past a boundary (radians) before a detent, endstop or magnet
    /// changes state (default: two encoder counts). The index switches at
    /// `max(snap·width, width/2 + hysteresis)` from the centre, which must stay below the
    /// width.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1).hysteresis(1e-3);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn hysteresis(mut self, angle: f64) -> Self {
        self.hysteresis = Some(angle);
        self
    }

    /// A spring back to `centre` over the whole range, of `stiffness` N·m/rad.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).return_to_centre(0.0, 0.01);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.3).is_ok());
    /// ```
    #[must_use]
    pub const fn return_to_centre(mut self, centre: f64, stiffness: f64) -> Self {
        self.return_centre = centre;
        self.return_stiffness = stiffness;
        self
    }

    /// Magnetic detents at arbitrary angles (at most [`MAX_MAGNETS`], any order), each
    /// pulling the rotor within the [`magnet_radius`](Self::magnet_radius).
    ///
    /// [`MAX_MAGNETS`]: crate::knob::MAX_MAGNETS
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).magnets(&[0.0, 1.0]).magnet_stiffness(0.05);
    /// assert!(Knob::<f32>::new(&c, 0.0).is_ok());
    /// let c = c.magnets(&[0.0; 9]);
    /// assert!(matches!(Knob::<f32>::new(&c, 0.0).unwrap_err().error, Error::CapacityFull { .. }));
    /// ```
    #[must_use]
    pub fn magnets(mut self, angles: &[f64]) -> Self {
        let n = angles.len().min(MAX_MAGNETS);
        self.magnets = [0.0; MAX_MAGNETS];
        self.magnets[..n].copy_from_slice(&angles[..n]);
        self.magnet_count = n;
        self.magnets_asked = angles.len();
        self
    }

    /// The magnetic detents' stiffness, in N·m/rad (default 0).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).magnets(&[0.5]).magnet_stiffness(0.05);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn magnet_stiffness(mut self, stiffness: f64) -> Self {
        self.magnet_stiffness = stiffness;
        self
    }

    /// How close a magnetic detent captures the rotor (default: a quarter of the smallest
    /// spacing of the magnets, or 0.1 rad for a single one). Capture zones widened by the
    /// hysteresis must not overlap.
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).magnets(&[0.0, 1.0]).magnet_radius(0.6);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err().error.parameter(), Some(Parameter::CaptureRadius));
    /// ```
    #[must_use]
    pub const fn magnet_radius(mut self, radius: f64) -> Self {
        self.magnet_radius = Some(radius);
        self
    }

    /// The stiffest detent (N·m/rad) that [`Knob::new`](crate::Knob::new) accepts for
    /// backend `S` with everything else as configured: the loop guarantee in every zone
    /// and the detent's peak torque (a bisection over whole set-ups: a tool for the host,
    /// not for a boot path). Zero when no detent is accepted.
    ///
    /// # Errors
    ///
    /// The error of the configuration with a detent of (almost) no stiffness, when even
    /// that is refused.
    ///
    /// ```
    /// use stiffspring::KnobConfig;
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_count(24).endstops(0.0, 6.0);
    /// let k = c.detent_stiffness_limit::<f32>()?;
    /// assert!(k > 0.01 && k < 1.0);
    /// assert!(stiffspring::Knob::<f32>::new(&c.detent_stiffness(0.99 * k), 0.0).is_ok());
    /// assert!(stiffspring::Knob::<f32>::new(&c.detent_stiffness(1.01 * k), 0.0).is_err());
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn detent_stiffness_limit<S: Scalar>(&self) -> Result<f64, KnobError> {
        let at = |k: f64| self.detent_stiffness(k).validate::<S>().map(|_| ());
        let tiny = 1e-12;
        at(tiny)?;
        let mut hi = tiny;
        while at(2.0 * hi).is_ok() {
            hi *= 2.0;
            if hi > 1e12 {
                return Ok(hi);
            }
        }
        let (mut lo, mut hi) = (hi, 2.0 * hi);
        for _ in 0..48 {
            let mid = 0.5 * (lo + hi);
            if at(mid).is_ok() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Ok(lo)
    }
}

/// Everything the hot path needs, validated and in `f64`.
pub(crate) struct Validated {
    pub(crate) dt: f64,
    pub(crate) torque_limit: f64,
    /// The rest zone: one encoder count.
    pub(crate) count: f64,
    /// The largest angle magnitude the hot path takes (inputs are clamped to it).
    pub(crate) reach: f64,
    pub(crate) bounds: Option<(f64, f64)>,
    /// `(origin, width, threshold, (min, max) index)`, or `None` without detents.
    pub(crate) grid: Option<(f64, f64, f64, (i32, i32))>,
    pub(crate) hysteresis: f64,
    pub(crate) return_centre: f64,
    pub(crate) magnets: [f64; MAX_MAGNETS],
    pub(crate) magnet_count: usize,
    pub(crate) magnet_radius: f64,
    /// Stiffness of each layer, N·m/rad: detent, magnet, return, endstop.
    pub(crate) detent: f64,
    pub(crate) magnet: f64,
    pub(crate) ret: f64,
    pub(crate) endstop: f64,
    /// The damping, N·m·s/rad, and the velocity filter's `α`.
    pub(crate) damping: f64,
    pub(crate) alpha: f64,
    /// The damper's state scale: a power of two up to `law::STATE_SCALE`.
    pub(crate) state_scale: f64,
    /// Each zone's loop, `None` where the zone cannot occur.
    pub(crate) zones: [Option<LoopCoefficients>; 3],
    pub(crate) zone_stiffness: [f64; 3],
}

/// `floor` for non-negative values below 2⁵², without `libm`.
pub(crate) fn libm_free_floor(value: f64) -> f64 {
    if value.is_nan() || value < 0.0 {
        return 0.0;
    }
    if value >= 4_503_599_627_370_496.0 {
        return value;
    }
    (value as u64) as f64
}

/// `floor` for any finite value.
pub(crate) fn floor(value: f64) -> f64 {
    if value >= 0.0 {
        libm_free_floor(value)
    } else {
        let f = -libm_free_floor(-value);
        if f > value { f - 1.0 } else { f }
    }
}

/// The index of the detent nearest to `angle`: `round((angle − origin)/width)`, clamped.
pub(crate) fn nearest_index(angle: f64, origin: f64, width: f64, (lo, hi): (i32, i32)) -> i32 {
    let r = floor((angle - origin) / width + 0.5);
    r.clamp(f64::from(lo), f64::from(hi)) as i32
}

/// The multiples of the inside stiffness tried for the default endstop, stiffest first.
/// At most 4×: the endstop zone then keeps a damping ratio of `ζ/√5` (0.31 at the default
/// 0.7), so that a knob flicked into the stop bounces little.
const ENDSTOP_MULTIPLES: [f64; 5] = [4.0, 2.0, 1.0, 0.5, 0.25];

impl KnobConfig {
    /// Checks everything, for backend `S`.
    pub(crate) fn validate<S: Scalar>(&self) -> Result<Validated, KnobError> {
        use Parameter as P;
        let rate = KnobError::positive(self.rate, P::TimeStep)?;
        let dt = 1.0 / rate;
        let inertia = KnobError::positive(self.inertia, P::Inertia)?;
        let torque_limit = KnobError::positive(self.torque_limit, P::TorqueLimit)?;
        if self.counts_per_turn == 0 {
            return Err(KnobError::range(
                P::EncoderResolution,
                Limit::Positive,
                0.0,
                0.0,
            ));
        }
        let count = TAU / f64::from(self.counts_per_turn);
        if count < S::RESOLUTION {
            // A count finer than the backend's LSB: the backend cannot tell counts apart.
            return Err(KnobError::range(
                P::EncoderResolution,
                Limit::AtMost,
                f64::from(self.counts_per_turn),
                TAU / S::RESOLUTION,
            ));
        }
        let damping_spec = match self.damping {
            Damping::Ratio(z) => {
                let z = KnobError::finite(z, P::DampingRatio)?;
                let (lo, hi) = DAMPING_RATIO_RANGE;
                if z < lo {
                    return Err(KnobError::range(P::DampingRatio, Limit::AtLeast, z, lo));
                }
                if z > hi {
                    return Err(KnobError::range(P::DampingRatio, Limit::AtMost, z, hi));
                }
                Damping::Ratio(z)
            }
            Damping::Coefficient(b) => {
                Damping::Coefficient(KnobError::non_negative(b, P::DampingConstant)?)
            }
        };

        // The backend's reach: fixed point takes its whole range (it saturates); a float
        // is limited below, once the gains are known.
        let backend_half = S::MAX / 2.0;
        let bounds = match self.endstops {
            None => None,
            Some((lo, hi)) => {
                let lo = KnobError::finite(lo, P::Position)?;
                let hi = KnobError::finite(hi, P::Position)?;
                if lo >= hi {
                    return Err(KnobError::range(P::Position, Limit::Below, lo, hi));
                }
                let m = lo.abs().max(hi.abs());
                if m > backend_half {
                    return Err(KnobError::range(
                        P::Position,
                        Limit::BackendRange,
                        m,
                        backend_half,
                    ));
                }
                Some((lo, hi))
            }
        };
        let hysteresis = match self.hysteresis {
            Some(h) => KnobError::non_negative(h, P::Hysteresis)?,
            None => Self::DEFAULT_HYSTERESIS_COUNTS * count,
        };
        let snap = KnobError::finite(self.snap_point, P::SnapPoint)?;
        if snap < 0.5 {
            return Err(KnobError::range(P::SnapPoint, Limit::AtLeast, snap, 0.5));
        }
        if snap >= 1.0 {
            return Err(KnobError::range(P::SnapPoint, Limit::Below, snap, 1.0));
        }
        let layout = match (self.detents, bounds) {
            (DetentSpacing::None, _) => None,
            (DetentSpacing::Count(n), Some((lo, hi))) if n >= 2 => {
                Some((lo, (hi - lo) / f64::from(n - 1), Some(n - 1)))
            }
            (DetentSpacing::Count(n), Some(_)) => {
                return Err(KnobError::range(
                    P::DetentWidth,
                    Limit::AtLeast,
                    f64::from(n),
                    2.0,
                ));
            }
            (DetentSpacing::Count(n), None) => {
                // A count needs endstops to spread over.
                return Err(KnobError::range(
                    P::DetentWidth,
                    Limit::NeedsEndstops,
                    f64::from(n),
                    f64::NAN,
                ));
            }
            (DetentSpacing::Width(w), Some((lo, hi))) => {
                let w = KnobError::positive(w, P::DetentWidth)?;
                // The last detent at or just below `max` (1e−9 absorbs the rounding of a
                // width that divides the range).
                let n = libm_free_floor((hi - lo) / w + 1e-9);
                if n > f64::from(i32::MAX - 1) {
                    return Err(KnobError::range(
                        P::DetentWidth,
                        Limit::AtLeast,
                        w,
                        (hi - lo) / f64::from(i32::MAX - 1),
                    ));
                }
                Some((lo, w, Some(n as u32)))
            }
            (DetentSpacing::Width(w), None) => Some((
                KnobError::finite(self.detent_origin, P::Position)?,
                KnobError::positive(w, P::DetentWidth)?,
                None,
            )),
        };
        let grid = match layout {
            None => None,
            Some((origin, width, span)) => {
                // A width of at least four counts, so that the switching points and the
                // rest zone stay apart; and one the backend resolves to 1%.
                let least = (4.0 * count).max(100.0 * S::RESOLUTION);
                if width < least {
                    return Err(KnobError::range(
                        P::DetentWidth,
                        Limit::AtLeast,
                        width,
                        least,
                    ));
                }
                if origin.abs() > backend_half {
                    return Err(KnobError::range(
                        P::Position,
                        Limit::BackendRange,
                        origin.abs(),
                        backend_half,
                    ));
                }
                let threshold = (snap * width).max(0.5 * width + hysteresis);
                if threshold >= width {
                    return Err(KnobError::range(
                        P::Hysteresis,
                        Limit::Below,
                        hysteresis,
                        0.5 * width,
                    ));
                }
                let range = match span {
                    Some(n) => (0, n.min(i32::MAX as u32 - 1) as i32),
                    None => {
                        // Keep every centre within half the reach.
                        let n = libm_free_floor((backend_half - origin.abs()) / width);
                        let n = n.min(f64::from(i32::MAX - 1));
                        (-(n as i32), n as i32)
                    }
                };
                Some((origin, width, threshold, range))
            }
        };

        // The layers' stiffnesses.
        let detent = match self.detent_spring {
            DetentSpring::Stiffness(k) => KnobError::non_negative(k, P::SpringConstant)?,
            DetentSpring::PeakTorque(t) => {
                let t = KnobError::non_negative(t, P::TorqueLimit)?;
                match grid {
                    Some((_, _, threshold, _)) => t / threshold,
                    None => 0.0,
                }
            }
        };
        let detent = if grid.is_some() { detent } else { 0.0 };
        let ret = KnobError::non_negative(self.return_stiffness, P::SpringConstant)?;
        let return_centre = KnobError::finite(self.return_centre, P::Position)?;
        if return_centre.abs() > backend_half {
            return Err(KnobError::range(
                P::Position,
                Limit::BackendRange,
                return_centre.abs(),
                backend_half,
            ));
        }
        let magnet = KnobError::non_negative(self.magnet_stiffness, P::SpringConstant)?;
        let endstop = match self.endstop_stiffness {
            Some(k) => Some(KnobError::non_negative(k, P::SpringConstant)?),
            None => None,
        };

        // Magnets.
        if self.magnets_asked > MAX_MAGNETS {
            return Err(KnobError::range(
                P::CaptureRadius,
                Limit::Capacity,
                self.magnets_asked as f64,
                MAX_MAGNETS as f64,
            ));
        }
        let mut magnets = self.magnets;
        let magnet_count = self.magnet_count;
        for &m in &magnets[..magnet_count] {
            let m = KnobError::finite(m, P::Position)?;
            match bounds {
                Some((lo, _)) if m < lo => {
                    return Err(KnobError::range(P::Position, Limit::AtLeast, m, lo));
                }
                Some((_, hi)) if m > hi => {
                    return Err(KnobError::range(P::Position, Limit::AtMost, m, hi));
                }
                None if m.abs() > backend_half => {
                    return Err(KnobError::range(
                        P::Position,
                        Limit::BackendRange,
                        m.abs(),
                        backend_half,
                    ));
                }
                _ => {}
            }
        }
        // Insertion sort: at most MAX_MAGNETS elements, no allocation.
        for i in 1..magnet_count {
            let mut j = i;
            while j > 0 && magnets[j - 1] > magnets[j] {
                magnets.swap(j - 1, j);
                j -= 1;
            }
        }
        let spacing = magnets[..magnet_count]
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        let magnet_radius = match self.magnet_radius {
            Some(r) => KnobError::positive(r, P::CaptureRadius)?,
            None if spacing.is_finite() => 0.25 * spacing,
            None => 0.1,
        };
        if magnet_count > 0 {
            let least = (2.0 * count).max(100.0 * S::RESOLUTION);
            if magnet_radius < least {
                return Err(KnobError::range(
                    P::CaptureRadius,
                    Limit::AtLeast,
                    magnet_radius,
                    least,
                ));
            }
            let most = 0.5 * spacing - hysteresis;
            if magnet_radius > most {
                return Err(KnobError::range(
                    P::CaptureRadius,
                    Limit::AtMost,
                    magnet_radius,
                    most,
                ));
            }
        }
        let magnet = if magnet_count > 0 { magnet } else { 0.0 };

        // Peak torques: a detent or magnet the motor renders unclipped.
        if let Some((_, _, threshold, _)) = grid {
            let peak = detent * threshold;
            if peak > torque_limit {
                return Err(KnobError::range(
                    P::SpringConstant,
                    Limit::PeakTorque,
                    peak,
                    torque_limit,
                ));
            }
        }
        if magnet_count > 0 {
            let peak = magnet * (magnet_radius + hysteresis);
            if peak > torque_limit {
                return Err(KnobError::range(
                    P::SpringConstant,
                    Limit::PeakTorque,
                    peak,
                    torque_limit,
                ));
            }
        }

        // The loop design.
        let free = detent + ret;
        let held = free + magnet;
        let has_magnets = magnet_count > 0;
        let has_stops = bounds.is_some();
        let inside = if has_magnets { held } else { free };
        let plant = |damping: f64, radius: f64| Plant {
            dt,
            inertia,
            damping,
            latency: self.latency,
            radius,
        };
        // The reference stiffness of the damping ratio, and the endstop if it needs one.
        let mut ratio = None;
        let (damping, endstop) = match damping_spec {
            Damping::Coefficient(b) => (b, endstop),
            Damping::Ratio(z) => {
                let (reference, zone) = if has_magnets && held > 0.0 {
                    (held, 1)
                } else if free > 0.0 {
                    (free, 0)
                } else if let (true, Some(k)) = (has_stops, endstop) {
                    (k, 2)
                } else {
                    // Nothing sets a stiffness: the stiffest spring that meets the
                    // guarantee on its own at this damping ratio (also the default
                    // endstop, if there are endstops).
                    let top = top_stiffness(z, dt, inertia, self.latency);
                    if has_stops && endstop.is_none() {
                        return self.finish::<S>(
                            Design {
                                ratio: Some((z, 2)),
                                dt,
                                inertia,
                                torque_limit,
                                count,
                                damping: 2.0 * z * sqrt(top * inertia),
                                detent,
                                magnet,
                                ret,
                                endstop: top,
                            },
                            bounds,
                            grid,
                            hysteresis,
                            return_centre,
                            magnets,
                            magnet_count,
                            magnet_radius,
                        );
                    }
                    (top, 2)
                };
                ratio = Some((z, zone));
                (2.0 * z * sqrt(reference * inertia), endstop)
            }
        };
        // The default endstop: the stiffest multiple of the inside stiffness that meets
        // the guarantee with the filter the inside needs.
        let endstop = match (has_stops, endstop) {
            (false, _) => 0.0,
            (true, Some(k)) => k,
            (true, None) => {
                // Without springs inside, the stiffness this damping gives ζ = 0.7.
                let base = if inside > 0.0 {
                    inside
                } else {
                    let root = damping / (2.0 * Self::DEFAULT_DAMPING_RATIO);
                    root * root / inertia
                };
                let sigma =
                    DECAY_FRACTION * zone_decays(free, held, has_magnets, None, damping, inertia);
                let p = plant(damping, decay_radius(sigma * dt));
                let omega = reference_frequency(inside, damping, inertia);
                let mut found = None;
                'ladder: for &c in &FILTER_LADDER {
                    let a = p.alpha(c, omega);
                    if !(p.zone_ok(free, a) && (!has_magnets || p.zone_ok(held, a))) {
                        continue;
                    }
                    for m in ENDSTOP_MULTIPLES {
                        let k = free + m * base;
                        let ripple = (k + damping * a / dt) * count;
                        if ripple <= COUNT_TORQUE_FRACTION * torque_limit && p.zone_ok(k, a) {
                            found = Some(m * base);
                            break 'ladder;
                        }
                    }
                }
                match found {
                    Some(k) => k,
                    None => {
                        // Even a quarter of the inside is too stiff: report that bound.
                        let k = free + 0.25 * base;
                        return Err(KnobError::range(
                            P::SpringConstant,
                            Limit::LoopStiffness(Zone::Beyond),
                            k,
                            p.stiffness_limit(k),
                        ));
                    }
                }
            }
        };
        self.finish::<S>(
            Design {
                ratio,
                dt,
                inertia,
                torque_limit,
                count,
                damping,
                detent,
                magnet,
                ret,
                endstop,
            },
            bounds,
            grid,
            hysteresis,
            return_centre,
            magnets,
            magnet_count,
            magnet_radius,
        )
    }

    /// The loop check and the backend's range, once every stiffness is known.
    #[allow(clippy::too_many_arguments)]
    fn finish<S: Scalar>(
        &self,
        d: Design,
        bounds: Option<(f64, f64)>,
        grid: Option<(f64, f64, f64, (i32, i32))>,
        hysteresis: f64,
        return_centre: f64,
        magnets: [f64; MAX_MAGNETS],
        magnet_count: usize,
        magnet_radius: f64,
    ) -> Result<Validated, KnobError> {
        use Parameter as P;
        let has_magnets = magnet_count > 0;
        let has_stops = bounds.is_some();
        let free = d.detent + d.ret;
        let held = free + d.magnet;
        let beyond = free + d.endstop;
        let stiffness = [free, held, beyond];
        let present = [true, has_magnets, has_stops];
        let sigma = DECAY_FRACTION
            * zone_decays(
                free,
                held,
                has_magnets,
                has_stops.then_some(beyond),
                d.damping,
                d.inertia,
            );
        let p = Plant {
            dt: d.dt,
            inertia: d.inertia,
            damping: d.damping,
            latency: self.latency,
            radius: decay_radius(sigma * d.dt),
        };
        // With the damping from a ratio, the zone that sets it moves with it: its bound is
        // the stiffest spring that meets the guarantee at that damping ratio.
        let ratio_error = |zone: usize| {
            d.ratio.filter(|&(_, z)| z == zone).map(|(zeta, _)| {
                KnobError::range(
                    P::SpringConstant,
                    Limit::LoopStiffness(super::stability::ZONES[zone]),
                    stiffness[zone],
                    top_stiffness(zeta, d.dt, d.inertia, self.latency),
                )
            })
        };
        // The damper alone: a velocity loop that must meet the guarantee too.
        if !p.zone_ok(0.0, 1.0) {
            return Err(match d.ratio {
                Some((_, zone)) => {
                    ratio_error(zone).unwrap_or_else(|| damping_limit(p, d.inertia, d.dt))
                }
                None => damping_limit(p, d.inertia, d.dt),
            });
        }
        let inside = if has_magnets { held } else { free };
        let omega = reference_frequency(
            if inside > 0.0 { inside } else { beyond },
            d.damping,
            d.inertia,
        );
        let zones_ok = |a: f64| (0..3).all(|z| !present[z] || p.zone_ok(stiffness[z], a));
        let Some(alpha) = FILTER_LADDER
            .iter()
            .map(|&c| p.alpha(c, omega))
            .find(|&a| zones_ok(a))
        else {
            // No filter passes: name the first zone that fails without one.
            let zone = (0..3)
                .find(|&z| present[z] && !p.zone_ok(stiffness[z], 1.0))
                .unwrap_or(0);
            if let Some(e) = ratio_error(zone) {
                return Err(e);
            }
            return Err(KnobError::range(
                P::SpringConstant,
                Limit::LoopStiffness(super::stability::ZONES[zone]),
                stiffness[zone],
                p.stiffness_limit(stiffness[zone]),
            ));
        };

        // The encoder: one count must not command more than a fraction of the limit.
        let most = COUNT_TORQUE_FRACTION * d.torque_limit;
        for z in 0..3 {
            let ripple = (stiffness[z] + d.damping * alpha / d.dt) * d.count;
            if present[z] && ripple > most {
                return Err(KnobError::range(
                    if stiffness[z] * d.count > 0.5 * most {
                        P::SpringConstant
                    } else {
                        P::DampingConstant
                    },
                    Limit::CountTorque(super::stability::ZONES[z]),
                    ripple,
                    most,
                ));
            }
        }

        // The backend: the gains (torque fraction per radian) and the reach.
        let damping_gain = d.damping / (d.torque_limit * d.dt);
        let per_rad = [
            (d.detent / d.torque_limit, P::SpringConstant),
            (d.magnet / d.torque_limit, P::SpringConstant),
            (d.ret / d.torque_limit, P::SpringConstant),
            (d.endstop / d.torque_limit, P::SpringConstant),
            (damping_gain, P::DampingConstant),
        ];
        let (largest, which) = per_rad
            .iter()
            .fold((1.0f64, P::SpringConstant), |m, &(g, p)| {
                if g > m.0 { (g, p) } else { m }
            });
        if largest >= S::MAX / 4.0 {
            return Err(KnobError::range(
                which,
                Limit::BackendRange,
                largest,
                S::MAX / 4.0,
            ));
        }
        // The damper's state keeps up to four more bits where the range allows.
        let mut state_scale = super::law::STATE_SCALE;
        while state_scale > 1.0 && state_scale * damping_gain >= S::MAX / 4.0 {
            state_scale /= 2.0;
        }
        // Floats: angles (and differences of two) times any gain stay finite, with room.
        let reach = if S::RESOLUTION > 0.0 {
            S::MAX
        } else {
            S::MAX / (16.0 * largest)
        };
        let half = reach / 2.0;
        let beyond_reach = bounds
            .map(|(lo, hi)| lo.abs().max(hi.abs()))
            .into_iter()
            .chain(grid.map(|g| g.0.abs()))
            .chain(core::iter::once(return_centre.abs()))
            .chain(magnets[..magnet_count].iter().map(|m| m.abs()))
            .fold(0.0f64, f64::max);
        if beyond_reach > half {
            return Err(KnobError::range(
                P::Position,
                Limit::BackendRange,
                beyond_reach,
                half,
            ));
        }
        // An endless grid spans the whole reach (less a width, so that a centre and the
        // next switching point stay inside it).
        let grid = grid.map(|(origin, width, threshold, range)| {
            let range = if bounds.is_none() {
                let n = libm_free_floor((reach - origin.abs()) / width - 1.0)
                    .min(f64::from(i32::MAX - 1));
                (-(n as i32), n as i32)
            } else {
                range
            };
            (origin, width, threshold, range)
        });

        let mut zones = [None; 3];
        for z in 0..3 {
            if present[z] {
                zones[z] = Some(p.coefficients(stiffness[z], alpha));
            }
        }
        Ok(Validated {
            dt: d.dt,
            torque_limit: d.torque_limit,
            count: d.count,
            reach,
            bounds,
            grid,
            hysteresis,
            return_centre,
            magnets,
            magnet_count,
            magnet_radius,
            detent: d.detent,
            magnet: d.magnet,
            ret: d.ret,
            endstop: d.endstop,
            damping: d.damping,
            alpha,
            state_scale,
            zones,
            zone_stiffness: stiffness,
        })
    }
}

/// The error of a damper that fails the guarantee on its own, with the most damping that
/// passes (bisection; an error path).
#[cold]
#[inline(never)]
fn damping_limit(p: Plant, inertia: f64, dt: f64) -> KnobError {
    let mut q = p;
    let (mut lo, mut hi) = (0.0, p.damping);
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        q.damping = mid;
        // The damper's own decay target (the velocity mode, B/J).
        q.radius = decay_radius(DECAY_FRACTION * slowest_decay(0.0, mid, inertia) * dt);
        if q.zone_ok(0.0, 1.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    KnobError::range(
        Parameter::DampingConstant,
        Limit::LoopDamping,
        p.damping,
        lo,
    )
}

/// The physical design, before the loop check.
struct Design {
    /// With the damping set by a ratio: `ζ` and the zone whose stiffness sets it (for the
    /// errors: that zone's bound then moves with its damping).
    ratio: Option<(f64, usize)>,
    dt: f64,
    inertia: f64,
    torque_limit: f64,
    count: f64,
    damping: f64,
    detent: f64,
    magnet: f64,
    ret: f64,
    endstop: f64,
}

/// The slowest decay rate over the zones that occur (1/s).
fn zone_decays(
    free: f64,
    held: f64,
    has_magnets: bool,
    beyond: Option<f64>,
    damping: f64,
    inertia: f64,
) -> f64 {
    let mut s = slowest_decay(free, damping, inertia);
    if has_magnets {
        s = s.min(slowest_decay(held, damping, inertia));
    }
    if let Some(k) = beyond {
        s = s.min(slowest_decay(k, damping, inertia));
    }
    s
}

/// The frequency the filter's time constant is measured against: the higher of the
/// natural frequency `√(K/J)` and the damper's `B/J`.
fn reference_frequency(stiffness: f64, damping: f64, inertia: f64) -> f64 {
    sqrt(stiffness / inertia).max(damping / inertia)
}

/// The stiffest spring with damping ratio `zeta` that meets the guarantee on its own
/// without a filter (bisection on `C_k`; set-up only, and rare: a knob with no stiffness
/// inside its range).
#[cold]
#[inline(never)]
fn top_stiffness(zeta: f64, dt: f64, inertia: f64, latency: Latency) -> f64 {
    // In dimensionless form: C_k = K·dt²/J, C_d = 2ζ√C_k, decay σ·dt from the same.
    let ok = |ck: f64| {
        let cd = 2.0 * zeta * sqrt(ck);
        let sigma_dt = DECAY_FRACTION * slowest_decay(ck, cd, 1.0);
        let p = Plant {
            dt: 1.0,
            inertia: 1.0,
            damping: cd,
            latency,
            radius: decay_radius(sigma_dt),
        };
        p.zone_ok(ck, 1.0)
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        if ok(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo * inertia / (dt * dt)
}
