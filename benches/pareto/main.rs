//! Run time against error, side by side with the peer crates, in one run.
//!
//! ```sh
//! cargo bench --bench pareto                        # everything, a few minutes
//! cargo bench --bench pareto -- --quick             # fewer rounds, for a smoke test
//! cargo bench --bench pareto -- --only targets,xpbd # some sections
//! cargo bench --bench pareto -- --no-count          # without the callgrind counts
//! ```
//!
//! Sections (`--only` takes a comma-separated list): `values` (the 1D scenes against the
//! peers), `targets` (the host cost targets of issue 12, `targets.rs`), `networks`,
//! `xpbd` (XPBD with small steps against stiffspring at equal cost, `xpbd.rs`), `knob`,
//! `precision` (the error-against-cost table of issue 10, `precision.rs`).
//!
//! Writes `target/pareto/results.csv` (columns
//! `scene,implementation,backend,step_hz,ns_per_step,max_rel_error`),
//! `target/pareto/pareto.svg` (error against time per step, log-log, one panel per scene
//! and step rate), `target/pareto/targets.csv`, `target/pareto/xpbd.csv`,
//! `target/pareto/xpbd.svg`, `target/pareto/precision.csv`, and the tables
//! docs/benchmarks.md includes (`target/pareto/targets.md`, `targets-detail.md`,
//! `values.md`, `values-instructions.md`, `xpbd-cost.md`, `xpbd.md`, `networks.md`,
//! `knob.md`, `precision.md`), and prints
//! the tables of
//! `docs/benchmarks.md`.
//!
//! Instruction counts: where Valgrind is installed, the bench runs itself again under
//! callgrind once per counted case (`--count <section> <case>…`, a mode for that only),
//! counting the instructions inside `lab::measure::counted`, which holds the stepping
//! loop and nothing else (see `lab::measure::callgrind` for the exact command). The
//! callgrind output files are kept in `target/pareto/callgrind/`.
//!
//! - Times are the fastest of interleaved batches (`lab::measure::fastest`) of one value
//!   step, one knob update, one spring of a network step (a scene step divided by its
//!   springs), one value step of a batch, or one frame. Every implementation of a scene
//!   is timed in the same process, round-robin, so the ratios hold on a noisy machine;
//!   absolute numbers move from run to run.
//! - `max_rel_error` is the worst deviation over the run from the analytic solution
//!   (1D scenes, `values.rs` and `lab::pareto`), from the f64 reference model (networks,
//!   `networks.rs`), or
//!   from the f64 knob (`knob.rs`), relative to the scene's amplitude.

mod knob;
mod networks;
mod precision;
mod targets;
mod values;
mod xpbd;

use lab::measure::{self, Candidate, Plan};
use lab::pareto::{BATCH, BatchScene, ValueScene};
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
    let ns = measure::fastest(&mut candidates, plan);
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

/// Instructions per step of every implementation of the 1D scenes released from rest at
/// 1 kHz (2000 steps per run, so the reset between runs is amortised), by callgrind:
/// `(scene, implementation, backend, instructions)`.
fn value_counts() -> Vec<(String, String, String, f64)> {
    let mut out = Vec::new();
    for (s, scene) in ValueScene::all().iter().enumerate() {
        if scene.rate != 1000.0 || scene.velocity != 0.0 {
            continue;
        }
        for (e, entry) in values::entries(scene).iter().enumerate() {
            if let Some(n) = count(&["values".into(), s.to_string(), e.to_string()]) {
                out.push((
                    scene.name(),
                    entry.implementation.to_string(),
                    entry.backend.to_string(),
                    n as f64 / scene.steps() as f64,
                ));
            }
        }
    }
    out
}

