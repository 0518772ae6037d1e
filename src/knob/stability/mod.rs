//! What the knob guarantees, and the analysis behind it.
//!
//! # The loop
//!
//! Each control period `dt` the firmware reads the encoder angle `θ_n` (quantised to one
//! count), and the knob commands a torque that the motor holds over a period (a zero-order
//! hold), one period later with [`Latency::OneStep`]. The rotor integrates it exactly:
//! `J·dω/dt = τ`. The torque law is a spring and a damper,
//!
//! ```text
//! τ_n = −K·dz(e_n) − B·v_n          v_n = v_{n−1} + α·((θ_n − θ_{n−1})/dt − v_{n−1})
//! ```
//!
//! with `e` the extension (from the detent centre, the endstop, the magnet, the return
//! centre), `dz` a rest zone of one count (the spring is zero within one count of the rest
//! point), and `v` the backward difference of the angles through a first-order low-pass
//! filter of time constant `T_f` (`α = dt/(T_f + dt)`). In dimensionless form, with the
//! step velocity `u = v·dt`, it is the crate's kernel `Δu = −(C_k·e + C_d·u)` with
//! `C_k = K·dt²/J` and `C_d = B·dt/J`, on the filtered `u`.
//!
//! With `β = 1 − α` and `d` periods of delay, the closed loop of one zone has the
//! characteristic polynomial ([`characteristic_polynomial`])
//!
//! ```text
//! p(z) = 2·(z − 1)²·(z − β)·z^d + (z + 1)·[C_k·(z − β) + C_d·α·(z − 1)]
//! ```
//!
//! (the ZOH rotor is `(z + 1)/(2(z − 1)²)` in step units; the filtered backward difference
//! is `α·(z − 1)/(z − β)`). Without the filter (`α = 1`) it is the classic sampled
//! spring-damper, stable for small gains exactly when `C_k < 2·C_d`, i.e. `K·dt/2 < B`:
//! Colgate and Schenkel's bound for a sampled virtual wall, with the knob's own damping in
//! the place of the device's physical damping.
//!
//! # What a linear test leaves out, and how each is covered
//!
//! A linearly stable loop can still limit-cycle: with the previous law (a strength map with
//! a gain margin of 2, commit `8898beb`), 297 of 21,870 runs of a grid like the sweep of
//! `tests/knob_sweep.rs` (detents without endstops; 10, 14 and 16 bits) oscillated at rest,
//! up to 10,223 counts peak to peak (a development harness on the same rotor model, not
//! kept: the old API is gone). Each effect, and what the knob does about it:
//!
//! | effect | mechanism | cover |
//! |---|---|---|
//! | inertia off by ×½…×2 | the loop gain is `1/J` | every check below holds for the gains `g ∈ [½, 2]` ([`INERTIA_UNCERTAINTY`]) |
//! | a loop that is stable but rings | a pole near the unit circle at `g = 2` rings for seconds | every pole at every `g` has a damping ratio ≥ [`MIN_DAMPING_RATIO`] (Tustin) and decays at least [`DECAY_FRACTION`] as fast as the designed spring |
//! | torque saturation | the clamp multiplies the loop gain by a factor in `(0, 1]` | the loop is also stable at gains `1/64…½`; a detent or magnet whose peak torque exceeds the limit (a relay over most of its cell) is refused |
//! | encoder quantisation, damping | a backward difference of counts is `±1` count for one period: the damping turns it into a kick that can reverse a slow rotor and pump energy | the velocity is low-pass filtered, so that the kick decays while the rotor turns around (the turn-around then loses energy); the same damping `B` in every zone, so that the kicks into and out of a zone cancel |
//! | encoder quantisation, spring | a centre between two counts makes the spring push back and forth | a rest zone of one count around the rest point |
//! | detent boundaries | the centre jumps | the switch happens past the snap point (≥ ½ width) and the hysteresis: the potential drops at each switch, so the switching dissipates |
//! | endstops | a stiffer spring switches in | the endstop adds to the detent field (the force is continuous at the stop), with the same damping; the endstop's stiffness is checked as a zone of its own |
//!
//! One more bound covers the torque a single count commands: a reading that toggles
//! between two counts makes the torque toggle by `(K + B·α/dt)·count`, which must stay
//! within [`COUNT_TORQUE_FRACTION`] of the limit in every zone (measured without it: a
//! 10-bit encoder at 1 kHz and the stiffest detent toggled 32 mN·m, 64 % of the limit, on a
//! one-count limit cycle that the position metric does not see).
//!
//! The filter's time constant is the longest (the least ripple at rest) that still passes
//! every check: `T_f = c/ω`, with `c` from `0.25` down to `0` (no filter) in steps of
//! `2^{-1/4}`, and `ω` the higher of the stiffest zone's natural frequency and `B/J`.
//!
//! # The checks
//!
//! All in `f64` at set-up, without `libm`, by Schur–Cohn (Jury) recursions on transformed
//! polynomials, so no root is computed:
//!
//! - **decay:** the roots of `p(r·z)` lie inside the unit circle, `r = e^{−σ·dt}`, with
//!   `σ` [`DECAY_FRACTION`] of the slowest decay rate of the designed continuous spring
//!   (`J·s² + B·s + K`);
//! - **damping ratio:** with `w = (z − 1)/(z + 1)` (Tustin), every root has
//!   `−Re w ≥ ζ_min·|w|`: the polynomial in `w` rotated by `asin ζ_min` and mapped back to
//!   the disc has its roots inside it (a complex Schur–Cohn test);
//! - **no slow Nyquist mode:** every root has `|w| < 6` (stays clear of `z = −1`, where the
//!   Tustin damping ratio says nothing);
//! - for [`Latency::OneStep`] the checks hold with and without the period of delay.
//!
//! The tests check the same conditions independently, from the eigenvalues of the rotor's
//! state matrix, on a denser grid of gains (`tests/knob_stability.rs`).

