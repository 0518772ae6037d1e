//! The sweep of issue 13: a torque law in closed loop with an independent rotor model,
//! over rates, inertias, torque limits, damping ratios, latencies, stiffnesses, detent
//! counts, encoders and a misestimated inertia, with the endstop cases.
//!
//! Written here in `f64`, independently of the library: the rotor is `J·dω/dt = τ` with the
//! torque held over each period (exact integration), delayed by 0 or 1 period, read by an
//! encoder that floors to a count. The law under test is a closure (encoder angle → torque
//! as a fraction of the limit, and whether an endstop was hit); `tests/knob_sweep.rs` sets
//! up the library's knob for each [`Case`] of a [`Grid`].
//!
//! "Oscillating" ([`Run::oscillating`]): more than 8 counts peak to peak over the last 10 %
//! of the run, with at least 4 reversals of the count sequence.

use std::f64::consts::TAU;

/// The rotor: exact ZOH integration of a torque held over each period.
#[derive(Clone, Debug)]
pub struct Rotor {
    /// The rotor's real moment of inertia, kg·m².
    pub inertia: f64,
    /// The control period, s.
    pub dt: f64,
    /// Periods of delay between the command and the torque (0 or 1).
    pub delay: usize,
    /// Angle, rad.
    pub theta: f64,
    /// Angular velocity, rad/s.
    pub omega: f64,
    pending: f64,
}

impl Rotor {
    /// A rotor at `theta` turning at `omega`, nothing commanded yet.
    pub fn new(inertia: f64, dt: f64, delay: usize, theta: f64, omega: f64) -> Self {
        Rotor {
            inertia,
            dt,
            delay,
            theta,
            omega,
            pending: 0.0,
        }
    }

    /// One period with `command` (N·m) computed from this period's reading: it acts now
    /// (no delay) or over the next period (one period of delay).
    pub fn step(&mut self, command: f64) {
        let tau = if self.delay == 1 {
            core::mem::replace(&mut self.pending, command)
        } else {
            command
        };
        let a = tau / self.inertia;
        self.theta += self.omega * self.dt + 0.5 * a * self.dt * self.dt;
        self.omega += a * self.dt;
    }
}

/// The encoder reading (count index) of an angle: floored to a whole count.
pub fn counts(theta: f64, count: f64) -> i64 {
    (theta / count).floor() as i64
}

/// What one run measured.
#[derive(Clone, Copy, Debug, Default)]
pub struct Run {
    /// Peak to peak of the count over the last 10 %.
    pub pp_counts: i64,
    /// Reversals of the count sequence over the last 10 %.
    pub reversals: usize,
    /// Peak to peak of the torque (N·m) over the last 10 %.
    pub tail_torque: f64,
    /// Endstop hits over the run.
    pub hits: usize,
    /// The largest |torque| fraction seen (a law that respects its limit keeps it ≤ 1).
    pub max_fraction: f64,
}

impl Run {
    /// The definition: more than 8 counts peak to peak over the last 10 %, with at
    /// least 4 reversals.
    pub fn oscillating(&self) -> bool {
        self.pp_counts > 8 && self.reversals >= 4
    }
}

/// Runs `law` on `rotor` for `seconds`. Each period the encoder reads the rotor (one
/// count is `count` rad), `law(reading)` gives the torque as a fraction of `limit` and
/// whether an endstop was hit, and the rotor integrates the torque.
pub fn run(
    rotor: &mut Rotor,
    count: f64,
    limit: f64,
    seconds: f64,
    mut law: impl FnMut(f64) -> (f64, bool),
) -> Run {
    let n = (seconds / rotor.dt).round() as usize;
    let tail = n - n / 10;
    let (mut lo, mut hi) = (i64::MAX, i64::MIN);
    let (mut tlo, mut thi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut last = None;
    let mut dir = 0;
    let mut out = Run::default();
    for k in 0..n {
        let c = counts(rotor.theta, count);
        let (fraction, hit) = law(c as f64 * count);
        out.max_fraction = out.max_fraction.max(fraction.abs());
        if hit {
            out.hits += 1;
        }
        let tau = fraction * limit;
        if k >= tail {
            lo = lo.min(c);
            hi = hi.max(c);
            tlo = tlo.min(tau);
            thi = thi.max(tau);
            if let Some(p) = last {
                let d: i64 = c - p;
                if d != 0 {
                    if dir != 0 && d.signum() != dir {
                        out.reversals += 1;
                    }
                    dir = d.signum();
                }
            }
            last = Some(c);
        }
        rotor.step(tau);
    }
    out.pp_counts = hi - lo;
    out.tail_torque = thi - tlo;
    out
}

/// One point of the grid.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Loop rate, Hz.
    pub rate: f64,
    /// The configured inertia, kg·m².
    pub inertia: f64,
    /// Torque limit, N·m.
    pub limit: f64,
    /// Damping ratio.
    pub zeta: f64,
    /// The periods of delay the law is designed for (0 or 1).
    pub latency: usize,
    /// Fraction of the stiffest accepted detent.
    pub strength: f64,
    /// Detents: per turn without endstops, over the range with them.
    pub detents: u32,
    /// Encoder bits.
    pub bits: u32,
    /// Endstops at ±135° (the last detent on each stop), or an endless knob.
    pub endstops: bool,
}