fn value_counts_report(counts: &[(String, String, String, f64)]) {
    println!("\n1D value step at 1 kHz: host instructions per step (callgrind)");
    println!("| scene | implementation | backend | instructions/step |");
    println!("|---|---|---|---|");
    for (scene, imp, backend, n) in counts {
        println!("| {scene} | {imp} | {backend} | {n:.1} |");
    }
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
/// The least and the largest of `values`; `(∞, −∞)` when there are none.
fn span(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

/// A [`span`] as text: both ends written by `f` and joined by `join`, one figure where
/// both ends write the same, `–` for an empty span.
fn span_text((lo, hi): (f64, f64), join: &str, f: impl Fn(f64) -> String) -> String {
    let (a, b) = (f(lo), f(hi));
    if lo > hi {
        "–".to_string()
    } else if a == b {
        a
    } else {
        format!("{a}{join}{b}")
    }
}

fn ratio(a: f64, b: f64) -> String {
    format!("{:.2}×", a / b)
}

/// The tables of ratios against each peer, for the terminal (and `docs/benchmarks.md`).
fn report(rows: &[Row]) {
    let find = |scene: &str, hz: f64, imp: &str, backend: &str| {
        rows.iter().find(|r| {
            r.scene == scene && r.step_hz == hz && r.implementation == imp && r.backend == backend
        })
    };
    if !rows.iter().any(|r| r.scene.starts_with("step")) {
        return network_report(rows);
    }
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
    network_report(rows);
}

/// The peers of section 2, each over the twelve scenes, as the Markdown table
/// docs/benchmarks.md includes (`target/pareto/values.md`): stiffspring's time over the
/// peer's, and both worst errors, per damping ratio.
fn values_summary(rows: &[Row]) -> String {
    const PEERS: [(&str, &str, &str); 5] = [
        ("damped-springs", "f64", "damped-springs 1.0.0, `f64`"),
        ("damped-springs", "f32", "damped-springs 1.0.0, `f32`"),
        (
            "animato-spring/semi-implicit-euler",
            "f32",
            "animato-spring 1.7.3, semi-implicit Euler (`f32`)",
        ),
        (
            "animato-spring/rk4",
            "f32",
            "animato-spring 1.7.3, RK4 (`f32`)",
        ),
        ("spring_damper", "f32", "spring_damper 0.1.1 (`f32`)"),
    ];
    let mut t = String::from(
        "| peer | ζ | time, stiffspring / peer | worst error, stiffspring | worst error, peer |\n\
         |---|---|---|---|---|\n",
    );
    for (imp, backend, name) in PEERS {
        for zeta in ["zeta0.3", "zeta1"] {
            // (stiffspring, peer) on each scene of this damping ratio.
            let pairs: Vec<(&Row, &Row)> = rows
                .iter()
                .filter(|p| p.implementation == imp && p.backend == backend)
                .filter(|p| p.scene.ends_with(zeta))
                .filter_map(|p| {
                    rows.iter()
                        .find(|o| {
                            o.scene == p.scene
                                && o.step_hz == p.step_hz
                                && o.implementation == "stiffspring"
                                && o.backend == backend
                        })
                        .map(|o| (o, p))
                })
                .collect();
            t.push_str(&format!(
                "| {name} | {} | {}× | {} | {} |\n",
                zeta.trim_start_matches("zeta"),
                span_text(
                    span(pairs.iter().map(|(o, p)| o.ns_per_step / p.ns_per_step)),
                    " to ",
                    |v| format!("{v:.2}")
                ),
                span_text(
                    span(pairs.iter().map(|(o, _)| o.max_rel_error)),
                    " to ",
                    |v| { format!("{v:.1e}") }
                ),
                span_text(
                    span(pairs.iter().map(|(_, p)| p.max_rel_error)),
                    " to ",
                    |v| { format!("{v:.1e}") }
                ),
            ));
        }
    }
    t
}

/// The host instructions per step of section 2 (`target/pareto/values-instructions.md`):
/// each implementation and backend over the 1 kHz scenes.
fn values_instructions(counts: &[(String, String, String, f64)]) -> String {
    let mut keys: Vec<(&str, &str)> = Vec::new();
    for (_, imp, backend, _) in counts {
        if !keys.contains(&(imp.as_str(), backend.as_str())) {
            keys.push((imp, backend));
        }
    }
    let mut t =
        String::from("| implementation | backend | instructions per step |\n|---|---|---|\n");
    for (imp, backend) in keys {
        let n = span_text(
            span(
                counts
                    .iter()
                    .filter(|(_, i, b, _)| i == imp && b == backend)
                    .map(|c| c.3),
            ),
            " to ",
            |v| format!("{v:.1}"),
        );
        t.push_str(&format!("| {imp} | `{backend}` | {n} |\n"));
    }
    t
}

/// Section 5's tables, as docs/benchmarks.md includes them: each network's
/// implementations with one column per backend (`target/pareto/networks.md`: time per
/// spring step and error, "diverges" where the error is not finite or above the size),
/// and the knob's update time and worst torque difference from the `f64` knob
/// (`target/pareto/knob.md`).
fn networks_summary(rows: &[Row]) -> (String, String) {
    const BACKENDS: [&str; 4] = ["f64", "f32", "I32F32", "I16F16"];
    let mut t = String::from(
        "| scene | implementation | `f64` | `f32` | `I32F32` | `I16F16` |\n|---|---|---|---|---|---|\n",
    );
    for scene in ["rope_64", "jelly_16x16"] {
        let mut implementations: Vec<&str> = Vec::new();
        for r in rows.iter().filter(|r| r.scene == scene) {
            if !implementations.contains(&r.implementation.as_str()) {
                implementations.push(&r.implementation);
            }
        }
        for imp in implementations {
            let cells: Vec<String> = BACKENDS
                .iter()
                .map(|b| {
                    match rows
                        .iter()
                        .find(|r| r.scene == scene && r.implementation == imp && r.backend == *b)
                    {
                        None => String::new(),
                        Some(r) if r.max_rel_error.is_nan() || r.max_rel_error > 1.0 => {
                            "diverges".into()
                        }
                        Some(r) => format!("{:.1} ns, {:.1e}", r.ns_per_step, r.max_rel_error),
                    }
                })
                .collect();
            t.push_str(&format!("| {scene} | {imp} | {} |\n", cells.join(" | ")));
        }
    }
    let mut k = String::from(
        "| rate | backend | time per update | worst torque difference from the `f64` knob |\n|---|---|---|---|\n",
    );
    for r in rows.iter().filter(|r| r.scene == "knob_torque") {
        k.push_str(&format!(
            "| {} Hz | `{}` | {:.1} ns | {:.1e} |\n",
            r.step_hz, r.backend, r.ns_per_step, r.max_rel_error
        ));
    }
    (t, k)
}

/// The networks' and the knob's tables.
fn network_report(rows: &[Row]) {
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

/// The bench's options.
struct Options {
    quick: bool,
    count: bool,
    only: Option<Vec<String>>,
}

impl Options {
    fn parse(args: &[String]) -> Options {
        let only = args
            .iter()
            .position(|a| a == "--only")
            .and_then(|i| args.get(i + 1))
            .map(|v| v.split(',').map(str::to_string).collect());
        Options {
            quick: args.iter().any(|a| a == "--quick"),
            count: !args.iter().any(|a| a == "--no-count"),
            only,
        }
    }

    fn runs(&self, section: &str) -> bool {
        self.only
            .as_ref()
            .is_none_or(|o| o.iter().any(|s| s == section))
    }
}

/// The callgrind child: `--count <section> <case…>` runs one case inside
/// `lab::measure::counted` and exits.
fn child(args: &[String]) {
    let index = |i: usize| -> usize { args[i].parse().expect("case index") };
    match args[0].as_str() {
        "targets" => {
            let scene = BatchScene::all()[index(1)];
            targets::each(&scene, Some(index(2)), &mut targets::Count(&scene));
        }
        "xpbd" => {
            let model = &xpbd::models()[index(1)];
            xpbd::each(
                index(1),
                &args[2],
                Some(index(3)),
                &mut xpbd::Count(model.frames),
            );
        }
        "precision" => precision::count(index(1), index(2)),
        "values" => {
            let scene = ValueScene::all()[index(1)];
            let mut entries = values::entries(&scene);
            let entry = &mut entries[index(2)];
            measure::counted(&mut || {
                (entry.candidate.batch)(1);
            });
        }
        other => panic!("no countable section {other}"),
    }
}

/// The instructions of one counted case: the bench run again under callgrind with
/// `--count <case…>`. `None` without Valgrind.
fn count(case: &[String]) -> Option<u64> {
    let exe = std::env::current_exe().ok()?;
    let dir = out_dir().join("callgrind");
    std::fs::create_dir_all(&dir).ok()?;
    let out = dir.join(format!("{}.out", case.join("_")));
    let mut args = vec!["--count".to_string()];
    args.extend(case.iter().cloned());
    measure::callgrind(&exe, &args, &out)
}

/// One row of `targets.csv`.
struct TargetRow {
    scene: String,
    step_hz: f64,
    implementation: &'static str,
    bytes: usize,
    ns: f64,
    instructions: Option<f64>,
    error: f64,
}

fn target_rows(plan: Plan, counting: bool) -> Vec<TargetRow> {
    let mut rows = Vec::new();
    for (s, scene) in BatchScene::all().iter().enumerate() {
        eprintln!("  targets: {} at {} Hz", scene.name(), scene.rate);
        let mut collect = targets::Collect(scene, Vec::new());
        targets::each(scene, None, &mut collect);
        let (meta, mut candidates): (Vec<_>, Vec<_>) = collect
            .1
            .into_iter()
            .map(|p| ((p.implementation, p.bytes, p.error), p.candidate))
            .unzip();
        let ns = measure::fastest(&mut candidates, plan);
        for (i, ((implementation, bytes, error), ns)) in meta.into_iter().zip(ns).enumerate() {
            let instructions = if counting {
                count(&["targets".into(), s.to_string(), i.to_string()])
                    .map(|n| n as f64 / (scene.frames() * BATCH) as f64)
            } else {
                None
            };
            rows.push(TargetRow {
                scene: scene.name(),
                step_hz: scene.rate,
                implementation,
                bytes,
                ns,
                instructions,
                error,
            });
        }
    }
    rows
}

fn targets_csv(rows: &[TargetRow]) -> String {
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.scene.clone(),
                r.step_hz.to_string(),
                r.implementation.to_string(),
                r.bytes.to_string(),
                format!("{:.4}", r.ns),
                r.instructions.map_or(String::new(), |i| format!("{i:.2}")),
                format!("{:.3e}", r.error),
            ]
        })
        .collect();
    lab::table::csv(
        &[
            "scene",
            "step_hz",
            "implementation",
            "bytes_per_value",
            "ns_per_value_step",
            "instructions_per_value_step",
            "max_rel_error",
        ],
        &cells,
    )
}

