//! The torque law of one control period, in the backend's arithmetic: a spring on the
//! extension with a rest zone and a soft knee, and a damper on the low-pass-filtered
//! movement of the angle through a play. Only `add`, `sub`, `neg`, `abs`, `mul`,
//! `mul_coef` and comparisons; no division, no `Result`.
//!
//! It is the crate's kernel `Δu = −(C_k·e + C_d·u)` on a fixed anchor, with `e` the
//! extension past the rest zone and `u` the filtered step velocity, scaled so that the
//! result is the torque as a fraction of the limit: each layer's `C_k·J/(dt²·τ_max)` is
//! its stiffness over the torque limit (`K/τ_max`, per radian), and `C_d·J/(dt²·τ_max)` is
//! `B/(τ_max·dt)`. The gains multiply the angles **before** anything is rounded, so that
//! fixed point keeps its 16 fractional bits in the torque, not in the angle: a stiff
//! spring of 1500 /rad would otherwise multiply an angle's LSB (1.5e−5 rad in `I16F16`)
//! into 2% of the limit.
//!
//! # Why the knob is silent at rest
//!
//! A rotor at rest sits between two encoder counts, and the reading toggles between them
//! (the rotor creeps, the encoder is noisy). Each toggle is a one-count step of the angle.
//! Without the three pieces below, a frictionless rotor answers every toggle with a
//! torque of the opposite sign: the current reverses at 1–1.5 kHz, and the motor whines.
//!
//! - **Play on the damper's input.** The damper differentiates not the angle but the
//!   output of a play (backlash) of half-width [`PLAY_COUNTS`] counts: `p ← clamp(p,
//!   θ − w, θ + w)`. A reading that toggles by one count, or by ±1 count of noise around a
//!   count (`2` counts in all, under `2w = 2.5`), does not move `p`: the damper sees no
//!   velocity. A turning rotor drags `p` along, and the damper sees its whole movement.
//! - **A rest zone of [`REST_COUNTS`] counts** on each side of the rest point, where the
//!   spring torque is exactly zero: a centre that falls between counts no longer pushes
//!   the rotor back and forth.
//! - **A soft knee** past the rest zone: the spring rises as `(e − r)²/(2·k)` over the
//!   knee `k` (up to [`KNEE_COUNTS`] counts), then goes on linearly with its full
//!   stiffness. The first count past the zone commands an eighth of a count's full torque
//!   instead of all of it.
//!
//! Inside the zone a frictionless rotor drifts without torque, and each time it meets the
//! knee it turns back with one reversal; the damper takes energy out of every crossing
//! (the crossing is longer than the play), so the crossings slow down and the reversals
//! stop. The cost is a soft centre: within `±(REST_COUNTS + KNEE_COUNTS)` counts of a
//! detent's centre the torque is below the linear spring's.

use crate::scalar::Scalar;

/// The damper's state scale: the state holds up to [`STATE_SCALE`] times the damping
/// torque (less where the backend's range needs it), so that fixed point keeps four more
/// fractional bits in the recursion, whose truncations add up over about `1/α` periods.
pub(crate) const STATE_SCALE: f64 = 16.0;

/// The play's half-width, in encoder counts: above 1, so that a reading toggling by ±1
/// count about a count (2 counts peak to peak) stays inside the play's `2·1.25 = 2.5`.
pub const PLAY_COUNTS: f64 = 1.25;

/// The play's half-width where the damper's own mode is poorly damped (the design's
/// `play_counts`): half a count, which still absorbs a reading toggling between two
/// counts, not ±1 count of noise about one.
pub const MIN_PLAY_COUNTS: f64 = 0.5;

/// The rest zone's half-width, in encoder counts.
pub const REST_COUNTS: f64 = 2.0;

/// The knee's width, in encoder counts (less where a detent is too narrow for it: at most
/// a quarter of the way from the rest zone to the snap point).
pub const KNEE_COUNTS: f64 = 4.0;

