//! Silence at rest and bad encoder samples (issue 17): a knob measured on torque, not
//! only on position, against three rotors written here from their physics, in `f64`,
//! independently of the library.
//!
//! # The rotors
//!
//! `J·dω/dt = τ_motor + τ_friction + τ_cogging`. The motor torque is held over each period
//! (zero-order hold), and acts either in the period it was computed for or one period
//! later ([`Rotor::delay`]). Three rotors ([`RotorKind`]), as the issue names them:
//!
//! - **frictionless**: `τ_friction = τ_cogging = 0`, integrated exactly (constant
//!   acceleration over each period);
//! - **Coulomb**: stick-slip friction of [`FRICTION`] (0.5 %) of the torque limit. A rotor
//!   at rest stays exactly at rest (`ω = 0`, the angle unchanged) while the applied torque
//!   `|τ_motor + τ_cogging|` is at most the static friction; otherwise it slips against the
//!   kinetic friction `−τ_k·sign(ω)` (`τ_k ≤ τ_s`; both 0.5 % here). A moving rotor that
//!   decelerates to `ω = 0` inside a step stops at the exact instant of the zero crossing
//!   and the rest of the step starts from rest, with the stick test again. So there is no
//!   friction integrator to chatter: a constant torque within the static friction
//!   holds the rotor exactly still, for ever. With constant applied torque this is the
//!   exact solution;
//! - **noisy**: the Coulomb rotor plus a sinusoidal cogging torque `−A·sin(n·θ)` of
//!   amplitude [`COGGING`] (2 %) of the limit, [`COGGING_PERIODS`] (24) periods per turn,
//!   integrated over [`COGGING_SUBSTEPS`] sub-steps per period (the cogging evaluated at
//!   each sub-step's predicted midpoint angle, so second-order accurate; the friction is
//!   still exact within each sub-step), read by an encoder that adds ±1 count to
//!   [`NOISE_PROBABILITY`] (5 %) of its readings (seeded: [`crate::rng`]).
//!
//! # The encoder
//!
//! [`Encoder`]: `2^bits` counts per turn, floored or rounded to a count ([`Rounding`]);
//! the knob is handed the count times the count's angle.
//!
//! # The torque window ([`Window`])
//!
//! Measured over the last [`WINDOW`] (30 %) of a run, from the commanded torque (the knob's
//! output, a fraction of the limit) and the rotor's clean encoder count:
//!
//! - **sign reversals per second**: the sign of each command is `+1`, `−1`, or `0` for an
//!   exact zero. A reversal is counted when a non-zero sign differs from the last non-zero
//!   sign seen in the window; zeros in between neither count nor reset the last sign
//!   (`+, 0, 0, −` is one reversal, `+, 0, +` none). The count over the window's duration
//!   (its periods times `dt`) is the rate. Any non-zero value counts, however small: a
//!   command of `±1e−9` alternating is a toggling current;
//! - **peak to peak**: the largest minus the smallest command in the window, as a fraction
//!   of the limit;
//! - **position peak to peak**: the largest minus the smallest clean encoder count (the
//!   rotor's angle quantised, without the injected noise), in counts, and the reversals of
//!   the count's direction. A run is **at rest** when its position stays within
//!   [`OSCILLATING_COUNTS`] (8) counts peak to peak; otherwise it is **oscillating** when
//!   the count also reverses direction at least [`OSCILLATING_REVERSALS`] (4) times (the
//!   definition of issue 13's sweep), and **unsettled** (still creeping towards its detent,
//!   as a heavily damped, heavy rotor on a wide detent does after 2 s) when it does not.
//!   The peak-to-peak bound on the torque applies to runs at rest; the reversal bound to
//!   every run.
//!
//! # The grid
//!
//! [`FULL`] is the grid (1/4/10 kHz, J 1e−6–1e−4 kg·m², limits 0.02–0.5 N·m,
//! ζ 0.2/0.7/2, both latencies, 2/24/100 detents, endless and between endstops at ±135°,
//! encoders of 10–16 bits) with two detent strengths (peak torque 0.1 and 0.5 of the limit,
//! the second that of the knob); [`short`] is every 113th configuration of it.
//! Each configuration runs [`SECONDS`] (2 s) from [`start`]: 0.45 of a detent off a centre
//! with a 5 rad/s flick. The law is a closure (encoder angle → torque fraction), so that
//! this module stays independent of the library's types: the caller builds its knob for
//! each [`Case`].

use crate::rng::Rng;
use std::f64::consts::TAU;

