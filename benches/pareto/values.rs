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
//! The scenes, the peers and the baselines are in `lab::pareto`; this file adds the
//! library's runner.

use lab::pareto::{Entry, FREQUENCY, Runner, TARGET, ValueScene, entry, peer_entries};
use stiffspring::{I16F16, I32F32, RestThreshold, Scalar, SpringValue, Tuning};

/// Every implementation on `scene`, in the order of the table: the library in each
/// backend, then the peers and the baselines.
pub fn entries(scene: &ValueScene) -> Vec<Entry> {
    let mut out = Vec::new();
    fn stiff<S: Scalar>(out: &mut Vec<Entry>, scene: &ValueScene) {
        match Stiff::<S>::new(scene) {
            Some(r) => out.push(entry("stiffspring", S::NAME, scene, r)),
            None => eprintln!("stiffspring {} rejected {scene:?}", S::NAME),
        }
    }
    stiff::<f64>(&mut out, scene);
    stiff::<f32>(&mut out, scene);
    stiff::<I32F32>(&mut out, scene);
    stiff::<I16F16>(&mut out, scene);
    out.extend(peer_entries(scene));
    out
}

// ---------------------------------------------------------------------------------------
// stiffspring
// ---------------------------------------------------------------------------------------

/// `SpringValue::<S, 1>` with the exact map, released from rest (and flung) toward the
/// target, with rest detection off.
pub struct Stiff<S: Scalar> {
    start: SpringValue<S, 1>,
    value: SpringValue<S, 1>,
}

impl<S: Scalar> Stiff<S> {
    /// `None` when the backend rejects the scene.
    pub fn new(scene: &ValueScene) -> Option<Self> {
        let tuning = Tuning::from_frequency(FREQUENCY, scene.zeta, scene.dt()).ok()?;
        let never = RestThreshold::new(1e-300, 1e-300).ok()?;
        let mut value = SpringValue::new([S::ZERO], &tuning)
            .ok()?
            .with_rest_threshold(never);
        value.try_set_target([S::from_f64(TARGET)]).ok()?;
        if scene.velocity != 0.0 {
            value.try_fling([S::from_f64(scene.velocity)]).ok()?;
        }
        Some(Stiff {
            start: value.clone(),
            value,
        })
    }
}

impl<S: Scalar> Runner for Stiff<S> {
    #[inline(always)]
    fn reset(&mut self) {
        self.value.clone_from(&self.start);
    }
    #[inline(always)]
    fn step(&mut self) {
        let _ = self.value.step();
    }
    #[inline(always)]
    fn offset(&self) -> f64 {
        self.value.offset()[0].to_f64()
    }
}
