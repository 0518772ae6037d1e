//! The knob's configuration, in physical units: what the user sets, recorded as given.
//!
//! The set-up flows one way: this configuration, then its validation (`validate.rs`),
//! then the loop design (`design.rs`, with the analysis of [`stability`](super::stability)),
//! then the backend's values (`compiled.rs`, [`KnobDesign`](super::KnobDesign)), which the
//! torque law runs on. This file imports none of them: the constants a configuration
//! needs (its magnet capacity, its latency) are defined here and flow from here.

use core::f64::consts::TAU;

/// The most magnetic detents a knob holds.
///
/// ```
/// use stiffspring::knob::MAX_MAGNETS;
/// assert_eq!(MAX_MAGNETS, 8);
/// ```
pub const MAX_MAGNETS: usize = 8;

/// When the torque computed from an angle reaches the rotor.
///
/// ```
/// use stiffspring::knob::Latency;
/// assert_eq!(Latency::default(), Latency::OneStep);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Latency {
    /// The torque computed from `θ_n` acts over `[t_n, t_{n+1}]`: the haptic loop sets the
    /// reference of a current loop that is much faster than it, within the same period.
    SameStep,
    /// The torque computed from `θ_n` acts over `[t_{n+1}, t_{n+2}]`: the structure of
    /// SimpleFOC-style firmware (`loopFOC()` applies what the previous `move()` stored).
    /// Configurations for it are also checked without the delay.
    #[default]
    OneStep,
}

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
/// `0.038·J·rate²` N·m/rad at damping ratio 0.7 with one period of delay
/// ([`detent_stiffness_limit`](Self::detent_stiffness_limit), checked below), less with
/// endstops, whose zone is stiffer. A configuration accepted at 1 kHz is accepted at 4
/// and 10 kHz in `f32` and `f64` (`tests/knob_rates.rs`; fixed point's shorter filter
/// bound is in `docs/knob.md`).
///
/// ```
/// use stiffspring::KnobConfig;
/// for rate in [1_000.0, 4_000.0, 10_000.0] {
///     let c = KnobConfig::new(rate, 1e-5, 100.0, 1 << 20).detent_width(0.5);
///     let k = c.detent_stiffness_limit::<f64>()? / (1e-5 * rate * rate);
///     assert!(k > 0.036 && k < 0.040, "{k}");
/// }
/// # Ok::<(), stiffspring::knob::KnobError>(())
/// ```
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
    pub(crate) max_speed: Option<f64>,
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
            max_speed: None,
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
    pub const fn dt(&self) -> f64 {
        1.0 / self.rate
    }

    /// One encoder count, in radians.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384);
    /// assert_eq!(c.count(), core::f64::consts::TAU / 16384.0);
    /// ```
    pub const fn count(&self) -> f64 {
        TAU / self.counts_per_turn as f64
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
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err().error.parameter(), Some(Parameter::Endstops));
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
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).magnets(&[0.0, 1.0]).magnet_stiffness(0.05);
    /// assert!(Knob::<f32>::new(&c, 0.0).is_ok());
    /// let c = c.magnets(&[0.0; 9]);
    /// assert!(matches!(Knob::<f32>::new(&c, 0.0).unwrap_err().error, Error::CapacityFull { .. }));
    /// ```
    #[must_use]
    pub const fn magnets(mut self, angles: &[f64]) -> Self {
        let n = if angles.len() < MAX_MAGNETS {
            angles.len()
        } else {
            MAX_MAGNETS
        };
        self.magnets = [0.0; MAX_MAGNETS];
        let mut i = 0;
        while i < n {
            self.magnets[i] = angles[i];
            i += 1;
        }
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

    /// The fastest the rotor may turn, rad/s: above it the knob commands no torque
    /// (against a runaway, as SmartKnob cuts its torque above 60 rad/s), and a reading
    /// that moves farther than `max_speed·dt` from the last is not used
    /// ([`SensorFault`](crate::knob::SensorFault)). Default: none (only the jolt
    /// the motor and a hand can give bounds a reading).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// use stiffspring::knob::SensorFault;
    ///
    /// let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).max_speed(60.0);
    /// let mut knob = Knob::<f32>::new(&config, 0.0)?;
    /// assert_eq!(knob.update(0.035).events.sensor, None); // 35 rad/s
    /// // 0.07 rad in the next 1 ms is 70 rad/s: the torque goes off.
    /// let out = knob.update(0.105);
    /// assert_eq!((out.events.sensor, out.torque), (Some(SensorFault::TooFast), 0.0));
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    #[must_use]
    pub const fn max_speed(mut self, max_speed: f64) -> Self {
        self.max_speed = Some(max_speed);
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

    /// This layout moved, endstops, detents, magnets and return centre alike, so that
    /// its detent `index` (clamped to the detents it has) is centred on `centre`: what
    /// [`Anchor::CurrentDetent`](crate::knob::Anchor::CurrentDetent) gives a running knob.
    /// A configuration without detents is moved so that its lower endstop (or its
    /// origin) is on `centre`.
    pub(crate) fn shifted_to(&self, index: i32, centre: f64) -> KnobConfig {
        let index = f64::from(index.max(0));
        let here = match (self.detents, self.endstops) {
            (DetentSpacing::Count(n), Some((lo, hi))) if n >= 2 => {
                let last = f64::from(n - 1);
                lo + index.min(last) * (hi - lo) / last
            }
            (DetentSpacing::Width(w), Some((lo, hi))) if w > 0.0 => {
                let last = libm::floor((hi - lo) / w + 1e-9).max(0.0);
                lo + index.min(last) * w
            }
            (DetentSpacing::Width(w), None) => self.detent_origin + index * w,
            (_, Some((lo, _))) => lo,
            (_, None) => self.detent_origin,
        };
        let delta = centre - here;
        let mut moved = *self;
        moved.endstops = self.endstops.map(|(lo, hi)| (lo + delta, hi + delta));
        moved.detent_origin = self.detent_origin + delta;
        moved.return_centre = self.return_centre + delta;
        for m in moved.magnets.iter_mut().take(self.magnet_count) {
            *m += delta;
        }
        moved
    }
}
