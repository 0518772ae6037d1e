//! A glide that crosses a bound hands over to the bounce spring at the instant of the
//! crossing, not at the frame after it.
//!
//! The step that first puts the glide past the bound `b` leaves it at `x_n` with velocity
//! `v_n`. Friction alone took it there from the crossing, `τ` seconds earlier:
//! `v(t) = v*·e^{−c·t}` and `x − b = (v*/c)(1 − e^{−c·τ})` give, with `d = x_n − b`,
//!
//! ```text
//! v* = v_n + c·d        τ = ln(1 + c·d/v_n) / c
//! ```
//!
//! so the crossing velocity needs no logarithm, and `τ` one. From the crossing on, the
//! continuous motion is the bounce spring's, started at the bound with `v*`; its state `τ`
//! later ([`Oscillator::state_after`](crate::Oscillator::state_after)) is where the frame
//! puts it, and the spring's exact start keeps every later frame on that continuous
//! motion. Starting the spring at `(x_n, v_n)` instead would run friction for up to a
//! frame past the bound: `v*·dt` of extra overshoot, 33 px for a 2,000 px/s throw at 60
//! Hz, varying from throw to throw with the phase of the frame.
//!
//! This runs once per throw, in `f64` (libm's `log1p`, `exp`, `sin`/`cos`).

use super::{Scroll, ScrollPhase};
use crate::scalar::Scalar;

impl<S: Scalar> Scroll<'_, S> {
    /// Hands the glide over to the bounce spring at `bound`, which its last step passed.
    pub(super) fn hand_over(&mut self, bound: S) {
        // The glide's state, finer than a position: the spring continues it, not its
        // rounding.
        let (x, v) = self.glide.state_f64(0);
        let c = self.friction.rate();
        let past = x - bound.to_f64();
        let tau = libm::log1p(c * past / v) / c;
        // Within the last step: a bound that moved inward under a glide (`set_bounds`)
        // was crossed earlier, and the spring then starts where the glide is.
        let (offset, velocity) = if tau.is_finite() && (0.0..=self.dt * (1.0 + 1e-9)).contains(&tau)
        {
            self.bounce_oscillator.state_after(0.0, v + c * past, tau)
        } else {
            (past, v)
        };
        self.bounce.start_at([bound], [offset], [velocity]);
        self.rest = bound;
        self.crossing = None;
        self.phase = ScrollPhase::Bouncing;
    }
}