/// Static and kinetic friction of the Coulomb and noisy rotors, as a fraction of the
/// torque limit.
pub const FRICTION: f64 = 0.005;
/// The cogging amplitude of the noisy rotor, as a fraction of the torque limit.
pub const COGGING: f64 = 0.02;
/// Cogging periods per turn (a 12N14P-class motor has 84; the issue asks for 12–24).
pub const COGGING_PERIODS: u32 = 24;
/// Sub-steps per control period of a rotor with cogging.
pub const COGGING_SUBSTEPS: usize = 16;
/// The fraction of the noisy encoder's readings that are one count off (either way).
pub const NOISE_PROBABILITY: f64 = 0.05;
/// The fraction of a run, at its end, that the [`Window`] measures.
pub const WINDOW: f64 = 0.3;
/// Seconds per run of the grid.
pub const SECONDS: f64 = 2.0;
/// More than this many counts peak to peak in the window is not at rest.
pub const OSCILLATING_COUNTS: i64 = 8;
/// Reversals of the count's direction in the window that make a run not at rest
/// "oscillating" rather than "unsettled".
pub const OSCILLATING_REVERSALS: usize = 4;
/// The chatter bound: sign reversals per second at rest.
pub const MAX_REVERSALS_PER_S: f64 = 20.0;
/// The ripple bound: peak to peak at rest, as a fraction of the limit.
pub const MAX_PEAK_TO_PEAK: f64 = 0.02;

/// A rotor with zero-order-hold motor torque, optional stick-slip friction and cogging.
#[derive(Clone, Debug)]
pub struct Rotor {
    /// Moment of inertia, kg·m².
    pub inertia: f64,
    /// The control period, s.
    pub dt: f64,
    /// Periods between the command and the torque (0 or 1).
    pub delay: usize,
    /// Angle, rad.
    pub theta: f64,
    /// Angular velocity, rad/s.
    pub omega: f64,
    /// Static friction (break-away torque), N·m.
    pub static_friction: f64,
    /// Kinetic friction, N·m; at most the static friction.
    pub kinetic_friction: f64,
    /// Cogging amplitude `A`, N·m: the cogging torque is `−A·sin(n·θ)`.
    pub cogging: f64,
    /// Cogging periods per turn `n`.
    pub cogging_periods: u32,
    /// Sub-steps per period (1 is exact without cogging).
    pub substeps: usize,
    pending: f64,
}

impl Rotor {
    /// A frictionless rotor at `theta` turning at `omega`, nothing commanded yet.
    pub fn new(inertia: f64, dt: f64, delay: usize, theta: f64, omega: f64) -> Self {
        Rotor {
            inertia,
            dt,
            delay,
            theta,
            omega,
            static_friction: 0.0,
            kinetic_friction: 0.0,
            cogging: 0.0,
            cogging_periods: COGGING_PERIODS,
            substeps: 1,
            pending: 0.0,
        }
    }

    /// Coulomb friction: `static_friction` to break away, `kinetic` while sliding (N·m).
    pub fn with_friction(mut self, static_friction: f64, kinetic: f64) -> Self {
        assert!(
            0.0 <= kinetic && kinetic <= static_friction,
            "need 0 ≤ τ_k ≤ τ_s"
        );
        self.static_friction = static_friction;
        self.kinetic_friction = kinetic;
        self
    }

    /// A cogging torque `−amplitude·sin(periods·θ)`, integrated over `substeps` per period.
    pub fn with_cogging(mut self, amplitude: f64, periods: u32, substeps: usize) -> Self {
        self.cogging = amplitude;
        self.cogging_periods = periods;
        self.substeps = substeps.max(1);
        self
    }

    /// The cogging torque at `theta`, N·m.
    pub fn cogging_torque(&self, theta: f64) -> f64 {
        -self.cogging * (f64::from(self.cogging_periods) * theta).sin()
    }

    /// Whether the rotor is stuck: exactly at rest.
    pub fn stuck(&self) -> bool {
        self.omega == 0.0
    }

    /// One period with `command` (N·m) computed from this period's reading: it acts over
    /// this period (no delay) or over the next one (one period of delay), held constant.
    pub fn step(&mut self, command: f64) {
        let tau = if self.delay == 1 {
            core::mem::replace(&mut self.pending, command)
        } else {
            command
        };
        if self.cogging == 0.0 {
            self.segment(tau, self.dt);
            return;
        }
        let h = self.dt / self.substeps as f64;
        for _ in 0..self.substeps {
            let mid = self.theta + 0.5 * self.omega * h;
            self.segment(tau + self.cogging_torque(mid), h);
        }
    }

    /// A constant applied torque `tau` over `h`, with stick-slip friction: exact.
    fn segment(&mut self, tau: f64, mut h: f64) {
        let j = self.inertia;
        loop {
            if h <= 0.0 {
                return;
            }
            if self.omega == 0.0 {
                if tau.abs() <= self.static_friction {
                    return; // stuck: the friction balances the torque exactly
                }
                // Breaks away in the direction of the torque; since τ_k ≤ τ_s < |τ| the
                // acceleration keeps that sign over the whole segment.
                let a = (tau - tau.signum() * self.kinetic_friction) / j;
                self.theta += 0.5 * a * h * h;
                self.omega = a * h;
                return;
            }
            let a = (tau - self.omega.signum() * self.kinetic_friction) / j;
            if a * self.omega < 0.0 {
                let stop = -self.omega / a;
                if stop < h {
                    self.theta += 0.5 * self.omega * stop;
                    self.omega = 0.0;
                    h -= stop;
                    continue;
                }
            }
            self.theta += self.omega * h + 0.5 * a * h * h;
            self.omega += a * h;
            return;
        }
    }
}

/// How the encoder turns an angle into a count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rounding {
    /// Down to the count below (a plain incremental or absolute encoder).
    Floor,
    /// To the nearest count.
    Nearest,
}

