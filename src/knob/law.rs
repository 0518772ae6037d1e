//! The torque law of one control period, in the backend's arithmetic: a spring on the
//! extension with a rest zone, and a damper on the low-pass-filtered velocity. Only
//! `add`, `sub`, `neg`, `mul`, `mul_coef` and comparisons; no division, no `Result`.
//!
//! It is the crate's kernel `Δu = −(C_k·e + C_d·u)` on a fixed anchor, with `e` the
//! extension past the rest zone and `u` the filtered step velocity, scaled so that the
//! result is the torque as a fraction of the limit: each layer's `C_k·J/(dt²·τ_max)` is
//! its stiffness over the torque limit (`K/τ_max`, per radian), and `C_d·J/(dt²·τ_max)` is
//! `B/(τ_max·dt)`. The gains multiply the angles **before** anything is rounded, so that
//! fixed point keeps its 16 fractional bits in the torque, not in the angle: a stiff
//! spring of 1500 /rad would otherwise multiply an angle's LSB (1.5e−5 rad in `I16F16`)
//! into 2% of the limit.

use crate::scalar::Scalar;

/// The damper's state scale: the state holds up to [`STATE_SCALE`] times the damping
/// torque (less where the backend's range needs it), so that fixed point keeps four more
/// fractional bits in the recursion, whose truncations add up over about `1/α` periods.
pub(crate) const STATE_SCALE: f64 = 16.0;

/// The damper's state update: the backward difference `u` (radians per period) times
/// `scale·B/(τ_max·dt)`, through the first-order low-pass `v ← β·v + α·(gain·u)`.
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

/// The damping torque (fraction of the limit) of a state: `state/scale`, with
/// `unscale = 1/scale` (a power of two: exact in every backend).
#[inline(always)]
pub(crate) fn damping_torque<S: Scalar>(state: S, unscale: S::Coef) -> S {
    state.mul_coef(unscale)
}

/// The spring torque (fraction of the limit) of the three layers acting in a zone, with
/// the rest zone: `t − clamp(t, −rest, rest)`, `t = Σ gainᵢ·eᵢ` and `rest` the zone's
/// stiffness times one count.
#[inline(always)]
pub(crate) fn spring<S: Scalar>(
    (detent, other, ret): (S, S, S),
    (detent_gain, other_gain, return_gain): (S, S, S),
    rest: S,
) -> S {
    let t = detent
        .mul(detent_gain)
        .add(other.mul(other_gain))
        .add(ret.mul(return_gain));
    if t > rest {
        t.sub(rest)
    } else if t < rest.neg() {
        t.add(rest)
    } else {
        S::ZERO
    }
}

/// The torque: `−(spring + damping)`, clamped to `[−1, 1]`; the last arm cannot be reached
/// from clamped inputs, but keeps a NaN from ever leaving.
#[inline(always)]
pub(crate) fn torque<S: Scalar>(spring: S, damping: S) -> S {
    let t = spring.add(damping).neg();
    if t > S::ONE {
        S::ONE
    } else if t < S::ONE.neg() {
        S::ONE.neg()
    } else if t >= S::ONE.neg() {
        t
    } else {
        S::ZERO
    }
}
