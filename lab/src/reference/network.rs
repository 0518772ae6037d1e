//! Particle and angular-spring NETWORKS for the independent reference model.
//!
//! Written straight from the seed article (eq. 16-21 for distance springs,
//! eq. 22-26 and 28 for angular springs, eq. 27/28 in their corrected form
//! `j = -(m_red/dt)·C_k·x - m_red·C_d·v`) and shares no code with the library.
//! Everything is f64 and std only; the dimension `D` (1, 2 or 3) is a const
//! generic and vectors are `[f64; D]`.
//!
//! Conventions:
//! - A particle has a position, a velocity and a mass. Mass `f64::INFINITY`
//!   means pinned: its position and velocity are never changed by a step
//!   (only by [`Network::teleport`]); it receives no gravity and no impulse.
//!   [`Network::add_particle`] zeroes the velocity of a pinned particle.
//! - A distance spring joins particles `a` and `b`. With `d = p_b - p_a`, its
//!   axis is `n = d/|d|`, its extension `x = |d| - L` and its relative
//!   velocity `v_rel = (v_b - v_a)·n`. In D = 1 the same formula is used
//!   (`|d|` is `d.abs()`, so `n = ±1`). The spring pushes `+j·n` on b and
//!   `-j·n` on a.
//! - **Coincident particles** (`|d| == 0`): the axis is undefined, and the
//!   spring applies nothing in that step (no impulse, no force). Its
//!   extension is then `-L` and [`Network::spring_energy`] still counts it.
//! - A spring whose two ends are both pinned does nothing (its reduced mass
//!   is infinite) and is left out of [`Network::spring_energy`].
//! - External acceleration (`gravity`) is added to every non-pinned particle
//!   at the start of each step, `v += g·dt`, before the springs act.
//! - Both steppers end with symplectic Euler: all non-pinned positions
//!   advance with the new velocities, `x += v·dt`.
//!
//! Two update orders (for a single spring the force form integrated by
//! symplectic Euler and the impulse form are the same map; for a network they
//! differ, and both are legitimate):
//! - [`Network::step_gauss_seidel`]: the impulse of each spring, in the order
//!   of `springs`, is applied at once, so later springs see the velocities
//!   left by earlier ones.
//! - [`Network::step_jacobi`]: every spring's force is computed from the same
//!   state (after gravity), summed per particle, then applied.
//!
//! For a single spring the two are the same map (up to rounding).
//!
//! The discrete hanging-rope equilibrium is worked out in the self-test
//! `rope_under_gravity_settles_at_the_discrete_equilibrium`: because gravity
//! is added to the velocities before the springs act, the damping term sees
//! a relative velocity at the fixed point, so the rest extension is not the
//! static `weight below / k` for Gauss-Seidel (nor, for the spring at a pinned
//! end, for Jacobi).

use super::{d_max, k_max, reduced_mass};

// ---------------------------------------------------------------------------
// Small vector helpers
// ---------------------------------------------------------------------------

fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    std::array::from_fn(|k| a[k] - b[k])
}

/// Dot product, accumulated left to right from `+0.0` (deterministic; in
/// D = 1 it is the single product).
fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    a.iter().zip(&b).fold(0.0, |s, (x, y)| s + x * y)
}

/// Euclidean length; in D = 1 exactly `|d|`.
fn length<const D: usize>(d: [f64; D]) -> f64 {
    if D == 1 { d[0].abs() } else { dot(d, d).sqrt() }
}

// ---------------------------------------------------------------------------
// Distance-spring network
// ---------------------------------------------------------------------------

/// A point mass. `mass == f64::INFINITY` means pinned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Particle<const D: usize> {
    pub pos: [f64; D],
    pub vel: [f64; D],
    pub mass: f64,
}

impl<const D: usize> Particle<D> {
    /// `true` for a pinned particle (infinite mass).
    pub fn is_pinned(&self) -> bool {
        self.mass.is_infinite()
    }
}