/// The targets table and the goals of issues 12 and 21, for the terminal; returns the
/// goals' table (`target/pareto/targets.md`).
fn targets_report(rows: &[TargetRow]) -> String {
    let instr = |r: &TargetRow| r.instructions.map_or("–".into(), |i| format!("{i:.1}"));
    println!("\nHost cost targets (issue 12): {BATCH} f32 values stepped frame by frame");
    println!(
        "| scene | Hz | implementation | bytes/value | ns/value step | × minimal | instructions/value step | error |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let find = |scene: &str, hz: f64, imp: &str| {
        rows.iter()
            .find(|r| r.scene == scene && r.step_hz == hz && r.implementation == imp)
    };
    for r in rows {
        let floor = find(&r.scene, r.step_hz, "minimal").map_or(f64::NAN, |m| m.ns);
        println!(
            "| {} | {} | {} | {} | {:.3} | {} | {} | {:.1e} |",
            r.scene,
            r.step_hz,
            r.implementation,
            r.bytes,
            r.ns,
            ratio(r.ns, floor),
            instr(r),
            r.error
        );
    }
    // The goals, over every scene: the worst case of each.
    let over = |imp: &str, f: &dyn Fn(&TargetRow) -> Option<f64>| -> (f64, f64) {
        span(
            rows.iter()
                .filter(|r| r.implementation == imp)
                .filter_map(f),
        )
    };
    let range = |s: (f64, f64), digits: usize| span_text(s, "–", |v| format!("{v:.digits$}"));
    let versus = |imp: &str, base: &str, f: &dyn Fn(&TargetRow, &TargetRow) -> f64| {
        over(imp, &|r| find(&r.scene, r.step_hz, base).map(|b| f(r, b)))
    };
    let goals = targets_goals(&over, &range, &versus);
    println!("\n{goals}");
    goals
}

