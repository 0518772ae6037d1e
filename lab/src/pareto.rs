//! The 1D scenes, the one kind of scene every peer can run: a spring toward a target,
//! `f = 2 Hz`, from rest at distance 1 (position 0, target 1) or flung at 10 units/s
//! toward the target from there, stepped for 2 s.
//!
//! Every implementation runs behind [`Runner`], from the same start, with the same
//! physics (`ω = 2π·f`, damping ratio `ζ`, unit mass):
//!
//! | implementation | what steps | how it starts |
//! |---|---|---|
//! | `stiffspring` (`f64`, `f32`, `I32F32`, `I16F16`) | `SpringValue::<S, 1>::step` with the exact map | `set_target` from rest (and `fling`): the analytic `u₀`, on the continuous trajectory |
//! | `animato-spring/semi-implicit-euler`, `/rk4` (`f32`) | `Update::update(dt)` | `Spring::from_velocity(0, v₀, 1, config)`, `k = ω²`, `c = 2ζω`, `epsilon = 0` |
//! | `damped-springs` (`f64`, `f32`) | `Spring::update` with a precomputed `SpringTimeStep` | `Spring::from_equilibrium(1).with_velocity(v₀)` |
//! | `spring_damper` (`f32`) | `spring_damper_exact_stiffness_damping(.., ω², 2ζω, dt, DEFAULT_EPS)` | the caller's `x = 0`, `v = v₀` |
//! | `baseline/…` (`f64`, `f32`) | written here from the textbook formulas | `x = 0`, `v = v₀` |
//!
//! Every peer takes the continuous state `(x₀, v₀)` at `t = 0` directly, so every one
//! starts on the analytic trajectory; stiffspring stores `u = x_n − x_{n−1}` and computes
//! it from the analytic solution at set-up. Rest detection is switched off where an API
//! allows it (stiffspring: a threshold of 1e−300; animato: `epsilon = 0`), so that every
//! step of the run is a moving step.
//!
//! Error: `max |x_n − x(t_n)|` over the run, relative to the amplitude
//! `max |x(t)|` of the analytic offset from the target (1 from rest; the overshoot of a
//! fling when it is larger).
//!
//! Used by `benches/pareto` and the tour (`examples/tour/bench.rs`), which add the
//! library's own [`Runner`] (this module does not use the library) and time the
//! [`Entry`]s with [`crate::measure`].

use crate::measure::Candidate;
use crate::reference;
use animato_core::Update;
use std::hint::black_box;
use std::ops::{Add, Mul, Sub};

/// The spring's natural frequency, in Hz.
pub const FREQUENCY: f64 = 2.0;
/// How long a scene runs, in seconds.
pub const DURATION: f64 = 2.0;
/// The target; the value starts at 0.
pub const TARGET: f64 = 1.0;
/// The velocity of a fling, toward the target (units per second).
pub const FLING: f64 = 10.0;
/// The damping ratios of the scenes.
pub const ZETAS: [f64; 2] = [0.3, 1.0];
/// The step rates of the scenes, in Hz.
pub const RATES: [f64; 3] = [60.0, 120.0, 1000.0];

/// One 1D scene: a damping ratio, a step rate, and a start (from rest or flung).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValueScene {
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Steps per second.
    pub rate: f64,
    /// Initial velocity toward the target: 0 from rest, [`FLING`] for a fling.
    pub velocity: f64,
}

impl ValueScene {
    /// Every 1D scene: from rest, then flung; each at both damping ratios and all rates.
    pub fn all() -> Vec<ValueScene> {
        let mut out = Vec::new();
        for velocity in [0.0, FLING] {
            for zeta in ZETAS {
                for rate in RATES {
                    out.push(ValueScene {
                        zeta,
                        rate,
                        velocity,
                    });
                }
            }
        }
        out
    }

    /// The scene's name in the CSV: `step_zeta0.3`, `fling_zeta1`, ...
    pub fn name(&self) -> String {
        let start = if self.velocity == 0.0 {
            "step"
        } else {
            "fling"
        };
        format!("{start}_zeta{}", self.zeta)
    }

