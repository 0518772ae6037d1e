//! The knob against SmartKnob-style PD detents (see `lab/src/knob/pd.rs` for the
//! set-up). Run `cargo test --release --test knob_vs_pd -- --nocapture` for the table.

use lab::knob::COUNT;
use lab::knob::pd::{DETENTS, INERTIA, KnobLaw, LIMIT, SNAP, compare};
use std::f64::consts::TAU;
use stiffspring::{Error, Knob, KnobConfig, Parameter};

/// The library's knob for [`compare`]: detents `width` apart with small-signal stiffness
/// `kp` at period `dt`, damping ratio 0.7, two counts of hysteresis, in `f32`.
fn knob_law(dt: f64, width: f64, kp: f64) -> KnobLaw {
    let config = KnobConfig::new(dt, INERTIA, LIMIT)
        .detent_width(width)
        .hysteresis(2.0 * COUNT);
    let strength = kp / config.stiffness_at_full_strength().expect("valid config");
    let mut knob =
        Knob::<f32>::new(&config.detent_strength(strength), 0.0).expect("accepted strength");
    let (_, cd) = knob.loop_coefficients()[0];
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
        "| k_p (N·m/rad) | peak detent torque | rate | law | ζ small-signal | settle | overshoot | torque ripple at rest | detents crossed |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut knob_settles = Vec::new();
    let mut pd_settles = Vec::new();
    for rate in [1_000.0, 10_000.0] {
        for kp in [0.02, 0.1, 0.25] {
            let c = compare(rate, kp, knob_law);
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
