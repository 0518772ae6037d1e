//! The hot loop of a scene: one step, in the order the stages run.
//!
//! Nothing here validates, divides (beyond what the length kernel chooses), allocates
//! or branches on a rare case: the schedule lists only awake particles and springs, split
//! by kind, so each loop body is the same for every element it visits.

use super::{Scene, SceneMotion, Spring, Stepper};
use crate::kernel;
use crate::length::LengthKernel;
use crate::scalar::Scalar;

/// True when `S` is a float that the machine adds in hardware: `f32` and `f64` on the
/// host, `f32` on a hard-float ARM (Cortex-M4F/M7/M33). In software float (`f32` on a
/// Cortex-M0, `f64` on a Cortex-M4F) an add costs several comparisons, so
/// `integrate_positions` then tests every value on its own.
#[inline(always)]
fn adds_in_hardware<S: Scalar>() -> bool {
    S::RESOLUTION == 0.0
        && (cfg!(not(target_arch = "arm"))
            || (cfg!(target_abi = "eabihf") && core::mem::size_of::<S>() == 4))
}

/// `x += u` for one particle, within `bound` (see `integrate_positions`), carrying the
/// position's remainder ([`Scalar::add_carrying`]).
#[inline(always)]
fn integrate<S: Scalar, const D: usize>(
    x: &mut [S::State; D],
    r: &mut [S::Remainder; D],
    u: &mut [S::State; D],
    bound: S::State,
) {
    if S::RESOLUTION > 0.0 {
        // Fixed point saturates by itself.
        for k in 0..D {
            (x[k], r[k]) = S::add_carrying(x[k], r[k], u[k]);
        }
        return;
    }
    if adds_in_hardware::<S>() {
        // The common case first: if every |x + u| and |u| is within the bound (and so not
        // NaN), no clamp below could change anything, and one test of their sum replaces
        // one per value. The result is the same either way, bit for bit.
        let (mut next, mut rest) = (*x, *r);
        let mut total = S::STATE_ZERO;
        for k in 0..D {
            (next[k], rest[k]) = S::add_carrying(x[k], r[k], u[k]);
            total = S::state_add(
                total,
                S::state_add(S::state_abs(u[k]), S::state_abs(next[k])),
            );
        }
        // `total` is a sum of magnitudes: `≤` is `within` without its `abs` (and is
        // false for NaN too).
        if total <= bound {
            *x = next;
            *r = rest;
            return;
        }
    }
    for k in 0..D {
        u[k] = S::state_clamp(u[k], bound);
        let (next, rest) = S::add_carrying(x[k], r[k], u[k]);
        x[k] = S::state_clamp(next, bound);
        // A clamped or non-finite position drops its remainder.
        r[k] = if x[k] == next {
            rest
        } else {
            Default::default()
        };
    }
}

/// `a − b` per component.
#[inline(always)]
fn difference<S: Scalar, const D: usize>(a: &[S::State; D], b: &[S::State; D]) -> [S::State; D] {
    let mut d = [S::STATE_ZERO; D];
    for k in 0..D {
        d[k] = S::state_sub(a[k], b[k]);
    }
    d
}

/// The positions of a scene with their remainders, as the hot loop reads them.
#[derive(Clone, Copy)]
struct Positions<'a, S: Scalar, const D: usize> {
    x: &'a [[S::State; D]],
    r: &'a [[S::Remainder; D]],
}

impl<S: Scalar, const D: usize> Positions<'_, S, D> {
    /// `p_b − p_a`, the remainders included.
    #[inline(always)]
    fn separation(&self, a: usize, b: usize) -> [S::State; D] {
        let (xa, xb, ra, rb) = (&self.x[a], &self.x[b], &self.r[a], &self.r[b]);
        let mut d = [S::STATE_ZERO; D];
        for k in 0..D {
            d[k] = S::difference_carrying(xb[k], rb[k], xa[k], ra[k]);
        }
        d
    }
}