    /// The time step, in seconds.
    pub fn dt(&self) -> f64 {
        1.0 / self.rate
    }

    /// Steps in one run.
    pub fn steps(&self) -> usize {
        (DURATION * self.rate).round() as usize
    }

    /// Angular natural frequency, rad/s.
    pub fn omega(&self) -> f64 {
        std::f64::consts::TAU * FREQUENCY
    }

    /// The offset from the target at the start, `x₀ = 0 − TARGET`.
    pub fn start_offset(&self) -> f64 {
        -TARGET
    }

    /// The analytic offset from the target after each step, `n = 1..=steps`.
    pub fn analytic(&self) -> Vec<f64> {
        (1..=self.steps())
            .map(|n| {
                reference::analytic(
                    self.start_offset(),
                    self.velocity,
                    self.omega(),
                    self.zeta,
                    n as f64 * self.dt(),
                )
                .0
            })
            .collect()
    }

    /// The amplitude errors are relative to: the largest analytic offset, start included.
    pub fn amplitude(&self) -> f64 {
        self.analytic()
            .iter()
            .fold(self.start_offset().abs(), |m, x| m.max(x.abs()))
    }
}

/// One implementation of the 1D spring, set up on one scene.
pub trait Runner {
    /// Back to the scene's start.
    fn reset(&mut self);
    /// One step.
    fn step(&mut self);
    /// The offset from the target, `position − target`, in `f64`.
    fn offset(&self) -> f64;
}

/// `runs` runs of `steps` steps from the start: what is timed. The state is made opaque
/// once per run, so that no run can be folded into another, and the final offset is
/// consumed, so that no step can be dropped.
#[inline(never)]
pub fn run_batch<R: Runner>(r: &mut R, runs: usize, steps: usize) {
    for _ in 0..runs {
        r.reset();
        black_box(&mut *r);
        for _ in 0..steps {
            r.step();
        }
        black_box(r.offset());
    }
}

/// The worst error over one run, relative to the amplitude.
pub fn max_error<R: Runner>(r: &mut R, scene: &ValueScene) -> f64 {
    r.reset();
    let mut worst = 0.0f64;
    for x in scene.analytic() {
        r.step();
        let e = (r.offset() - x).abs();
        // A NaN (a diverged run) is reported as an infinite error.
        worst = if e.is_nan() {
            f64::INFINITY
        } else {
            worst.max(e)
        };
    }
    worst / scene.amplitude()
}

/// One row of a scene: who, in what backend, how wrong, and how to time it.
pub struct Entry {
    /// The `implementation` column.
    pub implementation: &'static str,
    /// The `backend` column.
    pub backend: &'static str,
    /// `max_rel_error`.
    pub error: f64,
    /// The timing closure.
    pub candidate: Candidate<'static>,
}

/// The entry of `runner` on `scene`: its error over one run, and its timing closure.
pub fn entry<R: Runner + 'static>(
    implementation: &'static str,
    backend: &'static str,
    scene: &ValueScene,
    mut runner: R,
) -> Entry {
    let error = max_error(&mut runner, scene);
    let steps = scene.steps();
    Entry {
        implementation,
        backend,
        error,
        candidate: Candidate::new(steps, move |runs| run_batch(&mut runner, runs, steps)),
    }
}

