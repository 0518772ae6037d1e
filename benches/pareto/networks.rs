//! The network scenes: a 2D rope of 64 particles and a 16×16 jelly mesh.
//!
//! There is no analytic solution, so the error of every implementation is the worst
//! distance of any particle from the independent f64 reference model
//! (`lab::reference::network`) run with the same update order, over the run, relative
//! to the size of the network (the rope's length, the jelly's width).
//!
//! | implementation | what steps |
//! |---|---|
//! | `stiffspring/<kernel>` | `Scene::step`, Gauss-Seidel, every backend and length kernel |
//! | `stiffspring-jacobi/exact` | `Scene::step` with [`Stepper::Jacobi`] (against the Jacobi reference) |
//! | `baseline/minimal-gs` | the same Gauss-Seidel math written out by hand over plain arrays: the floor for the library's overhead |
//! | `baseline/semi-implicit-euler` | Hooke forces from one state, summed, symplectic Euler: the Jacobi map by hand |
//! | `baseline/explicit-euler` | the same forces with explicit Euler (positions move with the old velocity) |
//!
//! A Box2D-style soft step in a network whose springs are given as fractions `C_k`, `C_d`
//! is the minimal Gauss-Seidel loop with the coefficients renamed (Box2D v3's `b2MakeSoft`
//! gives `C_k = ω²h²/D` and `C_d = (2ζωh + ω²h²)/D` with `D = 1 + 2ζωh + ω²h²`), so it
//! has no row of its own here.
//!
//! The time is reported per spring step: a scene step divided by the number of springs.

use lab::measure::Candidate;
use lab::pareto::Real;
use lab::reference::network::Network;
use std::hint::black_box;
use stiffspring::length::{Approximate, ApproximateNewton, Exact, LengthKernel, Linearised};
use stiffspring::scene::{ParticleId, Scene, SceneConfig, Stepper};
use stiffspring::{I16F16, I32F32, Scalar, Tuning};

/// The rope: particles, the first one pinned.
pub const ROPE_PARTICLES: usize = 64;
/// The rope's springs.
pub const ROPE_SPRINGS: usize = ROPE_PARTICLES - 1;
/// The jelly's columns and rows.
pub const JELLY_W: usize = 16;
/// The jelly's rows.
pub const JELLY_H: usize = 16;
/// The jelly's particles.
pub const JELLY_PARTICLES: usize = JELLY_W * JELLY_H;
/// The jelly's springs: sides and both diagonals of every cell, less the bottom row's
/// sides, which join two pinned particles and could move nothing.
pub const JELLY_SPRINGS: usize =
    JELLY_W * (JELLY_H - 1) + JELLY_H * (JELLY_W - 1) + 2 * (JELLY_W - 1) * (JELLY_H - 1)
        - (JELLY_W - 1);

/// A network scene, described independently of any implementation.
#[derive(Clone, Debug)]
pub struct Net {
    /// The `scene` column.
    pub name: &'static str,
    /// Steps per second.
    pub rate: f64,
    /// Steps in one run.
    pub steps: usize,
    /// `C_k = C_d` of every spring.
    pub coefficient: f64,
    /// Gravity, m/s².
    pub gravity: [f64; 2],
    /// Position, velocity, pinned.
    pub particles: Vec<([f64; 2], [f64; 2], bool)>,
    /// `(a, b, rest)`, in the order the scene steps them: springs with a pinned end
    /// first, then the rest, each in the order added (what `Scene` does).
    pub springs: Vec<(usize, usize, f64)>,
    /// What the error is relative to, in metres.
    pub size: f64,
}

impl Net {
    /// A rope of [`ROPE_PARTICLES`] particles 5 cm apart, pinned at one end, released
    /// level under gravity at 240 Hz for 2 s, `C = 0.3` (the rope's limit is 1/3).
    pub fn rope() -> Net {
        let segment = 0.05;
        Net {
            name: "rope_64",
            rate: 240.0,
            steps: 480,
            coefficient: 0.3,
            gravity: [0.0, -9.81],
            particles: (0..ROPE_PARTICLES)
                .map(|i| ([i as f64 * segment, 0.0], [0.0; 2], i == 0))
                .collect(),
            springs: (0..ROPE_SPRINGS).map(|i| (i, i + 1, segment)).collect(),
            size: segment * ROPE_SPRINGS as f64,
        }
    }