// The tests below are written `!(a < b)` on purpose: a NaN must fail them.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod polynomial;

pub use super::config::Latency;
use super::error::Zone;
pub(crate) use crate::math::sqrt;
use polynomial::{damped, hurwitz, tustin_polynomial};

/// The factor by which the real rotor inertia may differ from the configured one, either
/// way: every check holds for inertias from `J/2` to `2·J` (loop gains `½…2`).
///
/// ```
/// assert_eq!(stiffspring::knob::INERTIA_UNCERTAINTY, 2.0);
/// ```
pub const INERTIA_UNCERTAINTY: f64 = 2.0;

/// The least damping ratio of any closed-loop pole, at any inertia in the uncertainty
/// range (the Tustin-equivalent damping ratio `−Re w/|w|`, `w = (z − 1)/(z + 1)`).
///
/// ```
/// assert_eq!(stiffspring::knob::MIN_DAMPING_RATIO, 0.1);
/// ```
pub const MIN_DAMPING_RATIO: f64 = 0.1;

/// Every pole decays at least this fraction as fast as the designed continuous spring
/// (`J·s² + B·s + K`), at any inertia in the uncertainty range. A rotor twice as heavy as
/// configured decays half as fast in continuous time; a third leaves room for the sampling.
///
/// ```
/// assert!((stiffspring::knob::DECAY_FRACTION - 1.0 / 3.0).abs() < 1e-15);
/// ```
pub const DECAY_FRACTION: f64 = 1.0 / 3.0;

/// The accepted damping ratios `ζ` of [`KnobConfig::damping_ratio`], inclusive.
///
/// [`KnobConfig::damping_ratio`]: crate::KnobConfig::damping_ratio
///
/// ```
/// let (lo, hi) = stiffspring::knob::DAMPING_RATIO_RANGE;
/// assert!(lo < 0.7 && 0.7 < hi);
/// ```
pub const DAMPING_RATIO_RANGE: (f64, f64) = (0.2, 2.0);

/// The gains of the robust checks: `½·2^{k/4}`, `k = 0..=8`, from `½` to `2`.
const ROBUST_GAINS: [f64; 9] = [
    0.5,
    0.594_603_557_501_360_5,
    core::f64::consts::FRAC_1_SQRT_2,
    0.840_896_415_253_714_5,
    1.0,
    1.189_207_115_002_721,
    core::f64::consts::SQRT_2,
    1.681_792_830_507_429,
    2.0,
];

/// The gains a saturating torque adds below the robust range: checked for stability.
const SMALL_GAINS: [f64; 3] = [1.0 / 64.0, 1.0 / 16.0, 0.25];