/// Every peer crate and textbook baseline on `scene`, in the order of the table (the
/// caller puts the library's own entries first).
pub fn peer_entries(scene: &ValueScene) -> Vec<Entry> {
    let mut out = vec![
        entry(
            "animato-spring/semi-implicit-euler",
            "f32",
            scene,
            Animato::new(scene, false),
        ),
        entry(
            "animato-spring/rk4",
            "f32",
            scene,
            Animato::new(scene, true),
        ),
        entry("damped-springs", "f64", scene, Damped::<f64>::new(scene)),
        entry("damped-springs", "f32", scene, Damped::<f32>::new(scene)),
        entry("spring_damper", "f32", scene, Holden::new(scene)),
    ];
    fn baselines<F: Real>(out: &mut Vec<Entry>, scene: &ValueScene) {
        out.push(entry(
            "baseline/explicit-euler",
            F::NAME,
            scene,
            Baseline::<F, EXPLICIT_EULER>::new(scene),
        ));
        out.push(entry(
            "baseline/semi-implicit-euler",
            F::NAME,
            scene,
            Baseline::<F, SEMI_IMPLICIT_EULER>::new(scene),
        ));
        out.push(entry(
            "baseline/box2d-soft",
            F::NAME,
            scene,
            Baseline::<F, BOX2D_SOFT>::new(scene),
        ));
    }
    baselines::<f64>(&mut out, scene);
    baselines::<f32>(&mut out, scene);
    out
}

// ---------------------------------------------------------------------------------------
// The peers, through their public APIs
// ---------------------------------------------------------------------------------------

/// animato-spring 1.7.3: `Spring` with `k = ω²`, `c = 2ζω`, `m = 1`, stepped by
/// `Update::update(dt)` (semi-implicit Euler, or classic RK4 with `use_rk4(true)`).
pub struct Animato {
    start: animato_spring::Spring,
    spring: animato_spring::Spring,
    dt: f32,
}

impl Animato {
    /// The spring at 0, moving at the scene's velocity, toward [`TARGET`].
    pub fn new(scene: &ValueScene, rk4: bool) -> Self {
        let w = scene.omega();
        let config = animato_spring::SpringConfig {
            stiffness: (w * w) as f32,
            damping: (2.0 * scene.zeta * w) as f32,
            mass: 1.0,
            // `is_settled` is `|x − target| < ε && |v| < ε`: with 0 it never is, so every
            // step is a moving step (the default 0.001 would stop the run early).
            epsilon: 0.0,
        };
        let spring = animato_spring::Spring::from_velocity(
            0.0,
            scene.velocity as f32,
            TARGET as f32,
            config,
        )
        .use_rk4(rk4);
        Animato {
            start: spring.clone(),
            spring,
            dt: scene.dt() as f32,
        }
    }
}

impl Runner for Animato {
    #[inline(always)]
    fn reset(&mut self) {
        self.spring.clone_from(&self.start);
    }
    #[inline(always)]
    fn step(&mut self) {
        self.spring.update(self.dt);
    }
    #[inline(always)]
    fn offset(&self) -> f64 {
        self.spring.position() as f64 - TARGET
    }
}

/// damped-springs 1.0.0: Juckett's exact 2×2 step, the matrix precomputed once per `dt`
/// (`SpringTimeStep::new`), applied by `Spring::update`.
pub struct Damped<F> {
    start: damped_springs::Spring<F>,
    spring: damped_springs::Spring<F>,
    step: damped_springs::SpringTimeStep<F>,
}

macro_rules! damped {
    ($F:ty) => {
        impl Damped<$F> {
            /// The spring at 0 with equilibrium [`TARGET`] and the scene's velocity.
            pub fn new(scene: &ValueScene) -> Self {
                let config =
                    damped_springs::SpringConfig::new(scene.omega() as $F, scene.zeta as $F);
                let spring = damped_springs::Spring::from_equilibrium(TARGET as $F)
                    .with_velocity(scene.velocity as $F);
                Damped {
                    start: spring,
                    spring,
                    step: damped_springs::SpringTimeStep::new(config, scene.dt() as $F),
                }
            }
        }

        impl Runner for Damped<$F> {
            #[inline(always)]
            fn reset(&mut self) {
                self.spring = self.start;
            }
            #[inline(always)]
            fn step(&mut self) {
                self.spring.update(self.step);
            }
            #[inline(always)]
            fn offset(&self) -> f64 {
                self.spring.position as f64 - TARGET
            }
        }
    };
}
damped!(f32);
damped!(f64);