/// The implementations of the targets section, each over the six scenes, as the
/// Markdown table docs/benchmarks.md includes (`target/pareto/targets-detail.md`):
/// bytes per value, instructions and time per value step, the time over the minimal
/// kernel's on the same scene, and the worst error.
fn targets_detail(rows: &[TargetRow]) -> String {
    const NAMES: [(&str, &str); 7] = [
        (
            "minimal",
            "minimal kernel: `u = r·u − k·x; x += u` over two `f32` arrays",
        ),
        (
            "value/advance",
            "`SpringValue::<f32, 1>::advance` (no rest test)",
        ),
        ("value/step", "`SpringValue::<f32, 1>::step` (rest test on)"),
        ("batch/advance", "`SpringBatch::<f32, 1, 1000>::advance`"),
        ("batch/step", "`SpringBatch::<f32, 1, 1000>::step`"),
        ("damped-springs", "damped-springs 1.0.0 (`f32`)"),
        (
            "animato/semi-implicit-euler",
            "animato-spring 1.7.3, semi-implicit Euler",
        ),
    ];
    let over = |imp: &str, f: &dyn Fn(&TargetRow) -> Option<f64>| {
        span(
            rows.iter()
                .filter(|r| r.implementation == imp)
                .filter_map(f),
        )
    };
    let shown = |s: (f64, f64), f: &dyn Fn(f64) -> String| span_text(s, " to ", f);
    let minimal = |r: &TargetRow| {
        rows.iter()
            .find(|m| m.scene == r.scene && m.step_hz == r.step_hz && m.implementation == "minimal")
            .map(|m| r.ns / m.ns)
    };
    let mut t = String::from(
        "| implementation | bytes per value | instructions per value step | time per value step | × minimal | worst error |\n\
         |---|---|---|---|---|---|\n",
    );
    for (imp, name) in NAMES {
        let bytes = over(imp, &|r| Some(r.bytes as f64));
        t.push_str(&format!(
            "| {name} | {} | {} | {} ns | {}× | {} |\n",
            shown(bytes, &|v| format!("{v:.0}")),
            shown(over(imp, &|r| r.instructions), &|v| format!("{v:.1}")),
            shown(over(imp, &|r| Some(r.ns)), &|v| format!("{v:.2}")),
            shown(over(imp, &minimal), &|v| format!("{v:.1}")),
            shown(over(imp, &|r| Some(r.error)), &|v| format!("{v:.1e}")),
        ));
    }
    t
}

/// The range `(lo, hi)` over the six scenes of a figure of one implementation.
type Over<'a> = &'a dyn Fn(&str, &dyn Fn(&TargetRow) -> Option<f64>) -> (f64, f64);
/// The range of a figure of one implementation against another on the same scene.
type Versus<'a> = &'a dyn Fn(&str, &str, &dyn Fn(&TargetRow, &TargetRow) -> f64) -> (f64, f64);