/// A quantising encoder, optionally noisy.
#[derive(Clone, Debug)]
pub struct Encoder {
    /// Counts per turn `2^bits`.
    pub bits: u32,
    /// Floor or nearest.
    pub rounding: Rounding,
    /// The fraction of readings one count off (0 for a clean encoder).
    pub noise: f64,
    rng: Rng,
}

impl Encoder {
    /// A clean encoder of `bits`.
    pub fn new(bits: u32, rounding: Rounding) -> Self {
        Encoder {
            bits,
            rounding,
            noise: 0.0,
            rng: Rng::seeded(0),
        }
    }

    /// Adds ±1 count (each equally likely) to `probability` of the readings, drawn from a
    /// generator seeded with `seed`.
    pub fn with_noise(mut self, probability: f64, seed: u64) -> Self {
        self.noise = probability;
        self.rng = Rng::seeded(seed);
        self
    }

    /// One count, rad.
    pub fn count(&self) -> f64 {
        TAU / (1u64 << self.bits) as f64
    }

    /// The clean count of `theta`.
    pub fn counts(&self, theta: f64) -> i64 {
        let c = theta / self.count();
        match self.rounding {
            Rounding::Floor => c.floor() as i64,
            Rounding::Nearest => c.round() as i64,
        }
    }

    /// A reading of `theta`: its count (plus the noise), times the count's angle.
    pub fn read(&mut self, theta: f64) -> f64 {
        let mut c = self.counts(theta);
        if self.noise > 0.0 && self.rng.unit() < self.noise {
            c += if self.rng.unit() < 0.5 { 1 } else { -1 };
        }
        c as f64 * self.count()
    }
}

/// The three rotors of the issue.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotorKind {
    /// No friction, no cogging, a clean encoder.
    Frictionless,
    /// Stick-slip friction of [`FRICTION`] of the limit, a clean encoder.
    Coulomb,
    /// Friction, cogging ([`COGGING`], [`COGGING_PERIODS`]) and an encoder with ±1-count
    /// noise in [`NOISE_PROBABILITY`] of its readings.
    Noisy,
}

impl RotorKind {
    /// All three, in the order of the tables.
    pub const ALL: [RotorKind; 3] = [
        RotorKind::Frictionless,
        RotorKind::Coulomb,
        RotorKind::Noisy,
    ];

    /// Its name in a table.
    pub fn name(self) -> &'static str {
        match self {
            RotorKind::Frictionless => "frictionless",
            RotorKind::Coulomb => "Coulomb friction 0.5 %",
            RotorKind::Noisy => "friction, cogging 2 % ×24, ±1-count noise 5 %",
        }
    }

    /// The rotor for a motor of torque `limit` (N·m).
    pub fn rotor(
        self,
        inertia: f64,
        limit: f64,
        dt: f64,
        delay: usize,
        theta: f64,
        omega: f64,
    ) -> Rotor {
        let r = Rotor::new(inertia, dt, delay, theta, omega);
        let f = FRICTION * limit;
        match self {
            RotorKind::Frictionless => r,
            RotorKind::Coulomb => r.with_friction(f, f),
            RotorKind::Noisy => r.with_friction(f, f).with_cogging(
                COGGING * limit,
                COGGING_PERIODS,
                COGGING_SUBSTEPS,
            ),
        }
    }

    /// Its encoder (the noisy rotor's draws its noise from `seed`).
    pub fn encoder(self, bits: u32, rounding: Rounding, seed: u64) -> Encoder {
        let e = Encoder::new(bits, rounding);
        match self {
            RotorKind::Noisy => e.with_noise(NOISE_PROBABILITY, seed),
            _ => e,
        }
    }
}

/// The torque-window metric: fed one period at a time.
#[derive(Clone, Copy, Debug)]
pub struct Window {
    periods: usize,
    reversals: usize,
    last_sign: f64,
    lo: f64,
    hi: f64,
    count_lo: i64,
    count_hi: i64,
    last_count: Option<i64>,
    direction: i64,
    count_reversals: usize,
    nan: bool,
}

impl Default for Window {
    fn default() -> Self {
        Window {
            periods: 0,
            reversals: 0,
            last_sign: 0.0,
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            count_lo: i64::MAX,
            count_hi: i64::MIN,
            last_count: None,
            direction: 0,
            count_reversals: 0,
            nan: false,
        }
    }
}

impl Window {
    /// One period: the commanded `torque` (a fraction of the limit) and the clean count.
    pub fn push(&mut self, torque: f64, count: i64) {
        self.periods += 1;
        let sign = if torque > 0.0 {
            1.0
        } else if torque < 0.0 {
            -1.0
        } else {
            0.0
        };
        if sign != 0.0 {
            if self.last_sign != 0.0 && sign != self.last_sign {
                self.reversals += 1;
            }
            self.last_sign = sign;
        }
        // A NaN command makes the peak to peak NaN, which no bound accepts.
        self.nan |= torque.is_nan();
        self.lo = self.lo.min(torque);
        self.hi = self.hi.max(torque);
        self.count_lo = self.count_lo.min(count);
        self.count_hi = self.count_hi.max(count);
        if let Some(last) = self.last_count {
            let d = (count - last).signum();
            if d != 0 {
                if self.direction != 0 && d != self.direction {
                    self.count_reversals += 1;
                }
                self.direction = d;
            }
        }
        self.last_count = Some(count);
    }