/// A damped distance spring between particles `a` and `b` with rest length
/// `rest` and the article's coefficients `ck` (C_k) and `cd` (C_d).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring {
    pub a: usize,
    pub b: usize,
    pub rest: f64,
    pub ck: f64,
    pub cd: f64,
}

/// Particles joined by distance springs, with a uniform external
/// acceleration `gravity` (zero by default).
#[derive(Clone, Debug, PartialEq)]
pub struct Network<const D: usize> {
    pub particles: Vec<Particle<D>>,
    pub springs: Vec<Spring>,
    pub gravity: [f64; D],
    /// A drag on every non-pinned particle's velocity, `dv/dt = −drag·v` (per second),
    /// applied by the kept-order steppers only (zero by default).
    pub drag: f64,
}

impl<const D: usize> Default for Network<D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const D: usize> Network<D> {
    /// Empty network without gravity.
    pub fn new() -> Self {
        assert!((1..=3).contains(&D), "Network: D must be 1, 2 or 3");
        Self {
            particles: Vec::new(),
            springs: Vec::new(),
            gravity: [0.0; D],
            drag: 0.0,
        }
    }

    /// Adds a particle and returns its index. `mass` must be `> 0` (or
    /// `f64::INFINITY` for a pinned particle, whose velocity is set to 0).
    pub fn add_particle(&mut self, pos: [f64; D], vel: [f64; D], mass: f64) -> usize {
        assert!(mass > 0.0, "add_particle: mass must be > 0 (or INFINITY)");
        let vel = if mass.is_infinite() { [0.0; D] } else { vel };
        self.particles.push(Particle { pos, vel, mass });
        self.particles.len() - 1
    }

    /// Adds a pinned particle (infinite mass, zero velocity).
    pub fn add_pinned(&mut self, pos: [f64; D]) -> usize {
        self.add_particle(pos, [0.0; D], f64::INFINITY)
    }

    /// Adds a spring and returns its index (its position in the
    /// Gauss-Seidel order).
    pub fn add_spring(&mut self, a: usize, b: usize, rest: f64, ck: f64, cd: f64) -> usize {
        assert!(a != b, "add_spring: a spring needs two different particles");
        assert!(a < self.particles.len() && b < self.particles.len());
        self.springs.push(Spring { a, b, rest, ck, cd });
        self.springs.len() - 1
    }

    /// Adds a spring whose rest length is the current distance of `a`, `b`.
    pub fn add_spring_at_current_length(&mut self, a: usize, b: usize, ck: f64, cd: f64) -> usize {
        let rest = self.distance(a, b);
        self.add_spring(a, b, rest, ck, cd)
    }

    /// Moves particle `i` to `pos` (the only way a pinned particle moves).
    /// The velocity is left as it is.
    pub fn teleport(&mut self, i: usize, pos: [f64; D]) {
        self.particles[i].pos = pos;
    }

    /// Distance `|p_b - p_a|` between two particles.
    pub fn distance(&self, a: usize, b: usize) -> f64 {
        length(sub(self.particles[b].pos, self.particles[a].pos))
    }

    /// Unit axis `n = (p_b - p_a)/|p_b - p_a|` of spring `s` and the length
    /// `|p_b - p_a|`, or `None` if the two particles coincide.
    pub fn axis(&self, s: usize) -> Option<([f64; D], f64)> {
        let sp = &self.springs[s];
        let d = sub(self.particles[sp.b].pos, self.particles[sp.a].pos);
        let len = length(d);
        if len == 0.0 {
            None // coincident: no direction, the spring is skipped
        } else {
            Some((d.map(|c| c / len), len))
        }
    }

    /// Extension `x = |p_b - p_a| - L` of spring `s`.
    pub fn extension(&self, s: usize) -> f64 {
        let sp = &self.springs[s];
        self.distance(sp.a, sp.b) - sp.rest
    }