/// The goals of issues 12 and 21 against the targets section, as the Markdown table
/// docs/benchmarks.md includes (`target/pareto/targets.md`).
fn targets_goals(
    over: Over<'_>,
    range: &dyn Fn((f64, f64), usize) -> String,
    versus: Versus<'_>,
) -> String {
    let met = |ok: bool| if ok { "✓" } else { "✗" };
    let mut t = String::new();
    t.push_str("| target | goal | measured, over the six scenes | |\n|---|---|---|---|\n");
    let advance = over("value/advance", &|r| r.instructions);
    let advance_time = versus("value/advance", "minimal", &|r, b| r.ns / b.ns);
    t.push_str(&format!(
        "| f32 value, no rest detection (`advance`) | ≤ 15 instructions/step (issue 12) | {} instructions ({}× the minimal kernel's time) | {} |\n",
        range(advance, 1),
        range(advance_time, 2),
        met(advance.1 <= 15.0)
    ));
    let step = over("value/step", &|r| r.instructions);
    t.push_str(&format!(
        "| f32 value, rest detection on (`step`) | ≤ 15 instructions/step (issue 21) | {} | {} |\n",
        range(step, 1),
        met(step.1 <= 15.0)
    ));
    let speed = versus("value/step", "animato/semi-implicit-euler", &|r, b| {
        b.ns / r.ns
    });
    let error = versus("value/step", "animato/semi-implicit-euler", &|r, b| {
        b.error / r.error
    });
    t.push_str(&format!(
        "| f32 value (`step`) against animato's semi-implicit Euler | ≥ 5× faster (issue 21) at ≥ 1000× lower error | {}× faster, {}× lower error | {} |\n",
        range(speed, 2),
        range(error, 0),
        met(speed.0 >= 5.0 && error.0 >= 1000.0)
    ));
    let batch = over("batch/step", &|r| r.instructions);
    t.push_str(&format!(
        "| batch (`step`) | ≤ 15 instructions per value (issue 12) | {} (`advance`: {}) | {} |",
        range(batch, 1),
        range(over("batch/advance", &|r| r.instructions), 1),
        met(batch.1 <= 15.0)
    ));
    t
}

/// One row of `xpbd.csv`.
struct XpbdRow {
    scene: &'static str,
    implementation: &'static str,
    backend: &'static str,
    substeps: usize,
    clamped: usize,
    ns_per_frame: f64,
    instructions_per_frame: Option<f64>,
    error: f64,
}

/// The reference of every model and its own error (against the run at half its step).
fn xpbd_rows(plan: Plan, counting: bool) -> (Vec<XpbdRow>, Vec<(&'static str, f64)>) {
    let mut rows = Vec::new();
    let mut references = Vec::new();
    for (m, model) in xpbd::models().iter().enumerate() {
        eprintln!(
            "  xpbd: {} reference at {} steps per frame",
            model.name,
            xpbd::REFERENCE_SUBSTEPS
        );
        let reference = model.reference(xpbd::REFERENCE_SUBSTEPS);
        let half = model.reference(xpbd::REFERENCE_SUBSTEPS / 2);
        references.push((model.name, model.error(&half, &reference)));
        for backend in ["f32", "f64"] {
            eprintln!("  xpbd: {} in {backend}", model.name);
            let mut collect = xpbd::Collect {
                model,
                reference: &reference,
                rows: Vec::new(),
            };
            xpbd::each(m, backend, None, &mut collect);
            let (meta, mut candidates): (Vec<_>, Vec<_>) = collect
                .rows
                .into_iter()
                .map(|p| {
                    (
                        (p.index, p.implementation, p.substeps, p.clamped, p.error),
                        p.candidate,
                    )
                })
                .unzip();
            let ns = measure::fastest(&mut candidates, plan);
            for ((index, implementation, substeps, clamped, error), ns) in meta.into_iter().zip(ns)
            {
                let instructions = if counting {
                    count(&[
                        "xpbd".into(),
                        m.to_string(),
                        backend.into(),
                        index.to_string(),
                    ])
                    .map(|n| n as f64 / model.frames as f64)
                } else {
                    None
                };
                rows.push(XpbdRow {
                    scene: model.name,
                    implementation,
                    backend,
                    substeps,
                    clamped,
                    ns_per_frame: ns,
                    instructions_per_frame: instructions,
                    error,
                });
            }
        }
    }
    (rows, references)
}

fn xpbd_csv(rows: &[XpbdRow]) -> String {
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.scene.to_string(),
                r.implementation.to_string(),
                r.backend.to_string(),
                r.substeps.to_string(),
                r.clamped.to_string(),
                format!("{:.1}", r.ns_per_frame),
                r.instructions_per_frame
                    .map_or(String::new(), |i| format!("{i:.0}")),
                format!("{:.3e}", r.error),
            ]
        })
        .collect();
    lab::table::csv(
        &[
            "scene",
            "implementation",
            "backend",
            "substeps",
            "clamped",
            "ns_per_frame",
            "instructions_per_frame",
            "max_rel_error",
        ],
        &cells,
    )
}

/// The cost of a row by `metric`: callgrind's instructions per frame (`None` if not
/// counted) or the time of a frame.
fn xpbd_cost(r: &XpbdRow, metric: Metric) -> Option<f64> {
    match metric {
        Metric::Instructions => r.instructions_per_frame,
        Metric::Time => Some(r.ns_per_frame),
    }
}

/// What "equal cost" means.
#[derive(Clone, Copy, PartialEq)]
enum Metric {
    Instructions,
    Time,
}

