//! Live: run time against error of the 1D scene, stiffspring beside the peer crates.
//!
//! The short version of `cargo bench --bench pareto` (see `docs/benchmarks.md`): one scene, a
//! value released from rest toward its target (2 Hz, ζ = 0.3, a 60 Hz display, 2 s),
//! every implementation timed in this process, interleaved, for about a tenth of a second.

use lab::measure::{self, Plan};
use lab::pareto::{Entry, FREQUENCY, Runner, TARGET, ValueScene, entry, peer_entries};
use lab::table::{print, sci};
use std::time::Duration;
use stiffspring::{I16F16, I32F32, RestThreshold, Scalar, SpringValue, Tuning};

/// A `SpringValue::<S, 1>` with the exact map, released from rest toward the target, rest
/// detection off (`advance`) (and flung, for a fling scene): the library's runner, as in the pareto
/// bench (`benches/pareto/values.rs`).
struct Stiff<S: Scalar> {
    start: SpringValue<S, 1>,
    value: SpringValue<S, 1>,
}

impl<S: Scalar> Stiff<S> {
    fn new(scene: &ValueScene) -> Option<Self> {
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
        self.value.advance();
    }
    #[inline(always)]
    fn offset(&self) -> f64 {
        self.value.offset()[0].to_f64()
    }
}

/// The library in each backend, then the peers and the baselines.
fn entries(scene: &ValueScene) -> Vec<Entry> {
    fn stiff<S: Scalar>(scene: &ValueScene) -> Option<Entry> {
        Stiff::<S>::new(scene).map(|r| entry("stiffspring", S::NAME, scene, r))
    }
    let ours = [
        stiff::<f64>(scene),
        stiff::<f32>(scene),
        stiff::<I32F32>(scene),
        stiff::<I16F16>(scene),
    ];
    ours.into_iter()
        .flatten()
        .chain(peer_entries(scene))
        .collect()
}

pub fn peers() {
    let scene = ValueScene {
        zeta: 0.3,
        rate: 60.0,
        velocity: 0.0,
    };
    println!(
        "Against the peers, live: a value released from rest toward its target, 2 Hz, ζ = {}, \
         stepped at {} Hz for 2 s",
        scene.zeta, scene.rate
    );
    let (meta, mut candidates): (Vec<_>, Vec<_>) = entries(&scene)
        .into_iter()
        .map(|e| ((e.implementation, e.backend, e.error), e.candidate))
        .unzip();
    let ns = measure::medians(
        &mut candidates,
        Plan {
            batch: Duration::from_micros(100),
            rounds: 15,
        },
    );
    let ours = meta
        .iter()
        .zip(&ns)
        .find(|((imp, backend, _), _)| *imp == "stiffspring" && *backend == "f32")
        .map(|(_, t)| *t)
        .unwrap_or(f64::NAN);
    let rows: Vec<Vec<String>> = meta
        .iter()
        .zip(&ns)
        .map(|((imp, backend, error), t)| {
            vec![
                imp.to_string(),
                backend.to_string(),
                format!("{t:.2}"),
                format!("{:.2}", t / ours),
                sci(*error),
            ]
        })
        .collect();
    print(
        &[
            "implementation",
            "backend",
            "ns/step",
            "× stiffspring f32",
            "worst error",
        ],
        &rows,
    );
    println!(
        "(measured now, on this machine: the ratios hold, the nanoseconds move; the error is \
         the worst distance from the analytic solution over the run, relative to the \
         amplitude. The full report, every scene and rate: cargo bench --bench pareto)\n"
    );
}
