//! XPBD with small steps against stiffspring's scenes, at equal cost (issue 12).
//!
//! Three networks in physical units (`lab::xpbd::Model`): a rope swinging under gravity,
//! the same rope twenty times stiffer, and a soft jelly pushed sideways, all shown 60
//! frames per second for 2 s.
//! Every implementation runs `n` substeps per frame, `n` from 1 to 64:
//!
//! | implementation | one substep |
//! |---|---|
//! | `xpbd` | `lab::xpbd::Xpbd`: predict, one projection of every constraint (compliance `1/k`, XPBD's damping), velocities from positions |
//! | `stiffspring/exact` | `Scene::step` at `60·n` Hz, every spring `Tuning::from_physical(k, c, m_red, dt)` (the exact map of the spring on its own) |
//! | `stiffspring/raw` | the same scene, `Tuning::from_coefficients(k·dt²/m_red, c·dt/m_red, dt)` (the article's naive map) |
//!
//! The scenes use `LimitPolicy::Clamp`: a spring tuned above the network limit is
//! clamped to it (the `clamped` column counts them), so the network stays stable and
//! its springs get softer than asked.
//!
//! The error is the worst distance of any particle from the f64 reference model
//! (`lab::reference::network`) run at [`REFERENCE_SUBSTEPS`] steps per frame (whose own
//! error, the distance to the run at half that step, is printed beside it), at every
//! frame, relative to the rope's length or the jelly's width. The cost is the time of a
//! frame (the fastest of interleaved batches) and callgrind's instructions per frame.

use lab::measure::Candidate;
use lab::pareto::Real;
use lab::xpbd::{JELLY_LINKS, JELLY_PARTICLES, Model, ROPE_PARTICLES, Xpbd};
use std::hint::black_box;
use std::time::{Duration, Instant};
use stiffspring::scene::{LimitPolicy, Scene, SceneConfig};
use stiffspring::{Error, Scalar, Tuning};

/// Substeps per frame.
pub const SUBSTEPS: [usize; 7] = [1, 2, 4, 8, 16, 32, 64];
/// Steps per frame of the reference model.
pub const REFERENCE_SUBSTEPS: usize = 4096;

/// The models, in the order of the tables.
pub fn models() -> [Model; 3] {
    [Model::rope(), Model::stiff_rope(), Model::jelly()]
}

/// The names of [`models`].
pub const MODELS: [&str; 3] = ["rope", "stiff_rope", "jelly"];

/// One implementation of a model, stepped frame by frame.
pub trait Frames {
    /// Back to the start.
    fn reset(&mut self);
    /// One frame (all its substeps).
    fn frame(&mut self);
    /// Particle `i`'s position, in `f64`.
    fn position(&self, i: usize) -> [f64; 2];
    /// The number of particles.
    fn len(&self) -> usize;
}

impl<F: Real> Frames for Xpbd<F> {
    fn reset(&mut self) {
        Xpbd::reset(self);
    }
    #[inline(always)]
    fn frame(&mut self) {
        Xpbd::frame(self);
    }
    fn position(&self, i: usize) -> [f64; 2] {
        Xpbd::position(self, i)
    }
    fn len(&self) -> usize {
        Xpbd::len(self)
    }
}

/// How the stiffspring scene tunes its springs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Map {
    /// `Tuning::from_physical`: the exact map of each spring on its own.
    Exact,
    /// `Tuning::from_coefficients(k·dt²/m_red, c·dt/m_red)`, each capped at 1.
    Raw,
}

/// A stiffspring scene of a model, stepped `substeps` times per frame.
pub struct Stiff<S: Scalar, const P: usize, const K: usize> {
    start: Scene<S, 2, P, K>,
    scene: Scene<S, 2, P, K>,
    ids: Vec<stiffspring::scene::ParticleId>,
    substeps: usize,
    /// Springs whose coefficients the scene lowered to the network limit (or that the
    /// raw map capped at 1).
    pub clamped: usize,
}