/// Section 3's two tables, as docs/benchmarks.md includes them: the cost of one substep
/// per spring (`target/pareto/xpbd-cost.md`: from the runs at 32 and 64 substeps, whose
/// difference is 32 substeps of every spring), and XPBD's error at 2, 8, 32 and 64
/// substeps against stiffspring's (`exact`) at the same instructions and the same time,
/// in `f32` (`target/pareto/xpbd.md`).
fn xpbd_summary(rows: &[XpbdRow]) -> (String, String) {
    let springs = |scene: &str| {
        xpbd::models()
            .iter()
            .find(|m| m.name == scene)
            .map_or(f64::NAN, |m| m.links.len() as f64)
    };
    let row = |scene: &str, backend: &str, imp: &str, n: usize| {
        rows.iter().find(|r| {
            r.scene == scene && r.backend == backend && r.implementation == imp && r.substeps == n
        })
    };
    let mut cost = String::from("| scene | backend | XPBD | stiffspring |\n|---|---|---|---|\n");
    for scene in xpbd::MODELS {
        for backend in ["f32", "f64"] {
            let cell = |imp: &str| {
                let (Some(a), Some(b)) =
                    (row(scene, backend, imp, 32), row(scene, backend, imp, 64))
                else {
                    return "–".to_string();
                };
                let per = 32.0 * springs(scene);
                let instructions = match (a.instructions_per_frame, b.instructions_per_frame) {
                    (Some(a), Some(b)) => format!("{:.0} instructions, ", (b - a) / per),
                    _ => String::new(),
                };
                format!(
                    "{instructions}{:.1} ns",
                    (b.ns_per_frame - a.ns_per_frame) / per
                )
            };
            cost.push_str(&format!(
                "| {scene} | `{backend}` | {} | {} |\n",
                cell("xpbd"),
                cell("stiffspring/exact")
            ));
        }
    }
    let mut errors = String::from(
        "| scene | XPBD substeps | XPBD error | stiffspring, equal instructions | stiffspring, equal time |\n\
         |---|---|---|---|---|\n",
    );
    for scene in xpbd::MODELS {
        let curve = |metric: Metric| -> Vec<(f64, f64)> {
            let mut c: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.scene == scene && r.backend == "f32")
                .filter(|r| r.implementation == "stiffspring/exact" && r.error.is_finite())
                .filter_map(|r| Some((xpbd_cost(r, metric)?, r.error)))
                .collect();
            c.sort_by(|a, b| a.0.total_cmp(&b.0));
            c
        };
        let (by_instructions, by_time) = (curve(Metric::Instructions), curve(Metric::Time));
        for n in [2, 8, 32, 64] {
            let Some(x) = row(scene, "f32", "xpbd", n) else {
                continue;
            };
            let at = |c: &[(f64, f64)], metric: Metric| {
                xpbd_cost(x, metric)
                    .and_then(|cost| at_cost(c, cost))
                    .map_or("(beyond the measured substeps)".to_string(), |e| {
                        format!("{e:.1e}")
                    })
            };
            errors.push_str(&format!(
                "| {scene} | {n} | {:.1e} | {} | {} |\n",
                x.error,
                at(&by_instructions, Metric::Instructions),
                at(&by_time, Metric::Time)
            ));
        }
    }
    (cost, errors)
}

/// `curve`'s error at `cost`, interpolated log-log between the two points around it
/// (`curve` sorted by cost, finite errors only); `None` outside the curve.
fn at_cost(curve: &[(f64, f64)], cost: f64) -> Option<f64> {
    let i = curve.iter().position(|&(c, _)| c >= cost)?;
    if curve[i].0 == cost {
        return Some(curve[i].1);
    }
    let (c1, e1) = curve[i.checked_sub(1)?];
    let (c2, e2) = curve[i];
    let t = (cost.ln() - c1.ln()) / (c2.ln() - c1.ln());
    Some((e1.ln() + t * (e2.ln() - e1.ln())).exp())
}

fn xpbd_svg(rows: &[XpbdRow]) -> String {
    let counted = rows.iter().any(|r| r.instructions_per_frame.is_some());
    let (metric, unit) = if counted {
        (Metric::Instructions, "instructions per frame (callgrind)")
    } else {
        (Metric::Time, "ns per frame")
    };
    let mut grid =
        Grid::new("XPBD (small steps) against stiffspring: worst error against cost per frame")
            .columns(2);
    for scene in xpbd::MODELS {
        for backend in ["f32", "f64"] {
            let mut plot = Plot::new(format!("{scene}, {backend}"))
                .x_label(unit)
                .y_label("max relative error")
                .log_x()
                .log_y()
                .size(560, 400);
            for imp in ["xpbd", "stiffspring/exact", "stiffspring/raw"] {
                let points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.scene == scene && r.backend == backend && r.implementation == imp)
                    .filter(|r| r.error.is_finite() && r.error < CEILING)
                    .filter_map(|r| Some((xpbd_cost(r, metric)?, r.error)))
                    .collect();
                let series = Series::line(imp, points);
                plot = plot.series(series);
            }
            grid = grid.plot(plot);
        }
    }
    grid.render()
}

