//! The simulated plant of the knob tests: a rotor of inertia `I` with optional viscous
//! friction, driven by a zero-order-hold motor torque (with a computational delay of a
//! fraction of a period) and a hand, integrated exactly over fine sub-steps, read by a
//! 14-bit encoder. Written here, in `f64`, independently of the library.
//!
//! | module | what it is |
//! |---|---|
//! | [`pd`] | SmartKnob-style PD detents, flicked on this rotor against a law the caller sets up |
//! | [`sweep`] | the sweep of issue 13: a rotor with a delay of whole periods, the oscillation metric, the grids |
//! | [`linear`] | the loop's state matrix from the rotor's physics, its poles and characteristic polynomial |
//! | [`rest`] | issue 17: silence at rest measured on torque, on frictionless, stick-slip and cogging/noisy rotors, and the rest grid |

pub mod linear;
pub mod pd;
pub mod rest;
pub mod sweep;

use std::f64::consts::TAU;

/// One count of a 14-bit encoder, in radians.
pub const COUNT: f64 = TAU / 16384.0;

/// The encoder: the angle floored to a whole count.
pub fn quantise(theta: f64) -> f64 {
    (theta / COUNT).floor() * COUNT
}

/// A rotor with ZOH motor torque and an external (hand) torque.
#[derive(Clone, Debug)]
pub struct Plant {
    pub inertia: f64,
    /// Viscous friction, N·m·s/rad.
    pub friction: f64,
    pub dt: f64,
    /// The computational delay as a fraction of the period: the command given at the end
    /// of period n starts acting `delay·dt` into period n + 1... (0: at once, 1: a period
    /// later).
    pub delay: f64,
    pub theta: f64,
    pub omega: f64,
    pub time: f64,
    /// The command still acting from the previous period.
    pending: f64,
    /// Sub-steps per segment: the hand torque is held over each.
    pub substeps: usize,
}

impl Plant {
    pub fn new(inertia: f64, dt: f64, delay: f64) -> Self {
        Plant {
            inertia,
            friction: 0.0,
            dt,
            delay,
            theta: 0.0,
            omega: 0.0,
            time: 0.0,
            pending: 0.0,
            substeps: 8,
        }
    }

    /// What the encoder reads now.
    pub fn read(&self) -> f64 {
        quantise(self.theta)
    }

    /// Constant torque `tau` over `h`, integrated exactly (with friction: the exponential
    /// solution of `I·ω' = τ − b·ω`).
    fn hold(&mut self, tau: f64, h: f64) {
        let (i, b) = (self.inertia, self.friction);
        if b == 0.0 {
            let a = tau / i;
            self.theta += self.omega * h + 0.5 * a * h * h;
            self.omega += a * h;
        } else {
            let k = b / i;
            let terminal = tau / b;
            let decay = (-k * h).exp();
            let gone = -(-k * h).exp_m1();
            self.theta += terminal * h + (self.omega - terminal) * gone / k;
            self.omega = terminal + (self.omega - terminal) * decay;
        }
        self.time += h;
    }

    /// One control period in which the controller commanded `command` (N·m) from the
    /// angle it read at the start; `hand(θ, ω, t)` is the hand's torque, held over each
    /// sub-step.
    pub fn step(&mut self, command: f64, hand: &mut dyn FnMut(f64, f64, f64) -> f64) {
        let segments = [
            (self.pending, self.delay * self.dt),
            (command, (1.0 - self.delay) * self.dt),
        ];
        for (tau, length) in segments {
            if length <= 0.0 {
                continue;
            }
            let h = length / self.substeps as f64;
            for _ in 0..self.substeps {
                let extra = hand(self.theta, self.omega, self.time);
                self.hold(tau + extra, h);
            }
        }
        self.pending = command;
    }
}

/// No hand.
pub fn no_hand(_: f64, _: f64, _: f64) -> f64 {
    0.0
}
