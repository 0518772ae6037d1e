//! What is measured on a stepper: tracking error, amplitude left, and how a fixed-point spring ends (Brent's cycle detection).

use super::*;

/// Max |x_n − x(n)| over n = 1..=len against precomputed samples; returns (error, step).
pub struct Track<'a> {
    /// `x(n)`, n = 0..=steps.
    pub reference: &'a [f64],
}

impl Job for Track<'_> {
    type Out = (f64, usize);
    fn run<S: Stepper>(&mut self, mut s: S) -> (f64, usize) {
        let mut worst = (0.0, 0);
        for (n, r) in self.reference.iter().enumerate().skip(1) {
            s.step();
            let e = (s.position() - r).abs();
            if e > worst.0 {
                worst = (e, n);
            }
        }
        worst
    }
}

/// Max |x| over the last `window` of `steps` steps.
pub struct Amplitude {
    /// Steps in all.
    pub steps: u64,
    /// The final window.
    pub window: u64,
}

impl Job for Amplitude {
    type Out = f64;
    fn run<S: Stepper>(&mut self, mut s: S) -> f64 {
        let mut m: f64 = 0.0;
        for n in 1..=self.steps {
            s.step();
            if n > self.steps - self.window {
                m = m.max(s.position().abs());
            }
        }
        m
    }
}

/// The final state of a fixed-point spring: run until the state repeats (Brent's cycle
/// detection, plus an immediate test for a fixed point) or `cap` steps.
pub struct Settle {
    /// Step cap.
    pub cap: u64,
    /// The window measured when no repeat is found.
    pub window: u64,
}

/// What a fixed-point spring ends in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Final {
    /// Steps until the repeat was seen (None: no repeat within the cap).
    pub steps: Option<u64>,
    /// Cycle length (1 for a fixed point).
    pub period: u64,
    /// Peak-to-peak of the visible position over the cycle, visible LSB.
    pub peak_to_peak: i128,
    /// Largest |visible position| over the cycle, visible LSB.
    pub offset: i128,
    /// Largest |internal offset| over the cycle, visible LSB, unrounded.
    pub internal: f64,
}

impl Job for Settle {
    type Out = Final;
    fn run<S: Stepper>(&mut self, mut s: S) -> Final {
        let mut power = 1u64;
        let mut lam = 0u64;
        let mut tortoise = s.key();
        let mut steps = 0u64;
        let found = loop {
            let before = s.key();
            s.step();
            steps += 1;
            lam += 1;
            if s.key() == before {
                // a fixed point, seen at once rather than at the next power of two
                lam = 1;
                break true;
            }
            if s.key() == tortoise {
                break true;
            }
            if lam == power {
                tortoise = s.key();
                power *= 2;
                lam = 0;
            }
            if steps >= self.cap {
                break false;
            }
        };
        let span = if found { lam } else { self.window };
        let (mut lo, mut hi, mut off, mut int) = (i128::MAX, i128::MIN, 0i128, 0.0f64);
        for _ in 0..span {
            s.step();
            let v = s.visible_lsb();
            lo = lo.min(v);
            hi = hi.max(v);
            off = off.max(v.abs());
            int = int.max(s.internal_lsb().abs());
        }
        Final {
            steps: found.then_some(steps),
            period: if found { lam } else { 0 },
            peak_to_peak: hi - lo,
            offset: off,
            internal: int,
        }
    }
}
