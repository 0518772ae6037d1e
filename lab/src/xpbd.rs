//! XPBD with small steps, written for the comparison with stiffspring's scenes, from the
//! two papers (no code taken from elsewhere):
//!
//! - M. Macklin, M. Müller, N. Chentanez, *XPBD: Position-Based Simulation of Compliant
//!   Constrained Dynamics*, MIG 2016: a constraint `C` of compliance `α` (the inverse
//!   stiffness) gets the multiplier update (eq. 18, with the damping of eq. 26)
//!
//!   ```text
//!   Δλ = (−C − α̃·λ − γ·∇C·(x − xⁿ)) / ((1 + γ)·∇C M⁻¹ ∇Cᵀ + α̃)     Δx = M⁻¹ ∇Cᵀ Δλ
//!   α̃ = α/Δt²        γ = α̃·β̃/Δt        β̃ = Δt²·β
//!   ```
//!
//!   where `β` is the damping coefficient of the Rayleigh dissipation along the
//!   constraint (a dashpot `c` on a distance constraint: `β = c`, so `γ = α·c/Δt`);
//! - M. Macklin, K. Storey, M. Lu, P. Terdiman, N. Chentanez, S. Jeschke, M. Müller,
//!   *Small Steps in Physics Simulation*, SCA 2019 (Algorithm 1): a frame is `n`
//!   substeps of `Δt = frame/n`, each one prediction `v += Δt·g; xⁿ = x; x += Δt·v`, **one**
//!   projection of every constraint with `λ = 0` (so the `α̃·λ` term vanishes), and the
//!   velocity update `v = (x − xⁿ)/Δt`.
//!
//! A distance spring of stiffness `k` and damping `c` between particles `a` and `b` is
//! the constraint `C = |x_b − x_a| − L` with `α = 1/k`, `β = c`; `∇C` is the unit axis
//! `n` at `b` and `−n` at `a`, so `∇C M⁻¹ ∇Cᵀ = w_a + w_b` (inverse masses). On a linear
//! spring one projection is exactly a step of implicit Euler (this module's test), which
//! is what the small-steps paper relies on: the error is first order in `Δt`.
//!
//! [`Model`] describes a network in physical units, independently of any solver;
//! [`Model::reference`] runs the f64 reference model (`crate::reference::network`) at a
//! fine step, [`Xpbd`] runs XPBD in `f32` or `f64`.

use crate::pareto::Real;
use crate::reference::network::Network;
use crate::reference::reduced_mass;

/// A particle: position (m), velocity (m/s), mass (kg; `f64::INFINITY` for pinned).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    /// Position at the start.
    pub position: [f64; 2],
    /// Velocity at the start.
    pub velocity: [f64; 2],
    /// Mass; infinite for a pinned particle.
    pub mass: f64,
}

/// A damped distance spring: ends, rest length (m), stiffness `k` (N/m), damping `c`
/// (N·s/m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link {
    /// One end.
    pub a: usize,
    /// The other end.
    pub b: usize,
    /// Rest length.
    pub rest: f64,
    /// Stiffness.
    pub k: f64,
    /// Damping coefficient.
    pub c: f64,
}

/// A 2D network in physical units, stepped frame by frame.
#[derive(Clone, Debug)]
pub struct Model {
    /// The scene's name.
    pub name: &'static str,
    /// Frames per second.
    pub frame_rate: f64,
    /// Frames in one run.
    pub frames: usize,
    /// Gravity, m/s².
    pub gravity: [f64; 2],
    /// The particles.
    pub bodies: Vec<Body>,
    /// The springs, springs with a pinned end first (the order a stiffspring scene steps
    /// them in), each group in the order added.
    pub links: Vec<Link>,
    /// What the error is relative to, in metres.
    pub size: f64,
}

