//! The hot loop of a scene: one step, in the order the stages run.
//!
//! Nothing here validates, divides (beyond what the length kernel chooses), allocates
//! or branches on a rare case: the schedule lists only awake particles and springs, split
//! by kind, so each loop body is the same for every element it visits.

use super::{Scene, Stepper};
use crate::length::LengthKernel;
use crate::scalar::Scalar;

/// `a − b` per component.
#[inline(always)]
fn difference<S: Scalar, const D: usize>(a: &[S; D], b: &[S; D]) -> [S; D] {
    let mut d = [S::ZERO; D];
    for k in 0..D {
        d[k] = a[k].sub(b[k]);
    }
    d
}

/// `v += n·s` per component.
#[inline(always)]
fn add_along<S: Scalar, const D: usize>(v: &mut [S; D], n: &[S; D], s: S) {
    for k in 0..D {
        v[k] = v[k].add(n[k].mul(s));
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
    /// let mut s = Scene::<f64, 2, 1, 1>::new(SceneConfig::new(0.5)?.gravity([0.0, -2.0])?)?;
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// s.step();
    /// // Symplectic Euler: v = −1 after the step, x = −0.5.
    /// assert_eq!(s.position(p)?, [0.0, -0.5]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step(&mut self) {
        self.apply_gravity();
        match self.config.stepper {
            Stepper::GaussSeidel => self.solve_in_place(),
            Stepper::Jacobi => self.solve_from_one_state(),
        }
        self.integrate_positions();
        self.settle_anchors();
        self.update_sleep();
    }

    /// Stage 1: `u += g·dt²` for every awake free particle.
    fn apply_gravity(&mut self) {
        let g = self.gravity_step;
        if g.iter().all(|g| *g == S::ZERO) {
            return;
        }
        for &p in self.free.iter() {
            let u = &mut self.step_velocities[p as usize];
            for k in 0..D {
                u[k] = u[k].add(g[k]);
            }
        }
    }

    /// Stage 2, Gauss-Seidel: each spring's impulse (eq. 27 in position form) applied in
    /// place, so later springs see it. Springs with a pinned end first: they need no
    /// weights and move one particle.
    fn solve_in_place(&mut self) {
        let positions = &self.positions;
        let u = &mut self.step_velocities;
        for &i in self.one_sided.iter() {
            let s = &self.springs[i as usize];
            let (a, b) = (s.a as usize, s.b as usize);
            let (x, n) = L::measure(&difference(&positions[b], &positions[a]), &s.rest);
            let relative = S::dot(&difference(&u[b], &u[a]), &n);
            let delta = s.coefficients.respond(x, relative).sub(relative);
            add_along(&mut u[b], &n, delta);
        }
        for &i in self.two_sided.iter() {
            let s = &self.springs[i as usize];
            let (a, b) = (s.a as usize, s.b as usize);
            let (x, n) = L::measure(&difference(&positions[b], &positions[a]), &s.rest);
            let relative = S::dot(&difference(&u[b], &u[a]), &n);
            let delta = s.coefficients.respond(x, relative).sub(relative);
            let (da, db) = s.weights.split(delta);
            add_along(&mut u[a], &n, da);
            add_along(&mut u[b], &n, db);
        }
    }

    /// Stage 2, Jacobi: every spring's impulse from the state at the start of the stage,
    /// summed per particle, then applied: the force form of eq. 16/21 integrated with
    /// symplectic Euler.
    fn solve_from_one_state(&mut self) {
        let positions = &self.positions;
        let u = &self.step_velocities;
        let sums = &mut self.accumulated;
        for &i in self.one_sided.iter() {
            let s = &self.springs[i as usize];
            let (a, b) = (s.a as usize, s.b as usize);
            let (x, n) = L::measure(&difference(&positions[b], &positions[a]), &s.rest);
            let relative = S::dot(&difference(&u[b], &u[a]), &n);
            let delta = s.coefficients.respond(x, relative).sub(relative);
            add_along(&mut sums[b], &n, delta);
        }
        for &i in self.two_sided.iter() {
            let s = &self.springs[i as usize];
            let (a, b) = (s.a as usize, s.b as usize);
            let (x, n) = L::measure(&difference(&positions[b], &positions[a]), &s.rest);
            let relative = S::dot(&difference(&u[b], &u[a]), &n);
            let delta = s.coefficients.respond(x, relative).sub(relative);
            let (da, db) = s.weights.split(delta);
            add_along(&mut sums[a], &n, da);
            add_along(&mut sums[b], &n, db);
        }
        for &p in self.free.iter() {
            let (u, sum) = (&mut self.step_velocities[p as usize], &mut sums[p as usize]);
            for k in 0..D {
                u[k] = u[k].add(sum[k]);
            }
            *sum = [S::ZERO; D];
        }
    }

    /// Stage 3: `x += u` for every awake free particle, within the network bound.
    ///
    /// The bound is the safety net of floating point: a network that the limit policy
    /// let through but that is unstable anyway (a length kernel far outside its range, a
    /// topology the article's rule misjudges) saturates at `±NETWORK_MAGNITUDE` instead of
    /// overflowing, and a NaN made from an overflow inside the step is reset to 0, so no
    /// position or velocity ever leaves `step()` infinite or NaN. Free in fixed point.
    fn integrate_positions(&mut self) {
        let bound = self.bound;
        for &p in self.free.iter() {
            let x = &mut self.positions[p as usize];
            let u = &mut self.step_velocities[p as usize];
            for k in 0..D {
                u[k] = u[k].clamp_magnitude(bound);
                x[k] = x[k].add(u[k]).clamp_magnitude(bound);
            }
        }
    }

    /// Stage 4: anchors moved by `set_position` carried their motion into this step's
    /// damping; they are still again.
    fn settle_anchors(&mut self) {
        for &p in self.moved_anchors.iter() {
            self.step_velocities[p as usize] = [S::ZERO; D];
        }
        self.moved_anchors.clear();
    }

    /// Stage 5: islands whose particles all stayed below the threshold for the sleep
    /// time fall asleep: velocities zeroed, off the schedule.
    fn update_sleep(&mut self) {
        if self.sleep_steps == 0 {
            return;
        }
        let limit = self.sleep_step_velocity;
        for &p in self.free.iter() {
            let u = &self.step_velocities[p as usize];
            if u.iter().any(|c| c.abs() > limit) {
                let island = self.particles[p as usize].island as usize;
                self.islands[island].moving = true;
            }
        }
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
            for &p in self.free.iter() {
                let island = self.particles[p as usize].island as usize;
                if !self.islands[island].awake {
                    self.step_velocities[p as usize] = [S::ZERO; D];
                }
            }
            self.reschedule();
        }
    }
}
