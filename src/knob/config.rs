//! The knob's configuration: set once, validated when the knob is built.

use super::detents::MAX_MAGNETS;
use super::stability::{Latency, StrengthMap, check_strength};
use crate::error::{Error, Parameter, non_negative, positive};
use crate::scalar::Scalar;

/// How a knob feels and what it drives: everything a [`Knob`](crate::Knob) is built from.
///
/// The builder methods only record their arguments; [`Knob::new`](crate::Knob::new)
/// checks everything at once and names the first bad argument in its [`Error`]. Angles
/// are in the caller's unit (radians or encoder counts), consistently: the inertia is
/// then in torque·s² per that unit. The torque unit is the caller's too, and the knob
/// outputs torque as a fraction of the limit.
///
/// # Strengths
///
/// Every layer (detents, magnetic detents, return spring, endstops) has a strength in
/// `[0, 1]`: its stiffness as a fraction of the stiffest spring the loop takes with its
/// margin ([`StrengthMap`]). Stiffnesses that act at the same time add, so the strengths
/// that act at once must sum to at most 1:
///
/// - inside the range: `detent + magnet + return ≤ 1`;
/// - beyond an endstop (where the endstop replaces the detents and magnets):
///   `endstop + return ≤ 1`.
///
/// ```
/// use stiffspring::{Knob, KnobConfig};
///
/// let config = KnobConfig::new(1e-3, 1e-5, 0.05) // 1 kHz, 1e−5 kg·m², 50 mN·m
///     .endstops(0.0, 3.0)
///     .detent_count(16)
///     .detent_strength(0.02)
///     .hysteresis(2.0 * core::f64::consts::TAU / 16384.0); // two 14-bit counts
/// let knob = Knob::<f32>::new(&config, 0.0)?;
/// assert_eq!(knob.detent(), 0);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct KnobConfig {
    pub(crate) dt: f64,
    pub(crate) inertia: f64,
    pub(crate) torque_limit: f64,
    pub(crate) damping_ratio: f64,
    pub(crate) latency: Latency,
    pub(crate) endstops: Option<(f64, f64)>,
    pub(crate) endstop_strength: Option<f64>,
    pub(crate) detents: DetentSpacing,
    pub(crate) detent_origin: f64,
    pub(crate) detent_strength: f64,
    pub(crate) snap_point: f64,
    pub(crate) hysteresis: f64,
    pub(crate) return_centre: f64,
    pub(crate) return_strength: f64,
    pub(crate) magnets: [f64; MAX_MAGNETS],
    pub(crate) magnet_count: usize,
    pub(crate) magnets_overflow: bool,
    pub(crate) magnet_strength: f64,
    pub(crate) magnet_radius: Option<f64>,
    pub(crate) encoder_resolution: Option<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum DetentSpacing {
    None,
    Width(f64),
    Count(u32),
}

impl KnobConfig {
    /// The damping ratio of every spring of the knob unless set otherwise: a crisp detent
    /// that overshoots by about 5% after a flick and settles in one period of its own
    /// frequency.
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

