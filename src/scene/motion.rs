//! Moving a scene's particles from outside: teleports, dragged anchors, velocities,
//! impulses, and the exact release of stretched springs.

use super::build::check_network;
use super::{Kind, ParticleId, Scene};
use crate::error::{Bound, Error, Parameter};
use crate::input::check_position;
use crate::length::LengthKernel;
use crate::scalar::Scalar;

impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>
    Scene<S, D, P, K, L>
{
    /// Moves a particle. A free particle teleports and keeps its velocity; a pinned one
    /// is an anchor being moved (a drag handle). Either way its springs pull from the new
    /// position in the next step, and the damping of an anchor's springs acts on its
    /// motion at once: the particle it holds is carried along as if the anchor had moved
    /// at `distance/dt` during the step.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`]; [`Error::NotFinite`] or [`Error::OutOfRange`] with
    /// [`Parameter::Position`]. Nothing changes then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f32, 2, 1, 1>::new(SceneConfig::new(0.01)?);
    /// let p = s.add_particle([0.0, 0.0], 1.0)?;
    /// s.set_position(p, [2.0, 1.0])?;
    /// assert_eq!(s.position(p)?, [2.0, 1.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_position(&mut self, particle: ParticleId, position: [S; D]) -> Result<(), Error> {
        let slot = self.slot(particle)?;
        for p in position {
            check_network(p, Parameter::Position)?;
        }
        let to = position.map(|p| p.widen());
        let from = self.positions[slot];
        self.repulling(slot, |s| {
            s.positions[slot] = to;
            s.remainders[slot] = [Default::default(); D];
        });
        if self.particles[slot].inverse_mass == 0.0 {
            let mut moved = [S::STATE_ZERO; D];
            for k in 0..D {
                moved[k] = S::state_sub(to[k], from[k]);
            }
            self.damp_anchor_motion(slot, &moved);
        }
        if self.wake_around(slot) {
            self.reschedule();
        }
        Ok(())
    }

    /// The damping of every spring held by the anchor in `slot` on the anchor's motion
    /// `moved` (one step's worth): the held end's step velocity changes by
    /// `−C_d·(−moved·n)` along the axis (per component for a point spring), the part of
    /// the damping term `−C_d·(u_b − u_a)` that the anchor's velocity makes.
    fn damp_anchor_motion(&mut self, slot: usize, moved: &[S::State; D]) {
        for i in 0..self.springs.len() {
            let s = self.springs[i];
            if s.kind != Kind::OneSided || s.a as usize != slot {
                continue;
            }
            let b = s.b as usize;
            let mut change = [S::STATE_ZERO; D];
            if s.point {
                for k in 0..D {
                    let relative = S::state_sub(S::STATE_ZERO, moved[k]);
                    change[k] = S::state_sub(S::STATE_ZERO, S::damping_term(&s.gains, relative));
                }
            } else {
                let (_, n) = L::measure(&self.separation(slot, b), &s.rest);
                let mut relative = S::STATE_ZERO;
                for k in 0..D {
                    relative = S::state_sub(relative, S::state_mul_coef(moved[k], n[k]));
                }
                let delta = S::state_sub(S::STATE_ZERO, S::damping_term(&s.gains, relative));
                for k in 0..D {
                    change[k] = S::state_mul_coef(delta, n[k]);
                }
            }
            let u = &mut self.velocities[b];
            for k in 0..D {
                u[k] = S::state_add(u[k], change[k]);
            }
        }
    }

    /// Sets a free particle's velocity, in units per second: its next step moves it by
    /// `v·dt` (springs added or moved afterwards pull into that step too). With a drag (see
    /// [`Scene::set_linear_damping`]) a free particle then follows its continuous decay
    /// exactly: it moves by `v·(1 − e^{−c·t})/c` after `t` seconds.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`]; [`Error::Pinned`]; [`Error::NotFinite`] or
    /// [`Error::OutOfRange`] with [`Parameter::Velocity`]. Nothing changes then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 1, 1>::new(SceneConfig::new(0.5)?);
    /// let p = s.add_particle([0.0], 1.0)?;
    /// s.set_velocity(p, [2.0])?;
    /// let _ = s.step();
    /// assert_eq!(s.position(p)?, [1.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_velocity(&mut self, particle: ParticleId, velocity: [S; D]) -> Result<(), Error> {
        let slot = self.free_slot(particle)?;
        let dt = S::factor(self.start_factor(slot));
        let mut u = [S::STATE_ZERO; D];
        for k in 0..D {
            let v = check_position(velocity[k], Parameter::Velocity)?;
            u[k] = S::scale(v.widen(), dt);
            // Floats: the step velocity within the bound the step keeps it in (fixed point
            // saturates by itself and is not bounded there).
            if S::RESOLUTION == 0.0 && !S::within(u[k], S::state_from_f64(S::NETWORK_MAX)) {
                return Err(Error::OutOfRange {
                    parameter: Parameter::Velocity,
                    value: v.to_f64(),
                    bound: Bound::MagnitudeAtMost {
                        max: S::NETWORK_MAX / self.start_factor(slot),
                    },
                });
            }
        }
        // The next step moves it by `u`: gravity is added in the step.
        if let Some(g) = self.gravity_step {
            for k in 0..D {
                u[k] = S::state_sub(u[k], g[k]);
            }
        }
        self.velocities[slot] = u;
        if self.wake_around(slot) {
            self.reschedule();
        }
        Ok(())
    }

    /// Gives a free particle an impulse `j` (mass · units per second): its velocity
    /// changes by `j/m`.
    ///
    /// # Errors
    ///
    /// [`Error::Stale`]; [`Error::Pinned`]; [`Error::NotFinite`] or
    /// [`Error::OutOfRange`] with [`Parameter::Impulse`]; [`Error::Unrepresentable`]
    /// when the velocity leaves the state's range. Nothing changes then.
    ///
    /// ```
    /// # use stiffspring::scene::{Scene, SceneConfig};
    /// let mut s = Scene::<f64, 1, 1, 1>::new(SceneConfig::new(0.5)?);
    /// let p = s.add_particle([0.0], 2.0)?;
    /// s.apply_impulse(p, [4.0])?; // Δv = 2 per second
    /// assert_eq!(s.velocity(p)?, [2.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn apply_impulse(&mut self, particle: ParticleId, impulse: [S; D]) -> Result<(), Error> {
        let slot = self.free_slot(particle)?;
        let scale = S::factor(self.particles[slot].inverse_mass * self.start_factor(slot));
        let mut u = self.velocities[slot];
        for k in 0..D {
            let j = check_position(impulse[k], Parameter::Impulse)?;
            u[k] = self.within_state(
                S::state_add(u[k], S::scale(j.widen(), scale)),
                Parameter::Impulse,
            )?;
        }
        self.velocities[slot] = u;
        if self.wake_around(slot) {
            self.reschedule();
        }
        Ok(())
    }

    /// Starts every awake spring on the continuous trajectory of its oscillator, as a
    /// [`SpringValue`](crate::SpringValue) released from rest starts: each spring with a
    /// tuning from the exact map adds to the kept relative step velocity of its ends
    /// `P̃·x` for its extension `x` (`P̃·x = (1 − C_d)·(x(0) − x(−dt))` of the oscillator
    /// released from rest at `x`, the value's kept start), split by their weights.
    ///
    /// Call it once after building a scene whose springs start stretched and at rest. A
    /// released scene stepped from rest instead starts half a step behind: a phase error
    /// of `π·f·dt`, 10 % of a cycle for a 2 Hz spring at 60 Hz. Exact for springs that
    /// share no particle (a body on a spring, a drag handle: `tests/scene_release.rs`, to
    /// a value's error at every rate and damping); for a network each spring's share is
    /// added, a first-order correction. Raw coefficients have `P̃ = 0` and are left alone.
    ///
    /// The start is kept damped, as a value keeps it: a heavily overdamped spring at a
    /// low rate (ζ = 10 at 12 Hz and 60 Hz) extrapolates one step back to `x(−dt)` of
    /// 10⁸ times its stretch, but `P̃·x` is below `x`, and the first step moves by
    /// `(P̃ − C_k)·x`.
    ///
    /// # Errors
    ///
    /// [`Error::Unrepresentable`] naming [`Parameter::StepVelocity`] when a step velocity
    /// would leave the state's range, with the value it needed; nothing changes then.
    ///
    /// ```
    /// use stiffspring::scene::{Scene, SceneConfig};
    /// use stiffspring::Tuning;
    ///
    /// let dt = 1.0 / 60.0;
    /// let mut s = Scene::<f64, 1, 2, 1>::new(SceneConfig::new(dt)?.no_sleep());
    /// let anchor = s.add_pinned([0.0])?;
    /// let body = s.add_particle([1.0], 1.0)?; // stretched by 1 from a zero rest length
    /// s.add_spring(anchor, body, 0.0, &Tuning::from_frequency(2.0, 0.0, dt)?)?;
    /// s.release()?;
    /// for _ in 0..15 {
    ///     let _ = s.step();
    /// }
    /// // Undamped 2 Hz from x = 1: x(t) = cos(4πt), at t = 0.25 s.
    /// let exact = (4.0 * core::f64::consts::PI * 0.25).cos();
    /// assert!((s.position(body)?[0] - exact).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn release(&mut self) -> Result<(), Error> {
        let mut velocities = self.velocities.clone();
        // The same sums in f64, to report what a refused start needed (the state
        // saturates in fixed point).
        let mut needed: heapless::Vec<[f64; D], P> = heapless::Vec::new();
        for u in self.velocities.iter() {
            // Capacity P: always room.
            let _ = needed.push(u.map(S::state_to_f64));
        }
        for s in self.springs.iter() {
            if s.release == 0.0 || !matches!(s.kind, Kind::OneSided | Kind::TwoSided) {
                continue;
            }
            let (a, b) = (s.a as usize, s.b as usize);
            let d = self.separation(a, b);
            let p = S::factor(s.release);
            // The relative velocity of the ends grows by P̃·x along the axis, or by P̃·dᵢ
            // along every axis for a point spring.
            let mut change = [S::STATE_ZERO; D];
            let mut exact = [0.0; D];
            if s.point {
                for k in 0..D {
                    change[k] = S::scale(d[k], p);
                    exact[k] = s.release * S::state_to_f64(d[k]);
                }
            } else {
                let (x, n) = L::measure(&d, &s.rest);
                let delta = S::scale(x, p);
                for k in 0..D {
                    change[k] = S::state_mul_coef(delta, n[k]);
                    exact[k] = s.release * S::state_to_f64(x) * S::coef_to_f64(n[k]);
                }
            }
            let (ia, ib) = (
                self.particles[a].inverse_mass,
                self.particles[b].inverse_mass,
            );
            let wb = ib / (ia + ib);
            for k in 0..D {
                let (da, db) = if s.kind == Kind::OneSided {
                    (S::STATE_ZERO, change[k])
                } else {
                    s.weights.split(change[k])
                };
                velocities[a][k] = S::state_add(velocities[a][k], da);
                velocities[b][k] = S::state_add(velocities[b][k], db);
                needed[a][k] -= (1.0 - wb) * exact[k];
                needed[b][k] += wb * exact[k];
            }
        }
        for (v, exact) in velocities.iter().zip(needed.iter()) {
            for (v, exact) in v.iter().zip(exact) {
                if let Err(Error::Unrepresentable {
                    parameter,
                    backend,
                    limit,
                    remedy,
                    ..
                }) = self.within_state(*v, Parameter::StepVelocity)
                {
                    return Err(Error::Unrepresentable {
                        parameter,
                        backend,
                        value: *exact,
                        limit,
                        remedy,
                    });
                }
            }
        }
        self.velocities = velocities;
        Ok(())
    }

    /// `state` if it lies within half the state's range (room for one more step), else
    /// the error.
    fn within_state(&self, state: S::State, parameter: Parameter) -> Result<S::State, Error> {
        // Floats: the bound the step keeps step velocities in (beyond it the step would
        // clamp them); fixed point: half the state's range (room for one more step).
        let max = if S::RESOLUTION == 0.0 {
            S::NETWORK_MAX
        } else {
            0.5 * S::STATE_MAX
        };
        crate::start::bounded::<S>(state, S::state_from_f64(max), parameter)
    }
}
