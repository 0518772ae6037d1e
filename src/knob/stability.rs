//! The closed-loop stability region of the knob, and the map from a strength in `[0, 1]`
//! into it.
//!
//! # The loop is not the article's particle
//!
//! The article's spring moves a simulated particle: the spring's impulse and the particle's
//! position update are one symplectic step. A haptic knob instead drives a real rotor of
//! inertia `I`. Each control period `dt` the firmware reads the encoder angle `θ_n`, forms
//! the step velocity as a backward difference `u_n = θ_n − θ_{n−1}`, and commands the
//! torque
//!
//! ```text
//! τ_n = (I/dt²)·Δu_n,        Δu_n = respond(e_n, u_n) − u_n = −(C_k·e_n + C_d·u_n)
//! ```
//!
//! (`e_n = θ_n − target`, [`kernel::Coefficients::respond`]), which the motor holds
//! constant over the period (a zero-order hold). The rotor integrates it exactly:
//! with the per-step velocity `w_n = ω_n·dt`,
//!
//! ```text
//! θ_{n+1} = θ_n + w_n + Δu_n/2        w_{n+1} = w_n + Δu_n
//! ```
//!
//! The `/2` (a constant torque moves a rotor half as far in one period as the article's
//! impulse does) and the backward difference (the controller sees the velocity half a
//! period late) are what make this loop differ from the particle.
//!
//! # The characteristic polynomial and Jury's test
//!
//! In `z`, the ZOH rotor from `Δu` to `θ` is `P(z) = (z + 1)/(2·(z − 1)²)` and the
//! controller is `K(z) = C_k + C_d·(1 − z⁻¹)`. With the state `(θ_n, w_n, θ_{n−1})` the
//! closed loop `1 + P·K = 0` has the third-order characteristic polynomial
//! ([`Latency::SameStep`])
//!
//! ```text
//! p(z) = 2z³ + (C_k + C_d − 4)·z² + (2 + C_k)·z − C_d
//! ```
//!
//! Jury's conditions for `p(z)/2 = z³ + a₂z² + a₁z + a₀` are
//!
//! | condition | here | gives |
//! |---|---|---|
//! | `p(1) > 0` | `2·C_k > 0` | `C_k > 0` |
//! | `−p(−1) > 0` | `8 > 0` | always (the ZOH zero at `z = −1` cancels the gains) |
//! | `\|a₀\| < 1` | `C_d/2 < 1` | `C_d < 2` |
//! | `1 − a₀² > \|a₀a₂ − a₁\|` | `4 − C_d² > C_k·(2 + C_d) + (2 − C_d)²` | `C_k < 2·C_d·(2 − C_d)/(2 + C_d)` |
//!
//! so the loop is stable exactly in
//!
//! ```text
//! 0 < C_d < 2,        0 < C_k < 2·C_d·(2 − C_d)/(2 + C_d)        (same-step torque)
//! ```
//!
//! ([`same_step_stiffness_limit`]). It is much smaller than the particle's
//! (`C_k + 2·C_d < 4`): the stiffest stable spring is `C_k = 12 − 8√2 ≈ 0.686`, at
//! `C_d = 2√2 − 2 ≈ 0.828`, and the article's rigid spring `C_k = C_d = 1` is
//! **unstable** on a real rotor (its limit at `C_d = 1` is `C_k < 2/3`). For small gains
//! the condition reads `C_k < 2·C_d`, i.e. `k·dt/2 < d`: a sampled spring needs a
//! damping of at least half its stiffness times the period, the known condition for
//! sampled haptic walls. Without damping no stiffness is stable.
//!
//! # A one-sample computational delay
//!
//! Firmware structured like SimpleFOC (and SmartKnob on it) reads the sensor in
//! `loopFOC()`, computes the torque, and `move()` stores it; the phase voltages are set
//! from it by the *next* `loopFOC()`. The torque computed from `θ_n` then acts over
//! `[t_{n+1}, t_{n+2}]`: one period of delay, and the fourth-order polynomial
//! ([`Latency::OneStep`])
//!
//! ```text
//! p(z) = 2z⁴ − 4z³ + (2 + C_k + C_d)·z² + C_k·z − C_d
//! ```
//!
//! Its region (Jury's test on a quartic, evaluated numerically by [`is_stable`]) is
//! about four times smaller: the stiffest stable spring is `C_k ≈ 0.144` at `C_d ≈ 0.42`.
//! A firmware whose haptic loop sets the reference of a much faster current loop within
//! the same period has (almost) no delay. The delay is real for the common structure, and
//! a map designed for it also keeps the gain margin below without the delay (checked at
//! set-up and in `tests/knob_stability.rs`, also for fractional delays), so
//! [`Latency::OneStep`] is the default.
//!
//! # The margin and the strength map
//!
//! A strength `s ∈ [0, 1]` is a fraction of the stiffest spring the map allows, so the
//! stiffness is linear in `s` (`C_k = s·C_k,top`) and strengths add. The damping is not
//! chosen per strength by hand: `(C_k, C_d)` are placed so that the dominant closed-loop
//! pole pair is the bilinear (Tustin) image of a continuous spring with the knob's damping
//! ratio `ζ` (a closed form in `p(z)`, no `libm`), so every strength settles with the same
//! damping ratio. The top of the map is the largest such spring that
//!
//! - has a **gain margin of 2** ([`GAIN_MARGIN`]): the loop stays stable when both
//!   coefficients are multiplied by any factor up to 2. The loop gain is `k_t/I` (the
//!   motor's torque constant over the inertia); a factor of 2 covers an inertia
//!   overestimated by 2 (a lighter knob cap, a hand that lets go), a torque constant 2
//!   times higher than assumed, or both by √2. It also bounds the damping of the
//!   slowest mode away from zero at the top (the radius stays below 0.96 over the accepted
//!   `ζ`, `tests/knob_stability.rs`);
//! - is still on the rising part of the placement curve, so that a stronger strength is
//!   always a stiffer spring.
//!
//! For small damping ratios the margin is what stops the map (the loop at strength 1
//! turns unstable at 2.02 times its gains for `ζ = 0.2`); from `ζ ≈ 0.5` on, the rising
//! curve stops it first and the margin is larger (3.3 times at `ζ = 0.7`, 5.7 at `ζ = 2`
//! without delay; 2.8 and 4.6 with one period), measured in `tests/knob_stability.rs`.
//!
//! Everything is checked in `f64` at set-up by the exact Schur–Cohn (Jury) recursion, and
//! exhaustively in the tests over a grid of strengths, damping ratios and latencies, with
//! eigenvalues computed independently from the rotor's state matrix.
//!
//! | `ζ` | `C_k,top` same step | `C_k,top` one step |
//! |---|---|---|
//! | 0.3 | 0.29 | 0.064 |
//! | 0.7 | 0.12 | 0.030 |
//! | 1.0 | 0.070 | 0.019 |
//! | 2.0 | 0.021 | 0.0064 |
//!
//! For a feel of the numbers: at 1 kHz with one step of delay and `ζ = 0.7`, strength 1
//! is `k = C_k,top·I/dt² = 0.30 N·m/rad` for a rotor of `1e−5 kg·m²`, with its dominant
//! poles at 54 Hz; at 10 kHz it is 100 times stiffer. Real detents use a fraction of it,
//! and the torque limit clips the rest. (At the top, `√C_k` is about half of `ω·dt`: the
//! gains are large enough that the sampled loop is far from a continuous spring.)
//!
//! [`kernel::Coefficients::respond`]: crate::kernel::Coefficients::respond