/// Roots must stay inside `|w| < NYQUIST_GUARD` (clear of `z = −1`): on the negative real
/// axis, `z > −5/7`.
const NYQUIST_GUARD: f64 = 6.0;

/// `cos ψ` of the rotation `ψ = asin(ζ_min)` of the damping-ratio test.
const SECTOR_COS: f64 = 0.994_987_437_106_62; // √(1 − 0.1²)

/// The most torque, as a fraction of the torque limit, that one encoder count may command
/// through a zone's spring and filtered damper, `(K + B·α/dt)·count`. A reading that
/// toggles between two counts (a rotor at rest on a count edge) makes the torque toggle
/// by that much: above it, the knob buzzes. This is the knob's encoder-resolution bound
/// (Abbott and Okamura bound a virtual wall's stiffness by the device's friction over the
/// encoder resolution; here the bound is on the torque, and the velocity filter, chosen as
/// long as the loop allows, is what keeps the damper's share small).
///
/// ```
/// assert_eq!(stiffspring::knob::stability::COUNT_TORQUE_FRACTION, 0.125);
/// ```
pub const COUNT_TORQUE_FRACTION: f64 = 0.125;

/// The shortest filter step: `T_f ≤ 63·dt`. The filter state in fixed point keeps its
/// truncation errors for about `1/α` periods, so `α` is bounded below (with four extra
/// fractional bits in the state, the accumulated error stays under 8 LSB of the torque).
pub(crate) const MIN_FILTER_ALPHA: f64 = 1.0 / 64.0;

/// The filter constants `c = T_f·ω` tried, longest first, down to no filter.
pub(crate) const FILTER_LADDER: [f64; 16] = [
    0.25,
    0.210_224_103_813_429,
    0.176_776_695_296_637,
    0.148_650_889_375_340,
    0.125,
    0.105_112_051_906_714,
    0.088_388_347_648_318,
    0.074_325_444_687_670,
    0.0625,
    0.052_556_025_953_357,
    0.044_194_173_824_159,
    0.037_162_722_343_835,
    0.031_25,
    0.022_097_086_912_079,
    0.015_625,
    0.0,
];

/// The dimensionless coefficients of one zone's loop: `C_k = K·dt²/J`, `C_d = B·dt/J` and
/// the velocity filter's `α = dt/(T_f + dt)` (1: no filter).
///
/// ```
/// use stiffspring::knob::{is_stable, Latency, LoopCoefficients};
///
/// let c = LoopCoefficients { stiffness: 0.01, damping: 0.15, filter: 0.5 };
/// assert!(is_stable(c, Latency::OneStep));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LoopCoefficients {
    /// `C_k = K·dt²/J`.
    pub stiffness: f64,
    /// `C_d = B·dt/J`.
    pub damping: f64,
    /// `α` of the velocity filter, in `(0, 1]`.
    pub filter: f64,
}

impl LoopCoefficients {
    /// The loop of stiffness `k` (N·m/rad) and damping `b` (N·m·s/rad) with the filter
    /// `alpha`, on inertia `inertia` (kg·m²) stepped every `dt` (s): `C_k = k·dt²/J`,
    /// `C_d = b·dt/J`. The set-up and [`Knob::loop_coefficients`](crate::Knob::loop_coefficients)
    /// both compute it here, so that the two agree to the bit.
    pub(crate) const fn of(k: f64, b: f64, alpha: f64, dt: f64, inertia: f64) -> Self {
        LoopCoefficients {
            stiffness: k * dt * dt / inertia,
            damping: b * dt / inertia,
            filter: alpha,
        }
    }

    /// The loop with the inertia divided by `g` (both gains times `g`).
    const fn scaled(self, g: f64) -> Self {
        LoopCoefficients {
            stiffness: g * self.stiffness,
            damping: g * self.damping,
            filter: self.filter,
        }
    }
}

/// A polynomial of degree at most 5, coefficients from `z⁰` up.
type Poly = [f64; 6];

