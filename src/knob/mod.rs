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
//! τ = −K_zone·knee(dz(e)) − B·v,   p ← clamp(p, θ − w, θ + w),   v ← v + α·((p_n − p_{n−1})/dt − v)
//! ```
//!
//! - `e` is the extension from the rest point (the detent centre, the endstop, the magnet,
//!   the return centre, weighted by their stiffnesses), `dz` a **rest zone** of
//!   [`REST_COUNTS`] counts followed by a soft knee of up to [`KNEE_COUNTS`], and the
//!   damper sees the angle through a play of [`PLAY_COUNTS`]: the knob is silent at rest
//!   (`law.rs` has why; `docs/knob.md` the measurements).
//! - **Sensor faults**: a reading that is NaN, out of reach, or farther than the motor and
//!   a hand can move the rotor in a period is not used (`screen.rs`, [`SensorFault`]).
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
//! docs/knob.md has the tables of both sweeps, written by their tests (`cargo test
//! --release --test knob_sweep -- --nocapture` for the short one, `-- --ignored` for the
//! full one, which takes minutes).
//!
//! **Against SmartKnob-style PD detents** (`τ = −k_p·e − k_d·ω`), with the same rotor,
//! detents, torque limit, small-signal stiffness `k_p`, delay and encoder, flicked at
//! 20 rad/s: the knob settles in 0.10–0.43 of the time of SmartKnob's own PD
//! (`k_d = 0.005 s·k_p`, lightly damped), and in 0.77–1.17 of the time of a PD with the
//! knob's own damping, with less ripple at rest in most cases. docs/knob.md has the table
//! (`cargo test --release --test knob_vs_pd -- --nocapture` writes it).
//!
//! # Fixed point, far from the origin
//!
//! The gains multiply the angles before anything is rounded, so `I16F16` keeps its 16
//! fractional bits in the torque (a detent of 26 /rad would otherwise multiply an angle's
//! LSB into 4e−4 of the limit), and the damper's filter state keeps four more bits. The
//! detent centre of a fixed-point knob is carried from detent to detent with the width's
//! remainder below one LSB kept to 2⁻³² LSB, so an endless `I16F16` knob stays on the
//! `f64` knob's grid over its whole range. `tests/knob_fixed.rs` asserts the torque within
//! 1e−3 of the limit of the `f64` knob's on the same angles in `I16F16` (2.5e−3 for a
//! stiff endless knob out to 32,000 rad); docs/knob.md has the measured figures.
//!
//! # Cost
//!
//! `Knob::update` on QEMU (`scripts/cost`; 1 kHz, 16 detents between endstops, an encoder
//! swept up and down through both stops): docs/knob.md's table, generated by that script,
//! gives the instructions on the Cortex-M4F in `f32` and `I16F16` and on the Cortex-M0 in
//! `I16F16`. No `Result`, no division, no allocation.
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
//! // Turned at 1 rad/s a little past the first detent: pulled back.
//! let mut out = knob.update(0.0);
//! for n in 1..=50 {
//!     out = knob.update(n as f32 * 1e-3);
//! }
//! assert!(out.torque < 0.0 && out.torque >= -1.0);
//! assert_eq!(out.detent, 0);
//! // On past the snap point (0.56 of the 0.2 rad width): the next detent pulls it forward.
//! let mut steps = 0;
//! for n in 51..=120 {
//!     out = knob.update(n as f32 * 1e-3);
//!     steps += out.events.detent_step;
//! }
//! assert_eq!((out.detent, steps), (1, 1));
//! assert!(out.torque > 0.0);
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
mod parts;
mod reconfigure;
mod screen;
pub mod stability;
mod validate;

pub use compiled::KnobDesign;
#[doc(hidden)]
pub use compiled::refusal;
pub use config::{KnobConfig, Latency, MAX_MAGNETS};
pub use error::{KnobError, Limit, Zone};
pub use events::{Endstop, KnobEvents, SensorFault};
pub use law::{KNEE_COUNTS, MIN_PLAY_COUNTS, PLAY_COUNTS, REST_COUNTS};
pub use reconfigure::Anchor;
pub use screen::{AGREE_STEPS, FADE_PERIODS, HOLD_PERIODS};
pub use stability::{
    DAMPING_RATIO_RANGE, DECAY_FRACTION, INERTIA_UNCERTAINTY, LoopCoefficients, MIN_DAMPING_RATIO,
    characteristic_polynomial, is_stable, meets_guarantee, spectral_radius,
};
pub use validate::MIN_LOOP_RATE;