    /// A 16×16 jelly, 5 cm cells with both diagonals, its bottom row pinned to a plate,
    /// its top row pushed sideways at 0.8 m/s; 120 Hz for 2 s, `C = 0.1` (up to eight
    /// springs per particle: the limit is 1/9).
    pub fn jelly() -> Net {
        let cell = 0.05;
        let (w, h) = (JELLY_W, JELLY_H);
        let mut particles = Vec::new();
        for r in 0..h {
            for c in 0..w {
                let v = if r == h - 1 { [0.8, 0.0] } else { [0.0; 2] };
                particles.push(([c as f64 * cell, r as f64 * cell], v, r == 0));
            }
        }
        let mut all = Vec::new();
        for r in 0..h {
            for c in 0..w {
                let i = r * w + c;
                if c + 1 < w {
                    all.push((i, i + 1, cell));
                }
                if r + 1 < h {
                    all.push((i, i + w, cell));
                }
            }
        }
        let diagonal = cell * std::f64::consts::SQRT_2;
        for r in 0..h - 1 {
            for c in 0..w - 1 {
                let i = r * w + c;
                all.push((i, i + w + 1, diagonal));
                all.push((i + 1, i + w, diagonal));
            }
        }
        let pinned = |i: usize| particles[i].2;
        let mut springs: Vec<_> = all
            .iter()
            .copied()
            .filter(|&(a, b, _)| pinned(a) != pinned(b))
            .collect();
        springs.extend(
            all.iter()
                .copied()
                .filter(|&(a, b, _)| !pinned(a) && !pinned(b)),
        );
        Net {
            name: "jelly_16x16",
            rate: 120.0,
            steps: 240,
            coefficient: 0.1,
            gravity: [0.0, 0.0],
            particles,
            springs,
            size: cell * (w - 1) as f64,
        }
    }

    /// The time step.
    pub fn dt(&self) -> f64 {
        1.0 / self.rate
    }

    /// The reference model's positions after each step, with the given stepper.
    pub fn reference(&self, stepper: Stepper) -> Vec<Vec<[f64; 2]>> {
        let mut net = Network::<2>::new();
        for &(p, v, pinned) in &self.particles {
            if pinned {
                net.add_pinned(p);
            } else {
                net.add_particle(p, v, 1.0);
            }
        }
        for &(a, b, rest) in &self.springs {
            net.add_spring(a, b, rest, self.coefficient, self.coefficient);
        }
        net.gravity = self.gravity;
        // The scene's start: its springs' pull in the first step (the networks with a
        // velocity have no gravity, so `set_velocity`'s step is the velocity's).
        net.pull(self.dt());
        (0..self.steps)
            .map(|_| {
                match stepper {
                    Stepper::GaussSeidel => net.step_gauss_seidel_kept(self.dt()),
                    Stepper::Jacobi => net.step_jacobi_kept(self.dt()),
                }
                net.particles.iter().map(|p| p.pos).collect()
            })
            .collect()
    }
}

/// One implementation of a network, set up on one scene.
pub trait NetRunner {
    /// Back to the scene's start.
    fn reset(&mut self);
    /// One step.
    fn step(&mut self);
    /// The position of particle `i` (in the scene description's numbering), in `f64`.
    fn position(&self, i: usize) -> [f64; 2];
    /// A value that depends on every step, to keep the optimiser honest.
    fn checksum(&self) -> f64 {
        self.position(self.particles() - 1)[0]
    }
    /// The number of particles.
    fn particles(&self) -> usize;
}

/// `runs` runs of `steps` steps from the start.
#[inline(never)]
pub fn run_batch<R: NetRunner>(r: &mut R, runs: usize, steps: usize) {
    for _ in 0..runs {
        r.reset();
        black_box(&mut *r);
        for _ in 0..steps {
            r.step();
        }
        black_box(r.checksum());
    }
}

/// Worst distance from the reference over one run, relative to the network's size;
/// infinite if a position became NaN.
pub fn max_error<R: NetRunner>(r: &mut R, net: &Net, reference: &[Vec<[f64; 2]>]) -> f64 {
    r.reset();
    let mut worst = 0.0f64;
    for frame in reference {
        r.step();
        for (i, q) in frame.iter().enumerate() {
            let p = r.position(i);
            let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
            worst = if d.is_nan() {
                f64::INFINITY
            } else {
                worst.max(d)
            };
        }
    }
    worst / net.size
}

