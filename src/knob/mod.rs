//! A haptic knob: detents, endstops, magnetic detents and a return spring, computed from
//! the measured rotor angle once per control period, set up in physical units, with a
//! closed-loop guarantee that covers what a linear stability test leaves out.
//!
//! Firmware for a motorised knob (a BLDC motor under field-oriented control, as in
//! SmartKnob) calls [`Knob::update`] once per control period, at 1–10 kHz, with the encoder
//! angle, and commands the torque it returns (a fraction of the torque limit, what a FOC
//! current loop takes: `I_q = fraction·I_q,max`).
//!
//! # Set-up in physical units
//!
//! [`KnobConfig`] takes the loop rate (Hz), the rotor's inertia (kg·m²), the torque limit
//! (N·m), the encoder's counts per turn and the latency; stiffnesses in N·m/rad (or a
//! detent's peak torque), damping as a ratio or in N·m·s/rad. The same configuration feels
//! the same at 1, 4 and 10 kHz: a stiffness is a stiffness. The dimensionless loop
//! (`C_k = K·dt²/J`, `C_d = B·dt/J`, the filter's `α`) stays available from
//! [`Knob::loop_coefficients`], with the analysis in [`stability`].
//!
//! # The torque law
//!
//! ```text
//! τ = −K_zone·dz(e) − B·v,      v ← v + α·((θ_n − θ_{n−1})/dt − v)
//! ```
//!
//! - `e` is the extension from the rest point (the detent centre, the endstop, the magnet,
//!   the return centre, weighted by their stiffnesses), `dz` a **rest zone** of one encoder
//!   count: a centre that falls between two counts no longer pushes the rotor back and
//!   forth.
//! - `v` is the backward difference of the angles through a **low-pass filter**. A
//!   backward difference of counts is a one-count kick; unfiltered, the damper turns it
//!   into an impulse that can reverse a slow rotor and pump energy (the limit cycles of
//!   issue 13). Filtered, the kick decays while the rotor turns around, which then loses
//!   energy. The filter is the longest the loop guarantee allows (up to `T_f = 0.25/ω`).
//! - **One damping `B` in every zone.** The zones (free, held by a magnet, beyond an
//!   endstop) only add stiffness, so the force is continuous at every boundary and a count
//!   crossed into a zone and back gives equal and opposite kicks. With a damping per zone,
//!   as before, a stiff endstop kicked a slow rotor back out harder than it came in, and
//!   a weak detent on the stop returned it: the 3–7-count, 12 Hz cycle of issue 13.
//! - **Endstops add to the detent field**, which continues past the stop, so a detent on
//!   the stop and the endstop meet without a jump, and an endstop counts as hit only past
//!   its rest zone (and again only after coming back by the hysteresis).
//! - It is the crate's kernel `Δu = −(C_k·e + C_d·u)` with `u` the filtered step
//!   velocity, scaled to the torque limit; the gains multiply the angles before anything
//!   is rounded (`law.rs`).
//!
//! # The guarantee
//!
//! [`Knob::new`] (and [`KnobDesign::new`], at compile time with [`knob!`](crate::knob!))
//! refuses, with a [`KnobError`] that names the argument the user set, its value and the
//! value of it that would pass, every configuration for which [`stability`] cannot show, in every zone:
//!
//! - for any rotor inertia from `J/2` to `2J`, every closed-loop pole has a damping ratio
//!   of at least 0.1 and decays at least a third as fast as the designed spring, with and
//!   without the period of delay of [`Latency::OneStep`];
//! - the loop stays stable at the reduced gains a saturating torque gives;
//! - a detent's (or magnet's) peak torque is within the torque limit (else the clamp
//!   makes it a relay, which limit-cycles: without this bound, 95 of 29,160 detent runs of
//!   a development version of the sweep below oscillated, up to 6,902 counts);
//! - one encoder count commands at most an eighth of the limit (a reading toggling between
//!   two counts then cannot buzz).
//!
//! # Measured
//!
//! **The sweep of issue 13** (`tests/knob_sweep.rs`, an independent ZOH rotor model in
//! `lab/src/knob/sweep.rs`; more in `docs/knob.md`):
//! 1, 4 and 10 kHz; `J` 1e−6, 1e−5, 1e−4 kg·m²; torque limits 0.02 and 0.1 N·m; `ζ` 0.2,
//! 0.7 and 2; both latencies, the one-step knob also run without delay; detent stiffnesses
//! 0.01, 0.03, 0.1, 0.3 and 1 of the stiffest accepted; 2, 24 and 100 detents, endless or
//! between endstops at ±135° (the last detent on each stop); encoders of 10, 12, 14 and
//! 16 bits; the rotor's inertia ½, 1 and 2 times the configured one; started 0.45 of a
//! detent off centre with a 5 rad/s flick, and with endstops also released 3 counts inside
//! the stop, on the last detent, 3 counts beyond it, and flicked into it; 1 s each.
//! "Oscillating" is more than 8 counts peak to peak over the last 10 % with at least 4
//! reversals.
//!
//! | sweep | configurations | runs | oscillating | command |
//! |---|---|---|---|---|
//! | full | 12,960 | 204,120 | **0** | `cargo test --release --test knob_sweep -- --ignored --nocapture` (minutes; ignored in a plain `cargo test`) |
//! | short, `f64`, `f32`, `I16F16` | 256 | 2,688 each | **0** | `cargo test --release --test knob_sweep -- --nocapture` |
//!
//! **Against SmartKnob-style PD detents** (`τ = −k_p·e − k_d·ω`, SmartKnob's
//! `k_d = 0.005 s·k_p`), with the same rotor (1e−5 kg·m²), 24 detents, snap point, torque
//! limit (50 mN·m), small-signal stiffness `k_p`, one period of delay and 14-bit encoder, a
//! flick of 20 rad/s released on a detent; ripple is the torque's peak to peak over the
//! last third of 1.5 s (`cargo test --release --test knob_vs_pd -- --nocapture`):
//!
//! | `k_p` (N·m/rad) | rate | PD: settle, ripple | knob (`ζ` 0.7): settle, ripple |
//! |---|---|---|---|
//! | 0.02 | 1 kHz | 764 ms, 0.24 mN·m | 78 ms, 0.07 mN·m |
//! | 0.1 | 1 kHz | 177 ms, 0.42 mN·m | 33 ms, 0.33 mN·m |
//! | 0.25 | 1 kHz | 75 ms, 1.15 mN·m | 27 ms, 1.06 mN·m |
//! | 0.02 | 10 kHz | 574 ms, 0.81 mN·m | 86 ms, 0.00 mN·m |
//! | 0.1 | 10 kHz | 133 ms, 3.87 mN·m | 42 ms, 0.31 mN·m |
//! | 0.25 | 10 kHz | 61 ms, 9.68 mN·m | 27 ms, 0.80 mN·m |
//!
//! The knob settles in 0.10–0.44 of the PD's time with less ripple at rest: the PD's
//! ripple is its damping on a one-count velocity step, `k_d·count/dt`, which grows with
//! the rate; the knob's is the filtered kick, which does not.
//!
//! # Fixed point, far from the origin
//!
//! The gains multiply the angles before anything is rounded, so `I16F16` keeps its 16
//! fractional bits in the torque (a detent of 26 /rad would otherwise multiply an angle's
//! LSB into 4e−4 of the limit), and the damper's filter state keeps four more bits. The
//! detent centre of a fixed-point knob is carried from detent to detent with the width's
//! remainder below one LSB kept to 2⁻³² LSB, so an endless `I16F16` knob stays on the
//! `f64` knob's grid over its whole range (`cargo test --release --test knob_fixed --
//! --nocapture`; torque error as a fraction of the limit, on the same angles):
//!
//! | case | `I16F16` | `I32F32` | `f32` |
//! |---|---|---|---|
//! | scripted hand through detents/magnets and endstops, 1–10 kHz | ≤ 5.5e−5 | ≤ 9.1e−10 | ≤ 3.0e−7 |
//! | endless, 100 detents per turn, 10 kHz, at 1,000 / 10,000 / 32,000 rad | 2.2e−4 / 2.1e−4 / 9.5e−5 | | |
//!
//! # Cost
//!
//! `Knob::update` on QEMU (`scripts/cost`; 1 kHz, 16 detents between endstops, an encoder
//! swept through both stops): 136 instructions on the Cortex-M4F in `f32`, 199 in
//! `I16F16`; 586 on the Cortex-M0 in `I16F16`. No `Result`, no division, no allocation.
//!
//! ```
//! use stiffspring::{Knob, KnobConfig};
//!
//! // 1 kHz, 1e−5 kg·m², 50 mN·m, a 14-bit encoder.
//! let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
//!     .endstops(0.0, 3.0)
//!     .detent_count(16)
//!     .detent_stiffness(0.05); // N·m/rad
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
//! # Ok::<(), stiffspring::knob::KnobError>(())
//! ```