    /// Relative velocity along the axis, `(v_b - v_a)·n`, of spring `s`
    /// (0 if the particles coincide).
    pub fn relative_velocity(&self, s: usize) -> f64 {
        let sp = &self.springs[s];
        match self.axis(s) {
            Some((n, _)) => dot(sub(self.particles[sp.b].vel, self.particles[sp.a].vel), n),
            None => 0.0,
        }
    }

    /// Reduced mass of spring `s` (eq. 18); equals the free particle's mass
    /// if the other end is pinned, infinite if both are.
    pub fn reduced_mass(&self, s: usize) -> f64 {
        let sp = &self.springs[s];
        reduced_mass(self.particles[sp.a].mass, self.particles[sp.b].mass) // eq. 18
    }

    /// Stiffness `k = C_k·m_red/dt²` of spring `s` (eq. 19 times C_k).
    pub fn stiffness(&self, s: usize, dt: f64) -> f64 {
        self.springs[s].ck * k_max(self.reduced_mass(s), dt) // eq. 19 / 16
    }

    /// `v += g·dt` for every non-pinned particle.
    fn apply_gravity(&mut self, dt: f64) {
        let g = self.gravity;
        for p in self.particles.iter_mut().filter(|p| !p.is_pinned()) {
            for (v, gk) in p.vel.iter_mut().zip(g) {
                *v += gk * dt; // eq. 7: v = a·dt
            }
        }
    }

    /// `x += v·dt` for every non-pinned particle (symplectic Euler: with the
    /// velocities after this step's impulses/forces).
    fn drift(&mut self, dt: f64) {
        for p in self.particles.iter_mut().filter(|p| !p.is_pinned()) {
            for (x, v) in p.pos.iter_mut().zip(p.vel) {
                *x += v * dt; // eq. 1: x = v·dt
            }
        }
    }

    /// Axis, length and both masses of spring `s`, or `None` when the spring
    /// acts on nothing this step (both ends pinned, or coincident ends).
    fn active(&self, s: usize) -> Option<([f64; D], f64, f64, f64)> {
        let sp = &self.springs[s];
        let (ma, mb) = (self.particles[sp.a].mass, self.particles[sp.b].mass);
        if ma.is_infinite() && mb.is_infinite() {
            return None;
        }
        let (n, len) = self.axis(s)?;
        Some((n, len, ma, mb))
    }

    /// Gauss-Seidel impulse step: gravity; then for each spring in order the
    /// corrected eq. 27 impulse `j = -(m_red/dt)·C_k·x - m_red·C_d·v_rel`
    /// (eq. 18 reduced mass), `+j·n` to b and `-j·n` to a, velocities
    /// updated in place; then `x += v·dt` for all particles.
    pub fn step_gauss_seidel(&mut self, dt: f64) {
        self.apply_gravity(dt);
        self.impulses_in_place(dt);
        self.drift(dt);
    }

    /// Each spring's corrected eq. 27 impulse, in order, in place.
    fn impulses_in_place(&mut self, dt: f64) {
        for s in 0..self.springs.len() {
            let Some((n, len, ma, mb)) = self.active(s) else {
                continue;
            };
            let Spring { a, b, rest, ck, cd } = self.springs[s];
            let m_red = reduced_mass(ma, mb); // eq. 18
            let x = len - rest;
            let v = dot(sub(self.particles[b].vel, self.particles[a].vel), n);
            let j = -(m_red / dt) * ck * x - m_red * cd * v; // eq. 27 (corrected)
            if ma.is_finite() {
                for (va, nk) in self.particles[a].vel.iter_mut().zip(n) {
                    *va -= j * nk / ma;
                }
            }
            if mb.is_finite() {
                for (vb, nk) in self.particles[b].vel.iter_mut().zip(n) {
                    *vb += j * nk / mb;
                }
            }
        }
    }