/// Particles of [`Model::rope`].
pub const ROPE_PARTICLES: usize = 32;
/// The jelly's columns and rows ([`Model::jelly`]).
pub const JELLY_SIDE: usize = 12;
/// Particles of [`Model::jelly`].
pub const JELLY_PARTICLES: usize = JELLY_SIDE * JELLY_SIDE;
/// Springs of [`Model::jelly`]: sides and both diagonals of every cell, less the bottom
/// row's sides (both ends pinned).
pub const JELLY_LINKS: usize =
    2 * JELLY_SIDE * (JELLY_SIDE - 1) + 2 * (JELLY_SIDE - 1) * (JELLY_SIDE - 1) - (JELLY_SIDE - 1);

/// Mass of every particle, kg.
pub const MASS: f64 = 0.01;

impl Model {
    /// The spring of stiffness `k` whose two-free-particle oscillator (reduced mass
    /// `MASS/2`) has damping ratio `zeta`.
    fn link(a: usize, b: usize, rest: f64, k: f64, zeta: f64) -> Link {
        let c = 2.0 * zeta * (k * MASS / 2.0).sqrt();
        Link { a, b, rest, k, c }
    }

    /// Orders `links` with the springs that have a pinned end first.
    fn ordered(bodies: &[Body], links: Vec<Link>) -> Vec<Link> {
        let pinned = |i: usize| bodies[i].mass.is_infinite();
        let (mut first, rest): (Vec<Link>, Vec<Link>) = links
            .into_iter()
            .filter(|l| !(pinned(l.a) && pinned(l.b)))
            .partition(|l| pinned(l.a) || pinned(l.b));
        first.extend(rest);
        first
    }

    /// A rope: [`ROPE_PARTICLES`] particles of 10 g, 5 cm apart, hanging straight down
    /// from a pinned end (at its rest lengths, so it stretches under gravity as it
    /// starts) and swung: every particle starts moving sideways as a rigid pendulum at
    /// 2 rad/s (a swing of about 38°); 60 frames per second for 2 s. `k = 5000 N/m` (the
    /// top segment stretches 1.2 % under the rope's weight; a segment alone rings at
    /// 159 Hz), ζ = 0.1 per segment.
    pub fn rope() -> Model {
        Model::rope_with("rope", 5000.0)
    }

    /// The same rope twenty times stiffer, `k = 10⁵ N/m` (a stretch of 0.06 %; a segment
    /// rings at 712 Hz): nearly inextensible, where XPBD is at home.
    pub fn stiff_rope() -> Model {
        Model::rope_with("stiff_rope", 1e5)
    }

    fn rope_with(name: &'static str, k: f64) -> Model {
        let segment = 0.05;
        let spin = 2.0;
        let bodies: Vec<Body> = (0..ROPE_PARTICLES)
            .map(|i| {
                let r = i as f64 * segment;
                Body {
                    position: [0.0, -r],
                    velocity: [spin * r, 0.0],
                    mass: if i == 0 { f64::INFINITY } else { MASS },
                }
            })
            .collect();
        let links = (0..ROPE_PARTICLES - 1)
            .map(|i| Model::link(i, i + 1, segment, k, 0.1))
            .collect();
        Model {
            name,
            frame_rate: 60.0,
            frames: 120,
            gravity: [0.0, -9.81],
            links: Model::ordered(&bodies, links),
            bodies,
            size: segment * (ROPE_PARTICLES - 1) as f64,
        }
    }

