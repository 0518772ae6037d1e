//! Run time against error, side by side with the peer crates, in one run.
//!
//! ```sh
//! cargo bench --bench pareto            # about a minute
//! cargo bench --bench pareto -- --quick # fewer rounds, for a smoke test
//! ```
//!
//! Writes `target/pareto/results.csv` (columns
//! `scene,implementation,backend,step_hz,ns_per_step,max_rel_error`) and
//! `target/pareto/pareto.svg` (error against time per step, log-log, one panel per scene
//! and step rate), and prints the ratios against each peer. See `BENCHMARKS.md` for how
//! to read them.
//!
//! - `ns_per_step` is the median over interleaved batches (`lab::measure`) of one value
//!   step, one knob update, or one spring of a network step (a scene step divided by its
//!   springs). Every implementation of a scene is timed in the same process, round-robin,
//!   so the ratios hold on a noisy machine; absolute numbers move from run to run.
//! - `max_rel_error` is the worst deviation over the run from the analytic solution
//!   (1D scenes, `values.rs` and `lab::pareto`), from the f64 reference model (networks,
//!   `networks.rs`), or
//!   from the f64 knob (`knob.rs`), relative to the scene's amplitude.

mod knob;
mod networks;
mod values;

use lab::measure::{self, Candidate, Plan};
use lab::pareto::ValueScene;
use lab::plot::{Grid, Plot, Series};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Duration;

/// One line of the CSV.
#[derive(Clone, Debug)]
struct Row {
    scene: String,
    implementation: String,
    backend: String,
    step_hz: f64,
    ns_per_step: f64,
    max_rel_error: f64,
}

/// Rows of one scene and rate, before timing.
struct Pending {
    scene: String,
    implementation: String,
    backend: String,
    step_hz: f64,
    error: f64,
    candidate: Candidate<'static>,
}

/// Times every candidate of one scene interleaved and turns them into rows.
fn time(pending: Vec<Pending>, plan: Plan) -> Vec<Row> {
    let (meta, mut candidates): (Vec<_>, Vec<_>) = pending
        .into_iter()
        .map(|p| {
            (
                (p.scene, p.implementation, p.backend, p.step_hz, p.error),
                p.candidate,
            )
        })
        .unzip();
    let ns = measure::medians(&mut candidates, plan);
    meta.into_iter()
        .zip(ns)
        .map(
            |((scene, implementation, backend, step_hz, error), ns)| Row {
                scene,
                implementation,
                backend,
                step_hz,
                ns_per_step: ns,
                max_rel_error: error,
            },
        )
        .collect()
}

fn value_rows(plan: Plan) -> Vec<Row> {
    let mut rows = Vec::new();
    for scene in ValueScene::all() {
        let pending = values::entries(&scene)
            .into_iter()
            .map(|e| Pending {
                scene: scene.name(),
                implementation: e.implementation.into(),
                backend: e.backend.into(),
                step_hz: scene.rate,
                error: e.error,
                candidate: e.candidate,
            })
            .collect();
        eprintln!("  {} at {} Hz", scene.name(), scene.rate);
        rows.extend(time(pending, plan));
    }
    rows
}

fn network_rows(plan: Plan) -> Vec<Row> {
    let mut rows = Vec::new();
    let rope = networks::Net::rope();
    let jelly = networks::Net::jelly();
    for (net, entries) in [
        (
            &rope,
            networks::entries::<{ networks::ROPE_PARTICLES }, { networks::ROPE_SPRINGS }>(&rope),
        ),
        (
            &jelly,
            networks::entries::<{ networks::JELLY_PARTICLES }, { networks::JELLY_SPRINGS }>(&jelly),
        ),
    ] {
        let pending = entries
            .into_iter()
            .map(|e| Pending {
                scene: net.name.into(),
                implementation: e.implementation,
                backend: e.backend.into(),
                step_hz: net.rate,
                error: e.error,
                candidate: e.candidate,
            })
            .collect();
        eprintln!("  {} at {} Hz", net.name, net.rate);
        rows.extend(time(pending, plan));
    }
    rows
}