/// The characteristic polynomial of the closed loop with `delay` periods (0 or 1) of
/// delay, coefficients from `z⁰` up, and its degree (see the [module docs](self)). A zone
/// without stiffness (`C_k = 0`) has a root at `z = 1` (the rotor rests anywhere); it is
/// divided out, and the rest returned.
///
/// ```
/// use stiffspring::knob::{characteristic_polynomial, LoopCoefficients};
///
/// // No filter, no delay: 2z³ + (C_k + C_d − 4)z² + (2 + C_k)z − C_d.
/// let c = LoopCoefficients { stiffness: 0.1, damping: 0.3, filter: 1.0 };
/// let (p, n) = characteristic_polynomial(c, 0);
/// assert_eq!(n, 3);
/// for (a, b) in p.iter().zip([-0.3, 2.1, -3.6, 2.0]) {
///     assert!((a - b).abs() < 1e-12);
/// }
/// ```
pub const fn characteristic_polynomial(c: LoopCoefficients, delay: usize) -> ([f64; 6], usize) {
    let (ck, cd, a) = (c.stiffness, c.damping, c.filter);
    let b = 1.0 - a;
    let d = if delay > 1 { 1 } else { delay };
    let mut p = [0.0; 6];
    if ck == 0.0 {
        // (p / (z − 1)): 2(z − 1)(z − β)z^d + C_d·α·(z + 1).
        let base = [2.0 * b, -2.0 - 2.0 * b, 2.0];
        let mut k = 0;
        while k < base.len() {
            p[k + d] += base[k];
            k += 1;
        }
        p[0] += cd * a;
        p[1] += cd * a;
        return (p, 2 + d);
    }
    // 2(z − 1)²(z − β)z^d
    let base = [-2.0 * b, 2.0 + 4.0 * b, -4.0 - 2.0 * b, 2.0];
    let mut k = 0;
    while k < base.len() {
        p[k + d] += base[k];
        k += 1;
    }
    // (z + 1)·C_k·(z − β) = C_k·(z² + (1 − β)z − β)
    p[0] += -ck * b;
    p[1] += ck * (1.0 - b);
    p[2] += ck;
    // (z + 1)·C_d·α·(z − 1) = C_d·α·(z² − 1)
    p[0] -= cd * a;
    p[2] += cd * a;
    (p, 3 + d)
}

/// The delays a latency is checked with.
const fn delays(latency: Latency) -> &'static [usize] {
    match latency {
        Latency::SameStep => &[0],
        Latency::OneStep => &[1, 0],
    }
}

/// True when the closed loop with these coefficients is asymptotically stable with
/// `latency`'s delay (a zone without stiffness: stable apart from its rest position).
///
/// ```
/// use stiffspring::knob::{is_stable, Latency, LoopCoefficients};
///
/// let rigid = LoopCoefficients { stiffness: 1.0, damping: 1.0, filter: 1.0 };
/// // The article's rigid spring is stable as a particle, not on a sampled rotor.
/// assert!(!is_stable(rigid, Latency::SameStep));
/// ```
pub const fn is_stable(c: LoopCoefficients, latency: Latency) -> bool {
    if !(c.stiffness.is_finite() && c.damping.is_finite() && c.filter.is_finite()) {
        return false;
    }
    let d = delays(latency)[0];
    let (q, n) = tustin_polynomial(c, d, 0.0);
    hurwitz(&q, n)
}

