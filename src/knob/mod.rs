//! A haptic knob: detents, endstops, magnetic detents and a return spring, computed from
//! the measured rotor angle once per control period, with a closed-loop stability
//! guarantee.
//!
//! Firmware for a motorised knob (a BLDC motor under field-oriented control, as in
//! SmartKnob) calls [`Knob::update`] once per control loop, at 1–10 kHz, with the measured
//! rotor angle, and commands the torque it returns. Every spring goes through the crate's
//! two-body kernel, on a fixed anchor:
//!
//! ```text
//! Δu = respond(e, u) − u = −(C_k·e + C_d·u)        τ = (I/dt²)·Δu
//! ```
//!
//! with `e` the extension (the angle from the detent centre, endstop or magnet) and `u`
//! the backward difference of the angles.
//!
//! # Stability
//!
//! The torque acts on a real rotor through a zero-order hold, and the velocity is half a
//! period late; the loop is not the article's particle and its stable region is much
//! smaller (the article's rigid spring is unstable on a rotor). The [`stability`] module
//! derives it by Jury's test:
//!
//! ```text
//! 0 < C_d < 2,    0 < C_k < 2·C_d·(2 − C_d)/(2 + C_d)        (no delay)
//! ```
//!
//! and its numerical counterpart with one period of delay. Each strength in `[0, 1]` maps
//! into it with a gain margin of 2, and the strengths that act at the same time must sum
//! to at most 1, so **no configuration that [`Knob::new`] accepts makes the loop
//! unstable**. The torque clamp only lowers the loop gain (a saturation is a gain in
//! `[0, 1]` applied to the linear torque); flicks into a hard clamp are among the
//! closed-loop tests.
//!
//! # Torque in fixed point
//!
//! The output is the torque as a **fraction of the torque limit**, in `[−1, 1]`, which is
//! what a FOC current loop takes (`I_q = fraction·I_q,max`). The kernel runs on the
//! extension and step velocity scaled by `G = I/(dt²·τ_max)` (one multiply each), so its
//! output `Δu·G` already is that fraction. This keeps `I16F16` precise: `Δu` itself is
//! far below one LSB at 10 kHz (a rotor of `1e−5 kg·m²` at 10 kHz needs `Δu ≈ 1e−6 rad`
//! for 1% of a 0.1 N·m limit, a fifteenth of an LSB in radians), while the fraction has
//! 16 fractional bits. Measured against `f64` on the same angles
//! (`cargo test --release --test knob_fixed -- --nocapture`): the worst torque error of
//! `I16F16` is `1.2e−4` of the limit (8 of its LSB; radians, 1 to 10 kHz), of `f32`
//! `4e−6`. Choose the angle unit so that `G` lies in `[1/64, 32768)` for `I16F16`
//! (radians suit rotors of `1e−6` to `1e−4 kg·m²` at 1–10 kHz); set-up rejects the rest.
//!
//! # Compared with SmartKnob-style PD detents
//!
//! The same rotor (`1e−5 kg·m²`), 24 detents, snap point, hysteresis, torque limit and
//! small-signal stiffness `k_p`, one period of delay, a flick of 20 rad/s released on a
//! detent; the PD is `τ = −k_p·e − k_d·ω` with SmartKnob's raw `k_d = 0.005 s·k_p`
//! (`cargo test --release --test knob_vs_pd -- --nocapture`; 10 kHz in the README):
//!
//! | `k_p` (N·m/rad), 1 kHz | law | ζ | settle | overshoot | torque ripple at rest |
//! |---|---|---|---|---|---|
//! | 0.02 | SmartKnob PD | 0.11 | 764 ms | 95% | 0.24 mN·m |
//! | 0.02 | knob | 0.69 | 101 ms | 40% | 0.48 mN·m |
//! | 0.1 | SmartKnob PD | 0.25 | 177 ms | 59% | 0.42 mN·m |
//! | 0.1 | knob | 0.68 | 42 ms | 4% | 1.12 mN·m |
//! | 0.25 | SmartKnob PD | 0.40 | 75 ms | 39% | 1.15 mN·m |
//! | 0.25 | knob | 0.68 | 24 ms | 4% | 1.84 mN·m |
//!
//! The PD's damping ratio follows from its raw gains, so weak detents ring; the knob
//! places every strength at the same damping ratio, settles 2–7 times sooner, and
//! refuses gains outside the margin. Its stronger damping costs torque ripple at rest
//! (the damping acts on the encoder's one-count velocity steps).
//!
//! # Encoder resolution
//!
//! Where one count of extension and velocity commands more than the whole torque,
//! `(C_k + C_d)·G·count > 1` (very stiff strengths at 10 kHz with a 14-bit encoder), the
//! clamp makes the loop a relay that chatters over 1–4 counts at full torque; below it,
//! a flicked knob comes to rest within 1.4 counts (`tests/knob_closed_loop.rs`). Give the
//! knob its [`KnobConfig::encoder_resolution`] and it refuses such strengths.
//!
//! ```
//! use stiffspring::{Knob, KnobConfig};
//!
//! let count = core::f64::consts::TAU / 16384.0; // a 14-bit encoder
//! let config = KnobConfig::new(1e-3, 1e-5, 0.05) // 1 kHz, 1e−5 kg·m², 50 mN·m
//!     .endstops(0.0, 3.0)
//!     .detent_count(16)
//!     .detent_strength(0.05)
//!     .hysteresis(2.0 * count);
//! let mut knob = Knob::<f32>::new(&config, 0.0)?;
//!
//! // Turned a little past the first detent: pulled back.
//! let out = knob.update(0.05);
//! assert!(out.torque < 0.0 && out.torque >= -1.0);
//! assert_eq!(out.detent, 0);
//! // Past the snap point: the next detent pulls it forward.
//! let out = knob.update(0.2 * 0.56);
//! assert_eq!(out.detent, 1);
//! assert_eq!(out.events.detent_step, 1);
//! # Ok::<(), stiffspring::Error>(())
//! ```