    /// Jacobi force step: gravity; then every spring's force of eq. 21/16,
    /// `f = -k_max·C_k·x - d_max·C_d·v_rel` with `k_max = m_red/dt²`,
    /// `d_max = m_red/dt` (eq. 19, 20), all from the same state, `+f·n` on b
    /// and `-f·n` on a, summed per particle; then `v += F/m·dt` and
    /// `x += v·dt`.
    pub fn step_jacobi(&mut self, dt: f64) {
        self.apply_gravity(dt);
        self.forces_from_one_state(dt);
        self.drift(dt);
    }

    /// Every spring's eq. 21 force from the same state, summed per particle, applied as
    /// `v += F/m·dt`.
    fn forces_from_one_state(&mut self, dt: f64) {
        let mut force = vec![[0.0; D]; self.particles.len()];
        for s in 0..self.springs.len() {
            let Some((n, len, ma, mb)) = self.active(s) else {
                continue;
            };
            let Spring { a, b, rest, ck, cd } = self.springs[s];
            let m_red = reduced_mass(ma, mb); // eq. 18
            let x = len - rest;
            let v = dot(sub(self.particles[b].vel, self.particles[a].vel), n);
            let f = -k_max(m_red, dt) * ck * x - d_max(m_red, dt) * cd * v; // eq. 21 / 16
            for (fa, nk) in force[a].iter_mut().zip(n) {
                *fa -= f * nk;
            }
            for (fb, nk) in force[b].iter_mut().zip(n) {
                *fb += f * nk;
            }
        }
        for (p, fp) in self.particles.iter_mut().zip(&force) {
            if p.is_pinned() {
                continue;
            }
            for (v, fk) in p.vel.iter_mut().zip(fp) {
                *v += fk / p.mass * dt; // eq. 3 / 8: v += (f/m)·dt
            }
        }
    }

    // -- The kept order --
    //
    // The library's scenes keep, between steps, the velocity the next drift moves a
    // particle by: the springs act at the END of a step, at the positions it reached,
    // and what they leave (damped, and already pulled by their stiffness) is kept. The
    // steppers below run that order, written from the same equations:
    //
    //     v += g·dt;  x += v·dt;  v *= e^{−drag·dt};  springs (eq. 27 / eq. 21) on v
    //
    // A start is the velocities plus `pull` (each spring's stiffness impulse at the
    // start positions; the library's scenes start so). From rest, and without gravity or
    // drag, that is the same motion as `step_jacobi` from rest, and as undamped
    // `step_gauss_seidel`, because each stiffness impulse depends only on positions (the
    // self-test `kept_order_is_the_same_motion_without_gravity`); otherwise the two
    // differ in their first step by the damping of the start velocity (and, in place, of
    // the earlier springs' pull). With gravity, here the damping
    // never sees it: a hanging spring rests at the static weight/k.

    /// `v *= e^{−drag·dt}` for every non-pinned particle.
    fn apply_drag(&mut self, dt: f64) {
        let keep = (-self.drag * dt).exp();
        for p in self.particles.iter_mut().filter(|p| !p.is_pinned()) {
            for v in p.vel.iter_mut() {
                *v *= keep;
            }
        }
    }

    /// Adds every spring's stiffness impulse at the current positions,
    /// `j = −(m_red/dt)·C_k·x` (the damping term left out), to its ends' velocities: the
    /// pull a kept-order step starts from.
    pub fn pull(&mut self, dt: f64) {
        for s in 0..self.springs.len() {
            let Some((n, len, ma, mb)) = self.active(s) else {
                continue;
            };
            let Spring { a, b, rest, ck, .. } = self.springs[s];
            let j = -(reduced_mass(ma, mb) / dt) * ck * (len - rest); // eq. 27, stiffness
            if ma.is_finite() {
                for (va, nk) in self.particles[a].vel.iter_mut().zip(n) {
                    *va -= j * nk / ma;
                }
            }
            if mb.is_finite() {
                for (vb, nk) in self.particles[b].vel.iter_mut().zip(n) {
                    *vb += j * nk / mb;
                }
            }
        }
    }

