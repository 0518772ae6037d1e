//! The safe coefficient for springs that share particles: [`network_limit`], and the
//! scene's policy for springs above it.

use super::config::{LimitPolicy, Stepper};
use super::{Kind, Scene};
use crate::error::Error;
use crate::input::gains_of;
use crate::length::LengthKernel;
use crate::scalar::Scalar;
use crate::tuning::Tuning;
use heapless::Vec;

/// The fraction of the worst-case limit the scene accepts (see [`network_limit`]).
const MARGIN: f64 = 0.75;

/// The largest `C_k` and `C_d` the scene accepts for a spring whose busiest free
/// particle carries `springs_per_particle` springs (counting itself), with the given
/// stepper.
///
/// For `n ≤ 1` (the spring is alone on its free ends) this is 1, the article's square;
/// a scene accepts such a spring further, anywhere in the single spring's exact stable
/// region (Jury's `C_k + 2·C_d < 4`, with its ends' drag in `C_d`), as a
/// [`SpringValue`](crate::SpringValue) does.
///
/// A single spring is stable for any `(C_k, C_d)` in `[0, 1]²`. Springs that share a
/// particle compete: each corrects its own extension and disturbs its neighbours'. The
/// article's rule of thumb (eq. 29) is `C_max ≈ 1/(n + 1)`, with `n` the largest number of
/// springs on either free particle of a spring. The stress tests (`tests/network_limits.rs`)
/// measured the true limits; this is a rule that holds for
/// **every** network with share count `n`, whatever its geometry (the
/// geometry changes as a network deforms), masses and pinning, and whatever coefficients
/// its other springs have, each within its own limit:
///
/// ```text
/// limit(n) = min(1, ¾·W(n))        W_Jacobi(n) = 4/(3n)        W_GaussSeidel(n) = below
/// ```
///
/// rounded to a multiple of `2⁻²⁴`, so that the limit is exact in every backend's
/// coefficient format (`f32`, `Q3.29`, `Q3.61`) and a spring set exactly to it is stored
/// exactly at it.
///
/// **Jacobi: `W = 4/(3n)`, proven.** Linearised about its rest state, a Jacobi step
/// is `u' = u − D·u − K·p`, `p' = p + u'` with `K` and `D` symmetric and positive
/// semi-definite in the mass inner product (the sums of every spring's
/// `C·m_red·jᵀj`). Then `V = |u|² + pᵀK(p − u) − ½·uᵀDu` never grows
/// (`ΔV = −½·(u + u')ᵀD(u + u')`) and is positive definite when `K + 2D < 4` (the
/// matrix form of Jury's `C_k + 2·C_d < 4`). By Cauchy–Schwarz,
/// `m_red·|δp_b − δp_a|² ≤ m_a·|δp_a|² + m_b·|δp_b|²`, so `K + 2D` is at most the largest
/// `Σ (C_k + 2·C_d)` over the springs of one particle: below `3·n·C`. Tight for `n`
/// collinear springs on one particle, and approached by long straight ropes (`4/(3·2)`).
/// About a stretched state the bound still holds: a stretched spring's transverse
/// stiffness, `C_k·x/length`, is below its axial one.
///
/// **Gauss-Seidel: `W` from its worst geometry.** Without damping, Gauss-Seidel is the
/// Jacobi map (the stiffness impulses depend on positions only). With damping, its
/// worst case in the measurements is a particle with `n` collinear springs whose first
/// `m` are damped and the rest are not: the `n` in-place impulses compose into one spring
/// with `C_k' = Σₖ C_k·(1 − C_d)^{(damped after k)}` and `C_d' = 1 − (1 − C_d)^m`, so
/// at `C_k = C_d = L` it is stable exactly when
///
/// ```text
/// max over m = 0..n of  3·(1 − (1 − L)^m) + (n − m)·L  <  4
/// ```
///
/// which defines `W(n)`: 1 for `n = 2`, 0.8 for 3, ⅔ for 4, 0.36 for 8, `3.1/n` for
/// large `n` (always above `3/(n + 1)`, three times the article's rule). With one tuning
/// for all springs Gauss-Seidel tolerates much more (ropes `4/3`, meshes about 1).
///
/// **The margin `¾`** covers what the linear analysis leaves out: the
/// [length kernels](crate::length) (`Approximate` scales a spring's effective
/// coefficients by up to 7 %, [`Linearised`](crate::length::Linearised) by
/// `(length/rest)²`, 33 % at 15 % stretch),
/// the nonlinear measurements (from 10 % and 50 % deformation, every topology stayed
/// stable at `¾·W` with `C_k = C_d`, and with `C_d` down to 1 % of `C_k`), and the
/// coefficient rounding of each backend. An undamped network (`C_d = 0`) is only
/// neutrally stable: from a 50 % deformation it can blow up at this limit, and so can a
/// lightly damped one at the proven budget `Σ (C_k + 2·C_d) < 4` per particle, which is
/// why the limit is not that budget (`tests/network_limits.rs`,
/// `the_proven_jacobi_budget_is_not_nonlinearly_safe_and_the_rule_needs_some_damping`).
///
/// ```
/// use stiffspring::scene::{network_limit, Stepper};
///
/// // A lone spring: the article's unconditionally stable square.
/// assert_eq!(network_limit(1, Stepper::GaussSeidel), 1.0);
/// assert_eq!(network_limit(1, Stepper::Jacobi), 1.0);
/// // A rope (two springs per inner particle).
/// assert_eq!(network_limit(2, Stepper::GaussSeidel), 0.75);
/// assert_eq!(network_limit(2, Stepper::Jacobi), 0.5);
/// // A square mesh without diagonals (four).
/// assert_eq!(network_limit(4, Stepper::GaussSeidel), 0.5);
/// assert_eq!(network_limit(4, Stepper::Jacobi), 0.25);
/// ```
pub fn network_limit(springs_per_particle: usize, stepper: Stepper) -> f64 {
    let n = springs_per_particle;
    if n <= 1 {
        // One spring per free particle: the single-spring guarantee holds.
        return 1.0;
    }
    let worst = match stepper {
        Stepper::Jacobi => 4.0 / (3.0 * n as f64),
        // Beyond a few thousand springs on one particle, the closed lower bound
        // 3/(n + 1) is within 3 % of W(n) and needs no loop.
        Stepper::GaussSeidel if n > 4096 => 3.0 / (n as f64 + 1.0),
        Stepper::GaussSeidel => gauss_seidel_worst_case(n),
    };
    dyadic((MARGIN * worst).min(1.0))
}