use crate::error::{Error, Parameter};

/// When the torque computed from an angle reaches the rotor.
///
/// ```
/// use stiffspring::knob::Latency;
/// assert_eq!(Latency::default(), Latency::OneStep);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Latency {
    /// The torque computed from `θ_n` acts over `[t_n, t_{n+1}]`: the haptic loop sets the
    /// reference of a current loop that is much faster than it, within the same period.
    SameStep,
    /// The torque computed from `θ_n` acts over `[t_{n+1}, t_{n+2}]`: the structure of
    /// SimpleFOC-style firmware (`loopFOC()` applies what the previous `move()` stored).
    /// Maps designed for it also keep their margin without the delay.
    #[default]
    OneStep,
}

/// The gain margin every accepted configuration keeps: the loop stays stable with both
/// coefficients multiplied by any factor up to this.
///
/// ```
/// assert_eq!(stiffspring::knob::GAIN_MARGIN, 2.0);
/// ```
pub const GAIN_MARGIN: f64 = 2.0;

/// The accepted damping ratios `ζ` of the strength map, inclusive.
///
/// Below 0.2 a detent rings for many periods after a flick; above 2 the top stiffness
/// falls below a hundredth of a step's (`C_k,top ≈ 0.006` with one step of delay) and the
/// knob mostly feels viscous.
///
/// ```
/// let (lo, hi) = stiffspring::knob::DAMPING_RATIO_RANGE;
/// assert!(lo < 0.7 && 0.7 < hi);
/// ```
pub const DAMPING_RATIO_RANGE: (f64, f64) = (0.2, 2.0);