/// One row: who, in what backend, how wrong, and how to time it.
pub struct Entry {
    /// The `implementation` column.
    pub implementation: String,
    /// The `backend` column.
    pub backend: &'static str,
    /// `max_rel_error`.
    pub error: f64,
    /// The timing closure, per spring step.
    pub candidate: Candidate<'static>,
}

fn entry<R: NetRunner + 'static>(
    implementation: String,
    backend: &'static str,
    net: &Net,
    reference: &[Vec<[f64; 2]>],
    mut runner: R,
) -> Entry {
    let error = max_error(&mut runner, net, reference);
    let steps = net.steps;
    Entry {
        implementation,
        backend,
        error,
        candidate: Candidate::new(steps, move |runs| run_batch(&mut runner, runs, steps))
            .per(net.springs.len()),
    }
}

/// Every implementation on `net`, whose scene has `P` particles and `K` springs.
pub fn entries<const P: usize, const K: usize>(net: &Net) -> Vec<Entry> {
    assert_eq!((net.particles.len(), net.springs.len()), (P, K));
    let gs = net.reference(Stepper::GaussSeidel);
    let jacobi = net.reference(Stepper::Jacobi);
    let mut out = Vec::new();
    fn stiff<S: Scalar, L: LengthKernel<S>, const P: usize, const K: usize>(
        out: &mut Vec<Entry>,
        net: &Net,
        stepper: Stepper,
        reference: &[Vec<[f64; 2]>],
    ) {
        let prefix = match stepper {
            Stepper::GaussSeidel => "stiffspring",
            Stepper::Jacobi => "stiffspring-jacobi",
        };
        match StiffNet::<S, L, P, K>::new(net, stepper) {
            Some(r) => out.push(entry(
                format!("{prefix}/{}", L::NAME),
                S::NAME,
                net,
                reference,
                r,
            )),
            None => eprintln!("{prefix}/{} {} rejected {}", L::NAME, S::NAME, net.name),
        }
    }
    let g = Stepper::GaussSeidel;
    stiff::<f64, Exact, P, K>(&mut out, net, g, &gs);
    stiff::<f64, Linearised, P, K>(&mut out, net, g, &gs);
    stiff::<f32, Exact, P, K>(&mut out, net, g, &gs);
    stiff::<f32, Linearised, P, K>(&mut out, net, g, &gs);
    stiff::<f32, Approximate, P, K>(&mut out, net, g, &gs);
    stiff::<f32, ApproximateNewton, P, K>(&mut out, net, g, &gs);
    stiff::<I32F32, Exact, P, K>(&mut out, net, g, &gs);
    stiff::<I32F32, Linearised, P, K>(&mut out, net, g, &gs);
    stiff::<I16F16, Exact, P, K>(&mut out, net, g, &gs);
    stiff::<I16F16, Linearised, P, K>(&mut out, net, g, &gs);
    let j = Stepper::Jacobi;
    stiff::<f64, Exact, P, K>(&mut out, net, j, &jacobi);
    stiff::<f32, Exact, P, K>(&mut out, net, j, &jacobi);
    out.push(entry(
        "baseline/minimal-gs".into(),
        "f64",
        net,
        &gs,
        Minimal::<f64, GAUSS_SEIDEL>::new(net),
    ));
    out.push(entry(
        "baseline/minimal-gs".into(),
        "f32",
        net,
        &gs,
        Minimal::<f32, GAUSS_SEIDEL>::new(net),
    ));
    out.push(entry(
        "baseline/semi-implicit-euler".into(),
        "f32",
        net,
        &jacobi,
        Minimal::<f32, SEMI_IMPLICIT>::new(net),
    ));
    out.push(entry(
        "baseline/explicit-euler".into(),
        "f32",
        net,
        &jacobi,
        Minimal::<f32, EXPLICIT>::new(net),
    ));
    out
}

// ---------------------------------------------------------------------------------------
// stiffspring
// ---------------------------------------------------------------------------------------

/// A [`Scene`] built from a [`Net`]: particles in the description's order, springs in
/// its (= the scene's execution) order, default configuration (sleep on) otherwise.
pub struct StiffNet<S: Scalar, L: LengthKernel<S>, const P: usize, const K: usize> {
    start: Scene<S, 2, P, K, L>,
    scene: Scene<S, 2, P, K, L>,
    ids: Vec<ParticleId>,
}