/// The spectral radius of the closed loop (largest root magnitude of
/// [`characteristic_polynomial`] with `latency`'s delay), by bisection on `r` with the
/// roots of `p(r·z)` tested inside the unit circle. NaN for non-finite coefficients.
///
/// ```
/// use stiffspring::knob::{spectral_radius, Latency, LoopCoefficients};
///
/// let c = LoopCoefficients { stiffness: 0.01, damping: 0.15, filter: 0.5 };
/// assert!(spectral_radius(c, Latency::SameStep) < 1.0);
/// ```
pub const fn spectral_radius(c: LoopCoefficients, latency: Latency) -> f64 {
    if !(c.stiffness.is_finite() && c.damping.is_finite() && c.filter.is_finite()) {
        return f64::NAN;
    }
    let d = delays(latency)[0];
    let (p, n) = characteristic_polynomial(c, d);
    let mut hi = 1.0f64;
    let mut k = 0;
    while k < n {
        hi = hi.max(1.0 + (p[k] / p[n]).abs());
        k += 1;
    }
    // Bisect on r − 1 (the digits that matter near the unit circle).
    let (mut lo, mut hi) = (-1.0, hi - 1.0);
    let mut step = 0;
    while step < 80 {
        step += 1;
        let mid = 0.5 * (lo + hi);
        let (q, m) = tustin_polynomial(c, d, mid);
        if hurwitz(&q, m) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    1.0 + hi
}

/// The knob's guarantee for one zone (see the [module docs](self)): with the nominal
/// coefficients `c`, at every loop gain `g ∈ [½, 2]` and each of `latency`'s delays, every
/// pole lies inside the circle of radius `radius` and has a Tustin damping ratio of at
/// least [`MIN_DAMPING_RATIO`] (and stays clear of `z = −1`); at the gains `1/64 … ¼` the
/// loop is stable.
///
/// ```
/// use stiffspring::knob::{meets_guarantee, Latency, LoopCoefficients};
///
/// // A 0.1 N·m/rad detent on 1e−5 kg·m² at 1 kHz, damping ratio 0.7, a filter of 2 ms.
/// let (dt, j, k) = (1e-3, 1e-5, 0.1);
/// let b = 2.0 * 0.7 * (k * j as f64).sqrt();
/// let c = LoopCoefficients { stiffness: k * dt * dt / j, damping: b * dt / j, filter: dt / (2e-3 + dt) };
/// assert!(meets_guarantee(c, Latency::OneStep, 0.99));
/// // Ten times stiffer with the same damping is not guaranteed.
/// let stiff = LoopCoefficients { stiffness: 10.0 * c.stiffness, ..c };
/// assert!(!meets_guarantee(stiff, Latency::OneStep, 0.99));
/// ```
pub const fn meets_guarantee(c: LoopCoefficients, latency: Latency, radius: f64) -> bool {
    if !(c.stiffness.is_finite()
        && c.damping.is_finite()
        && c.filter.is_finite()
        && c.stiffness >= 0.0
        && c.damping >= 0.0
        && c.filter > 0.0
        && c.filter <= 1.0)
    {
        return false;
    }
    if c.stiffness == 0.0 && c.damping == 0.0 {
        // No torque at all: a free rotor.
        return true;
    }
    meets_guarantee_below(c, latency, radius - 1.0)
}

/// [`meets_guarantee`] with the decay radius given as `r − 1` (out of line: set-up calls
/// it a few dozen times, and a firmware should carry it once).
#[inline(never)]
pub(crate) const fn meets_guarantee_below(
    c: LoopCoefficients,
    latency: Latency,
    r_minus_1: f64,
) -> bool {
    let delays = delays(latency);
    let mut i = 0;
    while i < delays.len() {
        let d = delays[i];
        i += 1;
        let mut k = 0;
        while k < ROBUST_GAINS.len() {
            let cg = c.scaled(ROBUST_GAINS[k]);
            k += 1;
            let (q, n) = tustin_polynomial(cg, d, r_minus_1);
            if !hurwitz(&q, n) {
                return false;
            }
            let (q, n) = tustin_polynomial(cg, d, 0.0);
            if !damped(&q, n) {
                return false;
            }
        }
        let mut k = 0;
        while k < SMALL_GAINS.len() {
            let (q, n) = tustin_polynomial(c.scaled(SMALL_GAINS[k]), d, 0.0);
            k += 1;
            if !hurwitz(&q, n) {
                return false;
            }
        }
    }
    true
}

/// The slowest decay rate of `J·s² + B·s + K` (per second): `B/2J` when underdamped, the
/// slow real root otherwise, `B/J` without stiffness.
pub(crate) const fn slowest_decay(k: f64, b: f64, j: f64) -> f64 {
    if k <= 0.0 {
        return b / j;
    }
    let disc = b * b - 4.0 * j * k;
    if disc <= 0.0 {
        b / (2.0 * j)
    } else {
        2.0 * k / (b + sqrt(disc))
    }
}

/// `e^{−x} − 1` from below for `0 ≤ x ≤ ½` (the alternating series cut after a negative
/// term), so that the decay checked is at least the one asked.
pub(crate) const fn decay_radius(x: f64) -> f64 {
    let x = x.clamp(0.0, 0.5);
    -x + x * x / 2.0 - x * x * x / 6.0
}

/// The physical design of the loop: what [`meets_guarantee`] is asked about, per zone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Plant {
    pub(crate) dt: f64,
    pub(crate) inertia: f64,
    pub(crate) damping: f64,
    pub(crate) latency: Latency,
    /// Radius of the decay check, minus one.
    pub(crate) radius: f64,
}