mod config;
mod detents;
mod events;
pub mod stability;

pub use config::KnobConfig;
pub use detents::MAX_MAGNETS;
pub use events::{Endstop, KnobEvents};
pub use stability::{
    DAMPING_RATIO_RANGE, GAIN_MARGIN, Latency, StrengthMap, characteristic_polynomial, is_stable,
    same_step_stiffness_limit, spectral_radius,
};

use crate::error::{Error, Parameter};
use crate::kernel::Coefficients;
use crate::scalar::Scalar;
use crate::tuning::Tuning;
use config::nearest_index;
use detents::{Ladder, Magnets};

/// What one control period gives: the torque to command and the detent state.
///
/// ```
/// use stiffspring::{Knob, KnobConfig};
///
/// let mut knob = Knob::<f64>::new(&KnobConfig::new(1e-3, 1e-5, 0.05), 0.0)?;
/// let out = knob.update(0.0);
/// assert_eq!((out.torque, out.detent, out.events.any()), (0.0, 0, false));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct KnobOutput<S: Scalar> {
    /// The torque to command, as a fraction of the torque limit, in `[−1, 1]`.
    pub torque: S,
    /// The current detent index (0 at `min` with endstops; 0 at the origin without).
    pub detent: i32,
    /// What happened this period.
    pub events: KnobEvents,
}

/// The loop coefficients of one zone and the share of each layer's extension in it.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Zone<S: Scalar> {
    coefficients: Coefficients<S>,
    detent: S::Coef,
    other: S::Coef,
    ret: S::Coef,
}

/// Zones: inside the range and free, inside and held by a magnet, beyond an endstop.
const FREE: usize = 0;
const MAGNET: usize = 1;
const BEYOND: usize = 2;

/// A haptic knob in backend `S`: call [`Knob::update`] once per control period.
///
/// Set-up ([`Knob::new`]) validates the [`KnobConfig`] and precomputes everything in
/// `f64`; the per-period call has no `Result`, no division and no allocation, and gives a
/// finite torque in `[−1, 1]` for any finite angle.
///
/// ```
/// use stiffspring::{Knob, KnobConfig};
///
/// let config = KnobConfig::new(1e-4, 1e-5, 0.05).detent_width(0.1).detent_strength(0.01);
/// let mut knob = Knob::<f32>::new(&config, 0.0)?;
/// for n in 0..100 {
///     let angle = n as f32 * 1e-3; // the firmware reads its encoder here
///     let out = knob.update(angle);
///     assert!(out.torque.abs() <= 1.0);
/// }
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Knob<S: Scalar> {
    gain: S,
    step: S::Coef,
    lowest: S,
    highest: S,
    bounded: bool,
    lo: S,
    hi: S,
    lo_release: S,
    hi_release: S,
    return_centre: S,
    zones: [Zone<S>; 3],
    ladder: Ladder<S>,
    magnets: Magnets<S>,
    previous: S,
    beyond: Option<Endstop>,
    map: StrengthMap,
    torque_limit: f64,
    full_strength_stiffness: f64,
    zone_gains: [(f64, f64); 3],
    grid: Option<(f64, f64, (i32, i32))>,
}