// The set-up flows one way: config → validate → design (with stability) → compiled; the
// run time (law, detents, events) starts from the compiled design.
mod compiled;
mod config;
mod design;
mod detents;
mod error;
mod events;
mod law;
pub mod stability;
mod validate;

pub use compiled::KnobDesign;
#[doc(hidden)]
pub use compiled::refusal;
pub use config::{KnobConfig, Latency, MAX_MAGNETS};
pub use error::{KnobError, Limit, Zone};
pub use events::{Endstop, KnobEvents};
pub use stability::{
    DAMPING_RATIO_RANGE, DECAY_FRACTION, INERTIA_UNCERTAINTY, LoopCoefficients, MIN_DAMPING_RATIO,
    characteristic_polynomial, is_stable, meets_guarantee, spectral_radius,
};
pub use validate::MIN_LOOP_RATE;

use crate::error::Parameter;
use crate::scalar::Scalar;
use detents::{Ladder, Magnets};
use validate::nearest_index;

/// What one control period gives: the torque to command and the detent state.
///
/// ```
/// use stiffspring::{Knob, KnobConfig};
///
/// let mut knob = Knob::<f64>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 16384), 0.0)?;
/// let out = knob.update(0.0);
/// assert_eq!((out.torque, out.detent, out.events.any()), (0.0, 0, false));
/// # Ok::<(), stiffspring::knob::KnobError>(())
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