    /// The kept order with the Gauss-Seidel impulses: gravity, drift, drag, then each
    /// spring's corrected eq. 27 impulse in order, in place, at the new positions.
    pub fn step_gauss_seidel_kept(&mut self, dt: f64) {
        self.apply_gravity(dt);
        self.drift(dt);
        self.apply_drag(dt);
        self.impulses_in_place(dt);
    }

    /// The kept order with the Jacobi forces: gravity, drift, drag, then every spring's
    /// eq. 21 force from the same state at the new positions, summed, applied.
    pub fn step_jacobi_kept(&mut self, dt: f64) {
        self.apply_gravity(dt);
        self.drift(dt);
        self.apply_drag(dt);
        self.forces_from_one_state(dt);
    }

    // -- Invariants (pinned particles are external agents and are left out) --

    /// Sum of the finite masses.
    pub fn total_mass(&self) -> f64 {
        self.free().map(|p| p.mass).sum()
    }

    fn free(&self) -> impl Iterator<Item = &Particle<D>> {
        self.particles.iter().filter(|p| !p.is_pinned())
    }

    /// `Σ m·v` over the non-pinned particles.
    pub fn linear_momentum(&self) -> [f64; D] {
        let mut p = [0.0; D];
        for q in self.free() {
            for (pk, vk) in p.iter_mut().zip(q.vel) {
                *pk += q.mass * vk;
            }
        }
        p
    }

    /// `Σ m·x / Σ m` over the non-pinned particles (NaN if there are none).
    pub fn centre_of_mass(&self) -> [f64; D] {
        let mut c = [0.0; D];
        for q in self.free() {
            for (ck, xk) in c.iter_mut().zip(q.pos) {
                *ck += q.mass * xk;
            }
        }
        let m = self.total_mass();
        c.map(|ck| ck / m)
    }

    /// `Σ ½·m·|v|²` over the non-pinned particles.
    pub fn kinetic_energy(&self) -> f64 {
        self.free().map(|p| 0.5 * p.mass * dot(p.vel, p.vel)).sum()
    }

    /// `Σ ½·k·x²` with `k = C_k·m_red/dt²` per spring (springs with both
    /// ends pinned are left out).
    pub fn spring_energy(&self, dt: f64) -> f64 {
        (0..self.springs.len())
            .filter(|&s| self.reduced_mass(s).is_finite())
            .map(|s| {
                let x = self.extension(s);
                0.5 * self.stiffness(s, dt) * x * x
            })
            .sum()
    }

    /// Largest speed `|v|` of any particle.
    pub fn max_speed(&self) -> f64 {
        self.particles
            .iter()
            .map(|p| length(p.vel))
            .fold(0.0, f64::max)
    }
}

impl Network<2> {
    /// Angular momentum about the origin, `Σ m·(x·v_y - y·v_x)` over the
    /// non-pinned particles.
    pub fn angular_momentum_2d(&self) -> f64 {
        self.free()
            .map(|p| p.mass * (p.pos[0] * p.vel[1] - p.pos[1] * p.vel[0]))
            .sum()
    }
}

// ---------------------------------------------------------------------------
// Scene builders (deterministic; gravity zero, set `gravity` to add it)
// ---------------------------------------------------------------------------

/// Rope of `n >= 2` particles of mass 1, at rest, at `(i·segment, 0)` for
/// `i = 0..n`, with springs `(i, i+1)` of rest length `segment` in order
/// `i = 0, 1, ...`. Particle 0 is pinned if `pinned_first`.
pub fn rope_2d(n: usize, segment: f64, pinned_first: bool, ck: f64, cd: f64) -> Network<2> {
    assert!(n >= 2, "rope_2d: at least two particles");
    let mut net = Network::new();
    for i in 0..n {
        let pos = [i as f64 * segment, 0.0];
        if i == 0 && pinned_first {
            net.add_pinned(pos);
        } else {
            net.add_particle(pos, [0.0; 2], 1.0);
        }
    }
    for i in 0..n - 1 {
        net.add_spring(i, i + 1, segment, ck, cd);
    }
    net
}