impl<S: Scalar> Knob<S> {
    /// Builds a knob from `config`, at rest at `initial_angle` (which picks the starting
    /// detent).
    ///
    /// # Errors
    ///
    /// The first bad argument, as a typed [`Error`]:
    ///
    /// | argument | error |
    /// |---|---|
    /// | `dt`, inertia, torque limit not finite or `≤ 0` | `NotFinite` / `NotPositive` (`TimeStep`, `Inertia`, `TorqueLimit`) |
    /// | damping ratio outside [`DAMPING_RATIO_RANGE`] | `OutOfRange(DampingRatio)` |
    /// | `I/(dt²·τ_max)` not held by the backend to 1 part in 1024 | `OutOfRange(Inertia)` |
    /// | endstops not finite, `min ≥ max`, beyond half the backend's range | `NotFinite` / `OutOfRange(Position)` |
    /// | snap point outside `[0.5, 1)` | `OutOfRange(SnapPoint)` |
    /// | hysteresis negative, or switching point at or past the next centre | `Negative` / `OutOfRange(Hysteresis)` |
    /// | detent width `≤ 0`, below 100 LSB; a count below 2 or without endstops | `NotPositive` / `OutOfRange(DetentWidth)` |
    /// | a strength outside `[0, 1]`; strengths acting at once summing above 1 | `Negative` / `OutOfRange(Strength)` |
    /// | more than [`MAX_MAGNETS`] magnets | `CapacityFull` |
    /// | a magnet outside the endstops | `OutOfRange(Position)` |
    /// | capture radius `≤ 0`, or zones (plus hysteresis) overlapping | `OutOfRange(CaptureRadius)` |
    /// | encoder resolution not finite or `≤ 0` | `NotFinite` / `NotPositive(EncoderResolution)` |
    /// | with an encoder resolution: one count commanding more than the torque limit | `OutOfRange(Strength)` |
    /// | initial angle not finite or outside the backend's range | `NotFinite` / `OutOfRange(Position)` |
    ///
    /// ```
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    ///
    /// let too_strong = KnobConfig::new(1e-3, 1e-5, 0.05)
    ///     .detent_width(0.1)
    ///     .detent_strength(0.8)
    ///     .return_to_centre(0.0, 0.3);
    /// assert_eq!(
    ///     Knob::<f32>::new(&too_strong, 0.0).unwrap_err(),
    ///     Error::OutOfRange(Parameter::Strength)
    /// );
    /// ```
    pub fn new(config: &KnobConfig, initial_angle: f64) -> Result<Self, Error> {
        let v = config.validate::<S>()?;
        if !initial_angle.is_finite() {
            return Err(Error::NotFinite(Parameter::Position));
        }
        let reach = v.reach;
        if initial_angle.abs() > reach {
            return Err(Error::OutOfRange(Parameter::Position));
        }

        let st = v.strengths;
        let zone = |detent: f64, other: f64, ret: f64| -> Result<(Zone<S>, (f64, f64)), Error> {
            let total = (detent + other + ret).min(1.0);
            let (ck, cd) = v.map.coefficients(total)?;
            let tuning = Tuning::from_coefficients(ck, cd)?;
            let share = |s: f64| {
                if total > 0.0 {
                    S::coef(s / total)
                } else {
                    S::coef(0.0)
                }
            };
            let coefficients = Coefficients::new(&tuning);
            let actual = coefficients.tuning();
            Ok((
                Zone {
                    coefficients,
                    detent: share(detent),
                    other: share(other),
                    ret: share(ret),
                },
                (actual.stiffness(), actual.damping()),
            ))
        };
        let (free, free_gains) = zone(st.detent, 0.0, st.ret)?;
        let (magnet, magnet_gains) = zone(st.detent, st.magnet, st.ret)?;
        let (beyond, beyond_gains) = zone(0.0, st.endstop, st.ret)?;
        if let Some(count) = v.encoder_resolution {
            // The torque fraction one count of extension and of velocity command.
            for (ck, cd) in [free_gains, magnet_gains, beyond_gains] {
                if (ck + cd) * v.gain * count > 1.0 {
                    return Err(Error::OutOfRange(Parameter::Strength));
                }
            }
        }

        let ladder = match v.grid {
            Some((origin, width, threshold, range)) => {
                let index = nearest_index(initial_angle, origin, width, range);
                Ladder::new(origin, width, threshold, range, index)
            }
            None => Ladder::fixed(v.bounds.map_or(0.0, |(lo, _)| lo)),
        };
        let magnets = Magnets::new(
            &v.magnets[..v.magnet_count],
            v.magnet_radius,
            v.magnet_radius + v.hysteresis,
        );
        let (lo, hi) = v.bounds.unwrap_or((-reach, reach));
        let full_strength_stiffness = v.map.top_stiffness() * v.gain * v.torque_limit;
        let mut knob = Knob {
            gain: S::from_f64(v.gain),
            step: S::coef(v.dt),
            lowest: S::from_f64(-reach),
            highest: S::from_f64(reach),
            bounded: v.bounds.is_some(),
            lo: S::from_f64(lo),
            hi: S::from_f64(hi),
            lo_release: S::from_f64(lo + v.hysteresis),
            hi_release: S::from_f64(hi - v.hysteresis),
            return_centre: S::from_f64(v.return_centre),
            zones: [free, magnet, beyond],
            ladder,
            magnets,
            previous: S::from_f64(initial_angle),
            beyond: None,
            map: v.map,
            torque_limit: v.torque_limit,
            full_strength_stiffness,
            zone_gains: [free_gains, magnet_gains, beyond_gains],
            grid: v
                .grid
                .map(|(origin, width, _, range)| (origin, width, range)),
        };
        knob.reset(S::from_f64(initial_angle));
        Ok(knob)
    }