    /// A soft jelly: [`JELLY_SIDE`]² particles of 10 g on a 5 cm grid, springs on the
    /// sides and both diagonals of every cell, the bottom row pinned to a plate, the top
    /// row pushed sideways at 0.5 m/s, no gravity, 60 frames per second for 2 s.
    /// `k = 4 N/m` (a spring alone rings at 4.5 Hz), ζ = 0.1 per spring.
    pub fn jelly() -> Model {
        let (side, cell, k, zeta) = (JELLY_SIDE, 0.05, 4.0, 0.1);
        let mut bodies = Vec::new();
        for r in 0..side {
            for c in 0..side {
                bodies.push(Body {
                    position: [c as f64 * cell, r as f64 * cell],
                    velocity: if r == side - 1 { [0.5, 0.0] } else { [0.0; 2] },
                    mass: if r == 0 { f64::INFINITY } else { MASS },
                });
            }
        }
        let mut links = Vec::new();
        for r in 0..side {
            for c in 0..side {
                let i = r * side + c;
                if c + 1 < side {
                    links.push(Model::link(i, i + 1, cell, k, zeta));
                }
                if r + 1 < side {
                    links.push(Model::link(i, i + side, cell, k, zeta));
                }
            }
        }
        let diagonal = cell * std::f64::consts::SQRT_2;
        for r in 0..side - 1 {
            for c in 0..side - 1 {
                let i = r * side + c;
                links.push(Model::link(i, i + side + 1, diagonal, k, zeta));
                links.push(Model::link(i + 1, i + side, diagonal, k, zeta));
            }
        }
        Model {
            name: "jelly",
            frame_rate: 60.0,
            frames: 120,
            gravity: [0.0, 0.0],
            links: Model::ordered(&bodies, links),
            bodies,
            size: cell * (side - 1) as f64,
        }
    }

    /// The reduced mass of a link (the free particle's mass when the other is pinned).
    pub fn reduced_mass(&self, l: &Link) -> f64 {
        reduced_mass(self.bodies[l.a].mass, self.bodies[l.b].mass)
    }

    /// The positions after every frame of the f64 reference model
    /// (`crate::reference::network`, Gauss-Seidel in the links' order) stepped
    /// `substeps` times per frame, each spring given `C_k = k·h²/m_red`,
    /// `C_d = c·h/m_red` at `h = 1/(frame_rate·substeps)`: the impulse of the force
    /// `k·x + c·v` over the step, which converges to the continuous network as `h → 0`
    /// (first order).
    pub fn reference(&self, substeps: usize) -> Vec<Vec<[f64; 2]>> {
        let h = 1.0 / (self.frame_rate * substeps as f64);
        let mut net = Network::<2>::new();
        for b in &self.bodies {
            if b.mass.is_infinite() {
                net.add_pinned(b.position);
            } else {
                net.add_particle(b.position, b.velocity, b.mass);
            }
        }
        for l in &self.links {
            let m = self.reduced_mass(l);
            net.add_spring(l.a, l.b, l.rest, l.k * h * h / m, l.c * h / m);
        }
        net.gravity = self.gravity;
        (0..self.frames)
            .map(|_| {
                for _ in 0..substeps {
                    net.step_gauss_seidel(h);
                }
                net.particles.iter().map(|p| p.pos).collect()
            })
            .collect()
    }

    /// The worst distance of any particle from `reference` over the frames, relative to
    /// the model's size; infinite for a NaN.
    pub fn error(&self, frames: &[Vec<[f64; 2]>], reference: &[Vec<[f64; 2]>]) -> f64 {
        let mut worst = 0.0f64;
        for (frame, expected) in frames.iter().zip(reference) {
            for (p, q) in frame.iter().zip(expected) {
                let d = (p[0] - q[0]).hypot(p[1] - q[1]);
                worst = if d.is_nan() {
                    f64::INFINITY
                } else {
                    worst.max(d)
                };
            }
        }
        worst / self.size
    }
}

/// One constraint as the solver reads it, with everything per constraint precomputed for
/// the substep `Δt`.
#[derive(Clone, Copy, Debug)]
struct Constraint<F> {
    a: u32,
    b: u32,
    rest: F,
    /// `w_a`, `w_b`: inverse masses (0 for a pinned end).
    wa: F,
    wb: F,
    /// `γ = α·c/Δt`.
    gamma: F,
    /// `1/((1 + γ)·(w_a + w_b) + α̃)`.
    scale: F,
}

/// XPBD with small steps on a [`Model`], in `F` (`f32` or `f64`).
#[derive(Clone, Debug)]
pub struct Xpbd<F> {
    start: (Vec<[F; 2]>, Vec<[F; 2]>),
    x: Vec<[F; 2]>,
    previous: Vec<[F; 2]>,
    v: Vec<[F; 2]>,
    /// The free particles.
    free: Vec<u32>,
    constraints: Vec<Constraint<F>>,
    /// `Δt·g`.
    gravity: [F; 2],
    h: F,
    inverse_h: F,
    substeps: usize,
}