impl Case {
    /// One encoder count, rad.
    pub fn count(&self) -> f64 {
        TAU / f64::from(1u32 << self.bits)
    }
}

/// The endstops of a bounded case: ±135°, SmartKnob's bounded knob.
pub const ENDSTOPS: (f64, f64) = (-0.375 * TAU, 0.375 * TAU);

/// The grid's axes. [`FULL`] is the grid; [`SHORT`] runs in `cargo test`.
#[derive(Clone, Copy, Debug)]
pub struct Grid {
    /// Loop rates, Hz.
    pub rates: &'static [f64],
    /// Configured inertias, kg·m².
    pub inertias: &'static [f64],
    /// Torque limits, N·m.
    pub limits: &'static [f64],
    /// Damping ratios.
    pub zetas: &'static [f64],
    /// Fractions of the stiffest accepted detent.
    pub strengths: &'static [f64],
    /// Detent counts.
    pub detents: &'static [u32],
    /// Encoder bits.
    pub bits: &'static [u32],
    /// The real inertia over the configured one.
    pub mismatch: &'static [f64],
}

/// The grid, with encoders of 10–16 bits and the inertia misestimated ×½ and ×2.
pub const FULL: Grid = Grid {
    rates: &[1_000.0, 4_000.0, 10_000.0],
    inertias: &[1e-6, 1e-5, 1e-4],
    limits: &[0.02, 0.1],
    zetas: &[0.2, 0.7, 2.0],
    strengths: &[0.01, 0.03, 0.1, 0.3, 1.0],
    detents: &[2, 24, 100],
    bits: &[10, 12, 14, 16],
    mismatch: &[0.5, 1.0, 2.0],
};

/// A corner of the full grid: the extreme rates, inertias, damping ratios and encoders.
pub const SHORT: Grid = Grid {
    rates: &[1_000.0, 10_000.0],
    inertias: &[1e-6, 1e-4],
    limits: &[0.02],
    zetas: &[0.2, 2.0],
    strengths: &[0.03, 1.0],
    detents: &[24, 100],
    bits: &[10, 14],
    mismatch: &[0.5, 2.0],
};