fn knob_rows(plan: Plan) -> Vec<Row> {
    let mut rows = Vec::new();
    for rate in knob::RATES {
        let pending = knob::entries(rate)
            .into_iter()
            .map(|e| Pending {
                scene: "knob_torque".into(),
                implementation: "stiffspring".into(),
                backend: e.backend.into(),
                step_hz: rate,
                error: e.error,
                candidate: e.candidate,
            })
            .collect();
        eprintln!("  knob_torque at {rate} Hz");
        rows.extend(time(pending, plan));
    }
    rows
}

fn out_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("pareto")
}

fn csv(rows: &[Row]) -> String {
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.scene.clone(),
                r.implementation.clone(),
                r.backend.clone(),
                r.step_hz.to_string(),
                format!("{:.3}", r.ns_per_step),
                format!("{:.3e}", r.max_rel_error),
            ]
        })
        .collect();
    lab::table::csv(
        &[
            "scene",
            "implementation",
            "backend",
            "step_hz",
            "ns_per_step",
            "max_rel_error",
        ],
        &cells,
    )
}

/// The top of the error axis: a diverged run (an unstable kernel, the ζ = 1 bug of a
/// peer) is drawn there, labelled, instead of stretching the axis over 150 decades.
const CEILING: f64 = 10.0;

/// One panel per scene and rate. The 1D scenes group points by implementation (a colour
/// each) labelled with the backend; the networks and the knob by backend, labelled with
/// the implementation.
fn svg(rows: &[Row]) -> String {
    let mut panels: BTreeMap<(usize, String, u64), Vec<&Row>> = BTreeMap::new();
    let order = |scene: &str| match scene {
        s if s.starts_with("step") => 0,
        s if s.starts_with("fling") => 1,
        "rope_64" => 2,
        "jelly_16x16" => 3,
        _ => 4,
    };
    for r in rows {
        panels
            .entry((order(&r.scene), r.scene.clone(), r.step_hz as u64))
            .or_default()
            .push(r);
    }
    let mut grid = Grid::new(
        "stiffspring against its peers: worst error against time per step (log-log, one run)",
    )
    .columns(4);
    for ((kind, scene, hz), rows) in panels {
        let by_implementation = kind <= 1;
        let mut groups: Vec<(String, Vec<&Row>)> = Vec::new();
        for r in rows {
            let key = if by_implementation {
                r.implementation.clone()
            } else {
                r.backend.clone()
            };
            match groups.iter_mut().find(|(k, _)| *k == key) {
                Some((_, v)) => v.push(r),
                None => groups.push((key, vec![r])),
            }
        }
        let unit = if kind == 2 || kind == 3 {
            "ns per spring step"
        } else {
            "ns per step"
        };
        let title = if scene == "knob_torque" {
            format!("{scene}, {hz} Hz (against f64, not drawn)")
        } else {
            format!("{scene}, {hz} Hz")
        };
        let mut plot = Plot::new(title)
            .x_label(unit)
            .y_label("max relative error")
            .log_x()
            .log_y()
            .size(520, 380);
        if kind <= 3 {
            plot = plot.y_range(1e-17, 10.0 * CEILING);
        }
        for (key, rows) in groups {
            let labels: Vec<String> = rows
                .iter()
                .map(|r| {
                    let label = if by_implementation {
                        r.backend.clone()
                    } else {
                        r.implementation
                            .trim_start_matches("stiffspring/")
                            .trim_start_matches("baseline/")
                            .to_string()
                    };
                    if r.max_rel_error > CEILING {
                        format!("{label} (diverged)")
                    } else {
                        label
                    }
                })
                .collect();
            let name = key.trim_start_matches("animato-spring/").to_string();
            let name = if key.starts_with("animato-spring/") {
                format!("animato {name}")
            } else {
                name
            };
            let points = rows
                .iter()
                .map(|r| (r.ns_per_step, r.max_rel_error.min(CEILING)));
            plot = plot.series(Series::markers(name, points).labels(labels));
        }
        grid = grid.plot(plot);
    }
    grid.render()
}

/// `a/b` as `0.42×`.
fn ratio(a: f64, b: f64) -> String {
    format!("{:.2}×", a / b)
}