    /// Sign reversals counted so far.
    pub fn reversals(&self) -> usize {
        self.reversals
    }

    /// The metrics, for periods of `dt`.
    pub fn finish(&self, dt: f64) -> RestRun {
        let seconds = self.periods as f64 * dt;
        let torque_pp = if self.nan {
            f64::NAN
        } else {
            self.hi - self.lo
        };
        RestRun {
            reversals: self.reversals,
            reversals_per_s: if seconds > 0.0 {
                self.reversals as f64 / seconds
            } else {
                0.0
            },
            torque_pp,
            position_pp: self.count_hi.saturating_sub(self.count_lo),
            count_reversals: self.count_reversals,
            window: seconds,
            max_fraction: 0.0,
        }
    }
}

/// What one run measured, over its last [`WINDOW`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RestRun {
    /// Sign reversals of the command in the window.
    pub reversals: usize,
    /// The same per second.
    pub reversals_per_s: f64,
    /// Peak to peak of the command in the window, as a fraction of the limit.
    pub torque_pp: f64,
    /// Peak to peak of the clean encoder count in the window.
    pub position_pp: i64,
    /// Reversals of the clean count's direction in the window.
    pub count_reversals: usize,
    /// The window's duration, s.
    pub window: f64,
    /// The largest |command| of the whole run (a law within its limit keeps it ≤ 1).
    pub max_fraction: f64,
}

impl RestRun {
    /// More than [`MAX_REVERSALS_PER_S`] reversals per second.
    pub fn chatters(&self) -> bool {
        exceeds(self.reversals_per_s, MAX_REVERSALS_PER_S)
    }

    /// More than [`MAX_PEAK_TO_PEAK`] of the limit peak to peak (or a NaN command).
    pub fn ripples(&self) -> bool {
        exceeds(self.torque_pp, MAX_PEAK_TO_PEAK)
    }

    /// Within [`OSCILLATING_COUNTS`] counts peak to peak.
    pub fn at_rest(&self) -> bool {
        self.position_pp <= OSCILLATING_COUNTS
    }

    /// Not at rest, and the count reversed at least [`OSCILLATING_REVERSALS`] times.
    pub fn oscillating(&self) -> bool {
        !self.at_rest() && self.count_reversals >= OSCILLATING_REVERSALS
    }

    /// Not at rest, but not oscillating either: still creeping.
    pub fn unsettled(&self) -> bool {
        !self.at_rest() && !self.oscillating()
    }
}

/// Runs `knob` on `rotor` for `seconds`, read by `encoder`, with `fault` between the
/// encoder and the knob and `trace` told every period's command.
///
/// Each period `k`: the encoder reads the rotor, `fault(k, reading)` gives what the knob
/// is handed (return `reading` for a healthy sensor), `knob(angle)` gives the torque as a
/// fraction of `limit`, `trace(k, torque)` sees it, and the rotor integrates
/// `torque·limit` (a non-finite command is applied as zero torque, and counted in the
/// metrics as it is). The metrics are over the last [`WINDOW`] of the periods.
pub fn run_with(
    rotor: &mut Rotor,
    encoder: &mut Encoder,
    limit: f64,
    seconds: f64,
    mut fault: impl FnMut(usize, f64) -> f64,
    mut knob: impl FnMut(f64) -> f64,
    mut trace: impl FnMut(usize, f64),
) -> RestRun {
    let n = (seconds / rotor.dt).round() as usize;
    let tail = n - ((n as f64 * WINDOW).round() as usize).min(n);
    let mut window = Window::default();
    let mut max_fraction: f64 = 0.0;
    for k in 0..n {
        let reading = encoder.read(rotor.theta);
        let torque = knob(fault(k, reading));
        trace(k, torque);
        max_fraction = max_fraction.max(torque.abs());
        if k >= tail {
            window.push(torque, encoder.counts(rotor.theta));
        }
        rotor.step(if torque.is_finite() {
            torque * limit
        } else {
            0.0
        });
    }
    let mut out = window.finish(rotor.dt);
    out.max_fraction = if max_fraction.is_nan() {
        f64::NAN
    } else {
        max_fraction
    };
    out
}

/// Runs `knob` on `rotor` for `seconds`, read by `encoder` (see [`run_with`]).
pub fn run(
    rotor: &mut Rotor,
    encoder: &mut Encoder,
    limit: f64,
    seconds: f64,
    knob: impl FnMut(f64) -> f64,
) -> RestRun {
    run_with(rotor, encoder, limit, seconds, |_, a| a, knob, |_, _| {})
}

/// Everything a rest run needs besides the law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setup {
    /// Loop rate, Hz.
    pub rate: f64,
    /// The rotor's inertia, kg·m².
    pub inertia: f64,
    /// The motor's torque limit, N·m.
    pub limit: f64,
    /// Periods of delay of the torque (0 or 1).
    pub delay: usize,
    /// Encoder bits.
    pub bits: u32,
    /// Encoder rounding.
    pub rounding: Rounding,
    /// Which rotor.
    pub rotor: RotorKind,
    /// The noise seed of the noisy rotor's encoder.
    pub seed: u64,
}