impl Grid {
    /// Every case, both latencies, with and without endstops.
    pub fn cases(&self) -> Vec<Case> {
        let mut v = Vec::new();
        for &rate in self.rates {
            for &inertia in self.inertias {
                for &limit in self.limits {
                    for &zeta in self.zetas {
                        for latency in [0, 1] {
                            for &strength in self.strengths {
                                for &detents in self.detents {
                                    for &bits in self.bits {
                                        for endstops in [false, true] {
                                            v.push(Case {
                                                rate,
                                                inertia,
                                                limit,
                                                zeta,
                                                latency,
                                                strength,
                                                detents,
                                                bits,
                                                endstops,
                                            });
                                        }
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        v
    }
}

/// The starts of a case, `(angle, velocity)`: 0.45 of a width off a centre with a 5 rad/s
/// flick; with endstops also released 3 counts inside the upper stop, on the last detent
/// (on the stop), 3 counts beyond it, flicked into it from 0.45 of a width, and flicked
/// into the lower stop.
pub fn starts(c: &Case) -> Vec<(f64, f64)> {
    let count = c.count();
    if c.endstops {
        let (lo, hi) = ENDSTOPS;
        let width = (hi - lo) / f64::from(c.detents - 1);
        vec![
            (lo + 0.45 * width, 5.0),
            (hi - 3.0 * count, 0.0),
            (hi, 0.0),
            (hi + 3.0 * count, 0.0),
            (hi - 0.45 * width, 5.0),
            (lo + 0.45 * width, -5.0),
        ]
    } else {
        let width = TAU / f64::from(c.detents);
        vec![(0.45 * width, 5.0)]
    }
}

/// The plant delays a law designed for `latency` periods is run against: its own, and
/// none for one period (a law designed for a delay must also hold without it).
pub fn plant_delays(latency: usize) -> &'static [usize] {
    if latency == 0 { &[0] } else { &[1, 0] }
}

/// Totals of a sweep.
#[derive(Debug, Default)]
pub struct Totals {
    /// Configurations of the grid.
    pub configs: usize,
    /// Configurations the law refused altogether.
    pub rejected: usize,
    /// Runs a backend refused (a configuration the reference accepts).
    pub backend_rejected: usize,
    /// Runs made.
    pub runs: usize,
    /// Runs that oscillated.
    pub oscillating: usize,
    /// The worst oscillating run: counts peak to peak and a description.
    pub worst: (i64, String),
    /// The largest peak to peak of a run that did not oscillate.
    pub worst_quiet_pp: i64,
    /// The most endstop hits of a run, and its description.
    pub most_hits: usize,
    pub most_hits_run: String,
    /// The largest |torque| fraction of any run.
    pub max_fraction: f64,
}

impl Totals {
    /// Adds one run, described by `what` (kept when it is the worst oscillating run, or
    /// the one with the most endstop hits).
    pub fn record(&mut self, r: &Run, what: impl Fn() -> String) {
        self.runs += 1;
        if r.hits > self.most_hits {
            self.most_hits = r.hits;
            self.most_hits_run = what();
        }
        self.max_fraction = self.max_fraction.max(r.max_fraction);
        if r.oscillating() {
            self.oscillating += 1;
            if r.pp_counts > self.worst.0 {
                self.worst = (r.pp_counts, what());
            }
        } else {
            self.worst_quiet_pp = self.worst_quiet_pp.max(r.pp_counts);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rotor integrates a constant torque exactly: θ = θ₀ + ω₀t + ½(τ/J)t².
    #[test]
    fn rotor_is_exact_under_constant_torque() {
        let (j, dt, tau) = (1e-5, 1e-3, 2e-3);
        for delay in [0, 1] {
            let mut r = Rotor::new(j, dt, delay, 0.1, 3.0);
            let steps = 500;
            for _ in 0..steps {
                r.step(tau);
            }
            // With a delay the first period runs without torque.
            let held = (steps - delay) as f64 * dt;
            let coast = delay as f64 * dt;
            let theta = 0.1 + 3.0 * (held + coast) + 0.5 * tau / j * held * held;
            assert!((r.theta - theta).abs() < 1e-9 * theta.abs(), "{delay}");
            assert!((r.omega - (3.0 + tau / j * held)).abs() < 1e-9);
        }
    }

    /// An undamped spring (0.4 N·m/rad on 1e−5 kg·m², a 31 ms period) rings by the
    /// definition; a rotor left alone does not.
    #[test]
    fn the_oscillation_metric_can_fail() {
        let count = TAU / 16384.0;
        let mut r = Rotor::new(1e-5, 1e-3, 0, 0.05, 0.0);
        let spring = run(&mut r, count, 1.0, 1.0, |a| (-0.4 * a, false));
        assert!(spring.oscillating(), "{spring:?}");
        let mut r = Rotor::new(1e-5, 1e-3, 0, 0.05, 0.0);
        let still = run(&mut r, count, 0.01, 1.0, |_| (0.0, false));
        assert!(!still.oscillating() && still.pp_counts == 0, "{still:?}");
    }

    #[test]
    fn grids_have_the_documented_sizes() {
        // 3·3·2·3·2·5·3·4·2 configurations in the full grid.
        assert_eq!(FULL.cases().len(), 12_960);
        assert_eq!(SHORT.cases().len(), 256);
    }
}