/// The gains of one zone: the stiffness of the layer that joins the detents and the
/// return spring there (magnet or endstop), per radian of the torque limit, and the rest
/// zone in torque (the zone's stiffness times one count).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct ZoneGains<S: Scalar> {
    other: S,
    rest: S,
}

/// Zones: inside the range and free, inside and held by a magnet, beyond an endstop.
const FREE: usize = 0;
const MAGNET: usize = 1;
const BEYOND: usize = 2;

/// A haptic knob in backend `S`: call [`Knob::update`] once per control period with the
/// encoder angle (radians, in `S`).
///
/// Set-up ([`Knob::new`]) validates the [`KnobConfig`] and designs the loop in `f64`; the
/// per-period call has no `Result`, no division and no allocation, and gives a finite
/// torque in `[−1, 1]` (a fraction of the torque limit) for any angle.
///
/// ```
/// use stiffspring::{Knob, KnobConfig};
///
/// let config = KnobConfig::new(10_000.0, 1e-5, 0.05, 16384).detent_width(0.1).detent_stiffness(0.2);
/// let mut knob = Knob::<f32>::new(&config, 0.0)?;
/// for n in 0..100 {
///     let angle = n as f32 * 1e-3; // the firmware reads its encoder here
///     let out = knob.update(angle);
///     assert!(out.torque.abs() <= 1.0);
/// }
/// # Ok::<(), stiffspring::knob::KnobError>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Knob<S: Scalar> {
    lowest: S,
    highest: S,
    previous: S,
    /// The damper's filtered torque times the state scale (a power of two up to
    /// `law::STATE_SCALE`), a fraction of the limit.
    damping_state: S,
    damping_gain: S,
    unscale: S::Coef,
    alpha: S::Coef,
    beta: S::Coef,
    step: S::Coef,
    detent_gain: S,
    return_gain: S,
    zones: [ZoneGains<S>; 3],
    bounded: bool,
    lo: S,
    hi: S,
    lo_hit: S,
    hi_hit: S,
    lo_release: S,
    hi_release: S,
    return_centre: S,
    ladder: Ladder<S>,
    magnets: Magnets<S>,
    beyond: Option<Endstop>,
    // Reports (set-up values, in f64).
    torque_limit: f64,
    damping: f64,
    filter_time: f64,
    rest_zone: f64,
    loop_coefficients: [Option<LoopCoefficients>; 3],
    zone_stiffness: [f64; 3],
    grid: Option<(f64, f64, (i32, i32))>,
}