/// The gains checked at set-up: the margin, plus 1% so that rounding in a later
/// evaluation cannot put the margin point on the boundary, and fractions of it. The
/// tests check a dense grid of factors.
const CHECKED_GAINS: [f64; 4] = [0.5, 1.0, 1.5, GAIN_MARGIN * 1.01];

/// The characteristic polynomial of the closed loop, coefficients from `z⁰` up, and its
/// degree (3 for [`Latency::SameStep`], 4 for [`Latency::OneStep`]).
///
/// ```
/// use stiffspring::knob::{characteristic_polynomial, Latency};
///
/// // No gains: a free rotor, z·(z − 1)² (times 2).
/// let (p, n) = characteristic_polynomial(0.0, 0.0, Latency::SameStep);
/// assert_eq!((n, p), (3, [0.0, 2.0, -4.0, 2.0, 0.0]));
/// ```
pub fn characteristic_polynomial(
    stiffness: f64,
    damping: f64,
    latency: Latency,
) -> ([f64; 5], usize) {
    let (ck, cd) = (stiffness, damping);
    match latency {
        Latency::SameStep => ([-cd, 2.0 + ck, ck + cd - 4.0, 2.0, 0.0], 3),
        Latency::OneStep => ([-cd, ck, 2.0 + ck + cd, -4.0, 2.0], 4),
    }
}

/// The Schur–Cohn recursion (Jury's test in table form): all roots of the polynomial
/// `c[0] + c[1]·z + … + c[n]·zⁿ` strictly inside the unit circle.
fn schur_stable(coefficients: &[f64; 5], degree: usize) -> bool {
    let mut p = *coefficients;
    let mut n = degree;
    while n > 0 {
        // |c₀| < |cₙ|, then reduce: q_j = cₙ·c_{j+1} − c₀·c_{n−1−j}, degree n − 1.
        // (NaN coefficients fail too.)
        if p[0].abs() >= p[n].abs() || p[0].is_nan() || p[n].is_nan() {
            return false;
        }
        let mut q = [0.0; 5];
        for j in 0..n {
            q[j] = p[n] * p[j + 1] - p[0] * p[n - 1 - j];
        }
        // Rescale so that the recursion neither overflows nor underflows.
        let scale = q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if scale <= 0.0 || !scale.is_finite() {
            return false;
        }
        for x in q.iter_mut() {
            *x /= scale;
        }
        p = q;
        n -= 1;
    }
    true
}

/// True when the closed loop with these coefficients is asymptotically stable: every root
/// of [`characteristic_polynomial`] strictly inside the unit circle.
///
/// ```
/// use stiffspring::knob::{is_stable, Latency};
///
/// assert!(is_stable(0.1, 0.3, Latency::SameStep));
/// // The article's rigid spring is stable as a particle, not on a rotor.
/// assert!(!is_stable(1.0, 1.0, Latency::SameStep));
/// assert!(!is_stable(0.2, 0.3, Latency::OneStep));
/// ```
pub fn is_stable(stiffness: f64, damping: f64, latency: Latency) -> bool {
    if !stiffness.is_finite() || !damping.is_finite() {
        return false;
    }
    let (p, n) = characteristic_polynomial(stiffness, damping, latency);
    schur_stable(&p, n)
}