/// spring_damper 0.1.1: Holden's analytic spring-damper,
/// `spring_damper_exact_stiffness_damping` with `k = ω²`, `d = 2ζω` and the crate's
/// `DEFAULT_EPS`, on the caller's `f32` state.
pub struct Holden {
    start: (f32, f32),
    x: f32,
    v: f32,
    stiffness: f32,
    damping: f32,
    dt: f32,
}

impl Holden {
    /// The state `x = 0`, `v = v₀`.
    pub fn new(scene: &ValueScene) -> Self {
        let w = scene.omega();
        Holden {
            start: (0.0, scene.velocity as f32),
            x: 0.0,
            v: scene.velocity as f32,
            stiffness: (w * w) as f32,
            damping: (2.0 * scene.zeta * w) as f32,
            dt: scene.dt() as f32,
        }
    }
}

impl Runner for Holden {
    #[inline(always)]
    fn reset(&mut self) {
        (self.x, self.v) = self.start;
    }
    #[inline(always)]
    fn step(&mut self) {
        spring_damper::spring_damper_exact_stiffness_damping(
            &mut self.x,
            &mut self.v,
            TARGET as f32,
            0.0,
            self.stiffness,
            self.damping,
            self.dt,
            spring_damper::DEFAULT_EPS,
        );
    }
    #[inline(always)]
    fn offset(&self) -> f64 {
        self.x as f64 - TARGET
    }
}

// ---------------------------------------------------------------------------------------
// Baselines from the textbook formulas
// ---------------------------------------------------------------------------------------

/// The float formats the baselines are written for.
pub trait Real:
    Copy + Default + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + 'static
{
    /// `"f32"` or `"f64"`.
    const NAME: &'static str;
    /// From `f64`, rounded.
    fn of(v: f64) -> Self;
    /// To `f64`, exact.
    fn get(self) -> f64;
    /// The correctly rounded square root (std's, the hardware instruction on x86).
    fn sqrt(self) -> Self;
    /// `1/self`.
    fn recip(self) -> Self;
}

impl Real for f32 {
    const NAME: &'static str = "f32";
    fn of(v: f64) -> Self {
        v as f32
    }
    fn get(self) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn recip(self) -> Self {
        1.0 / self
    }
}