/// Runs `knob` on the rotor of `setup` for `seconds` from angle `theta0` and velocity
/// `omega0`: the entry point of the rest tests.
pub fn rest(
    setup: &Setup,
    theta0: f64,
    omega0: f64,
    seconds: f64,
    knob: impl FnMut(f64) -> f64,
) -> RestRun {
    let mut rotor = setup.rotor.rotor(
        setup.inertia,
        setup.limit,
        1.0 / setup.rate,
        setup.delay,
        theta0,
        omega0,
    );
    let mut encoder = setup.rotor.encoder(setup.bits, setup.rounding, setup.seed);
    run(&mut rotor, &mut encoder, setup.limit, seconds, knob)
}

/// One configuration of the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    /// Loop rate, Hz.
    pub rate: f64,
    /// Inertia (configured and real), kg·m².
    pub inertia: f64,
    /// Torque limit, N·m.
    pub limit: f64,
    /// Damping ratio.
    pub zeta: f64,
    /// Periods of delay the law is designed for, and the rotor's delay (0 or 1).
    pub latency: usize,
    /// Detents: per turn without endstops, over the range with them.
    pub detents: u32,
    /// Endstops at [`ENDSTOPS`] (the first and last detent on the stops), or endless.
    pub endstops: bool,
    /// Encoder bits.
    pub bits: u32,
    /// The detents' peak torque, as a fraction of the limit.
    pub detent_torque: f64,
}

impl Case {
    /// One encoder count, rad.
    pub fn count(&self) -> f64 {
        TAU / (1u64 << self.bits) as f64
    }

    /// The detent width, rad.
    pub fn width(&self) -> f64 {
        if self.endstops {
            (ENDSTOPS.1 - ENDSTOPS.0) / f64::from(self.detents - 1)
        } else {
            TAU / f64::from(self.detents)
        }
    }

    /// The detents' peak torque, N·m.
    pub fn peak_torque(&self) -> f64 {
        self.detent_torque * self.limit
    }

    /// The rest setup of this case on `rotor` (a floored encoder, noise seed from the
    /// case's position in the grid so that runs reproduce).
    pub fn setup(&self, rotor: RotorKind, seed: u64) -> Setup {
        Setup {
            rate: self.rate,
            inertia: self.inertia,
            limit: self.limit,
            delay: self.latency,
            bits: self.bits,
            rounding: Rounding::Floor,
            rotor,
            seed,
        }
    }
}

/// The endstops of a bounded case: ±135°, SmartKnob's bounded knob.
pub const ENDSTOPS: (f64, f64) = (-0.375 * TAU, 0.375 * TAU);

/// The grid's axes.
#[derive(Clone, Copy, Debug)]
pub struct Grid {
    /// Loop rates, Hz.
    pub rates: &'static [f64],
    /// Inertias, kg·m².
    pub inertias: &'static [f64],
    /// Torque limits, N·m.
    pub limits: &'static [f64],
    /// Damping ratios.
    pub zetas: &'static [f64],
    /// Detent counts.
    pub detents: &'static [u32],
    /// Encoder bits.
    pub bits: &'static [u32],
    /// Detent peak torques, fractions of the limit.
    pub detent_torques: &'static [f64],
}

/// The grid: 3 rates · 3 inertias · 3 limits · 3 ζ · 2 latencies · 3 detent
/// counts · 2 (endless, endstops) · 4 encoders · 2 strengths = 7,776 configurations.
pub const FULL: Grid = Grid {
    rates: &[1_000.0, 4_000.0, 10_000.0],
    inertias: &[1e-6, 1e-5, 1e-4],
    limits: &[0.02, 0.1, 0.5],
    zetas: &[0.2, 0.7, 2.0],
    detents: &[2, 24, 100],
    bits: &[10, 12, 14, 16],
    detent_torques: &[0.1, 0.5],
};

/// The stride of [`short`] through [`FULL`]'s configurations (a prime, so that it
/// cycles through every axis).
pub const SHORT_STRIDE: usize = 113;