impl<S: Scalar, const P: usize, const K: usize> Stiff<S, P, K> {
    /// The scene, or why the library rejects the model.
    pub fn new(model: &Model, substeps: usize, map: Map) -> Result<Self, Error> {
        let h = 1.0 / (model.frame_rate * substeps as f64);
        let config = SceneConfig::new(h)?
            .gravity(model.gravity.map(S::from_f64))?
            .limit_policy(LimitPolicy::Clamp);
        let mut scene = Scene::<S, 2, P, K>::new(config);
        let mut ids = Vec::new();
        for b in &model.bodies {
            let p = b.position.map(S::from_f64);
            let id = if b.mass.is_infinite() {
                scene.add_pinned(p)?
            } else {
                let id = scene.add_particle(p, S::from_f64(b.mass))?;
                scene.set_velocity(id, b.velocity.map(S::from_f64))?;
                id
            };
            ids.push(id);
        }
        let mut asked = Vec::new();
        let mut springs = Vec::new();
        for l in &model.links {
            let m = model.reduced_mass(l);
            let tuning = match map {
                Map::Exact => Tuning::from_physical(l.k, l.c, m, h)?,
                Map::Raw => {
                    let (ck, cd) = (l.k * h * h / m, l.c * h / m);
                    Tuning::from_coefficients(ck.min(1.0), cd.min(1.0), h)?
                }
            };
            let added = scene.add_spring(ids[l.a], ids[l.b], S::from_f64(l.rest), &tuning)?;
            let ck = match map {
                Map::Exact => tuning.stiffness(),
                Map::Raw => l.k * h * h / m,
            };
            asked.push(ck);
            springs.push(added.spring);
        }
        let clamped = springs
            .iter()
            .zip(&asked)
            .filter(|(s, ck)| {
                scene
                    .tuning(**s)
                    // Beyond the rounding of the backend's coefficient format.
                    .is_ok_and(|t| t.stiffness() < **ck * (1.0 - 1e-6))
            })
            .count();
        Ok(Stiff {
            start: scene.clone(),
            scene,
            ids,
            substeps,
            clamped,
        })
    }
}

impl<S: Scalar, const P: usize, const K: usize> Frames for Stiff<S, P, K> {
    fn reset(&mut self) {
        self.scene.clone_from(&self.start);
    }
    #[inline(always)]
    fn frame(&mut self) {
        for _ in 0..self.substeps {
            let _ = self.scene.step();
        }
    }
    fn position(&self, i: usize) -> [f64; 2] {
        self.scene
            .precise_position(self.ids[i])
            .unwrap_or([f64::NAN; 2])
    }
    fn len(&self) -> usize {
        self.ids.len()
    }
}

/// The frames of one run.
pub fn run<R: Frames>(r: &mut R, frames: usize) -> Vec<Vec<[f64; 2]>> {
    r.reset();
    (0..frames)
        .map(|_| {
            r.frame();
            (0..r.len()).map(|i| r.position(i)).collect()
        })
        .collect()
}

/// `frames` frames, each handed on through `black_box`.
#[inline(always)]
fn frames<R: Frames>(r: &mut R, frames: usize) {
    for _ in 0..frames {
        r.frame();
        black_box(&mut *r);
    }
}

/// What to do with a runner once built.
pub trait Visit {
    /// Called with the implementation's index in [`each`]'s order, its name, the
    /// backend, the substeps, the springs clamped, and the runner.
    #[allow(clippy::too_many_arguments)]
    fn visit<R: Frames + 'static>(
        &mut self,
        index: usize,
        implementation: &'static str,
        backend: &'static str,
        substeps: usize,
        clamped: usize,
        r: R,
    );
}