impl<F: Real> Xpbd<F> {
    /// `model` at its start, stepped in `substeps` substeps per frame.
    pub fn new(model: &Model, substeps: usize) -> Self {
        let h = 1.0 / (model.frame_rate * substeps as f64);
        let inverse = |i: usize| {
            let m = model.bodies[i].mass;
            if m.is_infinite() { 0.0 } else { 1.0 / m }
        };
        let constraints = model
            .links
            .iter()
            .map(|l| {
                let (wa, wb) = (inverse(l.a), inverse(l.b));
                let alpha = 1.0 / l.k;
                let alpha_tilde = alpha / (h * h);
                let gamma = alpha * l.c / h;
                Constraint {
                    a: l.a as u32,
                    b: l.b as u32,
                    rest: F::of(l.rest),
                    wa: F::of(wa),
                    wb: F::of(wb),
                    gamma: F::of(gamma),
                    scale: F::of(1.0 / ((1.0 + gamma) * (wa + wb) + alpha_tilde)),
                }
            })
            .collect();
        let x: Vec<[F; 2]> = model.bodies.iter().map(|b| b.position.map(F::of)).collect();
        let v: Vec<[F; 2]> = model.bodies.iter().map(|b| b.velocity.map(F::of)).collect();
        Xpbd {
            start: (x.clone(), v.clone()),
            previous: x.clone(),
            x,
            v,
            free: (0..model.bodies.len() as u32)
                .filter(|&i| model.bodies[i as usize].mass.is_finite())
                .collect(),
            constraints,
            gravity: model.gravity.map(|g| F::of(g * h)),
            h: F::of(h),
            inverse_h: F::of(1.0 / h),
            substeps,
        }
    }

    /// Back to the start.
    pub fn reset(&mut self) {
        self.x.clone_from(&self.start.0);
        self.v.clone_from(&self.start.1);
    }

    /// One substep: predict, project every constraint once, update the velocities.
    #[inline(always)]
    fn substep(&mut self) {
        let (g, h) = (self.gravity, self.h);
        for &i in &self.free {
            let i = i as usize;
            let v = [self.v[i][0] + g[0], self.v[i][1] + g[1]];
            self.v[i] = v;
            self.previous[i] = self.x[i];
            self.x[i] = [self.x[i][0] + v[0] * h, self.x[i][1] + v[1] * h];
        }
        for k in 0..self.constraints.len() {
            let c = self.constraints[k];
            let (a, b) = (c.a as usize, c.b as usize);
            let (xa, xb) = (self.x[a], self.x[b]);
            let d = [xb[0] - xa[0], xb[1] - xa[1]];
            let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
            let inverse = length.recip();
            let n = [d[0] * inverse, d[1] * inverse];
            // ∇C·(x − xⁿ): the motion of b relative to a along the axis in this substep.
            let (pa, pb) = (self.previous[a], self.previous[b]);
            let moved =
                (xb[0] - pb[0] - (xa[0] - pa[0])) * n[0] + (xb[1] - pb[1] - (xa[1] - pa[1])) * n[1];
            let error = length - c.rest;
            // Δλ = −(C + γ·∇C·(x − xⁿ)) / ((1 + γ)(w_a + w_b) + α̃), with λ = 0.
            let dl = F::of(0.0) - (error + c.gamma * moved) * c.scale;
            let (da, db) = (dl * c.wa, dl * c.wb);
            self.x[a] = [xa[0] - n[0] * da, xa[1] - n[1] * da];
            let xb = self.x[b];
            self.x[b] = [xb[0] + n[0] * db, xb[1] + n[1] * db];
        }
        let inverse_h = self.inverse_h;
        for &i in &self.free {
            let i = i as usize;
            self.v[i] = [
                (self.x[i][0] - self.previous[i][0]) * inverse_h,
                (self.x[i][1] - self.previous[i][1]) * inverse_h,
            ];
        }
    }