impl Grid {
    /// Every configuration; the detent strength varies fastest, then the encoder,
    /// endstops, detents, latency, ζ, limit, inertia, rate.
    pub fn cases(&self) -> Vec<Case> {
        let mut v = Vec::new();
        for &rate in self.rates {
            for &inertia in self.inertias {
                for &limit in self.limits {
                    for &zeta in self.zetas {
                        for latency in [0, 1] {
                            for &detents in self.detents {
                                for endstops in [false, true] {
                                    for &bits in self.bits {
                                        for &detent_torque in self.detent_torques {
                                            v.push(Case {
                                                rate,
                                                inertia,
                                                limit,
                                                zeta,
                                                latency,
                                                detents,
                                                endstops,
                                                bits,
                                                detent_torque,
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

/// The short grid: every [`SHORT_STRIDE`]th configuration of [`FULL`] (69 of them).
pub fn short() -> Vec<Case> {
    FULL.cases().into_iter().step_by(SHORT_STRIDE).collect()
}

/// The start of a case, `(angle, velocity)`: 0.45 of a width off a detent centre with a
/// 5 rad/s flick. Endless: off the detent at 0. Between endstops: off the middle detent
/// (with 2 detents, off the lower one, towards the upper).
pub fn start(c: &Case) -> (f64, f64) {
    let width = c.width();
    if c.endstops {
        let middle = f64::from((c.detents - 1) / 2);
        (ENDSTOPS.0 + (middle + 0.45) * width, 5.0)
    } else {
        (0.45 * width, 5.0)
    }
}

/// Totals over a sweep, for one rotor.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    /// Runs recorded.
    pub runs: usize,
    /// Runs above [`MAX_REVERSALS_PER_S`].
    pub chatter: usize,
    /// The most reversals per second, and its run.
    pub worst_chatter: (f64, String),
    /// Runs at rest (see [`RestRun::at_rest`]).
    pub at_rest: usize,
    /// Runs at rest above [`MAX_PEAK_TO_PEAK`].
    pub ripple: usize,
    /// The largest peak to peak (fraction of the limit) of a run at rest, and its run.
    pub worst_ripple: (f64, String),
    /// Runs oscillating ([`RestRun::oscillating`]).
    pub oscillating: usize,
    /// Runs still creeping ([`RestRun::unsettled`]).
    pub unsettled: usize,
    /// The largest position peak to peak (counts), and its run.
    pub worst_position: (i64, String),
    /// The largest |command| of any run.
    pub max_fraction: f64,
}

impl Tally {
    /// Adds a run, described by `what` when it is a new worst.
    pub fn record(&mut self, r: &RestRun, what: impl Fn() -> String) {
        self.runs += 1;
        if r.chatters() {
            self.chatter += 1;
        }
        if r.at_rest() {
            self.at_rest += 1;
            if r.ripples() {
                self.ripple += 1;
            }
            if exceeds(r.torque_pp, self.worst_ripple.0) {
                self.worst_ripple = (r.torque_pp, what());
            }
        }
        if r.oscillating() {
            self.oscillating += 1;
        }
        if r.unsettled() {
            self.unsettled += 1;
        }
        // NaN compares false: a NaN is recorded as the worst at once.
        if exceeds(r.reversals_per_s, self.worst_chatter.0) {
            self.worst_chatter = (r.reversals_per_s, what());
        }
        if r.position_pp > self.worst_position.0 {
            self.worst_position = (r.position_pp, what());
        }
        if exceeds(r.max_fraction, self.max_fraction) {
            self.max_fraction = r.max_fraction;
        }
    }
}

/// A sweep's totals: the configurations and a [`Tally`] per rotor.
#[derive(Clone, Debug, Default)]
pub struct Sweep {
    /// Configurations of the grid.
    pub configs: usize,
    /// Configurations the knob accepted (and ran).
    pub accepted: usize,
    /// One tally per [`RotorKind::ALL`].
    pub rotors: [Tally; 3],
}

impl Sweep {
    /// The table of the issue: one row per rotor, Markdown.
    pub fn table(&self, backend: &str) -> String {
        let mut s = format!(
            "{backend}: {} of {} configurations accepted\n\n\
             | rotor | runs | chatter > 20 rev/s | worst rev/s | at rest (≤ 8 counts) | of them p-p > 2 % | worst p-p | oscillating | unsettled | worst position p-p | max torque |\n\
             |---|---|---|---|---|---|---|---|---|---|---|\n",
            self.accepted, self.configs
        );
        for (kind, t) in RotorKind::ALL.iter().zip(&self.rotors) {
            s.push_str(&format!(
                "| {} | {} | {} | {:.0} | {} | {} | {:.2} % | {} | {} | {} | {:.3} |\n",
                kind.name(),
                t.runs,
                t.chatter,
                t.worst_chatter.0,
                t.at_rest,
                t.ripple,
                100.0 * t.worst_ripple.0,
                t.oscillating,
                t.unsettled,
                t.worst_position.0,
                t.max_fraction,
            ));
        }
        s
    }

    /// The columns of [`Sweep::rows`].
    pub const ROW_HEADER: [&'static str; 9] = [
        "backend",
        "rotor",
        "runs",
        "chatter above 20/s (runs)",
        "worst",
        "at rest above 2 % p-p (runs)",
        "worst",
        "oscillating",
        "unsettled",
    ];

    /// One row per rotor, for the docs' table of several backends ([`Sweep::ROW_HEADER`]).
    pub fn rows(&self, backend: &str) -> Vec<Vec<String>> {
        RotorKind::ALL
            .iter()
            .zip(&self.rotors)
            .map(|(kind, t)| {
                vec![
                    format!("`{backend}`"),
                    kind.name().to_string(),
                    t.runs.to_string(),
                    t.chatter.to_string(),
                    format!("{:.0}/s", t.worst_chatter.0),
                    t.ripple.to_string(),
                    format!("{:.2} %", 100.0 * t.worst_ripple.0),
                    t.oscillating.to_string(),
                    t.unsettled.to_string(),
                ]
            })
            .collect()
    }

    /// The worst runs, one line each: for finding them again.
    pub fn worst(&self) -> String {
        let mut s = String::new();
        for (kind, t) in RotorKind::ALL.iter().zip(&self.rotors) {
            s.push_str(&format!(
                "{}: worst chatter {:.0}/s: {}\n{}: worst p-p {:.2} %: {}\n{}: worst position {} counts: {}\n",
                kind.name(),
                t.worst_chatter.0,
                t.worst_chatter.1,
                kind.name(),
                100.0 * t.worst_ripple.0,
                t.worst_ripple.1,
                kind.name(),
                t.worst_position.0,
                t.worst_position.1
            ));
        }
        s
    }
}

/// `value > bound`, or `value` NaN: a NaN breaks every bound.
pub fn exceeds(value: f64, bound: f64) -> bool {
    value.is_nan() || value > bound
}

/// Periods, from `from` on, in which `|torque(k)| > bound` in `trace` (the torques of
/// periods `0, 1, …`): the bad-sample metric of the issue.
pub fn periods_above(trace: &[f64], from: usize, bound: f64) -> usize {
    trace
        .iter()
        .skip(from)
        .filter(|t| exceeds(t.abs(), bound))
        .count()
}

/// Periods, from `from` on, in which two traces differ by more than `bound`: a faulty run
/// against its healthy twin (the same readings but one).
pub fn periods_apart(faulty: &[f64], healthy: &[f64], from: usize, bound: f64) -> usize {
    faulty
        .iter()
        .zip(healthy)
        .skip(from)
        .filter(|(a, b)| exceeds((*a - *b).abs(), bound))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without friction a constant torque is integrated exactly: θ = θ₀ + ω₀t + ½(τ/J)t²,
    /// also across the instant the velocity changes sign.
    #[test]
    fn frictionless_rotor_is_exact() {
        let (j, dt, tau) = (1e-5, 1e-3, -2e-3);
        for delay in [0, 1] {
            let mut r = Rotor::new(j, dt, delay, 0.1, 3.0);
            let steps = 500;
            for _ in 0..steps {
                r.step(tau);
            }
            let held = (steps - delay) as f64 * dt;
            let t = steps as f64 * dt;
            let theta = 0.1 + 3.0 * t + 0.5 * tau / j * held * held;
            assert!((r.theta - theta).abs() < 1e-9 * theta.abs(), "{delay}");
            assert!((r.omega - (3.0 + tau / j * held)).abs() < 1e-9);
        }
    }

    /// Stiction: a torque at or below the static friction never moves a rotor at rest,
    /// for ever (not a drift, not a tremble); just above it, it breaks away against the
    /// kinetic friction.
    #[test]
    fn stuck_rotor_stays_exactly_still() {
        let mut r = Rotor::new(1e-5, 1e-4, 0, 0.3, 0.0).with_friction(1e-4, 1e-4);
        for k in 0..100_000 {
            r.step(if k % 2 == 0 { 1e-4 } else { -1e-4 });
            assert_eq!((r.theta, r.omega), (0.3, 0.0));
        }
        r.step(2e-4);
        let a = (2e-4 - 1e-4) / 1e-5;
        assert!((r.omega - a * 1e-4).abs() < 1e-15);
        assert!((r.theta - 0.3 - 0.5 * a * 1e-8).abs() < 1e-15);
    }

    /// A flick against Coulomb friction stops at t = J·ω₀/τ_k, having turned J·ω₀²/(2τ_k),
    /// and then stays put: no velocity sign flips from the friction itself.
    #[test]
    fn flick_against_friction_stops_exactly() {
        let (j, tk, w0) = (1e-5, 1e-4, 5.0);
        let mut r = Rotor::new(j, 1e-3, 0, 0.0, w0).with_friction(tk, tk);
        let mut stopped_at = None;
        for k in 0..2000 {
            r.step(0.0);
            assert!(r.omega >= 0.0);
            if r.stuck() && stopped_at.is_none() {
                stopped_at = Some(k);
            }
        }
        let t_stop = j * w0 / tk; // 0.5 s
        let k = (t_stop / 1e-3).round() as usize - 1;
        assert!(
            stopped_at == Some(k) || stopped_at == Some(k + 1),
            "{stopped_at:?}"
        );
        assert!((r.theta - j * w0 * w0 / (2.0 * tk)).abs() < 1e-12);
    }

    /// Cogging without friction: small oscillations about a cogging minimum at
    /// ω = √(A·n/J); the sub-stepped integrator keeps the energy.
    #[test]
    fn cogging_rings_at_its_frequency() {
        let (j, a, n) = (1e-5, 4e-4, 24u32);
        let dt = 1e-4;
        let mut r = Rotor::new(j, dt, 0, 1e-3, 0.0).with_cogging(a, n, 16);
        let w = (a * f64::from(n) / j).sqrt();
        let period = TAU / w;
        // Count upward zero crossings over 20 periods.
        let steps = (20.0 * period / dt) as usize;
        let mut crossings = 0;
        let mut last = r.theta;
        let mut e_max: f64 = 0.0;
        let energy = |r: &Rotor| {
            0.5 * j * r.omega * r.omega + a / f64::from(n) * (1.0 - (f64::from(n) * r.theta).cos())
        };
        let e0 = energy(&r);
        for _ in 0..steps {
            r.step(0.0);
            if last < 0.0 && r.theta >= 0.0 {
                crossings += 1;
            }
            last = r.theta;
            e_max = e_max.max((energy(&r) - e0).abs() / e0);
        }
        assert!((19..=20).contains(&crossings), "{crossings}");
        assert!(e_max < 1e-4, "{e_max}");
    }

    #[test]
    fn encoder_floors_or_rounds() {
        let e = Encoder::new(10, Rounding::Floor);
        let c = e.count();
        assert_eq!(e.counts(2.7 * c), 2);
        assert_eq!(e.counts(-0.2 * c), -1);
        let e = Encoder::new(10, Rounding::Nearest);
        assert_eq!(e.counts(2.7 * c), 3);
        assert_eq!(e.counts(-0.2 * c), 0);
    }

    /// About 5 % of the noisy readings are off, by one count, either way.
    #[test]
    fn noise_hits_five_percent_by_one_count() {
        let mut e = Encoder::new(14, Rounding::Floor).with_noise(0.05, 7);
        let theta = 100.5 * e.count();
        let (mut up, mut down) = (0, 0);
        let n = 100_000;
        for _ in 0..n {
            match (e.read(theta) / e.count()).round() as i64 - 100 {
                0 => {}
                1 => up += 1,
                -1 => down += 1,
                d => panic!("off by {d}"),
            }
        }
        let off = f64::from(up + down) / f64::from(n);
        assert!((off - 0.05).abs() < 0.003, "{off}");
        assert!((f64::from(up) / f64::from(up + down) - 0.5).abs() < 0.03);
    }

    /// The reversal definition: zeros neither count nor reset the last sign.
    #[test]
    fn reversals_skip_zeros() {
        let mut w = Window::default();
        for t in [0.0, 0.1, 0.0, 0.0, -0.1, -0.2, 0.0, 0.3, 0.0, 0.3, -0.0] {
            w.push(t, 0);
        }
        let r = w.finish(1e-3);
        assert_eq!(r.reversals, 2);
        assert!((r.reversals_per_s - 2.0 / 11e-3).abs() < 1e-9);
        assert!((r.torque_pp - 0.5).abs() < 1e-15);
        let mut w = Window::default();
        w.push(0.1, 0);
        w.push(f64::NAN, 0);
        w.push(0.1, 0);
        assert!(w.finish(1e-3).ripples());
    }

    /// The metric can fail: a law that toggles one count's torque chatters at the rate;
    /// a law that is silent in a dead band does not. A spring on the frictionless
    /// rotor, undamped, oscillates.
    #[test]
    fn the_metrics_can_fail() {
        let setup = Setup {
            rate: 4_000.0,
            inertia: 1e-5,
            limit: 0.02,
            delay: 1,
            bits: 14,
            rounding: Rounding::Floor,
            rotor: RotorKind::Frictionless,
            seed: 1,
        };
        let mut flip = 1.0;
        let toggling = rest(&setup, 0.0, 0.0, 1.0, |_| {
            flip = -flip;
            0.01 * flip
        });
        assert!(toggling.chatters() && (toggling.reversals_per_s - 4_000.0).abs() < 5.0);
        let silent = rest(&setup, 0.0, 0.0, 1.0, |_| 0.0);
        assert_eq!(
            (silent.reversals, silent.torque_pp, silent.position_pp),
            (0, 0.0, 0)
        );
        let spring = rest(&setup, 0.05, 0.0, 1.0, |a| -0.4 * a / 0.02);
        assert!(spring.oscillating(), "{spring:?}");
    }

    /// A PD whose set point lies between two counts (so its error is never zero) limit-
    /// cycles across the count boundary on the frictionless rotor: it chatters. On the
    /// Coulomb rotor the same law sticks within a few counts.
    #[test]
    fn a_pd_chatters_on_the_frictionless_rotor() {
        let (rate, j, limit) = (4_000.0, 1e-5, 0.02);
        let count = TAU / 16384.0;
        let (k, b) = (0.05, 2.0 * 0.7 * (0.05f64 * 1e-5).sqrt());
        let pd = |setup: &Setup| {
            let mut prev = 0.0;
            rest(setup, 0.3 * count, 1.0, 2.0, |a| {
                let v = (a - prev) * rate;
                prev = a;
                ((-k * (a - 0.5 * count) - b * v) / limit).clamp(-1.0, 1.0)
            })
        };
        let mut setup = Setup {
            rate,
            inertia: j,
            limit,
            delay: 1,
            bits: 14,
            rounding: Rounding::Floor,
            rotor: RotorKind::Frictionless,
            seed: 1,
        };
        let free = pd(&setup);
        assert!(free.chatters(), "{free:?}");
        setup.rotor = RotorKind::Coulomb;
        let stuck = pd(&setup);
        assert!(!stuck.oscillating(), "{stuck:?}");
    }

    #[test]
    fn grids_have_the_documented_sizes() {
        assert_eq!(FULL.cases().len(), 7_776);
        assert_eq!(short().len(), 69);
        let c = FULL.cases()[5];
        let (theta, omega) = start(&c);
        assert_eq!(omega, 5.0);
        assert!((theta - 0.45 * c.width()).abs() < 1e-15 || c.endstops);
    }
}