impl<S: Scalar, L: LengthKernel<S>, const P: usize, const K: usize> StiffNet<S, L, P, K> {
    /// `None` when the scene rejects the network.
    pub fn new(net: &Net, stepper: Stepper) -> Option<Self> {
        let dt = net.dt();
        let gravity = net.gravity.map(S::from_f64);
        let config = SceneConfig::new(dt)
            .ok()?
            .gravity(gravity)
            .ok()?
            .stepper(stepper);
        let mut scene = Scene::<S, 2, P, K, L>::new(config);
        let mut ids = Vec::new();
        for &(p, v, pinned) in &net.particles {
            let p = p.map(S::from_f64);
            let id = if pinned {
                scene.add_pinned(p).ok()?
            } else {
                let id = scene.add_particle(p, S::from_f64(0.01)).ok()?;
                if v != [0.0; 2] {
                    scene.set_velocity(id, v.map(S::from_f64)).ok()?;
                }
                id
            };
            ids.push(id);
        }
        let tuning = Tuning::from_coefficients(net.coefficient, net.coefficient, dt).ok()?;
        for &(a, b, rest) in &net.springs {
            scene
                .add_spring(ids[a], ids[b], S::from_f64(rest), &tuning)
                .ok()?;
        }
        Some(StiffNet {
            start: scene.clone(),
            scene,
            ids,
        })
    }
}

impl<S: Scalar, L: LengthKernel<S>, const P: usize, const K: usize> NetRunner
    for StiffNet<S, L, P, K>
{
    #[inline(always)]
    fn reset(&mut self) {
        self.scene.clone_from(&self.start);
    }
    #[inline(always)]
    fn step(&mut self) {
        let _ = self.scene.step();
    }
    fn position(&self, i: usize) -> [f64; 2] {
        self.scene
            .precise_position(self.ids[i])
            .unwrap_or([f64::NAN; 2])
    }
    fn particles(&self) -> usize {
        self.ids.len()
    }
}

// ---------------------------------------------------------------------------------------
// Hand-written baselines
// ---------------------------------------------------------------------------------------

/// The Gauss-Seidel impulse loop of the article (the library's math, one spring at a
/// time, in place).
pub const GAUSS_SEIDEL: u8 = 0;
/// Hooke forces from one state, summed per particle, symplectic Euler.
pub const SEMI_IMPLICIT: u8 = 1;
/// Hooke forces from one state, explicit Euler.
pub const EXPLICIT: u8 = 2;

/// One spring of a [`Minimal`] network: ends, rest length, `C_k`, `1 − C_d`, and the
/// weights `w_a`, `w_b` (0 for a pinned end).
#[derive(Clone, Copy, Debug)]
struct MinimalSpring<F> {
    a: u32,
    b: u32,
    rest: F,
    stiffness: F,
    retention: F,
    wa: F,
    wb: F,
}

/// A network over plain arrays, stepped by `METHOD`, all in step units (`u = v·dt`):
/// the least a hand-written loop of the same math does. No sleeping, no bound, no
/// schedule: gravity, the springs, the positions.
pub struct Minimal<F, const METHOD: u8> {
    start: (Vec<[F; 2]>, Vec<[F; 2]>),
    positions: Vec<[F; 2]>,
    velocities: Vec<[F; 2]>,
    sums: Vec<[F; 2]>,
    springs: Vec<MinimalSpring<F>>,
    free: Vec<u32>,
    gravity: [F; 2],
}

