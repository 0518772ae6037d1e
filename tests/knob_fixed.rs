//! The knob's torque in `I16F16` (and `f32`) against `f64`, on the same encoder angles.
//!
//! A scripted hand turns the knob through its detents, into and out of an endstop, then
//! lets go; the `f64` knob closes the loop on the simulated rotor and its encoder angles
//! are replayed into the other backends. The torque is a fraction of the limit, so the
//! error is too. Run `cargo test --release --test knob_fixed -- --nocapture` for the
//! table; the bounds asserted are the measured worst cases with about 50% headroom.

use lab::knob::{COUNT, Plant};
use stiffspring::{I16F16, I32F32, Knob, KnobConfig, Scalar};

const INERTIA: f64 = 1e-5;
const LIMIT: f64 = 0.05;

fn scene(rate: f64, magnets: bool) -> KnobConfig {
    let base = KnobConfig::new(1.0 / rate, INERTIA, LIMIT);
    // The same physical feel at every rate: 50 mN·m/rad detents, 0.2 N·m/rad endstops,
    // 5 mN·m/rad back to the centre.
    let full = base.stiffness_at_full_strength().unwrap();
    let base = base
        .endstops(0.0, 3.0)
        .endstop_strength(0.2 / full)
        .return_to_centre(1.5, 0.005 / full)
        .hysteresis(2.0 * COUNT);
    if magnets {
        base.magnets(&[0.5, 1.5, 2.2])
            .magnet_strength(0.05 / full)
            .magnet_radius(0.1)
    } else {
        base.detent_count(16).detent_strength(0.05 / full)
    }
}

/// The encoder angles of the `f64` closed loop with a hand that sweeps from 0 past the
/// upper endstop and back below the lower one over 3 s, then lets go.
fn recorded_angles(config: &KnobConfig) -> Vec<f64> {
    let dt = config.dt();
    let mut knob = Knob::<f64>::new(config, 0.0).unwrap();
    let mut plant = Plant::new(INERTIA, dt, 1.0);
    let mut hand = |theta: f64, omega: f64, t: f64| {
        let target = if t < 1.5 {
            3.3 * t / 1.5
        } else {
            3.3 - 3.6 * (t - 1.5) / 1.5
        };
        if t < 3.0 {
            -2.0 * (theta - target) - 0.02 * omega
        } else {
            0.0
        }
    };
    let mut angles = Vec::new();
    for _ in 0..(4.0 / dt) as usize {
        let angle = plant.read();
        angles.push(angle);
        let out = knob.update(angle);
        plant.step(out.torque * LIMIT, &mut hand);
    }
    angles
}

/// Worst |τ_S − τ_f64| over the replay, and the number of periods whose detent index
/// differs. With `same_input` the `f64` knob is fed the angle as the backend holds it
/// (the arithmetic alone); without, the exact encoder angle (the input's rounding too,
/// which can move a zone or index decision by one period).
fn replay<S: Scalar>(config: &KnobConfig, angles: &[f64], same_input: bool) -> (f64, usize) {
    let mut reference = Knob::<f64>::new(config, 0.0).unwrap();
    let mut knob = Knob::<S>::new(config, 0.0).unwrap();
    let mut worst: f64 = 0.0;
    let mut index_differs = 0;
    for &a in angles {
        let held = S::from_f64(a);
        let r = reference.update(if same_input { held.to_f64() } else { a });
        let o = knob.update(held);
        if r.detent != o.detent {
            index_differs += 1;
            continue;
        }
        worst = worst.max((o.torque.to_f64() - r.torque).abs());
    }
    (worst, index_differs)
}

#[test]
fn fixed_point_torque_matches_f64() {
    println!("| rate | scene | I16F16 | I16F16, exact angles | I32F32 | f32 |");
    println!("|---|---|---|---|---|---|");
    let mut worst16: f64 = 0.0;
    let mut worst_input: f64 = 0.0;
    let mut index_periods = 0;
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        for magnets in [false, true] {
            let config = scene(rate, magnets);
            let angles = recorded_angles(&config);
            let (e16, d16) = replay::<I16F16>(&config, &angles, true);
            let (x16, _) = replay::<I16F16>(&config, &angles, false);
            let (e32, d32) = replay::<I32F32>(&config, &angles, true);
            let (ef, df) = replay::<f32>(&config, &angles, true);
            // The backend's detent width is rounded (by up to half an LSB, times the
            // index for the centre), so a switch can come one period earlier or later;
            // those periods are counted, not compared.
            assert!(d16 <= 4 && d32 == 0 && df <= 4, "{rate}: {d16} {d32} {df}");
            index_periods += d16;
            let name = if magnets { "magnets" } else { "detents" };
            println!("| {rate} Hz | {name} | {e16:.1e} | {x16:.1e} | {e32:.1e} | {ef:.1e} |");
            worst16 = worst16.max(e16);
            worst_input = worst_input.max(x16);
            assert!(e32 < 1e-6 && ef < 1e-4, "{rate} {name}: {e32} {ef}");
        }
    }
    println!(
        "worst I16F16 torque error: {worst16:.2e} of the limit on the same angles, \
         {worst_input:.2e} with the angles' own rounding; {index_periods} periods with the \
         index switched a period apart"
    );
    assert!(worst16 < 2e-4, "{worst16}");
}