impl Real for f64 {
    const NAME: &'static str = "f64";
    fn of(v: f64) -> Self {
        v
    }
    fn get(self) -> f64 {
        self
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn recip(self) -> Self {
        1.0 / self
    }
}

/// Hooke's spring `a = −k·(x − t) − c·v`, explicit Euler: `x += v·dt`, `v += a·dt`,
/// both from the old state.
pub const EXPLICIT_EULER: u8 = 0;
/// The same force, semi-implicit (symplectic) Euler: `v += a·dt`, then `x += v·dt`.
pub const SEMI_IMPLICIT_EULER: u8 = 1;
/// Box2D v3's soft step (`b2MakeSoft`, one iteration, no warm start): with
/// `a₁ = 2ζ + h·ω`, `a₂ = h·ω·a₁`, `a₃ = 1/(1 + a₂)`, `biasRate = ω/a₁` and
/// `massScale = a₂·a₃`, `v ← v − massScale·(v + biasRate·(x − t))`, `x += h·v`.
/// Implicit Euler in disguise: with `D = 1 + 2ζωh + ω²h²` it is the spring map with
/// `C_k = ω²h²/D` and `C_d = (2ζωh + ω²h²)/D`, always stable, but it lags and loses
/// energy.
pub const BOX2D_SOFT: u8 = 2;

/// A textbook spring of unit mass in `F`, stepped by `METHOD` (one of the constants
/// above, a type parameter so that each loop is compiled for its own method).
pub struct Baseline<F, const METHOD: u8> {
    start: (F, F),
    x: F,
    v: F,
    target: F,
    dt: F,
    /// `k` (Euler) or `biasRate` (Box2D).
    a: F,
    /// `c` (Euler) or `massScale` (Box2D).
    b: F,
}

impl<F: Real, const METHOD: u8> Baseline<F, METHOD> {
    /// The state `x = 0`, `v = v₀`, with the method's constants precomputed.
    pub fn new(scene: &ValueScene) -> Self {
        let (w, z, h) = (scene.omega(), scene.zeta, scene.dt());
        let (a, b) = if METHOD == BOX2D_SOFT {
            let a1 = 2.0 * z + h * w;
            let a2 = h * w * a1;
            let a3 = 1.0 / (1.0 + a2);
            (w / a1, a2 * a3)
        } else {
            (w * w, 2.0 * z * w)
        };
        Baseline {
            start: (F::of(0.0), F::of(scene.velocity)),
            x: F::of(0.0),
            v: F::of(scene.velocity),
            target: F::of(TARGET),
            dt: F::of(h),
            a: F::of(a),
            b: F::of(b),
        }
    }
}

impl<F: Real, const METHOD: u8> Runner for Baseline<F, METHOD> {
    #[inline(always)]
    fn reset(&mut self) {
        (self.x, self.v) = self.start;
    }
    #[inline(always)]
    fn step(&mut self) {
        let (x, v, dt) = (self.x, self.v, self.dt);
        match METHOD {
            EXPLICIT_EULER => {
                let a = F::of(0.0) - self.a * (x - self.target) - self.b * v;
                self.x = x + v * dt;
                self.v = v + a * dt;
            }
            SEMI_IMPLICIT_EULER => {
                let a = F::of(0.0) - self.a * (x - self.target) - self.b * v;
                self.v = v + a * dt;
                self.x = x + self.v * dt;
            }
            _ => {
                self.v = v - self.b * (v + self.a * (x - self.target));
                self.x = x + self.v * dt;
            }
        }
    }
    #[inline(always)]
    fn offset(&self) -> f64 {
        self.x.get() - TARGET
    }
}

// ---------------------------------------------------------------------------------------
// The batch scene: many values stepped frame by frame
// ---------------------------------------------------------------------------------------

/// Values in one [`BatchScene`].
pub const BATCH: usize = 1000;

/// The host scene of the cost targets: [`BATCH`] values of the 1D spring (`f = 2 Hz`), each
/// released from rest at 0 toward its own target, stepped frame by frame for
/// [`DURATION`]: every frame steps every value once, then the frame is handed on (the
/// state goes through `black_box`, as to a renderer), so no frame can be fused with the
/// next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatchScene {
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Frames per second.
    pub rate: f64,
}

impl BatchScene {
    /// Both damping ratios at every rate.
    pub fn all() -> Vec<BatchScene> {
        let mut out = Vec::new();
        for zeta in ZETAS {
            for rate in RATES {
                out.push(BatchScene { zeta, rate });
            }
        }
        out
    }

    /// The scene's name in the CSV: `batch_zeta0.3`, `batch_zeta1`.
    pub fn name(&self) -> String {
        format!("batch_zeta{}", self.zeta)
    }

    /// The time step, in seconds.
    pub fn dt(&self) -> f64 {
        1.0 / self.rate
    }

    /// Frames in one run.
    pub fn frames(&self) -> usize {
        (DURATION * self.rate).round() as usize
    }

    /// Angular natural frequency, rad/s.
    pub fn omega(&self) -> f64 {
        std::f64::consts::TAU * FREQUENCY
    }

    /// The targets of the values: seeded, magnitudes from 1 to 100 (log-uniform), either
    /// sign. Every value starts at 0, at rest.
    pub fn targets(&self) -> Vec<f64> {
        let mut rng = crate::rng::Rng::seeded(12);
        (0..BATCH)
            .map(|_| {
                let m = rng.log_range(1.0, 100.0);
                if rng.unit() < 0.5 { -m } else { m }
            })
            .collect()
    }