impl<F: Real, const METHOD: u8> Minimal<F, METHOD> {
    /// The network at its start; masses 1 (weights ½, or 1 against a pinned end).
    pub fn new(net: &Net) -> Self {
        let dt = net.dt();
        let positions: Vec<[F; 2]> = net
            .particles
            .iter()
            .map(|(p, _, _)| [F::of(p[0]), F::of(p[1])])
            .collect();
        let velocities: Vec<[F; 2]> = net
            .particles
            .iter()
            .map(|(_, v, pinned)| {
                if *pinned {
                    [F::of(0.0); 2]
                } else {
                    [F::of(v[0] * dt), F::of(v[1] * dt)]
                }
            })
            .collect();
        let inverse = |i: usize| if net.particles[i].2 { 0.0 } else { 1.0 };
        let c = net.coefficient;
        let springs = net
            .springs
            .iter()
            .map(|&(a, b, rest)| {
                let (ia, ib) = (inverse(a), inverse(b));
                MinimalSpring {
                    a: a as u32,
                    b: b as u32,
                    rest: F::of(rest),
                    stiffness: F::of(c),
                    retention: F::of(1.0 - c),
                    wa: F::of(ia / (ia + ib)),
                    wb: F::of(ib / (ia + ib)),
                }
            })
            .collect();
        Minimal {
            start: (positions.clone(), velocities.clone()),
            sums: vec![[F::of(0.0); 2]; positions.len()],
            positions,
            velocities,
            springs,
            free: (0..net.particles.len() as u32)
                .filter(|&i| !net.particles[i as usize].2)
                .collect(),
            gravity: [
                F::of(net.gravity[0] * dt * dt),
                F::of(net.gravity[1] * dt * dt),
            ],
        }
    }

    /// Extension and unit axis of spring `s`.
    #[inline(always)]
    fn measure(&self, s: &MinimalSpring<F>) -> (F, [F; 2], [F; 2]) {
        let (pa, pb) = (self.positions[s.a as usize], self.positions[s.b as usize]);
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let inverse = length.recip();
        let n = [d[0] * inverse, d[1] * inverse];
        let (ua, ub) = (self.velocities[s.a as usize], self.velocities[s.b as usize]);
        let du = [ub[0] - ua[0], ub[1] - ua[1]];
        (length - s.rest, n, du)
    }
}

impl<F: Real, const METHOD: u8> NetRunner for Minimal<F, METHOD> {
    fn reset(&mut self) {
        self.positions.clone_from(&self.start.0);
        self.velocities.clone_from(&self.start.1);
    }

    #[inline(always)]
    fn step(&mut self) {
        let g = self.gravity;
        for &p in &self.free {
            let u = &mut self.velocities[p as usize];
            *u = [u[0] + g[0], u[1] + g[1]];
        }
        if METHOD == GAUSS_SEIDEL {
            for i in 0..self.springs.len() {
                let s = self.springs[i];
                let (x, n, du) = self.measure(&s);
                let relative = du[0] * n[0] + du[1] * n[1];
                let delta = relative * s.retention - x * s.stiffness - relative;
                let (da, db) = (delta * s.wa, delta * s.wb);
                let ua = &mut self.velocities[s.a as usize];
                *ua = [ua[0] - n[0] * da, ua[1] - n[1] * da];
                let ub = &mut self.velocities[s.b as usize];
                *ub = [ub[0] + n[0] * db, ub[1] + n[1] * db];
            }
        } else {
            for i in 0..self.springs.len() {
                let s = self.springs[i];
                let (x, n, du) = self.measure(&s);
                let relative = du[0] * n[0] + du[1] * n[1];
                let delta = relative * s.retention - x * s.stiffness - relative;
                let (da, db) = (delta * s.wa, delta * s.wb);
                let sa = &mut self.sums[s.a as usize];
                *sa = [sa[0] - n[0] * da, sa[1] - n[1] * da];
                let sb = &mut self.sums[s.b as usize];
                *sb = [sb[0] + n[0] * db, sb[1] + n[1] * db];
            }
        }
        for &p in &self.free {
            let p = p as usize;
            let (x, u, sum) = (self.positions[p], self.velocities[p], self.sums[p]);
            let zero = F::of(0.0);
            if METHOD == GAUSS_SEIDEL {
                self.positions[p] = [x[0] + u[0], x[1] + u[1]];
            } else if METHOD == SEMI_IMPLICIT {
                let u = [u[0] + sum[0], u[1] + sum[1]];
                self.velocities[p] = u;
                self.positions[p] = [x[0] + u[0], x[1] + u[1]];
                self.sums[p] = [zero; 2];
            } else {
                self.positions[p] = [x[0] + u[0], x[1] + u[1]];
                self.velocities[p] = [u[0] + sum[0], u[1] + sum[1]];
                self.sums[p] = [zero; 2];
            }
        }
    }

    fn position(&self, i: usize) -> [f64; 2] {
        [self.positions[i][0].get(), self.positions[i][1].get()]
    }

    fn particles(&self) -> usize {
        self.positions.len()
    }
}
