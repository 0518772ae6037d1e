//! Live: run time against error of the 1D scene, stiffspring beside the peer crates.
//!
//! The short version of `cargo bench --bench pareto` (see BENCHMARKS.md): one scene, a
//! value released from rest toward its target (2 Hz, ζ = 0.3, a 60 Hz display, 2 s),
//! every implementation timed in this process, interleaved, for about a tenth of a second.

use crate::measure::{self, Plan};
use crate::pareto_values::{ValueScene, entries};
use crate::table::{print, sci};
use std::time::Duration;

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