    /// Puts the knob at rest at `angle`: the previous angle (so the next velocity is
    /// zero), the nearest detent, the endstop and magnet states. For after the motor was
    /// off, or the encoder re-zeroed.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let config = KnobConfig::new(1e-3, 1e-5, 0.05).detent_width(0.5).detent_strength(0.1);
    /// let mut knob = Knob::<f64>::new(&config, 0.0)?;
    /// knob.reset(2.0);
    /// assert_eq!(knob.detent(), 4);
    /// assert_eq!(knob.update(2.0).torque, 0.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn reset(&mut self, angle: S) {
        let angle = self.sanitize(angle);
        self.previous = angle;
        if let Some((origin, width, range)) = self.grid {
            self.ladder
                .set_index(nearest_index(angle.to_f64(), origin, width, range));
        }
        self.magnets.reset();
        let _ = self.magnets.update(angle);
        self.beyond = if self.bounded && angle > self.hi {
            Some(Endstop::Max)
        } else if self.bounded && angle < self.lo {
            Some(Endstop::Min)
        } else {
            None
        };
    }

    /// Clamps an angle into the range the arithmetic is safe in; a NaN (a float backend
    /// only) holds the previous angle.
    #[inline(always)]
    fn sanitize(&self, angle: S) -> S {
        if angle > self.highest {
            self.highest
        } else if angle < self.lowest {
            self.lowest
        } else if angle >= self.lowest {
            angle
        } else {
            self.previous
        }
    }

    /// One control period: the torque for the measured `angle`, with the velocity taken
    /// as the backward difference from the previous call's angle.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let config = KnobConfig::new(1e-3, 1e-5, 0.05).endstops(-1.0, 1.0);
    /// let mut knob = Knob::<f32>::new(&config, 0.0)?;
    /// let out = knob.update(1.01); // past the upper endstop
    /// assert!(out.torque < 0.0);
    /// assert_eq!(out.events.endstop_hit, Some(stiffspring::knob::Endstop::Max));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline]
    pub fn update(&mut self, angle: S) -> KnobOutput<S> {
        let angle = self.sanitize(angle);
        let u = angle.sub(self.previous);
        self.period(angle, u)
    }

    /// One control period with the velocity supplied by the caller (angle units per
    /// second), for firmware that has an observer or a hardware velocity. The stability
    /// guarantee is proven for the backward difference; a velocity that is as recent as
    /// the angle only widens the region (`C_k < 2·C_d` instead), a low-pass-filtered one
    /// narrows it.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let config = KnobConfig::new(1e-3, 1e-5, 0.05).return_to_centre(0.0, 0.2);
    /// let mut knob = Knob::<f32>::new(&config, 0.0)?;
    /// // At the centre, moving forward: damping pushes back.
    /// assert!(knob.update_with_velocity(0.0, 1.0).torque < 0.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline]
    pub fn update_with_velocity(&mut self, angle: S, velocity: S) -> KnobOutput<S> {
        let angle = self.sanitize(angle);
        // Clamped like an angle difference; a NaN (float backends only) is no motion.
        let u = velocity.mul_coef(self.step);
        let u = if u > self.highest {
            self.highest
        } else if u < self.lowest {
            self.lowest
        } else if u >= self.lowest {
            u
        } else {
            S::ZERO
        };
        self.period(angle, u)
    }

    #[inline(always)]
    fn period(&mut self, angle: S, u: S) -> KnobOutput<S> {
        self.previous = angle;
        let mut events = KnobEvents {
            detent_step: self.ladder.update(angle),
            ..KnobEvents::default()
        };
        let (magnet_extension, captured, newly) = self.magnets.update(angle);
        events.magnet_captured = newly;

        // Which zone: beyond an endstop (the endstop replaces detents and magnets), held
        // by a magnet, or free.
        let above = self.bounded && angle > self.hi;
        let below = self.bounded && angle < self.lo;
        let (zone, other) = if above {
            (BEYOND, angle.sub(self.hi))
        } else if below {
            (BEYOND, angle.sub(self.lo))
        } else if captured {
            (MAGNET, magnet_extension)
        } else {
            (FREE, S::ZERO)
        };
        match self.beyond {
            None if above => {
                self.beyond = Some(Endstop::Max);
                events.endstop_hit = Some(Endstop::Max);
            }
            None if below => {
                self.beyond = Some(Endstop::Min);
                events.endstop_hit = Some(Endstop::Min);
            }
            Some(Endstop::Max) if angle < self.hi_release => self.beyond = None,
            Some(Endstop::Min) if angle > self.lo_release => self.beyond = None,
            _ => {}
        }

        let z = &self.zones[zone];
        // The zone's stiffness times its strength-weighted extension is the sum of the
        // layers' springs (`C_k,i = share_i·C_k`).
        let extension = angle
            .sub(self.ladder.centre())
            .mul_coef(z.detent)
            .add(other.mul_coef(z.other))
            .add(angle.sub(self.return_centre).mul_coef(z.ret));
        // Scaled by G = I/(dt²·τ_max), the kernel's Δu is the torque fraction.
        let e = extension.mul(self.gain);
        let w = u.mul(self.gain);
        let torque = z.coefficients.respond(e, w).sub(w);
        // The clamp; its last arm cannot be reached from clamped inputs, but keeps a NaN
        // from ever leaving.
        let torque = if torque > S::ONE {
            S::ONE
        } else if torque < S::ONE.neg() {
            S::ONE.neg()
        } else if torque >= S::ONE.neg() {
            torque
        } else {
            S::ZERO
        };
        KnobOutput {
            torque,
            detent: self.ladder.index(),
            events,
        }
    }

    /// The current detent index.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05).endstops(0.0, 1.0).detent_count(5);
    /// assert_eq!(Knob::<f32>::new(&c, 0.74)?.detent(), 3);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn detent(&self) -> i32 {
        self.ladder.index()
    }

    /// The torque limit the output is a fraction of (multiply to get the torque).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// assert_eq!(Knob::<f32>::new(&KnobConfig::new(1e-3, 1e-5, 0.05), 0.0)?.torque_limit(), 0.05);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn torque_limit(&self) -> f64 {
        self.torque_limit
    }

    /// The stiffness at strength 1, in torque per angle unit.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05);
    /// let k = Knob::<f64>::new(&c, 0.0)?.stiffness_at_full_strength();
    /// assert!((k - c.stiffness_at_full_strength()?).abs() < 1e-9 * k);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn stiffness_at_full_strength(&self) -> f64 {
        self.full_strength_stiffness
    }

    /// The strength map the knob was built with.
    ///
    /// ```
    /// use stiffspring::{knob::Latency, Knob, KnobConfig};
    /// let knob = Knob::<f32>::new(&KnobConfig::new(1e-3, 1e-5, 0.05), 0.0)?;
    /// assert_eq!(knob.strength_map().latency(), Latency::OneStep);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn strength_map(&self) -> StrengthMap {
        self.map
    }

    /// The loop coefficients `(C_k, C_d)` the knob runs with in each zone, as rounded to
    /// the backend: inside the range, held by a magnet, beyond an endstop. The stability
    /// tests check these.
    ///
    /// ```
    /// use stiffspring::{knob::{is_stable, Latency}, Knob, KnobConfig};
    /// let c = KnobConfig::new(1e-3, 1e-5, 0.05).detent_width(0.1).detent_strength(1.0);
    /// let knob = Knob::<f32>::new(&c, 0.0)?;
    /// for (ck, cd) in knob.loop_coefficients() {
    ///     assert!(is_stable(2.0 * ck, 2.0 * cd, Latency::OneStep) || ck == 0.0);
    /// }
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn loop_coefficients(&self) -> [(f64, f64); 3] {
        self.zone_gains
    }
}