    /// One frame: the substeps.
    #[inline(always)]
    pub fn frame(&mut self) {
        for _ in 0..self.substeps {
            self.substep();
        }
    }

    /// Particle `i`'s position, in `f64`.
    pub fn position(&self, i: usize) -> [f64; 2] {
        self.x[i].map(F::get)
    }

    /// The number of particles.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True for a model without particles.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One particle on a spring to a pinned anchor, along x.
    fn pendulum(k: f64, c: f64) -> Model {
        Model {
            name: "one spring",
            frame_rate: 100.0,
            frames: 50,
            gravity: [0.0, 0.0],
            bodies: vec![
                Body {
                    position: [0.0, 0.0],
                    velocity: [0.0; 2],
                    mass: f64::INFINITY,
                },
                Body {
                    position: [1.3, 0.0],
                    velocity: [0.7, 0.0],
                    mass: 0.5,
                },
            ],
            links: vec![Link {
                a: 0,
                b: 1,
                rest: 1.0,
                k,
                c,
            }],
            size: 1.0,
        }
    }

    /// One projection of a spring along a fixed axis is a step of implicit Euler:
    /// `(m + c·h + k·h²)·v' = m·v − h·k·(x − L)`, `x' = x + h·v'`.
    #[test]
    fn one_substep_on_a_spring_is_implicit_euler() {
        let (k, c, m) = (40.0, 0.9, 0.5);
        let model = pendulum(k, c);
        for substeps in [1, 3] {
            let h = 1.0 / (model.frame_rate * substeps as f64);
            let mut xpbd = Xpbd::<f64>::new(&model, substeps);
            let (mut x, mut v) = (1.3f64, 0.7f64);
            for _ in 0..model.frames {
                xpbd.frame();
                for _ in 0..substeps {
                    v = (m * v - h * k * (x - 1.0)) / (m + c * h + k * h * h);
                    x += h * v;
                }
                let p = xpbd.position(1);
                assert!((p[0] - x).abs() < 1e-12 && p[1] == 0.0, "{p:?} against {x}");
            }
        }
    }

    /// Small steps converge to the continuous spring at first order: the analytic
    /// solution of the damped oscillator.
    #[test]
    fn small_steps_converge_at_first_order() {
        let (k, c, m) = (40.0, 0.9, 0.5);
        let model = pendulum(k, c);
        let (omega, zeta) = ((k / m).sqrt(), c / (2.0 * (k * m).sqrt()));
        let error = |substeps: usize| {
            let mut xpbd = Xpbd::<f64>::new(&model, substeps);
            let mut worst = 0.0f64;
            for n in 1..=model.frames {
                xpbd.frame();
                let t = n as f64 / model.frame_rate;
                let (x, _) = crate::reference::analytic(0.3, 0.7, omega, zeta, t);
                worst = worst.max((xpbd.position(1)[0] - 1.0 - x).abs());
            }
            worst
        };
        let (e4, e8, e16) = (error(4), error(8), error(16));
        for (coarse, fine) in [(e4, e8), (e8, e16)] {
            let order = (coarse / fine).log2();
            assert!(
                (0.8..1.2).contains(&order),
                "{coarse} → {fine}: order {order}"
            );
        }
    }

    /// The reference at a fine step and XPBD with many substeps agree on a rope (two
    /// independent discretisations of the same network converge to one solution).
    #[test]
    fn xpbd_and_the_reference_converge_together() {
        let mut model = Model::rope();
        model.frames = 30;
        let reference = model.reference(256);
        let error = |substeps: usize| {
            let mut xpbd = Xpbd::<f64>::new(&model, substeps);
            let frames: Vec<Vec<[f64; 2]>> = (0..model.frames)
                .map(|_| {
                    xpbd.frame();
                    (0..xpbd.len()).map(|i| xpbd.position(i)).collect()
                })
                .collect();
            model.error(&frames, &reference)
        };
        // First order: four times the substeps, about a quarter of the error.
        let (coarse, fine) = (error(16), error(64));
        assert!(fine < 0.4 * coarse, "{coarse} → {fine}");
    }
}