    /// A knob run every `dt` seconds, driving a rotor of moment of inertia `inertia` with
    /// a motor that can give at most `torque_limit`; no detents, endstops or springs yet,
    /// damping ratio [`Self::DEFAULT_DAMPING_RATIO`], [`Latency::OneStep`].
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-4, 2e-5, 0.1);
    /// assert_eq!(c.dt(), 1e-4);
    /// ```
    pub const fn new(dt: f64, inertia: f64, torque_limit: f64) -> Self {
        KnobConfig {
            dt,
            inertia,
            torque_limit,
            damping_ratio: Self::DEFAULT_DAMPING_RATIO,
            latency: Latency::OneStep,
            endstops: None,
            endstop_strength: None,
            detents: DetentSpacing::None,
            detent_origin: 0.0,
            detent_strength: 0.0,
            snap_point: Self::DEFAULT_SNAP_POINT,
            hysteresis: 0.0,
            return_centre: 0.0,
            return_strength: 0.0,
            magnets: [0.0; MAX_MAGNETS],
            magnet_count: 0,
            magnets_overflow: false,
            magnet_strength: 0.0,
            magnet_radius: None,
            encoder_resolution: None,
        }
    }

    /// The control period, in seconds.
    ///
    /// ```
    /// assert_eq!(stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).dt(), 1e-3);
    /// ```
    pub const fn dt(&self) -> f64 {
        self.dt
    }

    /// The damping ratio `ζ` of the knob's springs, in
    /// [`DAMPING_RATIO_RANGE`](crate::knob::DAMPING_RATIO_RANGE).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).damping_ratio(1.0);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn damping_ratio(mut self, zeta: f64) -> Self {
        self.damping_ratio = zeta;
        self
    }

    /// When the torque reaches the rotor (default [`Latency::OneStep`], which also keeps
    /// the margin without the delay).
    ///
    /// ```
    /// use stiffspring::{knob::Latency, KnobConfig};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05).latency(Latency::SameStep);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn latency(mut self, latency: Latency) -> Self {
        self.latency = latency;
        self
    }

    /// Endstops at `min` and `max`. Beyond them a spring of the endstop strength pulls the
    /// rotor back (default strength: all that the return spring leaves, `1 − return`).
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05).endstops(1.0, -1.0);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err(), Error::OutOfRange(Parameter::Position));
    /// ```
    #[must_use]
    pub const fn endstops(mut self, min: f64, max: f64) -> Self {
        self.endstops = Some((min, max));
        self
    }

    /// The strength of the endstops, in `[0, 1]`.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).endstops(0.0, 1.0).endstop_strength(0.5);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.5).is_ok());
    /// ```
    #[must_use]
    pub const fn endstop_strength(mut self, strength: f64) -> Self {
        self.endstop_strength = Some(strength);
        self
    }

    /// `count` detents spread over the endstops' range, the first at `min` and the last at
    /// `max` (needs [`endstops`](Self::endstops) and `count ≥ 2`).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).endstops(0.0, 1.0).detent_count(11);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn detent_count(mut self, count: u32) -> Self {
        self.detents = DetentSpacing::Count(count);
        self
    }

    /// Detents every `width`, from `min` when there are endstops (up to `max`), else from
    /// the [`detent_origin`](Self::detent_origin), without end.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).detent_width(0.1);
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
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).detent_width(0.1).detent_origin(0.05);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn detent_origin(mut self, origin: f64) -> Self {
        self.detent_origin = origin;
        self
    }

    /// The strength of the detents, in `[0, 1]` (default 0).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).detent_width(0.1).detent_strength(0.05);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn detent_strength(mut self, strength: f64) -> Self {
        self.detent_strength = strength;
        self
    }

    /// How far from the current detent's centre the rotor must go before the index
    /// switches, as a fraction of the width in `[0.5, 1)` (default
    /// [`Self::DEFAULT_SNAP_POINT`]). Above 0.5 the detent holds the rotor past the
    /// midpoint and then snaps it into the next one.
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05).detent_width(0.1).snap_point(0.4);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err(), Error::OutOfRange(Parameter::SnapPoint));
    /// ```
    #[must_use]
    pub const fn snap_point(mut self, fraction: f64) -> Self {
        self.snap_point = fraction;
        self
    }

    /// The least distance past a boundary before a detent, endstop or magnet changes
    /// state: set it to a few encoder counts (default 0). The index switches at
    /// `max(snap·width, width/2 + hysteresis)` from the centre; it must stay below the
    /// width.
    ///
    /// ```
    /// let count = core::f64::consts::TAU / 16384.0;
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).detent_width(0.1).hysteresis(2.0 * count);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn hysteresis(mut self, angle: f64) -> Self {
        self.hysteresis = angle;
        self
    }

    /// The encoder's resolution (the angle of one count). When given, [`Knob::new`]
    /// also refuses strengths at which one count of extension and of velocity together
    /// would command more than the whole torque, `(C_k + C_d)·I/(dt²·τ_max)·count > 1`:
    /// there the clamp turns the loop into a relay that chatters over a few counts at
    /// full torque (`tests/knob_closed_loop.rs`); below it a flicked knob comes to rest
    /// within about one count.
    ///
    /// [`Knob::new`]: crate::Knob::new
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    ///
    /// let count = core::f64::consts::TAU / 16384.0;
    /// let stiff = KnobConfig::new(1e-4, 1e-5, 0.05).detent_width(0.2).detent_strength(1.0);
    /// assert!(Knob::<f32>::new(&stiff, 0.0).is_ok());
    /// assert_eq!(
    ///     Knob::<f32>::new(&stiff.encoder_resolution(count), 0.0).unwrap_err(),
    ///     Error::OutOfRange(Parameter::Strength)
    /// );
    /// ```
    #[must_use]
    pub const fn encoder_resolution(mut self, angle_per_count: f64) -> Self {
        self.encoder_resolution = Some(angle_per_count);
        self
    }

    /// A spring back to `centre` over the whole range, of strength `strength` in `[0, 1]`.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).return_to_centre(0.0, 0.1);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.3).is_ok());
    /// ```
    #[must_use]
    pub const fn return_to_centre(mut self, centre: f64, strength: f64) -> Self {
        self.return_centre = centre;
        self.return_strength = strength;
        self
    }

    /// Magnetic detents at arbitrary angles (at most [`MAX_MAGNETS`], any order), each
    /// pulling the rotor within the [`magnet_radius`](Self::magnet_radius).
    ///
    /// [`MAX_MAGNETS`]: crate::knob::MAX_MAGNETS
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05).magnets(&[0.0, 1.0]).magnet_strength(0.1);
    /// assert!(Knob::<f32>::new(&c, 0.0).is_ok());
    /// let c = c.magnets(&[0.0; 9]);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err(), Error::CapacityFull);
    /// ```
    #[must_use]
    pub fn magnets(mut self, angles: &[f64]) -> Self {
        let n = angles.len().min(MAX_MAGNETS);
        self.magnets = [0.0; MAX_MAGNETS];
        self.magnets[..n].copy_from_slice(&angles[..n]);
        self.magnet_count = n;
        self.magnets_overflow = angles.len() > MAX_MAGNETS;
        self
    }

    /// The strength of the magnetic detents, in `[0, 1]` (default 0).
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05).magnets(&[0.5]).magnet_strength(0.2);
    /// assert!(stiffspring::Knob::<f32>::new(&c, 0.0).is_ok());
    /// ```
    #[must_use]
    pub const fn magnet_strength(mut self, strength: f64) -> Self {
        self.magnet_strength = strength;
        self
    }

    /// How close a magnetic detent captures the rotor (default: a quarter of the smallest
    /// spacing of the magnets, or 0.1 for a single one). Capture zones widened by the
    /// hysteresis must not overlap.
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05).magnets(&[0.0, 1.0]).magnet_radius(0.6);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0).unwrap_err(), Error::OutOfRange(Parameter::CaptureRadius));
    /// ```
    #[must_use]
    pub const fn magnet_radius(mut self, radius: f64) -> Self {
        self.magnet_radius = Some(radius);
        self
    }

    /// The stiffness at strength 1, in torque per angle unit: `C_k,top·I/dt²`. Divide a
    /// wanted stiffness by it to get a strength.
    ///
    /// # Errors
    ///
    /// As [`Knob::new`](crate::Knob::new), for `dt`, the inertia and the damping ratio.
    ///
    /// ```
    /// let c = stiffspring::KnobConfig::new(1e-3, 1e-5, 0.05);
    /// let k = c.stiffness_at_full_strength()?; // about 0.30 N·m/rad
    /// assert!(k > 0.25 && k < 0.35);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn stiffness_at_full_strength(&self) -> Result<f64, Error> {
        let dt = positive(self.dt, Parameter::TimeStep)?;
        let inertia = positive(self.inertia, Parameter::Inertia)?;
        let map = StrengthMap::new(self.damping_ratio, self.latency)?;
        Ok(map.top_stiffness() * inertia / (dt * dt))
    }
}

