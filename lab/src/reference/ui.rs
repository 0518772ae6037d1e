//! UI motion beyond a spring to a target, in f64 and closed form: a throw under friction,
//! platforms' friction parameters, the rubber band, a throw into a bound that hands over to
//! a spring, snapping, and the choreography of a list (stagger, trail).
//!
//! Written from the equations below and from the platforms' documented constants; it
//! shares no code with the library. Its self-tests are in `lab/tests/reference_ui_selftest.rs`.
//!
//! - **Friction** `dv/dt = −c·v`: `v(t) = v₀·e^{−ct}`, `x(t) = x₀ + (v₀/c)(1 − e^{−ct})`.
//! - **iOS** `UIScrollView.decelerationRate` `d`: the velocity keeps `d` of itself every
//!   millisecond, `v(t) = v₀·d^{t/1 ms}`, so `c = −1000·ln d` per second.
//! - **Android** `FlingAnimation.setFriction(f)`: `DragForce` steps `v·exp(Δt·(−4.2·f))`,
//!   so `c = 4.2·f` per second.
//! - **Rubber band** (UIScrollView, as reverse-engineered by Grant Paul and analysed in
//!   "Analysis of Apple's rubber band scrolling", 2013): a finger `x` past the edge moves
//!   the content `b = (1 − 1/(x·c/d + 1))·d`, with `c = 0.55` and `d` the viewport's
//!   dimension.

use super::analytic;

/// iOS's `UIScrollView.DecelerationRate.normal`, per millisecond.
pub const IOS_NORMAL: f64 = 0.998;
/// iOS's `UIScrollView.DecelerationRate.fast`, per millisecond.
pub const IOS_FAST: f64 = 0.99;
/// UIScrollView's rubber-band constant.
pub const RUBBER_BAND: f64 = 0.55;

/// The friction rate (1/s) of an iOS deceleration rate `d` per millisecond.
pub fn ios_rate(d: f64) -> f64 {
    -1000.0 * d.ln()
}

/// The friction rate (1/s) of Android's friction scalar `f`.
pub fn android_rate(f: f64) -> f64 {
    4.2 * f
}

/// `(x(t), v(t))` of a throw from `x0` at `v0` under friction `c`.
pub fn throw(x0: f64, v0: f64, c: f64, t: f64) -> (f64, f64) {
    let e = (-c * t).exp();
    // (1 − e^{−ct}) through expm1: exact near t = 0.
    (x0 - v0 / c * (-c * t).exp_m1(), v0 * e)
}

/// Where a throw from `x0` at `v0` under friction `c` comes to rest.
pub fn throw_rest(x0: f64, v0: f64, c: f64) -> f64 {
    x0 + v0 / c
}

/// How far the content moves for a finger `x` past the edge (`x ≥ 0`; odd in `x`), with
/// the rubber-band constant `c` over a dimension `d`.
pub fn rubber_band(x: f64, c: f64, d: f64) -> f64 {
    let b = (1.0 - 1.0 / (x.abs() * c / d + 1.0)) * d;
    b.copysign(x)
}

/// The finger distance past the edge that moves the content `b` (`|b| < d`): the inverse
/// of [`rubber_band`], `x = b·d / (c·(d − b))`.
pub fn rubber_band_inverse(b: f64, c: f64, d: f64) -> f64 {
    let x = b.abs() * d / (c * (d - b.abs()));
    x.copysign(b)
}

/// A throw from `x0` at `v0` under friction `c` toward a bound `bound` that it passes
/// (its resting point lies beyond): it decelerates by friction until it crosses the bound
/// at `t*`, then a spring (`omega`, `zeta`) pulls it back to the bound, starting there
/// with the velocity it crossed at. Returns `(x(t), v(t))` and `t*`.
pub fn throw_into_bound(
    x0: f64,
    v0: f64,
    c: f64,
    bound: f64,
    omega: f64,
    zeta: f64,
    t: f64,
) -> ((f64, f64), f64) {
    // x(t*) = bound: e^{−c·t*} = 1 − c·(bound − x0)/v0.
    let crossing = -(1.0 - c * (bound - x0) / v0).ln() / c;
    if t <= crossing {
        return (throw(x0, v0, c, t), crossing);
    }
    let (_, v_star) = throw(x0, v0, c, crossing);
    let (x, v) = analytic(0.0, v_star, omega, zeta, t - crossing);
    ((bound + x, v), crossing)
}

/// The motion toward a snap point `s` from `x0` at `v0` on the overdamped spring whose
/// poles are `−c` (the friction's) and `−p` (`p > c`): `x(t) − s = A·e^{−ct} + B·e^{−pt}`
/// with `A + B = x0 − s` and `−c·A − p·B = v0`. With `s` on the throw's own resting point
/// it is the throw itself (`B = 0`).
pub fn two_pole(x0: f64, v0: f64, s: f64, c: f64, p: f64, t: f64) -> (f64, f64) {
    if p <= c {
        // Both poles at −c: critically damped.
        let (x, v) = analytic(x0 - s, v0, c, 1.0, t);
        return (s + x, v);
    }
    let b = -(v0 + c * (x0 - s)) / (p - c);
    let a = (x0 - s) - b;
    let (ec, ep) = ((-c * t).exp(), (-p * t).exp());
    (s + a * ec + b * ep, -c * a * ec - p * b * ep)
}

/// The multiple of `spacing` (from `origin`) nearest to `x`, as an index.
pub fn nearest_index(x: f64, spacing: f64, origin: f64) -> i64 {
    ((x - origin) / spacing).round() as i64
}

/// One retarget-per-frame model of a chain of values that follow each other (a trail):
/// value 0 springs toward `head_target`; value `k` toward value `k − 1`'s position at the
/// start of each frame plus `gap`. Each frame every value moves on the analytic spring
/// (`omega`, `zeta`) from its position and velocity toward its target of that frame.
/// Returns every value's position after each of `frames` frames (`[frame][value]`).
pub fn trail(
    start: &[f64],
    head_target: f64,
    gap: f64,
    omega: f64,
    zeta: f64,
    dt: f64,
    frames: usize,
) -> Vec<Vec<f64>> {
    let mut x = start.to_vec();
    let mut v = vec![0.0; start.len()];
    let mut out = Vec::with_capacity(frames);
    for _ in 0..frames {
        let targets: Vec<f64> = (0..x.len())
            .map(|k| if k == 0 { head_target } else { x[k - 1] + gap })
            .collect();
        for k in 0..x.len() {
            let (dx, dv) = analytic(x[k] - targets[k], v[k], omega, zeta, dt);
            x[k] = targets[k] + dx;
            v[k] = dv;
        }
        out.push(x.clone());
    }
    out
}