/// The XPBD tables: every run, then XPBD and stiffspring compared at equal cost.
fn xpbd_report(rows: &[XpbdRow], references: &[(&'static str, f64)]) {
    println!(
        "\nXPBD with small steps against stiffspring (error against the f64 reference, relative to the size)"
    );
    for (scene, e) in references {
        println!(
            "{scene}: reference at {} steps per frame, its own error (against half as many) {e:.1e}",
            xpbd::REFERENCE_SUBSTEPS
        );
    }
    println!(
        "| scene | backend | substeps | implementation | clamped springs | ns/frame | instructions/frame | error |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for r in rows {
        println!(
            "| {} | {} | {} | {} | {} | {:.0} | {} | {:.1e} |",
            r.scene,
            r.backend,
            r.substeps,
            r.implementation,
            r.clamped,
            r.ns_per_frame,
            r.instructions_per_frame
                .map_or("–".into(), |i| format!("{i:.0}")),
            r.error
        );
    }
    println!(
        "\nAt equal cost: each XPBD point against stiffspring's error at the same cost, interpolated log-log between its substep counts"
    );
    println!(
        "| scene | backend | cost | XPBD substeps | cost per frame | XPBD error | stiffspring/exact error | stiffspring/raw error | best |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for metric in [Metric::Instructions, Metric::Time] {
        let unit = match metric {
            Metric::Instructions => "instructions",
            Metric::Time => "time (ns)",
        };
        for scene in xpbd::MODELS {
            for backend in ["f32", "f64"] {
                let here = |r: &&XpbdRow| r.scene == scene && r.backend == backend;
                let curve = |imp: &str| -> Vec<(f64, f64)> {
                    let mut c: Vec<(f64, f64)> = rows
                        .iter()
                        .filter(here)
                        .filter(|r| r.implementation == imp && r.error.is_finite())
                        .filter_map(|r| Some((xpbd_cost(r, metric)?, r.error)))
                        .collect();
                    c.sort_by(|a, b| a.0.total_cmp(&b.0));
                    c
                };
                let (exact, raw) = (curve("stiffspring/exact"), curve("stiffspring/raw"));
                for r in rows
                    .iter()
                    .filter(here)
                    .filter(|r| r.implementation == "xpbd")
                {
                    let Some(cost) = xpbd_cost(r, metric) else {
                        continue;
                    };
                    let (e, w) = (at_cost(&exact, cost), at_cost(&raw, cost));
                    let cell = |v: Option<f64>| v.map_or("–".into(), |v| format!("{v:.1e}"));
                    // A winner only where stiffspring was measured at this cost.
                    let best = match (e, w) {
                        (Some(e), Some(w)) => [
                            ("xpbd", r.error),
                            ("stiffspring/exact", e),
                            ("stiffspring/raw", w),
                        ]
                        .into_iter()
                        .min_by(|a, b| a.1.total_cmp(&b.1))
                        .map_or("–", |b| b.0),
                        _ => "–",
                    };
                    println!(
                        "| {scene} | {backend} | {unit} | {} | {:.0} | {:.1e} | {} | {} | {best} |",
                        r.substeps,
                        cost,
                        r.error,
                        cell(e),
                        cell(w),
                    );
                }
            }
        }
    }
}

fn precision_rows(plan: Plan, quick: bool, counting: bool) -> Vec<precision::Row> {
    eprintln!("  precision: the study's grid at 60 Hz, 1 kHz and 10 kHz");
    let runs = precision::runs(quick);
    let mut rows = Vec::new();
    for (b, &backend) in precision::BACKENDS.iter().enumerate() {
        eprintln!("  precision: {} cost", backend.name());
        let all = lab::precision::candidates(backend);
        let mut candidates: Vec<Candidate> = all
            .iter()
            .map(|&c| precision::candidate(backend, c))
            .collect();
        candidates.push(precision::library(backend));
        let ns = measure::fastest(&mut candidates, plan);
        for (c, ns) in ns.into_iter().enumerate() {
            let (candidate, (errors, rejected)) = match all.get(c) {
                Some(&cand) => (cand.name(), precision::errors(&runs, backend, cand)),
                None => ("kept (library kernel)".to_string(), ([None; 3], 0)),
            };
            let instructions = if counting {
                count(&["precision".into(), b.to_string(), c.to_string()])
                    .map(|n| n as f64 / precision::STEPS as f64)
            } else {
                None
            };
            rows.push(precision::Row {
                backend: backend.name(),
                candidate,
                errors,
                rejected,
                instructions,
                ns,
            });
        }
    }
    rows
}

fn precision_csv(rows: &[precision::Row]) -> String {
    let e = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.3e}"));
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.backend.to_string(),
                r.candidate.clone(),
                e(r.errors[0]),
                e(r.errors[1]),
                e(r.errors[2]),
                r.rejected.to_string(),
                r.instructions.map_or(String::new(), |i| format!("{i:.2}")),
                format!("{:.3}", r.ns),
            ]
        })
        .collect();
    lab::table::csv(
        &[
            "backend",
            "candidate",
            "max_rel_error_60hz",
            "max_rel_error_1khz",
            "max_rel_error_10khz",
            "rejected_starts",
            "host_instructions_per_step",
            "host_ns_per_step",
        ],
        &cells,
    )
}