/// Square grid of `w × h` particles of mass 1, at rest; particle
/// `r·w + c` (row `r < h`, column `c < w`) sits at `(c·spacing, r·spacing)`.
/// Springs, at rest length, in this order: for each particle in row-major
/// order, the spring to its right neighbour `(i, i+1)` then to the one above
/// `(i, i+w)`; then, if `diagonals`, for each cell (row-major by its lower
/// left corner `i`) both diagonals `(i, i+w+1)` and `(i+1, i+w)` of rest
/// length `spacing·√2`. Nothing is pinned.
pub fn mesh_2d(w: usize, h: usize, spacing: f64, diagonals: bool, ck: f64, cd: f64) -> Network<2> {
    assert!(
        w >= 1 && h >= 1 && w * h >= 2,
        "mesh_2d: at least two particles"
    );
    let mut net = Network::new();
    for r in 0..h {
        for c in 0..w {
            net.add_particle([c as f64 * spacing, r as f64 * spacing], [0.0; 2], 1.0);
        }
    }
    for r in 0..h {
        for c in 0..w {
            let i = r * w + c;
            if c + 1 < w {
                net.add_spring(i, i + 1, spacing, ck, cd);
            }
            if r + 1 < h {
                net.add_spring(i, i + w, spacing, ck, cd);
            }
        }
    }
    if diagonals {
        let diag = spacing * std::f64::consts::SQRT_2;
        for r in 0..h.saturating_sub(1) {
            for c in 0..w.saturating_sub(1) {
                let i = r * w + c;
                net.add_spring(i, i + w + 1, diag, ck, cd);
                net.add_spring(i + 1, i + w, diag, ck, cd);
            }
        }
    }
    net
}

/// Two free particles at rest: a (mass `m_a`) at the origin, b (mass `m_b`)
/// at `offset`, joined by one spring `(0, 1)` of rest length `rest`.
pub fn pair_2d(m_a: f64, m_b: f64, offset: [f64; 2], rest: f64, ck: f64, cd: f64) -> Network<2> {
    let mut net = Network::new();
    net.add_particle([0.0, 0.0], [0.0; 2], m_a);
    net.add_particle(offset, [0.0; 2], m_b);
    net.add_spring(0, 1, rest, ck, cd);
    net
}

/// Two particles of equal `mass` at `(∓d0/2, 0)`, joined by a spring `(0, 1)`
/// of rest length `rest` (meant `!= d0`), with velocities `(0, ∓ω·d0/2)`:
/// they revolve counter-clockwise about their centre of mass (the origin)
/// at angular velocity `omega`, with zero linear momentum and angular
/// momentum `mass·omega·d0²/2`.
pub fn spinning_pair_2d(mass: f64, d0: f64, rest: f64, omega: f64, ck: f64, cd: f64) -> Network<2> {
    let (h, u) = (0.5 * d0, 0.5 * omega * d0);
    let mut net = Network::new();
    net.add_particle([-h, 0.0], [0.0, -u], mass);
    net.add_particle([h, 0.0], [0.0, u], mass);
    net.add_spring(0, 1, rest, ck, cd);
    net
}

// ---------------------------------------------------------------------------
// Angular-spring network
// ---------------------------------------------------------------------------

/// A rotating body. `inertia == f64::INFINITY` means pinned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    pub angle: f64,
    pub omega: f64,
    pub inertia: f64,
}

impl Body {
    /// `true` for a pinned body (infinite moment of inertia).
    pub fn is_pinned(&self) -> bool {
        self.inertia.is_infinite()
    }
}