/// Everything the hot path needs, validated and in `f64`.
pub(crate) struct Validated {
    pub(crate) map: StrengthMap,
    /// `I/(dt²·τ_max)`: a step velocity change in angle units → torque fraction.
    pub(crate) gain: f64,
    /// The largest angle magnitude the hot path takes (inputs are clamped to it).
    pub(crate) reach: f64,
    pub(crate) dt: f64,
    pub(crate) torque_limit: f64,
    pub(crate) bounds: Option<(f64, f64)>,
    /// `(origin, width, threshold, (min, max) index)`, or `None` without detents.
    pub(crate) grid: Option<(f64, f64, f64, (i32, i32))>,
    pub(crate) hysteresis: f64,
    pub(crate) strengths: Strengths,
    pub(crate) return_centre: f64,
    pub(crate) magnets: [f64; MAX_MAGNETS],
    pub(crate) magnet_count: usize,
    pub(crate) magnet_radius: f64,
    pub(crate) encoder_resolution: Option<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Strengths {
    pub(crate) detent: f64,
    pub(crate) magnet: f64,
    pub(crate) ret: f64,
    pub(crate) endstop: f64,
}

/// Sums of strengths may exceed 1 by rounding (`0.7 + 0.3`); a few ULPs are accepted and
/// the sum clamped to 1.
const SUM_SLACK: f64 = 1e-12;

fn finite(value: f64, what: Parameter) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NotFinite(what))
    }
}