/// The precision table docs/benchmarks.md includes (`target/pareto/precision.md`): every
/// representation's worst error at each rate, the starts it rejects, and its model's host
/// instructions per step (the time, which moves from run to run, is in the CSV).
fn precision_summary(rows: &[precision::Row]) -> String {
    let e = |v: Option<f64>| v.map_or("–".into(), |v| format!("{v:.1e}"));
    let mut t = String::from(
        "| backend | representation | 60 Hz | 1 kHz | 10 kHz | starts rejected | host instructions per step |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        t.push_str(&format!(
            "| `{}` | `{}` | {} | {} | {} | {} | {} |\n",
            r.backend,
            r.candidate,
            e(r.errors[0]),
            e(r.errors[1]),
            e(r.errors[2]),
            r.rejected,
            r.instructions.map_or("–".into(), |i| format!("{i:.1}")),
        ));
    }
    t
}

fn precision_report(rows: &[precision::Row]) {
    println!(
        "\nPrecision (issue 10): worst error over the study's grid at each rate, and the host cost of a step of the study's model (host times in precision.csv)"
    );
    print!("{}", precision_summary(rows));
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(i) = args.iter().position(|a| a == "--count") {
        child(&args[i + 1..]);
        return;
    }
    let options = Options::parse(&args);
    let (value_plan, network_plan) = if options.quick {
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
    let counting = options.count && !options.quick;
    eprintln!("pareto: measuring (interleaved, fastest batch; ratios hold, absolute ns move)");
    let dir = out_dir();
    std::fs::create_dir_all(&dir).expect("create target/pareto");
    let mut written = Vec::new();

    let mut rows = Vec::new();
    if options.runs("values") {
        rows.extend(value_rows(value_plan));
    }
    if options.runs("networks") {
        rows.extend(network_rows(network_plan));
    }
    if options.runs("knob") {
        rows.extend(knob_rows(value_plan));
    }
    if !rows.is_empty() {
        std::fs::write(dir.join("results.csv"), csv(&rows)).expect("write results.csv");
        std::fs::write(dir.join("pareto.svg"), svg(&rows)).expect("write pareto.svg");
        written.extend(["results.csv", "pareto.svg"]);
        report(&rows);
        if options.runs("values") {
            std::fs::write(dir.join("values.md"), values_summary(&rows)).expect("write values.md");
            written.push("values.md");
        }
        if options.runs("networks") && options.runs("knob") {
            let (networks, knob) = networks_summary(&rows);
            std::fs::write(dir.join("networks.md"), networks).expect("write networks.md");
            std::fs::write(dir.join("knob.md"), knob).expect("write knob.md");
            written.extend(["networks.md", "knob.md"]);
        }
    }
    if counting && options.runs("values") {
        let counts = value_counts();
        value_counts_report(&counts);
        std::fs::write(
            dir.join("values-instructions.md"),
            values_instructions(&counts),
        )
        .expect("write values-instructions.md");
        written.push("values-instructions.md");
    }
    if options.runs("xpbd") {
        let (rows, references) = xpbd_rows(network_plan, counting);
        std::fs::write(dir.join("xpbd.csv"), xpbd_csv(&rows)).expect("write xpbd.csv");
        std::fs::write(dir.join("xpbd.svg"), xpbd_svg(&rows)).expect("write xpbd.svg");
        written.extend(["xpbd.csv", "xpbd.svg"]);
        xpbd_report(&rows, &references);
        let (cost, errors) = xpbd_summary(&rows);
        std::fs::write(dir.join("xpbd-cost.md"), cost).expect("write xpbd-cost.md");
        std::fs::write(dir.join("xpbd.md"), errors).expect("write xpbd.md");
        written.extend(["xpbd-cost.md", "xpbd.md"]);
    }
    if options.runs("precision") {
        let rows = precision_rows(value_plan, options.quick, counting);
        std::fs::write(dir.join("precision.csv"), precision_csv(&rows))
            .expect("write precision.csv");
        written.push("precision.csv");
        precision_report(&rows);
        std::fs::write(dir.join("precision.md"), precision_summary(&rows))
            .expect("write precision.md");
        written.push("precision.md");
    }
    if options.runs("targets") {
        let rows = target_rows(value_plan, counting);
        std::fs::write(dir.join("targets.csv"), targets_csv(&rows)).expect("write targets.csv");
        written.push("targets.csv");
        let goals = targets_report(&rows);
        std::fs::write(dir.join("targets.md"), goals + "\n").expect("write targets.md");
        written.push("targets.md");
        std::fs::write(dir.join("targets-detail.md"), targets_detail(&rows))
            .expect("write targets-detail.md");
        written.push("targets-detail.md");
    }
    for file in written {
        println!("wrote {}", dir.join(file).display());
    }
}
