//! The knob against SmartKnob-style PD detents (see `lab/src/knob/pd.rs` for the set-up):
//! the same rotor, detent logic, torque limit and small-signal stiffness `k_p`, one period
//! of delay, a 14-bit encoder, a flick of 20 rad/s released on a detent.
//! Run `cargo test --release --test knob_vs_pd -- --nocapture` for the table.
//!
//! Targets (issue 13): torque ripple at rest at most the PD's, at 1 kHz and at 10 kHz;
//! settling time at most half the PD's.

use lab::knob::COUNT;
use lab::knob::pd::{DETENTS, INERTIA, KnobLaw, LIMIT, SNAP, compare};
use std::f64::consts::TAU;
use stiffspring::{Knob, KnobConfig};

/// The library's knob for [`compare`]: detents `width` apart of stiffness `kp` (N·m/rad)
/// at period `dt`, the default damping ratio (0.7), two counts of hysteresis, in `f32`.
fn knob_law(dt: f64, width: f64, kp: f64) -> KnobLaw {
    let config = KnobConfig::new(1.0 / dt, INERTIA, LIMIT, 16384)
        .detent_width(width)
        .hysteresis(2.0 * COUNT)
        .detent_stiffness(kp);
    let mut knob = Knob::<f32>::new(&config, 0.0).expect("the knob accepts every k_p of the table");
    let cd = knob.loop_coefficients()[0].expect("the free zone").damping;
    let law = move |angle: f64| {
        let out = knob.update(angle as f32);
        (f64::from(out.torque) * LIMIT, out.detent)
    };
    (Box::new(law), cd)
}

#[test]
fn knob_against_smartknob_pd() {
    let width = TAU / DETENTS;
    println!(
        "| k_p (N·m/rad) | peak detent torque | rate | law | ζ small-signal | settle | overshoot | torque ripple at rest |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut compared = 0;
    let mut rows = Vec::new();
    for rate in [1_000.0, 10_000.0] {
        for kp in [0.02, 0.1, 0.25] {
            let c = compare(rate, kp, knob_law);
            let cell = |r: &lab::knob::pd::FlickResult| {
                format!("{:.0} ms, {:.2} mN·m", r.settle_ms, r.ripple_mnm)
            };
            rows.push(vec![
                format!("{kp}"),
                format!("{} kHz", rate / 1e3),
                format!("ζ {:.2}: {}", c.pd_zeta, cell(&c.pd)),
                format!("ζ {:.2}: {}", c.knob_zeta, cell(&c.matched)),
                cell(&c.knob),
                format!("{:.2}", c.knob.settle_ms / c.pd.settle_ms),
                format!("{:.2}", c.knob.settle_ms / c.matched.settle_ms),
            ]);
            for (law, zeta, r) in [
                ("SmartKnob PD", c.pd_zeta, &c.pd),
                ("stiffspring", c.knob_zeta, &c.knob),
            ] {
                println!(
                    "| {kp} | {:.1} mN·m | {} kHz | {law} | {zeta:.2} | {:.0} ms | {:.0}% | {:.2} mN·m |",
                    kp * SNAP * width * 1e3,
                    rate / 1e3,
                    r.settle_ms,
                    r.overshoot_pct,
                    r.ripple_mnm,
                );
            }
            // Matched stiffness: the knob's damping ratio is the configured one.
            assert!((c.knob_zeta - 0.7).abs() < 1e-6, "{}", c.knob_zeta);
            // Both came to rest in a detent (the tables compare settled runs).
            assert!(c.pd.settle_ms < 1_000.0 && c.knob.settle_ms < 1_000.0);
            assert!(
                c.knob.ripple_mnm <= c.pd.ripple_mnm,
                "{rate} Hz, k_p {kp}: ripple {} against the PD's {}",
                c.knob.ripple_mnm,
                c.pd.ripple_mnm
            );
            assert!(
                c.knob.settle_ms <= 0.5 * c.pd.settle_ms,
                "{rate} Hz, k_p {kp}: settles in {} ms against the PD's {}",
                c.knob.settle_ms,
                c.pd.settle_ms
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 6);
    // docs/knob.md's table, checked by scripts/check-figures.
    let header = [
        "`k_p` (N·m/rad)",
        "rate",
        "SmartKnob's PD: settle, ripple",
        "PD with the knob's damping",
        "knob: settle, ripple",
        "knob / SmartKnob's PD",
        "knob / matched PD",
    ];
    let path = lab::table::write_figures("knob/vs-pd.md", &lab::table::markdown(&header, &rows));
    println!("wrote {}", path.display());
}