/// The spectral radius of the closed loop: the largest root magnitude of
/// [`characteristic_polynomial`], by bisection on `r` with the roots of `p(r·z)` tested
/// inside the unit circle: to about `1e−12` for a simple root, `1e−5` for a double one
/// (whose position moves with the square root of the coefficients' rounding). `NaN` for
/// non-finite coefficients.
///
/// ```
/// use stiffspring::knob::{spectral_radius, Latency};
///
/// // A free rotor has its double pole at 1.
/// assert!((spectral_radius(0.0, 0.0, Latency::SameStep) - 1.0).abs() < 1e-5);
/// assert!(spectral_radius(0.1, 0.3, Latency::SameStep) < 1.0);
/// ```
pub fn spectral_radius(stiffness: f64, damping: f64, latency: Latency) -> f64 {
    if !stiffness.is_finite() || !damping.is_finite() {
        return f64::NAN;
    }
    let (p, n) = characteristic_polynomial(stiffness, damping, latency);
    // Cauchy's bound: every root has |z| ≤ 1 + max |c_k/c_n|.
    let mut hi = 1.0;
    for c in &p[..n] {
        hi = f64::max(hi, 1.0 + (c / p[n]).abs());
    }
    let mut lo = 0.0;
    for _ in 0..64 {
        let r = 0.5 * (lo + hi);
        let mut scaled = p;
        let mut rk = 1.0;
        for c in scaled.iter_mut().take(n + 1) {
            *c *= rk;
            rk *= r;
        }
        if schur_stable(&scaled, n) {
            hi = r;
        } else {
            lo = r;
        }
    }
    hi
}

/// The largest stable `C_k` for a given `C_d` without delay,
/// `2·C_d·(2 − C_d)/(2 + C_d)` (Jury's fourth condition, see the module docs); 0 outside
/// `0 < C_d < 2`, where no stiffness is stable.
///
/// ```
/// use stiffspring::knob::same_step_stiffness_limit;
///
/// let best = 2.0 * 2f64.sqrt() - 2.0;
/// assert!((same_step_stiffness_limit(best) - (12.0 - 8.0 * 2f64.sqrt())).abs() < 1e-12);
/// assert_eq!(same_step_stiffness_limit(1.0), 2.0 / 3.0);
/// assert_eq!(same_step_stiffness_limit(0.0), 0.0);
/// ```
pub fn same_step_stiffness_limit(damping: f64) -> f64 {
    if damping > 0.0 && damping < 2.0 {
        2.0 * damping * (2.0 - damping) / (2.0 + damping)
    } else {
        0.0
    }
}

/// True when the loop is stable for both coefficients scaled by each of the checked gains
/// (up to [`GAIN_MARGIN`]), for the latency and, for [`Latency::OneStep`], also without it.
pub(crate) fn has_margin(stiffness: f64, damping: f64, latency: Latency) -> bool {
    CHECKED_GAINS.iter().all(|&g| {
        let (ck, cd) = (g * stiffness, g * damping);
        is_stable(ck, cd, latency)
            && (latency == Latency::SameStep || is_stable(ck, cd, Latency::SameStep))
    })
}

/// `(C_k, C_d)` whose dominant closed-loop pole pair is the Tustin image of a continuous
/// spring with `ω·dt = wh` and damping ratio `zeta`.
///
/// The pair's sum `a` and product `b` follow from `z = (1 + s·dt/2)/(1 − s·dt/2)` with
/// `s² + 2ζω·s + ω² = 0`; matching `p(z) = (z² − a·z + b)·(remaining factor)` coefficient
/// by coefficient is linear in the gains (the factorisations below).
fn place(wh: f64, zeta: f64, latency: Latency) -> (f64, f64) {
    let q = wh * wh / 4.0;
    let den = 1.0 + zeta * wh + q;
    let b = (1.0 - zeta * wh + q) / den;
    let a = (2.0 - 2.0 * q) / den;
    match latency {
        // p = (z² − a·z + b)·(2z + c):  c = 2(a + b − 3)/(1 + a + b),
        // C_d = −b·c, C_k = 2b − 2 − a·c.
        Latency::SameStep => {
            let c = 2.0 * (a + b - 3.0) / (1.0 + a + b);
            (2.0 * b - 2.0 - a * c, -b * c)
        }
        // p = (z² − a·z + b)·(2z² + c·z + d):  c = 2a − 4,
        // d = (2 − 2b + c·(a + b))/(1 + a + b), C_k = b·c − a·d, C_d = −b·d.
        Latency::OneStep => {
            let c = 2.0 * a - 4.0;
            let d = (2.0 - 2.0 * b + c * (a + b)) / (1.0 + a + b);
            (b * c - a * d, -b * d)
        }
    }
}