/// `W(n)` for Gauss-Seidel (`n ≥ 2`): the largest `L` with
/// `max_m 3·(1 − (1 − L)^m) + (n − m)·L < 4`, by bisection (set-up only, no `libm`).
fn gauss_seidel_worst_case(n: usize) -> f64 {
    // The worst m is where the next damped spring stops adding: the term grows with m
    // while 3·(1 − L)^m > 1, so the loop stops there (about 1.1/L steps) or at n.
    let worst = |l: f64| {
        let mut keep = 1.0; // (1 − L)^m
        let mut m = 0;
        while m < n && 3.0 * keep > 1.0 {
            keep *= 1.0 - l;
            m += 1;
        }
        3.0 * (1.0 - keep) + (n - m) as f64 * l
    };
    // W(2) = 1, and W decreases with n: search (0, 1].
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        if worst(mid) < 4.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// `value` (in `[0, 1]`) rounded to the nearest multiple of `2⁻²⁴`: exact in `f32` and in
/// the fixed-point coefficient formats. (The bisection above ends a few ULP below `W`;
/// rounding to nearest gives the round values ¾, ½, ... exactly, and moves a limit by at
/// most `3e−8`, nothing against the margin.)
fn dyadic(value: f64) -> f64 {
    const SCALE: f64 = (1u32 << 24) as f64;
    // `as` truncates toward zero: for a non-negative value, + ½ makes it round to nearest.
    ((value * SCALE + 0.5) as u32) as f64 / SCALE
}

/// A hypothetical change to the share counts: one more spring on each `extra` slot, and a
/// pinned particle that becomes free.
pub(crate) struct Change {
    pub(crate) extra: [Option<usize>; 2],
    pub(crate) freed: Option<usize>,
}

impl Change {
    pub(crate) const NONE: Change = Change {
        extra: [None, None],
        freed: None,
    };
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// The springs on slot `p` under `change`, if it is (or becomes) free; 0 if pinned
    /// (pinned ends do not move, so springs meeting there do not compete).
    pub(crate) fn share_count_of(&self, p: usize, change: &Change) -> u16 {
        let free = self.particles[p].inverse_mass > 0.0 || change.freed == Some(p);
        if !free {
            return 0;
        }
        let extra = change.extra.iter().filter(|&&e| e == Some(p)).count() as u16;
        self.particles[p].springs + extra
    }

    /// The share count `n` of a spring between slots `a` and `b` under `change`: the
    /// springs on its busiest free end.
    pub(crate) fn share_count(&self, a: usize, b: usize, change: &Change) -> u16 {
        self.share_count_of(a, change)
            .max(self.share_count_of(b, change))
    }

    /// The gains of raw coefficients `(C_k, C_d)` at the scene's `dt`: a spring clamped to
    /// the network limit.
    pub(crate) fn gains_at(&self, (ck, cd): (f64, f64)) -> Result<S::Gains, Error> {
        gains_of::<S>(&Tuning::from_coefficients_extended(ck, cd, self.config.dt)?)
    }

    /// The length kernel's stiffening factors ([`LengthKernel::stiffening`]) for a
    /// spring with rest data `rest` between slots `a` and `b` at their current distance;
    /// `(1, 1)` for angles and point springs.
    pub(crate) fn stiffening(&self, a: usize, b: usize, rest: &L::Rest) -> (f64, f64) {
        let length = L::rest_length(rest).to_f64();
        if L::SIGNED_REST || length <= 0.0 {
            return (1.0, 1.0);
        }
        let distance = S::state_to_f64(S::norm(&self.separation(a, b)));
        L::stiffening(distance / length)
    }

    /// The coefficients `(C_k, C_d)` as the policy allows them for share count `degree`
    /// and the length kernel's stiffening factors `(a, b)` (`a·C_k` and `b·C_d` must be
    /// within the limit), and whether they were clamped.
    pub(crate) fn checked(
        &self,
        coefficients: (f64, f64),
        degree: u16,
        (a, b): (f64, f64),
        (end_a, end_b): (usize, usize),
    ) -> Result<((f64, f64), bool), Error> {
        if degree <= 1 {
            let retention = self.retention(end_a).min(self.retention(end_b));
            return self.checked_alone(coefficients, (a, b), retention);
        }
        let limit = network_limit(degree as usize, self.config.stepper);
        let (limit_k, limit_d) = (limit / a, limit / b);
        let (ck, cd) = coefficients;
        // A stored spring's coefficients are the requested ones rounded to the backend's
        // format (24 significant bits in f32, 30 in fixed point), so a spring tuned
        // exactly at the limit may read back a hair above it; a relative slack of 1e−6,
        // far below any stability margin, keeps it accepted.
        let slack = limit * 1e-6;
        if ck <= limit_k + slack && cd <= limit_d + slack {
            return Ok(((ck, cd), false));
        }
        match self.config.policy {
            LimitPolicy::Reject => Err(Error::ExceedsNetworkLimit {
                coefficient: if ck > limit_k + slack { ck } else { cd },
                limit: if ck > limit_k + slack {
                    limit_k
                } else {
                    limit_d
                },
            }),
            LimitPolicy::Clamp => Ok(((ck.min(limit_k), cd.min(limit_d)), true)),
        }
    }

    /// A spring whose free ends carry no other spring: a single spring in the relative
    /// coordinate of its ends, stable exactly in Jury's region as a
    /// [`SpringValue`](crate::SpringValue) is (`C_k + 2·C_d < 4`), with the drag's
    /// retention `r` of its ends folded into the damping (`1 − C_d → r·(1 − C_d)`) and
    /// the length kernel's stiffening `(a, b)`.
    fn checked_alone(
        &self,
        (ck, cd): (f64, f64),
        (a, b): (f64, f64),
        retention: f64,
    ) -> Result<((f64, f64), bool), Error> {
        // Without a drag or a stiffening the spring is exactly the value's: every tuning
        // that exists lies in the square or in Jury's region (`Tuning` refuses the rest),
        // and the scene runs the same rounded gains a `SpringValue` would. Accepted as is,
        // so that no rounding of the test below can refuse what a value takes.
        if a == 1.0 && b == 1.0 && retention == 1.0 {
            return Ok(((ck, cd), false));
        }
        let damping = 1.0 - retention * (1.0 - b * cd);
        if a * ck + 2.0 * damping < 4.0 {
            return Ok(((ck, cd), false));
        }
        // The largest C_k (before the stiffening) with a·C_k + 2·C_d' < 4, a hair inside
        // (the clamped spring must be strictly stable).
        let limit = (4.0 - 2.0 * damping) / a * (1.0 - 1e-9);
        match self.config.policy {
            LimitPolicy::Reject => Err(Error::ExceedsNetworkLimit {
                coefficient: ck,
                limit,
            }),
            LimitPolicy::Clamp => Ok(((limit, cd), true)),
        }
    }

    /// The fraction `r = e^{−c·dt}` of its velocity a particle keeps from its drag per
    /// step (1 for a pinned particle, or none).
    pub(crate) fn retention(&self, slot: usize) -> f64 {
        let p = &self.particles[slot];
        if p.inverse_mass == 0.0 || p.damping == 0.0 {
            1.0
        } else {
            crate::math::exp(-p.damping * self.config.dt)
        }
    }

    /// Checks every live spring touching `slots` against its limit under `change`, and
    /// returns the clamped gains to apply once the change commits (empty under
    /// [`LimitPolicy::Reject`], which fails instead).
    pub(crate) fn check_neighbours(
        &self,
        slots: &[usize],
        change: &Change,
    ) -> Result<Vec<(u16, S::Gains), K>, Error> {
        let mut clamps: Vec<(u16, S::Gains), K> = Vec::new();
        for (i, s) in self.springs.iter().enumerate() {
            let (a, b) = (s.a as usize, s.b as usize);
            if s.kind == Kind::Dead || !(slots.contains(&a) || slots.contains(&b)) {
                continue;
            }
            let degree = self.share_count(a, b, change);
            let factors = self.stiffening(a, b, &s.rest);
            let ((ck, cd), clamped) =
                self.checked(S::gains_to_f64(&s.gains), degree, factors, (a, b))?;
            if clamped {
                // At most K springs: always room.
                let _ = clamps.push((i as u16, self.gains_at((ck, cd))?));
            }
        }
        Ok(clamps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_seidel_worst_case_has_its_closed_forms() {
        // m = 1 gives (n + 2)·L < 4; m = 2 gives (n + 4)·L − 3L² < 4.
        assert!((gauss_seidel_worst_case(2) - 1.0).abs() < 1e-12);
        assert!((gauss_seidel_worst_case(3) - 0.8).abs() < 1e-12);
        assert!((gauss_seidel_worst_case(4) - 2.0 / 3.0).abs() < 1e-12);
        for n in 2..200 {
            let w = gauss_seidel_worst_case(n);
            assert!(w > 3.0 / (n as f64 + 1.0) - 1e-12, "{n}");
            assert!(w <= 4.0 / (n as f64 + 2.0) + 1e-12, "{n}");
        }
    }

    #[test]
    fn limits_are_exact_in_every_coefficient_format_and_decrease() {
        for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
            let mut last = 1.0;
            for n in 0..300 {
                let l = network_limit(n, stepper);
                assert_eq!(l as f32 as f64, l);
                assert_eq!((l * (1u64 << 24) as f64).fract(), 0.0);
                assert!(l <= last && l > 0.0);
                last = l;
            }
        }
        // Jacobi: ¾·4/(3n) = 1/n.
        assert_eq!(network_limit(3, Stepper::Jacobi), dyadic(1.0 / 3.0));
        assert_eq!(network_limit(8, Stepper::Jacobi), 0.125);
        // Huge share counts: tiny (or zero) limits, computed at once.
        for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
            let l = network_limit(usize::MAX, stepper);
            assert!((0.0..1e-12).contains(&l));
            let l = network_limit(u16::MAX as usize, stepper);
            assert!(l > 0.0 && l < 1e-4, "{l}");
        }
        let (near, far) = (gauss_seidel_worst_case(4096), 3.0 / 4097.0);
        assert!(far < near && far > 0.96 * near);
    }
}