/// Every implementation of model `m` (an index into [`models`]) in backend `backend`
/// (`"f32"` or `"f64"`), in table order, or only the `which`-th.
pub fn each(m: usize, backend: &str, which: Option<usize>, v: &mut impl Visit) {
    let model = &models()[m];
    let rope = model.bodies.len() == ROPE_PARTICLES;
    fn stiff<S: Scalar, const P: usize, const K: usize>(
        model: &Model,
        index: usize,
        n: usize,
        map: Map,
        v: &mut impl Visit,
    ) {
        let name = match map {
            Map::Exact => "stiffspring/exact",
            Map::Raw => "stiffspring/raw",
        };
        match Stiff::<S, P, K>::new(model, n, map) {
            Ok(s) => {
                let clamped = s.clamped;
                v.visit(index, name, S::NAME, n, clamped, s);
            }
            Err(e) => eprintln!(
                "{name} {} rejected {} at {n} substeps: {e}",
                S::NAME,
                model.name
            ),
        }
    }
    let maps = [None, Some(Map::Exact), Some(Map::Raw)];
    for (k, n) in SUBSTEPS.into_iter().enumerate() {
        for (j, map) in maps.into_iter().enumerate() {
            let i = k * maps.len() + j;
            if which.is_some_and(|w| w != i) {
                continue;
            }
            match (map, backend, rope) {
                (None, "f32", _) => v.visit(i, "xpbd", "f32", n, 0, Xpbd::<f32>::new(model, n)),
                (None, _, _) => v.visit(i, "xpbd", "f64", n, 0, Xpbd::<f64>::new(model, n)),
                (Some(map), "f32", true) => {
                    stiff::<f32, ROPE_PARTICLES, { ROPE_PARTICLES - 1 }>(model, i, n, map, v)
                }
                (Some(map), _, true) => {
                    stiff::<f64, ROPE_PARTICLES, { ROPE_PARTICLES - 1 }>(model, i, n, map, v)
                }
                (Some(map), "f32", _) => {
                    stiff::<f32, JELLY_PARTICLES, JELLY_LINKS>(model, i, n, map, v)
                }
                (Some(map), _, _) => {
                    stiff::<f64, JELLY_PARTICLES, JELLY_LINKS>(model, i, n, map, v)
                }
            }
        }
    }
}

/// One implementation, measured but not yet timed.
pub struct Pending {
    /// Its index in [`each`]'s order.
    pub index: usize,
    /// The implementation.
    pub implementation: &'static str,
    /// Substeps per frame.
    pub substeps: usize,
    /// Springs clamped to the network limit.
    pub clamped: usize,
    /// Worst error over the run.
    pub error: f64,
    /// The timing closure, per frame.
    pub candidate: Candidate<'static>,
}

/// Collects [`Pending`] rows against a reference.
pub struct Collect<'a> {
    /// The model.
    pub model: &'a Model,
    /// Its reference frames.
    pub reference: &'a [Vec<[f64; 2]>],
    /// The rows.
    pub rows: Vec<Pending>,
}

impl Visit for Collect<'_> {
    fn visit<R: Frames + 'static>(
        &mut self,
        index: usize,
        implementation: &'static str,
        _: &'static str,
        substeps: usize,
        clamped: usize,
        mut r: R,
    ) {
        let count = self.model.frames;
        let error = self.model.error(&run(&mut r, count), self.reference);
        let candidate = Candidate::self_timed(count, move |runs| {
            let mut total = Duration::ZERO;
            for _ in 0..runs {
                r.reset();
                black_box(&mut r);
                let t = Instant::now();
                frames(&mut r, count);
                total += t.elapsed();
            }
            total
        });
        self.rows.push(Pending {
            index,
            implementation,
            substeps,
            clamped,
            error,
            candidate,
        });
    }
}

/// Runs one run inside `lab::measure::counted` (the callgrind child).
pub struct Count(pub usize);

impl Visit for Count {
    fn visit<R: Frames + 'static>(
        &mut self,
        _: usize,
        _: &'static str,
        _: &'static str,
        _: usize,
        _: usize,
        mut r: R,
    ) {
        r.reset();
        black_box(&mut r);
        let count = self.0;
        lab::measure::counted(&mut || frames(&mut r, count));
    }
}
