//! The knob against SmartKnob-style PD detents (see `tests/knob_support/pd.rs` for the
//! set-up). Run `cargo test --release --test knob_vs_pd -- --nocapture` for the table.

mod knob_support;

use knob_support::pd::{DETENTS, INERTIA, LIMIT, SNAP, compare};
use std::f64::consts::TAU;
use stiffspring::{Error, Knob, KnobConfig, Parameter};

#[test]
fn knob_against_smartknob_pd() {
    let width = TAU / DETENTS;
    println!(
        "| k_p (N·m/rad) | peak detent torque | rate | law | ζ small-signal | settle | overshoot | torque ripple at rest | detents crossed |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut knob_settles = Vec::new();
    let mut pd_settles = Vec::new();
    for rate in [1_000.0, 10_000.0] {
        for kp in [0.02, 0.1, 0.25] {
            let c = compare(rate, kp);
            let (pd_result, knob_result) = (&c.pd, &c.knob);
            let (pd_zeta, knob_zeta) = (c.pd_zeta, c.knob_zeta);
            for (law, zeta, r) in [
                ("SmartKnob PD", pd_zeta, pd_result),
                ("stiffspring", knob_zeta, knob_result),
            ] {
                println!(
                    "| {kp} | {:.1} mN·m | {} kHz | {law} | {zeta:.2} | {:.0} ms | {:.0}% | {:.2} mN·m | {} |",
                    kp * SNAP * width * 1e3,
                    rate / 1e3,
                    r.settle_ms,
                    r.overshoot_pct,
                    r.ripple_mnm,
                    r.detents_crossed
                );
            }
            knob_settles.push(knob_result.settle_ms);
            pd_settles.push(pd_result.settle_ms);
            // The knob settles every case within 300 ms of the release.
            assert!(knob_result.settle_ms < 300.0, "{kp} {rate}");
        }
    }
    // A PD stiffer than the knob's strength 1 is accepted by nobody but the PD; the knob
    // refuses it.
    let config = KnobConfig::new(1e-3, INERTIA, LIMIT).detent_width(width);
    let top = config.stiffness_at_full_strength().unwrap();
    assert_eq!(
        Knob::<f32>::new(&config.detent_strength(1.5 * top / top), 0.0).unwrap_err(),
        Error::OutOfRange(Parameter::Strength)
    );
    println!("knob settle times (ms): {knob_settles:?}; PD: {pd_settles:?}");
}