impl Plant {
    /// The coefficients of a zone of stiffness `k` with the filter `alpha`.
    pub(crate) const fn coefficients(&self, k: f64, alpha: f64) -> LoopCoefficients {
        LoopCoefficients::of(k, self.damping, alpha, self.dt, self.inertia)
    }

    /// `α` for the filter constant `c` over the frequency `omega`, at least
    /// [`MIN_FILTER_ALPHA`].
    pub(crate) const fn alpha(&self, c: f64, omega: f64) -> f64 {
        if c <= 0.0 || omega <= 0.0 {
            1.0
        } else {
            let tf = c / omega;
            (self.dt / (tf + self.dt)).max(MIN_FILTER_ALPHA)
        }
    }

    /// True when a zone of stiffness `k` meets the guarantee with filter `alpha`.
    pub(crate) const fn zone_ok(&self, k: f64, alpha: f64) -> bool {
        meets_guarantee_below(self.coefficients(k, alpha), self.latency, self.radius)
    }
}

/// The zones a knob can be in, for reports.
pub(crate) const ZONES: [Zone; 3] = [Zone::Free, Zone::Magnet, Zone::Beyond];

#[cfg(test)]
mod tests {
    use super::polynomial::schur;
    use super::*;

    #[test]
    fn sector_test_matches_roots() {
        // (z − a)(z − ā): a = ρ·e^{iθ}. Tustin ζ of a, against the test.
        for &(rho, theta) in &[
            (0.9, 0.3),
            (0.99, 0.3),
            (0.95, 0.05),
            (0.5, 2.9),
            (0.9, 2.0),
        ] {
            let (ar, ai) = (rho * f64::cos(theta), rho * f64::sin(theta));
            let p: Poly = [ar * ar + ai * ai, -2.0 * ar, 1.0, 0.0, 0.0, 0.0];
            // w = (a − 1)/(a + 1)
            let (nr, ni) = (ar - 1.0, ai);
            let (dr, di) = (ar + 1.0, ai);
            let d = dr * dr + di * di;
            let (wr, wi) = ((nr * dr + ni * di) / d, (ni * dr - nr * di) / d);
            let zeta = -wr / (wr * wr + wi * wi).sqrt();
            let w = (wr * wr + wi * wi).sqrt();
            let expected = zeta > MIN_DAMPING_RATIO && w < NYQUIST_GUARD;
            // q(w) = (1 − w)² p((1 + w)/(1 − w)) for p = c0 + c1 z + z².
            let (c0, c1) = (p[0], p[1]);
            let q: Poly = [c0 + c1 + 1.0, 2.0 - 2.0 * c0, c0 - c1 + 1.0, 0.0, 0.0, 0.0];
            assert_eq!(damped(&q, 2), expected, "{rho} {theta}: ζ {zeta} |w| {w}");
        }
    }

    #[test]
    fn tustin_polynomial_matches_the_z_polynomial() {
        for &(ck, cd, a) in &[
            (0.1, 0.3, 1.0),
            (0.01, 0.2, 0.3),
            (0.0, 0.2, 0.5),
            (0.3, 0.5, 0.8),
        ] {
            for d in 0..2 {
                let c = LoopCoefficients {
                    stiffness: ck,
                    damping: cd,
                    filter: a,
                };
                let (p, n) = characteristic_polynomial(c, d);
                let (q, m) = tustin_polynomial(c, d, 0.0);
                assert_eq!(n, m);
                // q(w) = (1 − w)ⁿ p((1 + w)/(1 − w)) at a few points.
                for w in [0.1, -0.3, 0.7] {
                    let z: f64 = (1.0 + w) / (1.0 - w);
                    let pz: f64 = (0..=n).map(|k| p[k] * z.powi(k as i32)).sum();
                    let qw: f64 = (0..=n).map(|k| q[k] * w.powi(k as i32)).sum();
                    assert!(
                        (qw - (1.0 - w).powi(n as i32) * pz).abs() < 1e-12,
                        "{c:?} {d} {w}"
                    );
                }
                assert_eq!(hurwitz(&q, m), schur(&p, n), "{c:?} {d}");
            }
        }
    }
}