impl<S: Scalar> Knob<S> {
    /// Builds a knob from `config`, at rest at `initial_angle` (which picks the starting
    /// detent): [`KnobDesign::new`] then [`Self::from_design`], at run time. A
    /// configuration known when the firmware is built is cheaper designed by the compiler
    /// ([`knob!`](crate::knob!)): the run-time path links the validation, the stability
    /// analysis and `f64` arithmetic (`docs/knob.md`, "Set-up at compile time").
    ///
    /// # Errors
    ///
    /// The first bad argument, as a [`KnobError`]: the crate-wide [`Error`](crate::Error)
    /// naming the argument the user set, the [`Limit`] it broke, its value and the bound's
    /// limit in the same units (for the loop's bounds, the value of that argument that
    /// would pass).
    ///
    /// | argument | parameter | bound, limit |
    /// |---|---|---|
    /// | rate not finite, `≤ 0`, below [`MIN_LOOP_RATE`] | `LoopRate` | `Finite` / `Positive` / `AtLeast` |
    /// | inertia, torque limit not finite or `≤ 0` | `Inertia`, `TorqueLimit` | `Finite` / `Positive` |
    /// | counts per turn 0, more than the backend resolves | `CountsPerTurn` | `Positive` / `AtMost` |
    /// | damping ratio outside [`DAMPING_RATIO_RANGE`]; damping negative | `DampingRatio`; `DampingConstant` | `AtLeast`/`AtMost`; `NotNegative` |
    /// | endstops not finite, `min ≥ max`, beyond half the backend's range | `Endstops` | `Finite` / `Below` / `BackendRange` |
    /// | snap point outside `[0.5, 1)` | `SnapPoint` | `AtLeast` / `Below` |
    /// | hysteresis negative, or switching point at or past the next centre | `Hysteresis` | `NotNegative` / `Below` |
    /// | detent width `≤ 0` or under four counts | `DetentWidth` | `Positive` / `AtLeast` |
    /// | detent count below 2, without endstops, more than fit at four counts each | `DetentCount` | `AtLeast` / `NeedsEndstops` / `AtMost` |
    /// | detent origin, return centre, magnet angles not finite or beyond the backend | `DetentOrigin`, `ReturnCentre`, `Magnets` | `Finite` / `BackendRange` |
    /// | a stiffness or peak torque negative or not finite | `DetentStiffness`, `DetentTorque`, `EndstopStiffness`, `ReturnStiffness`, `MagnetStiffness` | `NotNegative` / `Finite` |
    /// | a detent's or magnet's peak torque above the torque limit | `DetentStiffness` / `DetentTorque` / `MagnetStiffness` | [`Limit::PeakTorque`], the most whose peak fits |
    /// | a zone beyond the loop guarantee | what makes it that stiff: the detent, else the return spring; the magnet; the endstop if set | [`Limit::LoopStiffness`], the most that passes ([`KnobConfig::detent_stiffness_limit`] for a detent) |
    /// | springs that no stiffness of theirs makes pass at this rate | `LoopRate` | `AtLeast`, the least rate that passes |
    /// | damping beyond the loop guarantee | `DampingConstant` | [`Limit::LoopDamping`], the most that passes |
    /// | one encoder count commanding more than ⅛ of the limit in a zone | `CountsPerTurn` | [`Limit::CountTorque`], the counts per turn that pass |
    /// | more than [`MAX_MAGNETS`] magnets; a magnet outside the endstops | `CapacityFull`; `Magnets` | `Capacity`; `AtLeast` / `AtMost` |
    /// | capture radius too small, or zones overlapping | `CaptureRadius` | `AtLeast` / `AtMost` |
    /// | a gain or angle the backend cannot hold | the stiffness, damping or angle | [`Limit::BackendRange`] |
    /// | initial angle not finite or outside the backend's range | `Position` | `Finite` / `BackendRange` |
    ///
    /// ```
    /// use stiffspring::knob::{Limit, Zone};
    /// use stiffspring::{Error, Knob, KnobConfig, Parameter};
    ///
    /// let too_strong = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
    ///     .detent_width(0.1)
    ///     .detent_stiffness(0.8);
    /// let err = Knob::<f32>::new(&too_strong, 0.0).unwrap_err();
    /// assert_eq!(err.error.parameter(), Some(Parameter::DetentStiffness));
    /// assert_eq!(err.bound, Limit::LoopStiffness(Zone::Free));
    /// assert_eq!(err.value, 0.8);
    /// assert_eq!(err.limit, too_strong.detent_stiffness_limit::<f32>()?);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn new(config: &KnobConfig, initial_angle: S) -> Result<Self, KnobError> {
        Self::from_design(&KnobDesign::new(config)?, initial_angle)
    }

    /// Starts a knob from a [`KnobDesign`] (made at compile time with
    /// [`knob!`](crate::knob!), or at run time with [`KnobDesign::new`]), at rest at
    /// `initial_angle`. No validation and no loop design happen here: the firmware of a
    /// knob designed at compile time links neither.
    ///
    /// # Errors
    ///
    /// `NotFinite(Position)` for a NaN or infinite angle, `OutOfRange(Position)` with
    /// [`Limit::BackendRange`] for one beyond the backend's range.
    ///
    /// ```
    /// use stiffspring::knob::KnobDesign;
    /// use stiffspring::{Knob, KnobConfig, knob};
    ///
    /// const CONFIG: KnobConfig = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
    ///     .endstops(0.0, 3.0)
    ///     .detent_count(16)
    ///     .detent_stiffness(0.05);
    /// const DESIGN: KnobDesign<f32> = knob!(CONFIG);
    /// let knob = Knob::from_design(&DESIGN, 1.0)?;
    /// assert_eq!(knob.detent(), 5);
    /// assert!(Knob::from_design(&DESIGN, f32::NAN).is_err());
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn from_design(design: &KnobDesign<S>, initial_angle: S) -> Result<Self, KnobError> {
        let v = &design.design;
        let start = initial_angle.to_f64();
        let start = KnobError::finite(start, Parameter::Position)?;
        if start.abs() > v.reach {
            return Err(KnobError::range(
                Parameter::Position,
                Limit::BackendRange,
                start.abs(),
                v.reach,
            ));
        }
        let limit = v.torque_limit;
        let per_rad = |k: f64| S::from_f64(k / limit);
        let rest = |k: f64| S::from_f64(k / limit * v.count);
        let zones = [
            ZoneGains {
                other: S::ZERO,
                rest: rest(v.zone_stiffness[FREE]),
            },
            ZoneGains {
                other: per_rad(v.magnet),
                rest: rest(v.zone_stiffness[MAGNET]),
            },
            ZoneGains {
                other: per_rad(v.endstop),
                rest: rest(v.zone_stiffness[BEYOND]),
            },
        ];
        let ladder = match v.grid {
            Some(g) => {
                let index = nearest_index(start, g.origin, g.width, g.range);
                Ladder::new(g.origin, g.width, g.threshold, g.range, index)
            }
            None => Ladder::fixed(match v.bounds {
                Some((lo, _)) => lo,
                None => 0.0,
            }),
        };
        let magnets = Magnets::new(
            &v.magnets[..v.magnet_count],
            v.magnet_radius,
            v.magnet_radius + v.hysteresis,
        );
        let (lo, hi) = v.bounds.unwrap_or((-v.reach, v.reach));
        let mut knob = Knob {
            lowest: S::from_f64(-v.reach),
            highest: S::from_f64(v.reach),
            previous: initial_angle,
            damping_state: S::ZERO,
            damping_gain: S::from_f64(v.state_scale * v.damping / (limit * v.dt)),
            unscale: S::coef(1.0 / v.state_scale),
            alpha: S::coef(v.alpha),
            beta: S::coef(1.0 - v.alpha),
            step: S::coef(v.dt),
            detent_gain: per_rad(v.detent),
            return_gain: per_rad(v.ret),
            zones,
            bounded: v.bounds.is_some(),
            lo: S::from_f64(lo),
            hi: S::from_f64(hi),
            lo_hit: S::from_f64(lo - v.count),
            hi_hit: S::from_f64(hi + v.count),
            lo_release: S::from_f64(lo + v.hysteresis),
            hi_release: S::from_f64(hi - v.hysteresis),
            return_centre: S::from_f64(v.return_centre),
            ladder,
            magnets,
            beyond: None,
            torque_limit: limit,
            damping: v.damping,
            filter_time: v.dt * (1.0 - v.alpha) / v.alpha,
            rest_zone: v.count,
            loop_coefficients: v.zones,
            zone_stiffness: v.zone_stiffness,
            grid: v.grid.map(|g| (g.origin, g.width, g.range)),
        };
        knob.reset(initial_angle);
        Ok(knob)
    }

    /// Puts the knob at rest at `angle`: the previous angle (so the next velocity is
    /// zero), the damper's state, the nearest detent, the endstop and magnet states. For
    /// after the motor was off, or the encoder re-zeroed.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.5).detent_stiffness(0.05);
    /// let mut knob = Knob::<f64>::new(&config, 0.0)?;
    /// knob.reset(2.0);
    /// assert_eq!(knob.detent(), 4);
    /// assert_eq!(knob.update(2.0).torque, 0.0);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn reset(&mut self, angle: S) {
        let angle = self.sanitize(angle);
        self.previous = angle;
        self.damping_state = S::ZERO;
        if let Some((origin, width, range)) = self.grid {
            self.ladder
                .set_index(nearest_index(angle.to_f64(), origin, width, range));
        }
        self.magnets.reset();
        let _ = self.magnets.update(angle);
        self.beyond = if self.bounded && angle > self.hi_hit {
            Some(Endstop::Max)
        } else if self.bounded && angle < self.lo_hit {
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

    /// One control period: the torque for the measured `angle` (radians), with the
    /// velocity taken as the backward difference from the previous call's angle.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(-1.0, 1.0);
    /// let mut knob = Knob::<f32>::new(&config, 0.0)?;
    /// let out = knob.update(1.01); // past the upper endstop
    /// assert!(out.torque < 0.0);
    /// assert_eq!(out.events.endstop_hit, Some(stiffspring::knob::Endstop::Max));
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    #[inline]
    pub fn update(&mut self, angle: S) -> KnobOutput<S> {
        let angle = self.sanitize(angle);
        let u = angle.sub(self.previous);
        self.period(angle, u)
    }

    /// One control period with the velocity supplied by the caller (radians per second),
    /// for firmware that has an observer or a hardware velocity. It goes through the same
    /// filter; the guarantee is for the backward difference of the angles.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).return_to_centre(0.0, 0.01);
    /// let mut knob = Knob::<f32>::new(&config, 0.0)?;
    /// // At the centre, moving forward: damping pushes back.
    /// assert!(knob.update_with_velocity(0.0, 1.0).torque < 0.0);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
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
        self.damping_state = law::filtered_damping(
            self.damping_state,
            u,
            self.damping_gain,
            self.alpha,
            self.beta,
        );
        let mut events = KnobEvents {
            detent_step: self.ladder.update(angle),
            ..KnobEvents::default()
        };
        let (magnet_extension, captured, newly) = self.magnets.update(angle);
        events.magnet_captured = newly;

        // Which zone: beyond an endstop (the endstop adds to the detents; magnets are
        // off), held by a magnet, or free.
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
        // An endstop is hit past its rest zone, and again only after coming back inside
        // by the hysteresis.
        match self.beyond {
            None if self.bounded && angle > self.hi_hit => {
                self.beyond = Some(Endstop::Max);
                events.endstop_hit = Some(Endstop::Max);
            }
            None if self.bounded && angle < self.lo_hit => {
                self.beyond = Some(Endstop::Min);
                events.endstop_hit = Some(Endstop::Min);
            }
            Some(Endstop::Max) if angle < self.hi_release => self.beyond = None,
            Some(Endstop::Min) if angle > self.lo_release => self.beyond = None,
            _ => {}
        }

        let z = &self.zones[zone];
        let spring = law::spring(
            (
                angle.sub(self.ladder.centre()),
                other,
                angle.sub(self.return_centre),
            ),
            (self.detent_gain, z.other, self.return_gain),
            z.rest,
        );
        KnobOutput {
            torque: law::torque(
                spring,
                law::damping_torque(self.damping_state, self.unscale),
            ),
            detent: self.ladder.index(),
            events,
        }
    }

    /// The current detent index.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(0.0, 1.0).detent_count(5);
    /// assert_eq!(Knob::<f32>::new(&c, 0.74)?.detent(), 3);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn detent(&self) -> i32 {
        self.ladder.index()
    }

    /// The torque limit the output is a fraction of (multiply to get the torque).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let knob = Knob::<f32>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 16384), 0.0)?;
    /// assert_eq!(knob.torque_limit(), 0.05);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn torque_limit(&self) -> f64 {
        self.torque_limit
    }

    /// The damping, N·m·s/rad (the same in every zone).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.2).detent_stiffness(0.1);
    /// let b = Knob::<f32>::new(&c, 0.0)?.damping(); // 2·0.7·√(0.1·1e−5)
    /// assert!((b - 1.4 * 1e-6f64.sqrt()).abs() < 1e-12);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn damping(&self) -> f64 {
        self.damping
    }

    /// The time constant of the velocity filter, in seconds (0: no filter).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.2).detent_stiffness(0.1);
    /// let tf = Knob::<f32>::new(&c, 0.0)?.filter_time_constant();
    /// assert!(tf > 0.0 && tf < 0.01);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn filter_time_constant(&self) -> f64 {
        self.filter_time
    }

    /// The rest zone: how far (radians, one encoder count) from its rest point the spring
    /// is zero.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let knob = Knob::<f32>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 4096), 0.0)?;
    /// assert_eq!(knob.rest_zone(), core::f64::consts::TAU / 4096.0);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn rest_zone(&self) -> f64 {
        self.rest_zone
    }

    /// The total stiffness (N·m/rad) of each zone: free, held by a magnet, beyond an
    /// endstop (zones that cannot occur report what they would be).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
    ///     .endstops(0.0, 3.0).detent_count(16).detent_stiffness(0.05).endstop_stiffness(0.1);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0)?.zone_stiffness(), [0.05, 0.05, 0.15000000000000002]);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn zone_stiffness(&self) -> [f64; 3] {
        self.zone_stiffness
    }

    /// The coefficient view: each zone's dimensionless loop `(C_k, C_d, α)` with the
    /// configured inertia, as checked at set-up (`None` for a zone that cannot occur):
    /// free, held by a magnet, beyond an endstop.
    ///
    /// ```
    /// use stiffspring::knob::{meets_guarantee, Latency};
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.1).detent_stiffness(0.2);
    /// let knob = Knob::<f32>::new(&c, 0.0)?;
    /// let [free, magnet, beyond] = knob.loop_coefficients();
    /// assert!(free.is_some() && magnet.is_none() && beyond.is_none());
    /// assert!(stiffspring::knob::is_stable(free.unwrap(), Latency::OneStep));
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn loop_coefficients(&self) -> [Option<LoopCoefficients>; 3] {
        self.loop_coefficients
    }
}
