//! The sweep of issue 13 (the rotor, the grids and the oscillation metric are in
//! `lab/src/knob/sweep.rs`): the knob in closed loop with an independent rotor model, over
//! the grid, with the inertia misestimated ×½ and ×2, encoders of 10–16 bits,
//! delays of 0 and 1 period and the endstop cases.
//!
//! - `cargo test --release --test knob_sweep -- --nocapture`: the short grid, in `f64`,
//!   `f32` and `I16F16`;
//! - `cargo test --release --test knob_sweep -- --ignored --nocapture`: the full grid in
//!   `f64` (12,960 configurations, 204,120 runs of 1 s; `full_sweep_has_no_oscillating_configuration`
//!   is ignored in a plain `cargo test` for its minutes of run time).

use lab::knob::sweep::{Case, ENDSTOPS, FULL, Grid, Rotor, SHORT, Totals, counts, plant_delays};
use std::f64::consts::TAU;
use stiffspring::knob::Latency;
use stiffspring::{I16F16, Knob, KnobConfig, Scalar};

/// The configuration of a case, with the detent stiffness a fraction of the stiffest the
/// `f64` knob accepts (`None` when nothing is accepted).
fn config(c: &Case) -> Option<KnobConfig> {
    let latency = if c.latency == 1 {
        Latency::OneStep
    } else {
        Latency::SameStep
    };
    let base = KnobConfig::new(c.rate, c.inertia, c.limit, 1 << c.bits)
        .latency(latency)
        .damping_ratio(c.zeta);
    let base = if c.endstops {
        // SmartKnob's bounded knob: endstops at ±135°, the last detent on each stop.
        base.endstops(ENDSTOPS.0, ENDSTOPS.1)
            .detent_count(c.detents)
    } else {
        base.detent_width(TAU / f64::from(c.detents))
    };
    let top = base.detent_stiffness_limit::<f64>().ok()?;
    (top > 0.0).then(|| base.detent_stiffness(c.strength * top))
}

/// Runs the sweep of `grid` on backend `S`, `seconds` per run.
fn sweep<S: Scalar>(grid: &Grid, seconds: f64) -> Totals {
    let mut t = Totals::default();
    for c in grid.cases() {
        t.configs += 1;
        let Some(config) = config(&c) else {
            t.rejected += 1;
            continue;
        };
        let count = c.count();
        for (theta0, omega0) in lab::knob::sweep::starts(&c) {
            for &delay in plant_delays(c.latency) {
                for &m in grid.mismatch {
                    let reading = S::from_f64(counts(theta0, count) as f64 * count);
                    // The stiffness limit is the f64 knob's; a backend that cannot hold
                    // the gains refuses the configuration (a typed error), counted apart.
                    let Ok(mut knob) = Knob::<S>::new(&config, reading) else {
                        t.backend_rejected += 1;
                        continue;
                    };
                    let mut rotor = Rotor::new(c.inertia * m, 1.0 / c.rate, delay, theta0, omega0);
                    let r = lab::knob::sweep::run(&mut rotor, count, c.limit, seconds, |a| {
                        let out = knob.update(S::from_f64(a));
                        (out.torque.to_f64(), out.events.endstop_hit.is_some())
                    });
                    t.record(&r, || {
                        format!(
                            "{c:?}, delay {delay}, J×{m}, start {theta0:.4} rad, {omega0} rad/s"
                        )
                    });
                }
            }
        }
    }
    t
}

fn report(name: &str, t: &Totals) {
    println!(
        "{name}: {} configurations ({} refused), {} runs ({} refused by the backend), {} oscillating; \
         largest swing of a quiet run {} counts, most endstop hits {}, largest torque {:.3} of the limit",
        t.configs,
        t.rejected,
        t.runs,
        t.backend_rejected,
        t.oscillating,
        t.worst_quiet_pp,
        t.most_hits,
        t.max_fraction
    );
    println!("{name}: the most endstop hits: {}", t.most_hits_run);
}

/// The columns of docs/knob.md's sweep tables ([`row`]).
const HEADER: [&str; 9] = [
    "backend",
    "configurations",
    "refused",
    "runs",
    "runs the backend refused",
    "oscillating",
    "largest swing of a quiet run (counts)",
    "most endstop hits in a run",
    "largest torque (of the limit)",
];

/// A row of docs/knob.md's sweep tables: the backend and what its sweep measured.
fn row(name: &str, t: &Totals) -> Vec<String> {
    vec![
        format!("`{name}`"),
        lab::table::grouped(t.configs),
        lab::table::grouped(t.rejected),
        lab::table::grouped(t.runs),
        lab::table::grouped(t.backend_rejected),
        format!("**{}**", t.oscillating),
        lab::table::grouped(t.worst_quiet_pp),
        lab::table::grouped(t.most_hits),
        format!("{:.3}", t.max_fraction),
    ]
}

/// The short grid in every backend; writes docs/knob.md's table ("The sweep of issue
/// 13"), which scripts/check-figures checks.
#[test]
fn short_sweep_has_no_oscillating_configuration() {
    let t = sweep::<f64>(&SHORT, 1.0);
    report("f64", &t);
    assert_eq!(t.oscillating, 0, "{:?}", t.worst);
    // Every configuration of the grid has an accepted detent, and every run was made.
    assert_eq!(t.rejected + t.backend_rejected, 0);
    assert_eq!(t.runs, 2_688);
    assert!(t.max_fraction <= 1.0);
    let mut rows = vec![row("f64", &t)];
    for (name, t) in [
        ("f32", sweep::<f32>(&SHORT, 1.0)),
        ("I16F16", sweep::<I16F16>(&SHORT, 1.0)),
    ] {
        report(name, &t);
        assert_eq!(t.oscillating, 0, "{name}: {:?}", t.worst);
        assert!(t.max_fraction <= 1.0, "{name}");
        rows.push(row(name, &t));
    }
    let path =
        lab::table::write_figures("knob/sweep-short.md", &lab::table::markdown(&HEADER, &rows));
    println!("wrote {}", path.display());
}

/// Ignored in a plain `cargo test` (minutes of run time); run it with
/// `cargo test --release --test knob_sweep -- --ignored --nocapture`. Fails today: one run
/// of the grid oscillates at 9 counts peak to peak (docs/knob.md, "The sweep of issue
/// 13"); the table is written before the assertion.
#[test]
#[ignore = "minutes of run time; one run oscillates at 9 counts (docs/knob.md)"]
fn full_sweep_has_no_oscillating_configuration() {
    let t = sweep::<f64>(&FULL, 1.0);
    report("f64, full grid", &t);
    // docs/knob.md's table of the full sweep, checked by `scripts/check-figures --long`.
    let path = lab::table::write_figures(
        "knob/sweep-full.md",
        &lab::table::markdown(&HEADER, &[row("f64", &t)]),
    );
    println!("wrote {}", path.display());
    assert_eq!(t.oscillating, 0, "{:?}", t.worst);
    assert!(t.max_fraction <= 1.0);
}
