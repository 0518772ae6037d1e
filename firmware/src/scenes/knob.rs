//! The `knob` scene: a knob of 20 detents over three quarters of a turn, with endstops,
//! at 1 kHz. Shared by `examples/check_knob.rs` (host and firmware) and by
//! `tests/knob_golden.rs`, which plays its scripted encoder sweep on an `f64` model of the
//! knob's torque law and writes `firmware/src/golden/knob.rs`. Change it (and the model's
//! constants with it), then regenerate the golden values:
//! `STIFFSPRING_BLESS=1 cargo test --release --test knob_golden`.

use stiffspring::KnobConfig;
use stiffspring::knob::Latency;

/// The control period: 1 kHz.
pub const DT: f64 = 1e-3;
/// The rotor and knob cap, kg·m².
pub const INERTIA: f64 = 1e-5;
/// The motor's torque limit, N·m.
pub const LIMIT: f64 = 0.05;
/// One count of a 14-bit encoder, rad.
pub const COUNT: f64 = core::f64::consts::TAU / 16384.0;
/// The range: three quarters of a turn.
pub const MAX: f64 = 0.75 * core::f64::consts::TAU;

/// The knob of the scene: 20 detents of 0.1 N·m/rad (a 12 mN·m click), endstops adding
/// 0.15 N·m/rad. A constant, so that firmware designs it when it is built
/// (`stiffspring::knob!(CONFIG)`).
pub const CONFIG: KnobConfig = KnobConfig::new(1.0 / DT, INERTIA, LIMIT, 16384)
    .latency(Latency::OneStep)
    .endstops(0.0, MAX)
    .endstop_stiffness(0.15)
    .detent_count(20)
    .detent_stiffness(0.1)
    .hysteresis(2.0 * COUNT);

/// [`CONFIG`], for code that builds the knob at run time.
pub const fn config() -> KnobConfig {
    CONFIG
}

/// Periods of the scripted sweep.
pub const SWEEP_STEPS: usize = 3000;

/// The scripted encoder input of period `n`: from 0.2 rad below the lower endstop to
/// 0.2 rad past the upper one and back, a triangle over `SWEEP_STEPS` periods (about 9
/// counts per period), read by the 14-bit encoder (floored to a count).
pub fn sweep_angle(n: usize) -> f64 {
    let half = SWEEP_STEPS / 2;
    let phase = if n <= half { n } else { SWEEP_STEPS - n };
    let angle = -0.2 + (MAX + 0.4) * phase as f64 / half as f64;
    let counts = angle / COUNT;
    // Floor without `std`: truncate, then step down for negative fractions.
    let whole = counts as i64 as f64;
    let floor = if whole > counts { whole - 1.0 } else { whole };
    floor * COUNT
}