    /// The analytic offset from the target after each frame `n = 1..=frames` of a value
    /// released from an offset of 1: value `i`'s offset is `−targets[i]` times this.
    pub fn unit_response(&self) -> Vec<f64> {
        (1..=self.frames())
            .map(|n| reference::analytic(1.0, 0.0, self.omega(), self.zeta, n as f64 * self.dt()).0)
            .collect()
    }

    /// The exact map's `(C_k, C_d)` at this scene's step, from the reference's poles.
    pub fn coefficients(&self) -> (f64, f64) {
        reference::exact_coefficients_from_poles(self.omega(), self.zeta, self.dt())
    }

    /// The step velocity `u₀ = x(0) − x(−dt)` of a value released from an offset of 1.
    pub fn unit_u0(&self) -> f64 {
        reference::u0_from_analytic(1.0, 0.0, self.omega(), self.zeta, self.dt())
    }
}

/// One implementation of the batch scene.
pub trait BatchRunner {
    /// Back to the scene's start.
    fn reset(&mut self);
    /// One frame: every value one step.
    fn frame(&mut self);
    /// Value `i`'s offset from its target, `position − target`, in `f64`.
    fn offset(&self, i: usize) -> f64;
}

/// The worst error of a batch over one run: `max |x_i − x_i(t)| / |target_i|` over every
/// value and frame (a NaN counts as infinite).
pub fn batch_error<R: BatchRunner>(r: &mut R, scene: &BatchScene) -> f64 {
    let targets = scene.targets();
    let unit = scene.unit_response();
    r.reset();
    let mut worst = 0.0f64;
    for g in unit {
        r.frame();
        for (i, t) in targets.iter().enumerate() {
            let e = (r.offset(i) + t * g).abs() / t.abs();
            worst = if e.is_nan() {
                f64::INFINITY
            } else {
                worst.max(e)
            };
        }
    }
    worst
}

/// `frames` frames of `r`, each handed on through `black_box`.
#[inline(always)]
pub fn run_frames<R: BatchRunner>(r: &mut R, frames: usize) {
    for _ in 0..frames {
        r.frame();
        black_box(&mut *r);
    }
}

/// The timing closure of a batch runner: per run, a reset (not timed) and the run's
/// frames (timed); reported per value step.
pub fn batch_candidate<R: BatchRunner + 'static>(
    scene: &BatchScene,
    mut r: R,
) -> Candidate<'static> {
    let frames = scene.frames();
    Candidate::self_timed(frames, move |runs| {
        let mut total = std::time::Duration::ZERO;
        for _ in 0..runs {
            r.reset();
            black_box(&mut r);
            let t = std::time::Instant::now();
            run_frames(&mut r, frames);
            total += t.elapsed();
        }
        total
    })
    .per(BATCH)
}

/// The instructions of one run of `r` (reset first, not counted), for
/// [`crate::measure::callgrind`]: runs the frames inside [`crate::measure::counted`].
pub fn batch_count<R: BatchRunner>(scene: &BatchScene, r: &mut R) {
    r.reset();
    black_box(&mut *r);
    let frames = scene.frames();
    crate::measure::counted(&mut || run_frames(r, frames));
}

/// The minimal position-level kernel of issue 12: plain arrays of offsets and step
/// velocities in `f32`, the coefficients hoisted, `u = r·u − k·x; x += u` with
/// `r = 1 − C_d`, `k = C_k` (the exact map's), started from the analytic `u₀`. No rest
/// test, no saturation, no target: the floor of a value step.
pub struct MinimalBatch {
    start: (Vec<f32>, Vec<f32>),
    x: Vec<f32>,
    u: Vec<f32>,
    r: f32,
    k: f32,
}

impl MinimalBatch {
    /// The scene's values at their start.
    pub fn new(scene: &BatchScene) -> Self {
        let (ck, cd) = scene.coefficients();
        let u0 = scene.unit_u0();
        let x: Vec<f32> = scene.targets().iter().map(|t| -t as f32).collect();
        let u: Vec<f32> = scene.targets().iter().map(|t| (-t * u0) as f32).collect();
        MinimalBatch {
            start: (x.clone(), u.clone()),
            x,
            u,
            r: (1.0 - cd) as f32,
            k: ck as f32,
        }
    }
}