/// A damped angular spring: displacement `θ = (angle_b - angle_a) - rest`,
/// relative angular velocity `ω = omega_b - omega_a`; torque/impulse `+` on
/// b, `-` on a. Angles are never wrapped (a spring can be wound up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngularSpring {
    pub a: usize,
    pub b: usize,
    pub rest_angle: f64,
    pub ck: f64,
    pub cd: f64,
}

/// Bodies joined by angular springs (no external torque).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AngularNetwork {
    pub bodies: Vec<Body>,
    pub springs: Vec<AngularSpring>,
    /// A drag on every non-pinned body's angular velocity, `dω/dt = −drag·ω` (per
    /// second), applied by the kept-order steppers only.
    pub drag: f64,
}

impl AngularNetwork {
    /// Empty network.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a body and returns its index. `inertia` must be `> 0` (or
    /// `f64::INFINITY` for a pinned body, whose angular velocity is set to 0).
    pub fn add_body(&mut self, angle: f64, omega: f64, inertia: f64) -> usize {
        assert!(inertia > 0.0, "add_body: inertia must be > 0 (or INFINITY)");
        let omega = if inertia.is_infinite() { 0.0 } else { omega };
        self.bodies.push(Body {
            angle,
            omega,
            inertia,
        });
        self.bodies.len() - 1
    }

    /// Adds an angular spring and returns its index (Gauss-Seidel order).
    pub fn add_spring(&mut self, a: usize, b: usize, rest_angle: f64, ck: f64, cd: f64) -> usize {
        assert!(a != b, "add_spring: a spring needs two different bodies");
        assert!(a < self.bodies.len() && b < self.bodies.len());
        self.springs.push(AngularSpring {
            a,
            b,
            rest_angle,
            ck,
            cd,
        });
        self.springs.len() - 1
    }

    /// Angular displacement `(angle_b - angle_a) - rest_angle` of spring `s`.
    pub fn displacement(&self, s: usize) -> f64 {
        let sp = &self.springs[s];
        (self.bodies[sp.b].angle - self.bodies[sp.a].angle) - sp.rest_angle
    }

    /// Relative angular velocity `omega_b - omega_a` of spring `s`.
    pub fn relative_velocity(&self, s: usize) -> f64 {
        let sp = &self.springs[s];
        self.bodies[sp.b].omega - self.bodies[sp.a].omega
    }

    /// Reduced moment of inertia of spring `s` (eq. 23).
    pub fn reduced_inertia(&self, s: usize) -> f64 {
        let sp = &self.springs[s];
        reduced_mass(self.bodies[sp.a].inertia, self.bodies[sp.b].inertia) // eq. 23
    }

    fn drift(&mut self, dt: f64) {
        for b in self.bodies.iter_mut().filter(|b| !b.is_pinned()) {
            b.angle += b.omega * dt; // angular eq. 1
        }
    }

    /// Gauss-Seidel: for each spring in order, corrected eq. 28
    /// `j = -(I_red/dt)·C_k·θ - I_red·C_d·ω`, `+j` on b, `-j` on a, in place;
    /// then `angle += omega·dt`.
    pub fn step_gauss_seidel(&mut self, dt: f64) {
        self.impulses_in_place(dt);
        self.drift(dt);
    }

    /// Each spring's corrected eq. 28 impulse, in order, in place.
    fn impulses_in_place(&mut self, dt: f64) {
        for s in 0..self.springs.len() {
            let i_red = self.reduced_inertia(s); // eq. 23
            if i_red.is_infinite() {
                continue; // both ends pinned
            }
            let AngularSpring { a, b, ck, cd, .. } = self.springs[s];
            let th = self.displacement(s);
            let w = self.relative_velocity(s);
            let j = -(i_red / dt) * ck * th - i_red * cd * w; // eq. 28 (corrected)
            if !self.bodies[a].is_pinned() {
                self.bodies[a].omega -= j / self.bodies[a].inertia;
            }
            if !self.bodies[b].is_pinned() {
                self.bodies[b].omega += j / self.bodies[b].inertia;
            }
        }
    }