/// The map from a strength in `[0, 1]` to `(C_k, C_d)` for one damping ratio and latency
/// (see the [module docs](self)): `C_k = s·C_k,top`, with `C_d` placing the dominant
/// poles at the damping ratio.
///
/// ```
/// use stiffspring::knob::{is_stable, Latency, StrengthMap, GAIN_MARGIN};
///
/// let map = StrengthMap::new(0.7, Latency::OneStep)?;
/// let (ck, cd) = map.coefficients(1.0)?;
/// assert_eq!(ck, map.top_stiffness());
/// assert!(is_stable(GAIN_MARGIN * ck, GAIN_MARGIN * cd, Latency::OneStep));
/// assert_eq!(map.coefficients(0.5)?.0, 0.5 * ck); // linear in the strength
/// assert!(map.coefficients(1.01).is_err());
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StrengthMap {
    zeta: f64,
    latency: Latency,
    top_wh: f64,
    top_stiffness: f64,
}

impl StrengthMap {
    /// The map for damping ratio `zeta` and `latency` (set-up only: a few hundred Jury
    /// tests in `f64`).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the damping ratio, outside
    /// [`DAMPING_RATIO_RANGE`].
    ///
    /// ```
    /// use stiffspring::knob::{Latency, StrengthMap};
    ///
    /// let same = StrengthMap::new(0.7, Latency::SameStep)?;
    /// let delayed = StrengthMap::new(0.7, Latency::OneStep)?;
    /// assert!(delayed.top_stiffness() < same.top_stiffness());
    /// assert!(StrengthMap::new(0.05, Latency::OneStep).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(zeta: f64, latency: Latency) -> Result<Self, Error> {
        if !zeta.is_finite() {
            return Err(Error::NotFinite(Parameter::DampingRatio));
        }
        if !(DAMPING_RATIO_RANGE.0..=DAMPING_RATIO_RANGE.1).contains(&zeta) {
            return Err(Error::OutOfRange(Parameter::DampingRatio));
        }
        // Accepted while the margin holds and the curve still rises.
        let ok = |wh: f64| {
            let (ck, cd) = place(wh, zeta, latency);
            let (ck_next, _) = place(wh * (1.0 + 1e-3), zeta, latency);
            ck > 0.0 && ck_next > ck && has_margin(ck, cd, latency)
        };
        // Scan in steps of 1/64 (the top lies between 0.17 and 1 over the accepted ζ),
        // then bisect between the last accepted and the first rejected point.
        const STEP: f64 = 1.0 / 64.0;
        let mut lo = 0.0;
        let mut hi = 4.0;
        let mut wh = STEP;
        while wh < 4.0 {
            if ok(wh) {
                lo = wh;
            } else {
                hi = wh;
                break;
            }
            wh += STEP;
        }
        for _ in 0..48 {
            let mid = 0.5 * (lo + hi);
            if ok(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (top_stiffness, _) = place(lo, zeta, latency);
        Ok(StrengthMap {
            zeta,
            latency,
            top_wh: lo,
            top_stiffness,
        })
    }

    /// The damping ratio.
    ///
    /// ```
    /// use stiffspring::knob::{Latency, StrengthMap};
    /// assert_eq!(StrengthMap::new(0.7, Latency::OneStep)?.damping_ratio(), 0.7);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn damping_ratio(&self) -> f64 {
        self.zeta
    }