impl BatchRunner for MinimalBatch {
    fn reset(&mut self) {
        self.x.copy_from_slice(&self.start.0);
        self.u.copy_from_slice(&self.start.1);
    }
    #[inline(always)]
    fn frame(&mut self) {
        let (r, k) = (self.r, self.k);
        for (x, u) in self.x.iter_mut().zip(self.u.iter_mut()) {
            *u = r * *u - k * *x;
            *x += *u;
        }
    }
    fn offset(&self, i: usize) -> f64 {
        self.x[i] as f64
    }
}

/// damped-springs 1.0.0 in `f32`: one `Spring` per value, one `SpringTimeStep` for all.
pub struct DampedBatch {
    start: Vec<damped_springs::Spring<f32>>,
    springs: Vec<damped_springs::Spring<f32>>,
    step: damped_springs::SpringTimeStep<f32>,
    targets: Vec<f32>,
}

impl DampedBatch {
    /// Bytes of state per value (one `Spring<f32>`).
    pub const BYTES_PER_VALUE: usize = size_of::<damped_springs::Spring<f32>>();

    /// Every value at 0, at rest, with its target as the equilibrium.
    pub fn new(scene: &BatchScene) -> Self {
        let config = damped_springs::SpringConfig::new(scene.omega() as f32, scene.zeta as f32);
        let targets: Vec<f32> = scene.targets().iter().map(|&t| t as f32).collect();
        let springs: Vec<_> = targets
            .iter()
            .map(|&t| damped_springs::Spring::from_equilibrium(t))
            .collect();
        DampedBatch {
            start: springs.clone(),
            springs,
            step: damped_springs::SpringTimeStep::new(config, scene.dt() as f32),
            targets,
        }
    }
}

impl BatchRunner for DampedBatch {
    fn reset(&mut self) {
        self.springs.copy_from_slice(&self.start);
    }
    #[inline(always)]
    fn frame(&mut self) {
        let step = self.step;
        for s in self.springs.iter_mut() {
            s.update(step);
        }
    }
    fn offset(&self, i: usize) -> f64 {
        self.springs[i].position as f64 - self.targets[i] as f64
    }
}

/// animato-spring 1.7.3, semi-implicit Euler (`f32`): one `Spring` per value, each
/// `update(dt)`, `epsilon = 0` (never settled).
pub struct AnimatoBatch {
    start: Vec<animato_spring::Spring>,
    springs: Vec<animato_spring::Spring>,
    targets: Vec<f32>,
    dt: f32,
}

impl AnimatoBatch {
    /// Bytes of state per value (one `Spring`).
    pub const BYTES_PER_VALUE: usize = size_of::<animato_spring::Spring>();

    /// Every value at 0, at rest, springing toward its target.
    pub fn new(scene: &BatchScene) -> Self {
        let w = scene.omega();
        let config = animato_spring::SpringConfig {
            stiffness: (w * w) as f32,
            damping: (2.0 * scene.zeta * w) as f32,
            mass: 1.0,
            epsilon: 0.0,
        };
        let targets: Vec<f32> = scene.targets().iter().map(|&t| t as f32).collect();
        let springs: Vec<_> = targets
            .iter()
            .map(|&t| animato_spring::Spring::from_velocity(0.0, 0.0, t, config.clone()))
            .collect();
        AnimatoBatch {
            start: springs.clone(),
            springs,
            targets,
            dt: scene.dt() as f32,
        }
    }
}

impl BatchRunner for AnimatoBatch {
    fn reset(&mut self) {
        self.springs.clone_from(&self.start);
    }
    #[inline(always)]
    fn frame(&mut self) {
        let dt = self.dt;
        for s in self.springs.iter_mut() {
            s.update(dt);
        }
    }
    fn offset(&self, i: usize) -> f64 {
        self.springs[i].position() as f64 - self.targets[i] as f64
    }
}