use crate::error::Parameter;
use crate::scalar::Scalar;
use core::mem::MaybeUninit;
use detents::{Ladder, Magnets};
use law::Shape;
use screen::Mode;

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
/// zone and knee in torque (the zone's stiffness times their widths).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct ZoneGains<S: Scalar> {
    other: S,
    shape: Shape<S>,
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
    /// The largest angle the arithmetic holds, either way (`Knob::reach`).
    reach: S,
    /// The last reading the law used.
    previous: S,
    /// Its movement from the one before (radians per period).
    last_step: S,
    /// The play's output, which the damper differentiates, and its half-width.
    held: S,
    play: S,
    /// The screen (`screen.rs`): the largest change of movement per period a good
    /// reading has while tracking, negative otherwise, so that the hot path's test fails;
    /// the same bound whatever the mode; the largest movement per period.
    gate: S,
    jolt: S,
    max_step: S,
    mode: Mode,
    /// The last torque commanded, held after a bad reading.
    last_torque: S,
    /// While lost: the last reading and its step from the one before.
    candidate: S,
    candidate_step: S,
    /// `1/FADE_PERIODS`, the fade's step, and while fading in the fraction of the
    /// torque given (the fade's steps so far times the step), whose reaching 1 ends the
    /// fade.
    fade_unit: S,
    fade: S,
    /// After a reconfiguration: the old layout's torque less the new one's, and the most
    /// it moves to zero per period (one count's torque in the free zone, at least
    /// 1/256 of the limit).
    offset: S,
    slew: S,
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
    floor: S,
    bounded: bool,
    lo: S,
    hi: S,
    lo_hit: S,
    hi_hit: S,
    lo_release: S,
    hi_release: S,
    return_centre: S,
    /// `1/width` of the detents (0 without), for [`Knob::detent_fraction`].
    inverse_width: S,
    ladder: Ladder<S>,
    magnets: Magnets<S>,
    beyond: Option<Endstop>,
    /// The quiet window (`Self::period`): a reading in `[quiet_lo, quiet_hi]` makes the
    /// common period, which takes the short path: tracking, inside the detent's
    /// switching points and the endstops, past no endstop, without magnets. Empty
    /// (`quiet_lo > quiet_hi`) where the period is not the common one; set again after
    /// every period that took the long path (`Self::refresh_quiet`).
    quiet_lo: S,
    quiet_hi: S,
    // Reports (set-up values, in f64).
    torque_limit: f64,
    damping: f64,
    filter_time: f64,
    rest_zone: f64,
    knee: f64,
    /// [`KnobConfig::max_speed`], or 0 for none (a maximum speed is positive): eight
    /// bytes fewer than an `Option<f64>`, which keeps the knob in the C API's handle.
    max_speed: f64,
    zone_stiffness: [f64; 3],
    // What `loop_coefficients` derives its report from (`LoopCoefficients::of`), with
    // `zone_stiffness`, `damping` and the zones that occur (`bounded`, the magnets), in
    // place of the report itself: 24 bytes instead of 96, and a knob started from a
    // `const` design copies no array of `f64` out of it (the copy that linked `memcpy`).
    dt: f64,
    inertia: f64,
    filter_alpha: f64,
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
        Self::check_start(design, initial_angle)?;
        let mut knob = Self::from_parts(design, initial_angle);
        knob.start(initial_angle);
        Ok(knob)
    }

    /// [`Knob::from_design`], built in `slot` instead of returned: for a knob kept in
    /// storage of its own (a `static` through `StaticCell::uninit`, a C caller's buffer).
    /// A knob is about 500 bytes, and moving one out of a `Result` copies all of it; built
    /// in place, a firmware whose only knob is started here links no `memcpy` (on the
    /// Cortex-M4F, `scripts/size-report`'s `knob_f32_const`). `slot` is written only when
    /// this returns `Ok`.
    ///
    /// # Errors
    ///
    /// As [`Knob::from_design`].
    ///
    /// ```
    /// use core::mem::MaybeUninit;
    /// use stiffspring::knob::KnobDesign;
    /// use stiffspring::{Knob, KnobConfig, knob};
    ///
    /// const DESIGN: KnobDesign<f32> = knob!(KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
    ///     .endstops(0.0, 3.0)
    ///     .detent_count(16)
    ///     .detent_stiffness(0.05));
    /// let mut slot = MaybeUninit::uninit();
    /// let knob = Knob::from_design_in(&mut slot, &DESIGN, 1.0)?;
    /// assert_eq!(knob.detent(), 5);
    /// assert!(Knob::from_design_in(&mut MaybeUninit::uninit(), &DESIGN, f32::NAN).is_err());
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn from_design_in<'a>(
        slot: &'a mut MaybeUninit<Self>,
        design: &KnobDesign<S>,
        initial_angle: S,
    ) -> Result<&'a mut Self, KnobError> {
        Self::check_start(design, initial_angle)?;
        let knob = slot.write(Self::from_parts(design, initial_angle));
        knob.start(initial_angle);
        Ok(knob)
    }

    /// Refuses an initial angle the backend cannot hold, or NaN.
    fn check_start(design: &KnobDesign<S>, initial_angle: S) -> Result<(), KnobError> {
        // Checked in the backend's arithmetic: a NaN fails the comparison.
        if initial_angle.abs() <= design.parts.reach.get() {
            return Ok(());
        }
        let start = initial_angle.to_f64();
        KnobError::finite(start, Parameter::Position)?;
        Err(KnobError::range(
            Parameter::Position,
            Limit::BackendRange,
            start.abs(),
            design.design.reach,
        ))
    }

    /// The knob of `design` at `initial_angle`, before its detent and states are found
    /// ([`Self::start`]). Inlined, so that [`Self::from_design_in`] writes it in place.
    #[inline(always)]
    fn from_parts(design: &KnobDesign<S>, initial_angle: S) -> Self {
        let v = &design.design;
        let p = &design.parts;
        let zone = |z: &parts::ZoneParts<S>| ZoneGains {
            other: z.other.get(),
            shape: Shape {
                rest: z.rest.get(),
                knee: z.knee.get(),
                half_knee: z.half_knee.get(),
                curvature: z.curvature.get(),
            },
        };
        let jolt = p.jolt.get();
        Knob {
            reach: p.reach.get(),
            previous: initial_angle,
            last_step: S::ZERO,
            held: initial_angle,
            play: p.play.get(),
            gate: jolt,
            jolt,
            max_step: p.max_step.get(),
            mode: Mode::Tracking,
            last_torque: S::ZERO,
            candidate: initial_angle,
            candidate_step: S::ZERO,
            fade_unit: p.fade_unit.get(),
            fade: S::ZERO,
            offset: S::ZERO,
            slew: p.slew.get(),
            damping_state: S::ZERO,
            damping_gain: p.damping_gain.get(),
            unscale: p.unscale.get(),
            alpha: p.alpha.get(),
            beta: p.beta.get(),
            step: p.step.get(),
            detent_gain: p.detent_gain.get(),
            return_gain: p.return_gain.get(),
            zones: [zone(&p.zones[0]), zone(&p.zones[1]), zone(&p.zones[2])],
            floor: p.floor.get(),
            bounded: v.bounds.is_some(),
            lo: p.lo.get(),
            hi: p.hi.get(),
            lo_hit: p.lo_hit.get(),
            hi_hit: p.hi_hit.get(),
            lo_release: p.lo_release.get(),
            hi_release: p.hi_release.get(),
            return_centre: p.return_centre.get(),
            inverse_width: p.inverse_width.get(),
            ladder: Ladder::from_parts(&p.ladder),
            magnets: Magnets::from_parts(&p.magnets),
            beyond: None,
            // Empty until `start` sets it.
            quiet_lo: p.reach.get(),
            quiet_hi: p.reach.get().neg(),
            torque_limit: v.torque_limit,
            damping: v.damping,
            filter_time: p.filter_time,
            rest_zone: p.rest_zone,
            knee: p.knee,
            max_speed: v.max_speed.unwrap_or(0.0),
            // Element by element: each load from a `const` design folds to an immediate,
            // where the copy of the array was one block copy out of the design, the last
            // use that kept the whole design constant in flash (1 KB of `knob_f32_const`
            // on the Cortex-M4F, `scripts/size-report`).
            zone_stiffness: [
                v.zone_stiffness[0],
                v.zone_stiffness[1],
                v.zone_stiffness[2],
            ],
            dt: v.dt,
            inertia: v.inertia,
            filter_alpha: v.alpha,
        }
    }

    /// The nearest detent to the initial angle, walked to from the set-up's index, and
    /// the knob at rest there.
    fn start(&mut self, initial_angle: S) {
        self.ladder.settle(initial_angle);
        self.reset(initial_angle);
    }

    /// Puts the knob at rest at `angle`: the previous angle (so the next velocity is
    /// zero), the damper's state, the nearest detent, the endstop and magnet states, and
    /// the sensor screen (a fault is forgotten). For after the motor was off, or the
    /// encoder re-zeroed. A NaN or out-of-range `angle` (see [`Knob::reach`]) keeps the
    /// last good angle.
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
        let angle = if self.in_reach(angle) {
            angle
        } else {
            self.previous
        };
        self.previous = angle;
        self.held = angle;
        self.last_step = S::ZERO;
        self.damping_state = S::ZERO;
        self.last_torque = S::ZERO;
        self.mode = Mode::Tracking;
        self.gate = self.jolt;
        let _ = self.ladder.seek(angle);
        self.magnets.reset();
        let _ = self.magnets.update(angle);
        self.beyond = self.beyond_at(angle);
        self.refresh_quiet();
    }

    /// Sets the quiet window (`quiet_lo`, `quiet_hi`) for the next period: the current
    /// detent's switching points within the endstops while the period would be the common
    /// one, and empty otherwise. One copy out of line for its four callers.
    #[inline(never)]
    fn refresh_quiet(&mut self) {
        let common =
            matches!(self.mode, Mode::Tracking) && self.beyond.is_none() && !self.magnets.any();
        (self.quiet_lo, self.quiet_hi) = if common {
            // No switching point that way: the largest angle the knob takes.
            let (down, up) = self.ladder.switching_points();
            let (down, up) = (down.unwrap_or(self.reach.neg()), up.unwrap_or(self.reach));
            if self.bounded {
                (
                    if down > self.lo { down } else { self.lo },
                    if up < self.hi { up } else { self.hi },
                )
            } else {
                (down, up)
            }
        } else {
            // `reach > 0`: no reading is at once at least `reach` and at most `−reach`.
            (self.reach, self.reach.neg())
        };
    }

    /// True for an angle inside the range the arithmetic holds (never for a NaN).
    #[inline(always)]
    fn in_reach(&self, angle: S) -> bool {
        // The reach is symmetric about 0 (and in fixed point the whole range, which
        // `abs` saturates into): one comparison.
        angle.abs() <= self.reach
    }

    /// The endstop the rotor is past at `angle` (beyond its rest zone and knee).
    fn beyond_at(&self, angle: S) -> Option<Endstop> {
        if self.bounded && angle > self.hi_hit {
            Some(Endstop::Max)
        } else if self.bounded && angle < self.lo_hit {
            Some(Endstop::Min)
        } else {
            None
        }
    }

    /// One control period: the torque for the measured `angle` (radians), with the
    /// velocity taken from the movement of the angles.
    ///
    /// A reading that cannot be physical (NaN, infinite, beyond [`Knob::reach`], or
    /// moving farther than [`Knob::max_jolt`] or the configured
    /// [`max_speed`](KnobConfig::max_speed) allow) is not used: the knob holds its last
    /// torque for [`HOLD_PERIODS`] periods, then commands none, and reports
    /// [`KnobEvents::sensor`]; it takes the readings up again once [`AGREE_STEPS`] steps
    /// agree, reports [`KnobEvents::resynced`], and fades the torque in over
    /// [`FADE_PERIODS`] periods. A single bad reading followed by one that continues the
    /// motion costs one held period and nothing else.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(-1.0, 1.0);
    /// let mut knob = Knob::<f32>::new(&config, 0.99)?;
    /// let out = knob.update(1.01); // past the upper endstop
    /// assert!(out.torque < 0.0);
    /// assert_eq!(out.events.endstop_hit, Some(stiffspring::knob::Endstop::Max));
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    // Never inlined: the firmware calls it from one place, and the screen's cold path
    // (`recover`) calls it too, which would otherwise carry a second copy of the law.
    #[inline(never)]
    pub fn update(&mut self, angle: S) -> KnobOutput<S> {
        let step = angle.sub(self.previous);
        let surprise = step.sub(self.last_step);
        // NaN fails every comparison; a knob not tracking has a negative gate.
        if surprise.abs() <= self.gate
            && step.abs() <= self.max_step
            && (S::RESOLUTION > 0.0 || self.in_reach(angle))
        {
            self.last_step = step;
            let held = law::play(self.held, angle, self.play);
            let u = held.sub(self.held);
            self.held = held;
            self.period(angle, u)
        } else {
            self.recover(angle)
        }
    }

    /// One control period with the velocity supplied by the caller (radians per second),
    /// for firmware that has an observer or a hardware velocity. It goes through the same
    /// filter (not through the play) and the same screen of the angle; the guarantee is
    /// for the angles' movement.
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
        // Clamped like an angle difference; a NaN (float backends only) is no motion.
        let u = velocity.mul_coef(self.step);
        let u = if u > self.max_step {
            self.max_step
        } else if u < self.max_step.neg() {
            self.max_step.neg()
        } else if u >= self.max_step.neg() {
            u
        } else {
            S::ZERO
        };
        let step = angle.sub(self.previous);
        let surprise = step.sub(self.last_step);
        if surprise.abs() <= self.gate && step.abs() <= self.max_step && self.in_reach(angle) {
            self.last_step = step;
            self.held = law::play(self.held, angle, self.play);
            self.period(angle, u)
        } else {
            self.recover(angle)
        }
    }

    /// The cold path of the screen (`screen.rs`): a reading that failed the hot test,
    /// or any reading while the knob is not tracking.
    #[cold]
    #[inline(never)]
    fn recover(&mut self, angle: S) -> KnobOutput<S> {
        let out = self.recover_reading(angle);
        self.refresh_quiet();
        out
    }

    /// [`Self::recover`]'s decision: what a reading that failed the hot test does.
    fn recover_reading(&mut self, angle: S) -> KnobOutput<S> {
        let fault = if angle.partial_cmp(&angle).is_none() {
            Some(SensorFault::NotANumber)
        } else if !self.in_reach(angle) {
            Some(SensorFault::OutOfRange)
        } else {
            None
        };
        let step = angle.sub(self.previous);
        let fits = |bound: S, x: S| x.abs() <= bound;
        match (self.mode, fault) {
            // One bad reading, and this one continues the motion from before it: go on
            // as if the missed period had moved the rotor at the same speed.
            (Mode::Holding { missed: 1 }, None)
                if fits(
                    self.jolt.add(self.jolt).add(self.jolt),
                    step.sub(self.last_step).sub(self.last_step),
                ) && fits(self.max_step, step.sub(self.last_step)) =>
            {
                self.previous = self.previous.add(self.last_step);
                self.held = self.held.add(self.last_step);
                self.mode = Mode::Tracking;
                self.gate = self.jolt;
                // (A caller's velocity is taken up again from the next period.)
                self.update(angle)
            }
            // A good reading of a rotor turning too fast for the configured maximum
            // speed, in step with the one before: the torque goes off at once.
            (Mode::Tracking | Mode::Fading | Mode::Blending, None)
                if !fits(self.max_step, step) && fits(self.jolt, step.sub(self.last_step)) =>
            {
                self.lose(angle, step, 2);
                self.fault_output(Some(SensorFault::TooFast), S::ZERO)
            }
            // The first bad reading: hold the last torque.
            (Mode::Tracking | Mode::Fading | Mode::Blending, _) => {
                self.mode = Mode::Holding { missed: 1 };
                self.gate = S::ONE.neg();
                // A reconfiguration's blend ends here: the torque fades in from zero
                // when the readings are taken up again.
                self.offset = S::ZERO;
                self.candidate = angle;
                self.candidate_step = S::ZERO;
                let fault = fault.unwrap_or(SensorFault::Jump);
                self.fault_output(Some(fault), self.last_torque)
            }
            (Mode::Holding { .. } | Mode::Lost { .. }, Some(fault)) => {
                let missed = match self.mode {
                    Mode::Holding { missed } => missed.saturating_add(1),
                    _ => u8::MAX,
                };
                if missed <= screen::HOLD_PERIODS {
                    self.mode = Mode::Holding { missed };
                    self.fault_output(Some(fault), self.last_torque)
                } else {
                    self.mode = Mode::Lost { agree: 0 };
                    self.fault_output(Some(fault), S::ZERO)
                }
            }
            (Mode::Holding { missed }, None) => {
                // A good reading that does not continue the motion: count agreement
                // from here, and hold while the hold lasts.
                let agree = self.agreement(angle, 1);
                let torque = if missed < screen::HOLD_PERIODS {
                    self.last_torque
                } else {
                    S::ZERO
                };
                if agree > screen::AGREE_STEPS {
                    return self.resync(angle);
                }
                self.mode = if missed < screen::HOLD_PERIODS {
                    Mode::Holding { missed: missed + 1 }
                } else {
                    Mode::Lost { agree }
                };
                let reason = if fits(self.max_step, step) {
                    SensorFault::Jump
                } else {
                    SensorFault::TooFast
                };
                self.fault_output(Some(reason), torque)
            }
            (Mode::Lost { agree }, None) => {
                let agree = self.agreement(angle, agree);
                if agree > screen::AGREE_STEPS {
                    return self.resync(angle);
                }
                self.mode = Mode::Lost { agree };
                let too_fast = agree >= 2 && !fits(self.max_step, self.candidate_step);
                let reason = if too_fast {
                    SensorFault::TooFast
                } else {
                    SensorFault::Jump
                };
                self.fault_output(Some(reason), S::ZERO)
            }
        }
    }

    /// Counts how many readings in a row agree, with `angle` the newest: `agree` so far
    /// (0: none yet). Steps agree when each is within the jolt of the one before.
    fn agreement(&mut self, angle: S, agree: u8) -> u8 {
        let d = angle.sub(self.candidate);
        let agree = match agree {
            0 => 1,
            1 => 2,
            n if d.sub(self.candidate_step).abs() <= self.jolt => n.saturating_add(1),
            _ => 2,
        };
        self.candidate_step = d;
        self.candidate = angle;
        agree
    }

    /// Enters the lost state at `angle`, moving by `step`, with `agree` readings agreeing.
    fn lose(&mut self, angle: S, step: S, agree: u8) {
        self.mode = Mode::Lost { agree };
        self.gate = S::ONE.neg();
        self.candidate = angle;
        self.candidate_step = step;
    }

    /// Takes up the readings again at `angle`, moving as the agreeing steps did.
    fn resync(&mut self, angle: S) -> KnobOutput<S> {
        let d = self.candidate_step;
        if d.abs() > self.max_step {
            // Agreeing, but too fast: stay off.
            self.mode = Mode::Lost {
                agree: screen::AGREE_STEPS,
            };
            return self.fault_output(Some(SensorFault::TooFast), S::ZERO);
        }
        self.previous = angle;
        self.last_step = d;
        self.held = law::play(angle.sub(d), angle, self.play);
        // The filter's steady state at this movement: no kick when the damper resumes.
        self.damping_state = d.mul(self.damping_gain);
        let moved = self.ladder.seek(angle);
        let (_, _, captured) = self.magnets.update(angle);
        let beyond = self.beyond_at(angle);
        let hit = if beyond != self.beyond { beyond } else { None };
        self.beyond = beyond;
        self.mode = Mode::Fading;
        self.fade = S::ZERO;
        // The hot path takes the readings again; `ease` fades the torque in.
        self.gate = self.jolt;
        self.last_torque = S::ZERO;
        KnobOutput {
            torque: S::ZERO,
            detent: self.ladder.index(),
            events: KnobEvents {
                detent_step: moved.clamp(i8::MIN.into(), i8::MAX.into()) as i8,
                endstop_hit: hit,
                magnet_captured: captured,
                resynced: true,
                ..KnobEvents::default()
            },
        }
    }

    /// The output of a period whose reading was not used.
    fn fault_output(&mut self, fault: Option<SensorFault>, torque: S) -> KnobOutput<S> {
        KnobOutput {
            torque,
            detent: self.ladder.index(),
            events: KnobEvents {
                sensor: fault,
                ..KnobEvents::default()
            },
        }
    }

    /// The torque of a period the law ran: kept as the last torque while tracking; faded
    /// in after a resync, or blended after a reconfiguration, otherwise. Only the torque
    /// goes through the cold path, so that the output is written once, in place.
    #[inline(always)]
    fn settle_torque(&mut self, out: KnobOutput<S>) -> KnobOutput<S> {
        let torque = if matches!(self.mode, Mode::Tracking) {
            out.torque
        } else {
            self.ease(out.torque)
        };
        self.last_torque = torque;
        KnobOutput { torque, ..out }
    }

    /// [`Self::settle_torque`] while fading in or blending (`screen.rs`), out of line.
    #[cold]
    #[inline(never)]
    fn ease(&mut self, torque: S) -> S {
        match self.mode {
            // Taken up again: the torque times `n/FADE_PERIODS` in the `n`-th period.
            Mode::Fading => {
                self.fade = self.fade.add(self.fade_unit);
                if self.fade >= S::ONE {
                    self.mode = Mode::Tracking;
                }
                torque.mul(self.fade)
            }
            // Reconfigured: the old torque's offset moved toward zero by one count's
            // torque per period.
            Mode::Blending => {
                let o = self.offset;
                self.offset = if o > self.slew {
                    o.sub(self.slew)
                } else if o < self.slew.neg() {
                    o.add(self.slew)
                } else {
                    S::ZERO
                };
                if self.offset == S::ZERO {
                    self.mode = Mode::Tracking;
                }
                law::torque(torque.neg(), self.offset.neg(), self.floor)
            }
            // Not reached: the gate is open only while tracking, fading or blending.
            _ => torque,
        }
    }

    /// One period of the law at `angle`, the play's output having moved by `u`: the
    /// damper's filter, then the torque, kept as the last one.
    ///
    /// Most periods are the common one (the quiet window, `quiet_lo ..= quiet_hi`): the
    /// knob tracking, in the free zone, its detent not switching. They take the short
    /// path inline, two comparisons and the free zone's spring. Every other period goes
    /// out of line to [`Self::period_zones`], which sets the window again. Both paths
    /// give the same bits for a common period: the short one is the long one with its
    /// tests decided.
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
        if angle >= self.quiet_lo && angle <= self.quiet_hi {
            let (detent, ret) = self.layer_terms(angle);
            let torque = self.zone_torque(detent.add(ret), FREE);
            self.last_torque = torque;
            KnobOutput {
                torque,
                detent: self.ladder.index(),
                events: KnobEvents::default(),
            }
        } else {
            self.period_zones(angle)
        }
    }

    /// The detent's and the return spring's terms of the spring sum at `angle`: each
    /// layer's extension times its gain (torque, a fraction of the limit).
    #[inline(always)]
    fn layer_terms(&self, angle: S) -> (S, S) {
        (
            angle.sub(self.ladder.centre()).mul(self.detent_gain),
            angle.sub(self.return_centre).mul(self.return_gain),
        )
    }

    /// The torque of the spring sum `stretch` through `zone`'s rest zone and knee, with
    /// the damper's, clamped ([`law::torque`]).
    #[inline(always)]
    fn zone_torque(&self, stretch: S, zone: usize) -> S {
        law::torque(
            law::spring(stretch, &self.zones[zone].shape),
            law::damping_torque(self.damping_state, self.unscale),
            self.floor,
        )
    }

    /// [`Self::period`] off the quiet window: the detent's switch, the magnets, the
    /// zone and the endstops, the fade or blend; then the window for the next period.
    #[inline(never)]
    fn period_zones(&mut self, angle: S) -> KnobOutput<S> {
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
        // An endstop is hit past its rest zone and knee, and again only after coming
        // back inside by the hysteresis. Its hit point lies beyond it (`hi_hit ≥ hi`,
        // `lo_hit ≤ lo`), so that a knob inside the range that was not beyond has
        // nothing to test.
        if zone == BEYOND || self.beyond.is_some() {
            self.track_endstops(angle, &mut events);
        }

        // The short path's sum with the zone's own term between.
        let (detent, ret) = self.layer_terms(angle);
        let out = KnobOutput {
            torque: self.zone_torque(detent.add(other.mul(self.zones[zone].other)).add(ret), zone),
            detent: self.ladder.index(),
            events,
        };
        let out = self.settle_torque(out);
        self.refresh_quiet();
        out
    }

    /// The endstop's hit and release (`Self::period`): a hit past its rest zone and
    /// knee, and again only after the rotor came back inside by the hysteresis.
    #[inline(always)]
    fn track_endstops(&mut self, angle: S, events: &mut KnobEvents) {
        // Only a bounded knob is beyond an endstop or was: no test of `bounded` here.
        match self.beyond {
            None if angle > self.hi_hit => {
                self.beyond = Some(Endstop::Max);
                events.endstop_hit = Some(Endstop::Max);
            }
            None if angle < self.lo_hit => {
                self.beyond = Some(Endstop::Min);
                events.endstop_hit = Some(Endstop::Min);
            }
            Some(Endstop::Max) if angle < self.hi_release => self.beyond = None,
            Some(Endstop::Min) if angle > self.lo_release => self.beyond = None,
            _ => {}
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

    /// The centre of the current detent, radians (the angle the knob pulls toward; the
    /// lower endstop, or 0, without detents).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(0.0, 1.0).detent_count(5);
    /// let knob = Knob::<f64>::new(&c, 0.74)?;
    /// assert_eq!(knob.detent_centre(), 0.75);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn detent_centre(&self) -> S {
        self.ladder.centre()
    }

    /// Where the rotor is within its detent, in detent widths from the current centre:
    /// 0 on the centre, about ±0.5 at the midpoints to the neighbours (up to the snap
    /// point plus the hysteresis before the detent switches). What a UI draws between two
    /// menu items. 0 without detents.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).endstops(0.0, 1.0).detent_count(5);
    /// let knob = Knob::<f64>::new(&c, 0.8)?;
    /// assert!((knob.detent_fraction() - 0.2).abs() < 1e-9); // 0.05 past 0.75, width 0.25
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn detent_fraction(&self) -> S {
        self.previous
            .sub(self.ladder.centre())
            .mul(self.inverse_width)
    }

    /// The last angle the knob used, radians.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let mut knob = Knob::<f32>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 16384), 0.0)?;
    /// let _ = knob.update(0.001);
    /// let _ = knob.update(f32::NAN); // not used
    /// assert_eq!(knob.angle(), 0.001);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn angle(&self) -> S {
        self.previous
    }

    /// The largest angle magnitude a reading may have (radians): the range the knob's
    /// arithmetic holds. A reading beyond it is a [`SensorFault::OutOfRange`]. Fixed point
    /// takes its whole range (its arithmetic saturates); a float knob stops where an
    /// angle times its stiffest gain would leave the float's range.
    ///
    /// ```
    /// use stiffspring::{I16F16, Knob, KnobConfig};
    /// let knob = Knob::<I16F16>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 16384), I16F16::ZERO)?;
    /// assert_eq!(knob.reach(), I16F16::MAX.to_num::<f64>());
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn reach(&self) -> f64 {
        self.reach.to_f64()
    }

    /// The largest change of the rotor's movement per period (radians per period per
    /// period) that a reading may show: four times the torque limit on half the
    /// configured inertia, `8·τ_max·dt²/J`, plus six encoder counts. A reading beyond
    /// it is a [`SensorFault::Jump`].
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let knob = Knob::<f64>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 16384), 0.0)?;
    /// let count = core::f64::consts::TAU / 16384.0;
    /// assert!((knob.max_jolt() - (8.0 * 0.05 * 1e-6 / 1e-5 + 6.0 * count)).abs() < 1e-12);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn max_jolt(&self) -> f64 {
        self.jolt.to_f64()
    }

    /// The configured maximum speed, rad/s ([`KnobConfig::max_speed`]).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).max_speed(60.0);
    /// assert_eq!(Knob::<f32>::new(&c, 0.0)?.max_speed(), Some(60.0));
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn max_speed(&self) -> Option<f64> {
        if self.max_speed > 0.0 {
            Some(self.max_speed)
        } else {
            None
        }
    }

    /// The knee past the rest zone, radians: over it the spring rises from zero to its
    /// full stiffness ([`KNEE_COUNTS`] counts, less in a narrow detent).
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let knob = Knob::<f32>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 4096), 0.0)?;
    /// assert_eq!(knob.knee(), 4.0 * core::f64::consts::TAU / 4096.0);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn knee(&self) -> f64 {
        self.knee
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

    /// The rest zone: how far (radians, [`REST_COUNTS`] encoder counts) from its rest
    /// point the spring is zero.
    ///
    /// ```
    /// use stiffspring::{Knob, KnobConfig};
    /// let knob = Knob::<f32>::new(&KnobConfig::new(1_000.0, 1e-5, 0.05, 4096), 0.0)?;
    /// assert_eq!(knob.rest_zone(), 2.0 * core::f64::consts::TAU / 4096.0);
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
        // The zones the set-up checked: free always, held where there are magnets,
        // beyond where there are endstops.
        let present = [true, self.magnets.any(), self.bounded];
        let mut zones = [None; 3];
        for (z, zone) in zones.iter_mut().enumerate() {
            if present[z] {
                let (k, b) = (self.zone_stiffness[z], self.damping);
                *zone = Some(LoopCoefficients::of(
                    k,
                    b,
                    self.filter_alpha,
                    self.dt,
                    self.inertia,
                ));
            }
        }
        zones
    }
}