impl KnobConfig {
    /// Checks everything, for backend `S`.
    pub(crate) fn validate<S: Scalar>(&self) -> Result<Validated, Error> {
        let dt = positive(self.dt, Parameter::TimeStep)?;
        let inertia = positive(self.inertia, Parameter::Inertia)?;
        let torque_limit = positive(self.torque_limit, Parameter::TorqueLimit)?;
        let map = StrengthMap::new(self.damping_ratio, self.latency)?;
        let gain = inertia / (dt * dt) / torque_limit;
        // The gain must be a number the backend holds to 1 part in 1024, so that its
        // rounding changes the loop gain by less than the 1% slack of the margin check
        // (in I16F16 radians: G ≥ 1/64, e.g. 1 kHz with I/τ_max ≥ 1.6e−8 s²).
        // Above the range an extension of one unit would already saturate.
        let lsb = S::RESOLUTION;
        if !gain.is_finite() || gain < 1024.0 * lsb || gain >= S::SAFE_MAGNITUDE {
            return Err(Error::OutOfRange(Parameter::Inertia));
        }

        // Angles are clamped to a range where `G·(θ − anything in range)` stays finite in
        // a float backend (four times the range, times G, below the safe magnitude);
        // fixed point saturates instead, so it takes its whole safe range. Positions
        // given at set-up must lie within half of it.
        let reach = if S::RESOLUTION > 0.0 {
            S::SAFE_MAGNITUDE
        } else {
            S::SAFE_MAGNITUDE / (8.0 * gain.max(1.0))
        };
        let half = reach / 2.0;

        let bounds = match self.endstops {
            None => None,
            Some((lo, hi)) => {
                let lo = finite(lo, Parameter::Position)?;
                let hi = finite(hi, Parameter::Position)?;
                if lo >= hi || lo.abs().max(hi.abs()) > half {
                    return Err(Error::OutOfRange(Parameter::Position));
                }
                Some((lo, hi))
            }
        };
        let hysteresis = non_negative(self.hysteresis, Parameter::Hysteresis)?;

        let snap = finite(self.snap_point, Parameter::SnapPoint)?;
        if !(0.5..1.0).contains(&snap) {
            return Err(Error::OutOfRange(Parameter::SnapPoint));
        }
        let detent = check_strength(self.detent_strength)?;
        let layout = match (self.detents, bounds) {
            (DetentSpacing::None, _) => None,
            (DetentSpacing::Count(n), Some((lo, hi))) if n >= 2 => {
                Some((lo, (hi - lo) / f64::from(n - 1), Some(n - 1)))
            }
            (DetentSpacing::Count(_), _) => return Err(Error::OutOfRange(Parameter::DetentWidth)),
            (DetentSpacing::Width(w), Some((lo, hi))) => {
                let w = positive(w, Parameter::DetentWidth)?;
                // The last detent at or just below `max` (1e−9 absorbs the rounding of
                // a width that divides the range).
                let n = libm_free_floor((hi - lo) / w + 1e-9);
                if n > f64::from(i32::MAX) {
                    return Err(Error::OutOfRange(Parameter::DetentWidth));
                }
                Some((lo, w, Some(n as u32)))
            }
            (DetentSpacing::Width(w), None) => Some((
                finite(self.detent_origin, Parameter::Position)?,
                positive(w, Parameter::DetentWidth)?,
                None,
            )),
        };
        let grid = match layout {
            None => None,
            Some((origin, width, span)) => {
                // A width the backend resolves to 1% (100 LSB), so that its centres stay
                // where they were asked.
                if width < 100.0 * lsb || origin.abs() > half {
                    return Err(Error::OutOfRange(Parameter::DetentWidth));
                }
                let threshold = (snap * width).max(0.5 * width + hysteresis);
                if threshold >= width {
                    return Err(Error::OutOfRange(Parameter::Hysteresis));
                }
                let range = match span {
                    Some(n) => (0, n.min(i32::MAX as u32) as i32),
                    None => {
                        // Keep every centre within half the reach.
                        let n = libm_free_floor((half - origin.abs()) / width);
                        let n = n.min(f64::from(i32::MAX - 1));
                        (-(n as i32), n as i32)
                    }
                };
                Some((origin, width, threshold, range))
            }
        };

        let ret = check_strength(self.return_strength)?;
        let return_centre = finite(self.return_centre, Parameter::Position)?;
        if return_centre.abs() > half {
            return Err(Error::OutOfRange(Parameter::Position));
        }
        let magnet = check_strength(self.magnet_strength)?;
        let endstop = match self.endstop_strength {
            Some(s) => check_strength(s)?,
            None => 1.0 - ret,
        };
        if detent + magnet + ret > 1.0 + SUM_SLACK || endstop + ret > 1.0 + SUM_SLACK {
            return Err(Error::OutOfRange(Parameter::Strength));
        }

        if self.magnets_overflow {
            return Err(Error::CapacityFull);
        }
        let mut magnets = self.magnets;
        let count = self.magnet_count;
        for &m in &magnets[..count] {
            let m = finite(m, Parameter::Position)?;
            let outside = match bounds {
                Some((lo, hi)) => m < lo || m > hi,
                None => m.abs() > half,
            };
            if outside {
                return Err(Error::OutOfRange(Parameter::Position));
            }
        }
        // Insertion sort: at most MAX_MAGNETS elements, no allocation.
        for i in 1..count {
            let mut j = i;
            while j > 0 && magnets[j - 1] > magnets[j] {
                magnets.swap(j - 1, j);
                j -= 1;
            }
        }
        let spacing = magnets[..count]
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        let magnet_radius = match self.magnet_radius {
            Some(r) => positive(r, Parameter::CaptureRadius)?,
            None if spacing.is_finite() => 0.25 * spacing,
            None => 0.1,
        };
        if count > 0
            && (magnet_radius < 100.0 * lsb || spacing < 2.0 * (magnet_radius + hysteresis))
        {
            return Err(Error::OutOfRange(Parameter::CaptureRadius));
        }

        // Zones that cannot occur (beyond absent endstops, held by absent magnets) run
        // with nothing, so that only the zones that can occur are checked below and in
        // the knob.
        let endstop = if bounds.is_some() { endstop } else { 0.0 };
        let magnet = if count > 0 { magnet } else { 0.0 };

        let encoder_resolution = match self.encoder_resolution {
            Some(c) => Some(positive(c, Parameter::EncoderResolution)?),
            None => None,
        };

        Ok(Validated {
            encoder_resolution,
            map,
            gain,
            reach,
            dt,
            torque_limit,
            bounds,
            grid,
            hysteresis,
            strengths: Strengths {
                detent,
                magnet,
                ret,
                endstop,
            },
            return_centre,
            magnets,
            magnet_count: count,
            magnet_radius,
        })
    }
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

/// The index of the detent nearest to `angle`: `round((angle − origin)/width)`, clamped.
pub(crate) fn nearest_index(angle: f64, origin: f64, width: f64, (lo, hi): (i32, i32)) -> i32 {
    let x = (angle - origin) / width;
    let r = if x >= 0.0 {
        libm_free_floor(x + 0.5)
    } else {
        -libm_free_floor(-x + 0.5)
    };
    r.clamp(f64::from(lo), f64::from(hi)) as i32
}
