//! The knob against SmartKnob-style PD detents, on the same simulated rotor (exact ZOH,
//! one period of delay as in SimpleFOC firmware, 14-bit encoder). Used by
//! `tests/knob_vs_pd.rs` and the tour, which hand [`compare`] the library's knob.
//!
//! Both run the same detent index logic (24 detents per turn, snap point 0.55, two
//! counts of hysteresis) and the same torque limit; only the torque law differs:
//!
//! - **PD**, as SmartKnob does: `τ = −k_p·e − k_d·ω`, `ω` the backward difference of the
//!   encoder angles over `dt`, with SmartKnob's raw ratio `k_d = 0.005 s·k_p`
//!   (`PID_velocity.P = 4·strength`, `D = 0.02·strength` for detents wider than 8°);
//! - **knob**: stiffspring's knob with detent stiffness `k_p` (N·m/rad), damping ratio
//!   0.7, set up by the caller (this module does not use the library).
//!
//! Matched on perceived strength: the same small-signal stiffness `k_p`, so the same
//! peak detent torque `k_p·0.55·width`. Each case is a flick of 20 rad/s released on a
//! detent centre, no hand.

use super::{COUNT, Plant};
use std::f64::consts::TAU;

pub const INERTIA: f64 = 1e-5;
pub const LIMIT: f64 = 0.05;
pub const DETENTS: f64 = 24.0;
pub const SNAP: f64 = 0.55;
pub const SMARTKNOB_RATIO: f64 = 0.005; // s: D/P = 0.02/4

/// What a flick measured.
pub struct FlickResult {
    /// Time until the rotor stays within 5 % of a width of its final detent, slower
    /// than 0.5 rad/s.
    pub settle_ms: f64,
    /// The swing past the final centre after the largest excursion, in percent.
    pub overshoot_pct: f64,
    /// Peak-to-peak torque over the last third of the run.
    pub ripple_mnm: f64,
    /// The final detent index.
    pub detents_crossed: i32,
}

/// SmartKnob's detent logic and PD law.
struct Pd {
    kp: f64,
    kd: f64,
    dt: f64,
    width: f64,
    threshold: f64,
    centre: f64,
    index: i32,
    previous: f64,
}

impl Pd {
    fn update(&mut self, angle: f64) -> (f64, i32) {
        let e = angle - self.centre;
        if e > self.threshold {
            self.centre += self.width;
            self.index += 1;
        } else if e < -self.threshold {
            self.centre -= self.width;
            self.index -= 1;
        }
        let omega = (angle - self.previous) / self.dt;
        self.previous = angle;
        let tau = -self.kp * (angle - self.centre) - self.kd * omega;
        (tau.clamp(-LIMIT, LIMIT), self.index)
    }
}

/// A flick of 20 rad/s released on a detent centre, no hand, with the torque law `law`
/// (encoder angle → torque in N·m and detent index) at `rate` hertz.
pub fn flick(rate: f64, mut law: impl FnMut(f64) -> (f64, i32)) -> FlickResult {
    let dt = 1.0 / rate;
    let width = TAU / DETENTS;
    let mut plant = Plant::new(INERTIA, dt, 1.0);
    plant.omega = 20.0;
    let n = (1.5 / dt) as usize;
    let mut trace = Vec::with_capacity(n);
    for _ in 0..n {
        let (tau, index) = law(plant.read());
        trace.push((plant.theta, plant.omega, tau, index));
        plant.step(tau, &mut super::no_hand);
    }
    let final_index = trace.last().unwrap().3;
    let centre = final_index as f64 * width;
    // Settled: within 5% of a width of the final centre, slower than 0.5 rad/s, for good.
    let last_out = trace
        .iter()
        .rposition(|&(th, om, _, _)| (th - centre).abs() > 0.05 * width || om.abs() > 0.5)
        .map_or(0, |k| k + 1);
    // Overshoot, as for a step response: in the final detent (after the last index
    // change), the largest swing past the centre after the largest excursion, relative
    // to that excursion (a damping ratio of 0.7 gives 5%).
    let last_change = trace
        .iter()
        .rposition(|t| t.3 != final_index)
        .map_or(0, |k| k + 1);
    let settle = &trace[last_change..];
    let (peak_at, peak) = settle
        .iter()
        .enumerate()
        .map(|(k, t)| (k, t.0 - centre))
        .fold((0, 0.0f64), |(bk, b), (k, x)| {
            if x.abs() > b.abs() { (k, x) } else { (bk, b) }
        });
    let overshoot = settle[peak_at..]
        .iter()
        .map(|t| -(t.0 - centre) * peak.signum())
        .fold(0.0f64, f64::max)
        / peak.abs().max(1e-12);
    let tail = &trace[n - n / 3..];
    let lo = tail.iter().map(|t| t.2).fold(f64::INFINITY, f64::min);
    let hi = tail.iter().map(|t| t.2).fold(f64::NEG_INFINITY, f64::max);
    FlickResult {
        settle_ms: last_out as f64 * dt * 1e3,
        overshoot_pct: 100.0 * overshoot,
        ripple_mnm: (hi - lo) * 1e3,
        detents_crossed: final_index,
    }
}

/// Both laws flicked at `rate` hertz with small-signal stiffness `kp` (N·m/rad).
pub struct Comparison {
    /// SmartKnob's PD.
    pub pd: FlickResult,
    /// The same PD with the knob's damping (`k_d = B`, the knob's `C_d·I/dt`): a PD
    /// matched to the knob in stiffness and damping, so that what differs is the law.
    pub matched: FlickResult,
    /// This crate's knob.
    pub knob: FlickResult,
    /// The PD's small-signal damping ratio.
    pub pd_zeta: f64,
    /// The knob's small-signal damping ratio, from its `C_d·I/dt`.
    pub knob_zeta: f64,
}

/// The knob's law for [`compare`], set up by the caller: encoder angle → (torque in N·m,
/// detent index), and the knob's `C_d` (for its small-signal damping ratio).
pub type KnobLaw = (Box<dyn FnMut(f64) -> (f64, i32)>, f64);

/// Runs both laws on the same flick. `knob(dt, width, k_p)` sets up the knob for a
/// period `dt`, detents `width` apart and small-signal stiffness `k_p`, on this module's
/// rotor ([`INERTIA`]), torque limit ([`LIMIT`]) and hysteresis (two counts).
pub fn compare(rate: f64, kp: f64, knob: impl FnOnce(f64, f64, f64) -> KnobLaw) -> Comparison {
    let width = TAU / DETENTS;
    let dt = 1.0 / rate;
    let kd = SMARTKNOB_RATIO * kp;
    let mut pd = Pd {
        kp,
        kd,
        dt,
        width,
        threshold: (SNAP * width).max(0.5 * width + 2.0 * COUNT),
        centre: 0.0,
        index: 0,
        previous: 0.0,
    };
    let mut matched = Pd {
        kp,
        kd: 0.0,
        dt,
        width,
        threshold: pd.threshold,
        centre: 0.0,
        index: 0,
        previous: 0.0,
    };
    let pd_result = flick(rate, |a| pd.update(a));
    let (mut law, cd) = knob(dt, width, kp);
    let knob_result = flick(rate, &mut law);
    matched.kd = cd * INERTIA / dt;
    let matched_result = flick(rate, |a| matched.update(a));
    Comparison {
        pd: pd_result,
        matched: matched_result,
        knob: knob_result,
        pd_zeta: kd / (2.0 * (kp * INERTIA).sqrt()),
        knob_zeta: cd * INERTIA / dt / (2.0 * (kp * INERTIA).sqrt()),
    }
}