/// The smallest torque commanded, as a fraction of the limit: a float backend's rounding
/// noise (a damper state decaying as `βⁿ`) is not sent to the motor. `2⁻²⁴` is below the
/// last bit of any current DAC; fixed point's last bit (`2⁻¹⁶`) is above it.
pub(crate) const TORQUE_FLOOR: f64 = 1.0 / 16_777_216.0;

/// The damper's state update: the movement `u` of the play's output (radians per
/// period) times `scale·B/(τ_max·dt)`, through the first-order low-pass
/// `v ← β·v + α·(gain·u)`.
#[inline(always)]
pub(crate) fn filtered_damping<S: Scalar>(
    state: S,
    step: S,
    gain: S,
    alpha: S::Coef,
    beta: S::Coef,
) -> S {
    state.mul_coef(beta).add(step.mul(gain).mul_coef(alpha))
}

/// The play: `held` moved just enough to be within `play` of `angle`.
#[inline(always)]
pub(crate) fn play<S: Scalar>(held: S, angle: S, play: S) -> S {
    let low = angle.sub(play);
    let high = angle.add(play);
    if held < low {
        low
    } else if held > high {
        high
    } else {
        held
    }
}

/// The damping torque (fraction of the limit) of a state: `state/scale`, with
/// `unscale = 1/scale` (a power of two: exact in every backend).
#[inline(always)]
pub(crate) fn damping_torque<S: Scalar>(state: S, unscale: S::Coef) -> S {
    state.mul_coef(unscale)
}

/// A zone's rest zone and knee, in torque (fractions of the limit): `rest` is the zone's
/// stiffness times the rest zone's half-width, `knee` its stiffness times the knee's
/// width, `half_knee = knee/2` and `curvature = 1/(2·knee)`.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Shape<S: Scalar> {
    pub(crate) rest: S,
    pub(crate) knee: S,
    pub(crate) half_knee: S,
    pub(crate) curvature: S,
}

/// The spring torque (fraction of the limit) of the layers acting in a zone, through the
/// zone's rest zone and knee: with `t = Σ gainᵢ·eᵢ` (the caller's sum of the layers'
/// stretches times their gains) and `o = |t| − rest`, zero for `o ≤ 0`, `o²/(2·knee)` up
/// to the knee, `o − knee/2` past it, signed as `t`.
#[inline(always)]
pub(crate) fn spring<S: Scalar>(t: S, shape: &Shape<S>) -> S {
    let over = t.abs().sub(shape.rest);
    if over > S::ZERO {
        let magnitude = if over < shape.knee {
            over.mul(over.mul(shape.curvature))
        } else {
            over.sub(shape.half_knee)
        };
        if t > S::ZERO {
            magnitude
        } else {
            magnitude.neg()
        }
    } else {
        S::ZERO
    }
}

/// The torque: `−(spring + damping)`, clamped to `[−1, 1]`, with a float's rounding noise
/// below [`TORQUE_FLOOR`] sent as zero; so is a NaN, which clamped inputs cannot give,
/// so that none ever leaves.
#[inline(always)]
pub(crate) fn torque<S: Scalar>(spring: S, damping: S, floor: S) -> S {
    let t = spring.add(damping).neg();
    if S::RESOLUTION > 0.0 {
        // Fixed point: two comparisons with constants (its `abs` saturates, at the cost
        // of five instructions), and no floor, which is below the last bit.
        if t > S::ONE {
            S::ONE
        } else if t < S::ONE.neg() {
            S::ONE.neg()
        } else {
            t
        }
    } else {
        // A float: one `abs` and two comparisons of it. Below the floor (or NaN) is
        // none, above the limit is the limit with the torque's sign.
        let size = t.abs();
        if size >= floor {
            if size > S::ONE {
                if t > S::ZERO { S::ONE } else { S::ONE.neg() }
            } else {
                t
            }
        } else {
            S::ZERO
        }
    }
}