    /// Jacobi: every spring's torque of eq. 26 (`k_max`, `d_max` of eq. 24,
    /// 25) from the same state, summed per body; then
    /// `omega += τ/I·dt`, `angle += omega·dt`.
    pub fn step_jacobi(&mut self, dt: f64) {
        self.torques_from_one_state(dt);
        self.drift(dt);
    }

    /// Every spring's eq. 26 torque from the same state, summed, applied.
    fn torques_from_one_state(&mut self, dt: f64) {
        let mut torque = vec![0.0; self.bodies.len()];
        for s in 0..self.springs.len() {
            let i_red = self.reduced_inertia(s); // eq. 23
            if i_red.is_infinite() {
                continue;
            }
            let AngularSpring { a, b, ck, cd, .. } = self.springs[s];
            let th = self.displacement(s);
            let w = self.relative_velocity(s);
            let tau = -k_max(i_red, dt) * ck * th - d_max(i_red, dt) * cd * w; // eq. 26
            torque[a] -= tau;
            torque[b] += tau;
        }
        for (body, t) in self.bodies.iter_mut().zip(torque) {
            if !body.is_pinned() {
                body.omega += t / body.inertia * dt; // angular eq. 8
            }
        }
    }

    /// The kept order (see [`Network::step_gauss_seidel_kept`]): drift, drag, then each
    /// spring's impulse in order, in place, at the new angles.
    pub fn step_gauss_seidel_kept(&mut self, dt: f64) {
        self.drift(dt);
        self.apply_drag(dt);
        self.impulses_in_place(dt);
    }

    /// The kept order with the Jacobi torques.
    pub fn step_jacobi_kept(&mut self, dt: f64) {
        self.drift(dt);
        self.apply_drag(dt);
        self.torques_from_one_state(dt);
    }

    /// `ω *= e^{−drag·dt}` for every non-pinned body.
    fn apply_drag(&mut self, dt: f64) {
        let keep = (-self.drag * dt).exp();
        for b in self.bodies.iter_mut().filter(|b| !b.is_pinned()) {
            b.omega *= keep;
        }
    }

    /// Adds every spring's stiffness impulse `j = −(I_red/dt)·C_k·θ` at the current
    /// angles to its ends' angular velocities: the pull a kept-order step starts from.
    pub fn pull(&mut self, dt: f64) {
        for s in 0..self.springs.len() {
            let i_red = self.reduced_inertia(s); // eq. 23
            if i_red.is_infinite() {
                continue;
            }
            let AngularSpring { a, b, ck, .. } = self.springs[s];
            let j = -(i_red / dt) * ck * self.displacement(s); // eq. 28, stiffness
            if !self.bodies[a].is_pinned() {
                self.bodies[a].omega -= j / self.bodies[a].inertia;
            }
            if !self.bodies[b].is_pinned() {
                self.bodies[b].omega += j / self.bodies[b].inertia;
            }
        }
    }

    /// `Σ I·ω` over the non-pinned bodies.
    pub fn angular_momentum(&self) -> f64 {
        self.bodies
            .iter()
            .filter(|b| !b.is_pinned())
            .map(|b| b.inertia * b.omega)
            .sum()
    }

    /// `Σ ½·I·ω²` over the non-pinned bodies.
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies
            .iter()
            .filter(|b| !b.is_pinned())
            .map(|b| 0.5 * b.inertia * b.omega * b.omega)
            .sum()
    }

    /// `Σ ½·k·θ²` with `k = C_k·I_red/dt²` (both-pinned springs left out).
    pub fn spring_energy(&self, dt: f64) -> f64 {
        (0..self.springs.len())
            .filter(|&s| self.reduced_inertia(s).is_finite())
            .map(|s| {
                let th = self.displacement(s);
                0.5 * self.springs[s].ck * k_max(self.reduced_inertia(s), dt) * th * th
            })
            .sum()
    }
}