/// The tables of ratios against each peer, for the terminal (and BENCHMARKS.md).
fn report(rows: &[Row]) {
    let find = |scene: &str, hz: f64, imp: &str, backend: &str| {
        rows.iter().find(|r| {
            r.scene == scene && r.step_hz == hz && r.implementation == imp && r.backend == backend
        })
    };
    println!(
        "\n1D value step: stiffspring's time and error against each peer's (same scene, same backend where the peer has it)"
    );
    println!(
        "| scene | Hz | vs damped-springs f64: time, error | vs damped-springs f32: time, error | vs animato semi-implicit (f32): time, error | vs animato rk4: time, error | vs spring_damper (f32): time, error |"
    );
    println!("|---|---|---|---|---|---|---|");
    for scene in ValueScene::all() {
        let (name, hz) = (scene.name(), scene.rate);
        let Some(ours64) = find(&name, hz, "stiffspring", "f64") else {
            continue;
        };
        let Some(ours32) = find(&name, hz, "stiffspring", "f32") else {
            continue;
        };
        let cell = |ours: &Row, imp: &str, backend: &str| match find(&name, hz, imp, backend) {
            Some(p) => format!(
                "{}, {:.1e} vs {:.1e}",
                ratio(ours.ns_per_step, p.ns_per_step),
                ours.max_rel_error,
                p.max_rel_error
            ),
            None => "–".into(),
        };
        println!(
            "| {name} | {hz} | {} | {} | {} | {} | {} |",
            cell(ours64, "damped-springs", "f64"),
            cell(ours32, "damped-springs", "f32"),
            cell(ours32, "animato-spring/semi-implicit-euler", "f32"),
            cell(ours32, "animato-spring/rk4", "f32"),
            cell(ours32, "spring_damper", "f32"),
        );
    }
    println!("\n(time ratios are stiffspring/peer: below 1× is faster; errors are ours vs theirs)");
    for scene in ["rope_64", "jelly_16x16"] {
        println!("\n{scene}: ns per spring step and error");
        println!("| implementation | backend | ns/spring | × minimal-gs f32 | error |");
        println!("|---|---|---|---|---|");
        let floor = rows
            .iter()
            .find(|r| {
                r.scene == scene && r.implementation == "baseline/minimal-gs" && r.backend == "f32"
            })
            .map(|r| r.ns_per_step)
            .unwrap_or(f64::NAN);
        for r in rows.iter().filter(|r| r.scene == scene) {
            println!(
                "| {} | {} | {:.2} | {} | {:.1e} |",
                r.implementation,
                r.backend,
                r.ns_per_step,
                ratio(r.ns_per_step, floor),
                r.max_rel_error
            );
        }
    }
    println!("\nknob_torque: ns per update and error (fraction of the torque limit)");
    println!("| Hz | backend | ns/update | error |");
    println!("|---|---|---|---|");
    for r in rows.iter().filter(|r| r.scene == "knob_torque") {
        println!(
            "| {} | {} | {:.2} | {:.1e} |",
            r.step_hz, r.backend, r.ns_per_step, r.max_rel_error
        );
    }
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (value_plan, network_plan) = if quick {
        (
            Plan {
                batch: Duration::from_micros(50),
                rounds: 5,
            },
            Plan {
                batch: Duration::from_micros(200),
                rounds: 3,
            },
        )
    } else {
        (
            Plan {
                batch: Duration::from_micros(200),
                rounds: 41,
            },
            Plan {
                batch: Duration::from_millis(2),
                rounds: 15,
            },
        )
    };
    eprintln!("pareto: measuring (interleaved medians; ratios hold, absolute ns move)");
    let mut rows = value_rows(value_plan);
    rows.extend(network_rows(network_plan));
    rows.extend(knob_rows(value_plan));

    let dir = out_dir();
    std::fs::create_dir_all(&dir).expect("create target/pareto");
    std::fs::write(dir.join("results.csv"), csv(&rows)).expect("write results.csv");
    std::fs::write(dir.join("pareto.svg"), svg(&rows)).expect("write pareto.svg");
    report(&rows);
    println!(
        "\nwrote {} and {}",
        dir.join("results.csv").display(),
        dir.join("pareto.svg").display()
    );
}