/// One spring's change of relative step velocity `Δ = −(C_k·x + C_d·u_rel)` (the kernel
/// of eq. 27/28) and the axis it acts along, from the separation `d = p_b − p_a` and the
/// step velocities of its ends.
#[inline(always)]
fn response<S: Scalar, const D: usize, L: LengthKernel<S>>(
    spring: &Spring<S, L>,
    d: &[S::State; D],
    ua: &[S::State; D],
    ub: &[S::State; D],
) -> (S::State, [S::Coef; D]) {
    let (x, n) = L::measure(d, &spring.rest);
    let du = difference::<S, D>(ub, ua);
    // The sum starts at its first term, not at 0 + it: in floating point the two differ
    // only in the sign of a zero, which `respond`'s `0 − (…)` makes +0 either way.
    let mut relative = if D > 0 {
        S::state_mul_coef(du[0], n[0])
    } else {
        S::STATE_ZERO
    };
    for k in 1..D {
        relative = S::state_add(relative, S::state_mul_coef(du[k], n[k]));
    }
    (kernel::respond::<S>(&spring.gains, x, relative), n)
}

/// [`response`] of the spring between particles `a` and `b` of the scene.
#[inline(always)]
fn spring_response<S: Scalar, const D: usize, L: LengthKernel<S>>(
    spring: &Spring<S, L>,
    positions: Positions<'_, S, D>,
    velocities: &[[S::State; D]],
) -> (S::State, [S::Coef; D]) {
    let (a, b) = (spring.a as usize, spring.b as usize);
    response(
        spring,
        &positions.separation(a, b),
        &velocities[a],
        &velocities[b],
    )
}

/// Gauss-Seidel's update of a two-sided distance spring whose ends are at `(xa, ra)`
/// and `(xb, rb)` with step velocities `ua`, `ub`: `ua −= w_a·Δ·n`, `ub += w_b·Δ·n`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn two_sided_update<S: Scalar, const D: usize, L: LengthKernel<S>>(
    spring: &Spring<S, L>,
    xa: &[S::State; D],
    ra: &[S::Remainder; D],
    xb: &[S::State; D],
    rb: &[S::Remainder; D],
    ua: &mut [S::State; D],
    ub: &mut [S::State; D],
) {
    let mut d = [S::STATE_ZERO; D];
    for k in 0..D {
        d[k] = S::difference_carrying(xb[k], rb[k], xa[k], ra[k]);
    }
    let (delta, n) = response(spring, &d, ua, ub);
    let (da, db) = spring.weights.split(delta);
    add_along::<S, D>(ua, &n, da);
    add_along::<S, D>(ub, &n, db);
}

/// A point spring's change of relative step velocity per component,
/// `Δᵢ = −(C_k·dᵢ + C_d·Δuᵢ)`: the kernel on every axis at once.
#[inline(always)]
fn point_response<S: Scalar, const D: usize, L: LengthKernel<S>>(
    spring: &Spring<S, L>,
    positions: Positions<'_, S, D>,
    velocities: &[[S::State; D]],
) -> [S::State; D] {
    let (a, b) = (spring.a as usize, spring.b as usize);
    let d = positions.separation(a, b);
    let du = difference::<S, D>(&velocities[b], &velocities[a]);
    let mut delta = [S::STATE_ZERO; D];
    for k in 0..D {
        delta[k] = kernel::respond::<S>(&spring.gains, d[k], du[k]);
    }
    delta
}