    /// The latency the map is designed for.
    ///
    /// ```
    /// use stiffspring::knob::{Latency, StrengthMap};
    /// assert_eq!(StrengthMap::new(1.0, Latency::SameStep)?.latency(), Latency::SameStep);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn latency(&self) -> Latency {
        self.latency
    }

    /// `C_k` at strength 1.
    ///
    /// ```
    /// use stiffspring::knob::{Latency, StrengthMap};
    /// let top = StrengthMap::new(0.7, Latency::SameStep)?.top_stiffness();
    /// assert!(top > 0.1 && top < 0.13);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn top_stiffness(&self) -> f64 {
        self.top_stiffness
    }

    /// `ω·dt` of the continuous spring at strength 1 (its natural frequency times the
    /// period).
    ///
    /// ```
    /// use stiffspring::knob::{Latency, StrengthMap};
    /// let wh = StrengthMap::new(0.7, Latency::OneStep)?.top_frequency_times_dt();
    /// assert!(wh > 0.3 && wh < 0.4);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn top_frequency_times_dt(&self) -> f64 {
        self.top_wh
    }

    /// `(C_k, C_d)` for `strength ∈ [0, 1]`: `C_k = strength·C_k,top`, and the damping that
    /// puts the dominant poles at the map's damping ratio. Strength 0 is `(0, 0)`, a free
    /// rotor.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`], [`Error::Negative`] or [`Error::OutOfRange`] (above 1) for
    /// the strength.
    ///
    /// ```
    /// use stiffspring::knob::{Latency, StrengthMap};
    /// let map = StrengthMap::new(0.7, Latency::OneStep)?;
    /// assert_eq!(map.coefficients(0.0)?, (0.0, 0.0));
    /// assert!(map.coefficients(-0.1).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn coefficients(&self, strength: f64) -> Result<(f64, f64), Error> {
        let s = check_strength(strength)?;
        if s == 0.0 {
            return Ok((0.0, 0.0));
        }
        let target = s * self.top_stiffness;
        // C_k rises monotonically on [0, top_wh]: bisect for the point where it equals
        // the target, then take its damping.
        let (mut lo, mut hi) = (0.0, self.top_wh);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if place(mid, self.zeta, self.latency).0 < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (_, cd) = place(hi, self.zeta, self.latency);
        Ok((target, cd))
    }
}

/// A strength must be finite and in `[0, 1]`.
pub(crate) fn check_strength(strength: f64) -> Result<f64, Error> {
    if !strength.is_finite() {
        Err(Error::NotFinite(Parameter::Strength))
    } else if strength < 0.0 {
        Err(Error::Negative(Parameter::Strength))
    } else if strength > 1.0 {
        Err(Error::OutOfRange(Parameter::Strength))
    } else {
        Ok(strength)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jury_matches_the_closed_form_region() {
        for i in 1..400 {
            let cd = i as f64 / 200.0;
            let limit = same_step_stiffness_limit(cd);
            assert!(is_stable(limit * 0.999, cd, Latency::SameStep), "{cd}");
            assert!(!is_stable(limit * 1.001, cd, Latency::SameStep), "{cd}");
        }
    }

    #[test]
    fn placement_hits_the_requested_poles() {
        // The placed loop has the pair (a, b) as a factor: p(z) vanishes at its roots.
        for latency in [Latency::SameStep, Latency::OneStep] {
            let (wh, zeta) = (0.2, 0.7);
            let (ck, cd) = place(wh, zeta, latency);
            let q = wh * wh / 4.0;
            let den = 1.0 + zeta * wh + q;
            let (b, a) = ((1.0 - zeta * wh + q) / den, (2.0 - 2.0 * q) / den);
            let re = a / 2.0;
            let im = (b - re * re).sqrt();
            let (p, n) = characteristic_polynomial(ck, cd, latency);
            // Horner in complex arithmetic.
            let (mut pr, mut pi) = (0.0, 0.0);
            for k in (0..=n).rev() {
                let (nr, ni) = (pr * re - pi * im + p[k], pr * im + pi * re);
                pr = nr;
                pi = ni;
            }
            assert!(
                pr.abs() < 1e-12 && pi.abs() < 1e-12,
                "{latency:?}: {pr} {pi}"
            );
        }
    }
}