/// `v += n·s` per component.
#[inline(always)]
fn add_along<S: Scalar, const D: usize>(v: &mut [S::State; D], n: &[S::Coef; D], s: S::State) {
    for k in 0..D {
        v[k] = S::state_add(v[k], S::state_mul_coef(s, n[k]));
    }
}

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// Advances the scene by one time step; see the [module docs](super) for the stages.
    ///
    /// ```
    /// use stiffspring::scene::{Scene, SceneConfig};
    ///
    /// let mut s = Scene::<f64, 2, 1, 1>::new(SceneConfig::new(0.5)?.gravity([0.0, -2.0])?);
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// let motion = s.step();
    /// assert_eq!(motion.moving, 1);
    /// // Symplectic Euler: v = −1 after the step, x = −0.5.
    /// assert_eq!(s.position(p)?, [0.0, -0.5]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step(&mut self) -> SceneMotion {
        self.fell_asleep.clear();
        let woke = core::mem::take(&mut self.woken);
        self.move_particles();
        match self.config.stepper {
            Stepper::GaussSeidel => self.solve_in_place(),
            Stepper::Jacobi => self.solve_from_one_state(),
        }
        self.update_sleep();
        SceneMotion {
            moving: self.free.len(),
            fell_asleep: self.fell_asleep.len(),
            woke,
        }
    }

    /// Stage 2, Gauss-Seidel: each spring's impulse (eq. 27 in position form) applied in
    /// place, so later springs see it. Springs with a pinned end first: they need no
    /// weights and move one particle.
    fn solve_in_place(&mut self) {
        // Every per-particle vector has the same length; slicing them to it once lets
        // the compiler drop the second bounds check of each particle a spring touches.
        let n = self.positions.len();
        let positions = Positions::<S, D> {
            x: &self.positions,
            r: &self.remainders[..n],
        };
        let u = &mut self.velocities[..n];
        for &i in self.one_sided.iter() {
            let s = &self.springs[i as usize];
            let (delta, n) = spring_response(s, positions, u);
            add_along::<S, D>(&mut u[s.b as usize], &n, delta);
        }
        // `two_sided`, in the same order, chain by chain (see `Chain`).
        for chain in self.chains.iter() {
            let first = chain.spring as usize;
            let Some(p) = chain.particle else {
                let s = &self.springs[first];
                let (delta, n) = spring_response(s, positions, u);
                let (da, db) = s.weights.split(delta);
                add_along::<S, D>(&mut u[s.a as usize], &n, da);
                add_along::<S, D>(&mut u[s.b as usize], &n, db);
                continue;
            };
            // Spring `j` of the chain joins particles `p + j` and `p + j + 1`: one
            // bounds check per slice, none per spring.
            let (p, count) = (p as usize, chain.count as usize);
            let springs = &self.springs[first..first + count];
            let (x, r) = (&positions.x[p..=p + count], &positions.r[p..=p + count]);
            let (Some((x0, xs)), Some((r0, rs)), Some((u0, us))) = (
                x.split_first(),
                r.split_first(),
                u[p..=p + count].split_first_mut(),
            ) else {
                continue;
            };
            // End `a` of each spring is end `b` of the one before: its position and
            // velocity stay in registers, and its velocity is stored once, when the
            // chain moves past it.
            let (mut xa, mut ra, mut ua, mut slot) = (*x0, *r0, *u0, u0);
            for ((s, (xb, rb)), next) in springs.iter().zip(xs.iter().zip(rs)).zip(us) {
                let (xb, rb, mut ub) = (*xb, *rb, *next);
                two_sided_update(s, &xa, &ra, &xb, &rb, &mut ua, &mut ub);
                *slot = ua;
                (xa, ra, ua, slot) = (xb, rb, ub, next);
            }
            *slot = ua;
        }
        for &i in self.one_sided_points.iter() {
            let s = &self.springs[i as usize];
            let delta = point_response(s, positions, u);
            let ub = &mut u[s.b as usize];
            for k in 0..D {
                ub[k] = S::state_add(ub[k], delta[k]);
            }
        }
        for &i in self.two_sided_points.iter() {
            let s = &self.springs[i as usize];
            let delta = point_response(s, positions, u);
            for k in 0..D {
                let (da, db) = s.weights.split(delta[k]);
                u[s.a as usize][k] = S::state_add(u[s.a as usize][k], da);
                u[s.b as usize][k] = S::state_add(u[s.b as usize][k], db);
            }
        }
    }

    /// Stage 2, Jacobi: every spring's impulse from the state at the start of the stage,
    /// summed per particle, then applied: the force form of eq. 16/21 integrated with
    /// symplectic Euler.
    fn solve_from_one_state(&mut self) {
        let n = self.positions.len();
        let positions = Positions::<S, D> {
            x: &self.positions,
            r: &self.remainders[..n],
        };
        let u = &self.velocities[..n];
        let sums = &mut self.accumulated[..n];
        for &i in self.one_sided.iter() {
            let s = &self.springs[i as usize];
            let (delta, n) = spring_response(s, positions, u);
            add_along::<S, D>(&mut sums[s.b as usize], &n, delta);
        }
        for &i in self.two_sided.iter() {
            let s = &self.springs[i as usize];
            let (delta, n) = spring_response(s, positions, u);
            let (da, db) = s.weights.split(delta);
            add_along::<S, D>(&mut sums[s.a as usize], &n, da);
            add_along::<S, D>(&mut sums[s.b as usize], &n, db);
        }
        for &i in self.one_sided_points.iter() {
            let s = &self.springs[i as usize];
            let delta = point_response(s, positions, u);
            let sb = &mut sums[s.b as usize];
            for k in 0..D {
                sb[k] = S::state_add(sb[k], delta[k]);
            }
        }
        for &i in self.two_sided_points.iter() {
            let s = &self.springs[i as usize];
            let delta = point_response(s, positions, u);
            for k in 0..D {
                let (da, db) = s.weights.split(delta[k]);
                sums[s.a as usize][k] = S::state_add(sums[s.a as usize][k], da);
                sums[s.b as usize][k] = S::state_add(sums[s.b as usize][k], db);
            }
        }
        for &p in self.free.iter() {
            let (u, sum) = (&mut self.velocities[p as usize], &mut sums[p as usize]);
            for k in 0..D {
                u[k] = S::state_add(u[k], sum[k]);
            }
            *sum = [S::STATE_ZERO; D];
        }
    }

    /// Stage 1: every awake free particle moves by its step velocity and gravity,
    /// `u = ũ + g·dt²`, `x += u`, within the network bound; then the drag takes `d·u` off
    /// (see [`damping`](super::damping)), leaving the velocity the springs damp next.
    ///
    /// The bound is the safety net of floating point: a network that the limit policy
    /// let through but that is unstable anyway (a length kernel far outside its range, a
    /// topology the article's rule misjudges) saturates at `±NETWORK_MAX` instead of
    /// overflowing, and a NaN made from an overflow inside the step is reset to 0, so no
    /// position or velocity ever leaves `step()` infinite or NaN. Free in fixed point.
    ///
    /// It also takes stage 3's census while each step is at hand: a particle that moved
    /// by more than the sleep threshold marks its island as moving.
    fn move_particles(&mut self) {
        let bound = S::state_from_f64(S::NETWORK_MAX);
        let census = self.sleep_steps != 0;
        let limit = self.sleep_step_velocity;
        let (gravity, dragged) = (self.gravity_step, self.dragged);
        let positions: &mut [[S::State; D]] = &mut self.positions;
        let n = positions.len();
        let remainders = &mut self.remainders[..n];
        let velocities = &mut self.velocities[..n];
        let drag = &self.drag[..n];
        let particles = &self.particles[..n];
        let islands = &mut self.islands;
        for &p in self.free.iter() {
            let p = p as usize;
            let u = &mut velocities[p];
            if let Some(g) = gravity {
                for k in 0..D {
                    u[k] = S::state_add(u[k], g[k]);
                }
            }
            integrate::<S, D>(&mut positions[p], &mut remainders[p], u, bound);
            if census && u.iter().any(|c| !S::within(*c, limit)) {
                islands[particles[p].island as usize].moving = true;
            }
            if dragged {
                let d = drag[p];
                for k in 0..D {
                    u[k] = S::state_sub(u[k], S::scale(u[k], d));
                }
            }
        }
    }

    /// Stage 3: islands whose particles all stayed below the threshold for the sleep
    /// time fall asleep: velocities zeroed, off the schedule.
    fn update_sleep(&mut self) {
        if self.sleep_steps == 0 {
            return;
        }
        // Which islands moved was marked in stage 1.
        let mut fell_asleep = false;
        for &root in self.awake_islands.iter() {
            let island = &mut self.islands[root as usize];
            if core::mem::take(&mut island.moving) {
                island.quiet = 0;
            } else {
                island.quiet += 1;
                if island.quiet >= self.sleep_steps {
                    island.awake = false;
                    fell_asleep = true;
                }
            }
        }
        if fell_asleep {
            // At rest: the next step moves nothing (`u + g·dt² = 0`), which at an
            // equilibrium is what the springs pull anyway, so the island wakes where it
            // fell asleep, without a jolt.
            let mut still = [S::STATE_ZERO; D];
            if let Some(g) = self.gravity_step {
                for k in 0..D {
                    still[k] = S::state_sub(S::STATE_ZERO, g[k]);
                }
            }
            for &p in self.free.iter() {
                let island = self.particles[p as usize].island as usize;
                if !self.islands[island].awake {
                    self.velocities[p as usize] = still;
                    // Capacity P: always room.
                    let _ = self.fell_asleep.push(p);
                }
            }
            self.reschedule();
        }
    }
}
