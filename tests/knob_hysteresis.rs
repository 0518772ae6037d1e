//! Encoder quantisation at a detent boundary: a hand holds the knob on the boundary with
//! a tremor of a few counts, read by a 14-bit encoder. With the hysteresis the detent
//! index (and with it the sign of the detent torque) does not flip; without it, it flips
//! back and forth with the counts, and the motor buzzes.

use lab::knob::{COUNT, Plant};
use stiffspring::{Knob, KnobConfig};

const INERTIA: f64 = 1e-5;
const LIMIT: f64 = 0.05;
const WIDTH: f64 = 0.2;
const STIFFNESS: f64 = 0.015; // N·m/rad

/// Holds the rotor at `at` with a stiff hand (a spring-damper, as a finger is) whose
/// target trembles by `tremor` counts at 7 Hz; returns (index changes, detent torque sign
/// flips).
fn hold(config: &KnobConfig, at: f64, tremor: f64, seconds: f64) -> (usize, usize) {
    let dt = config.dt();
    let mut knob = Knob::<f64>::new(config, at - 0.25 * WIDTH).unwrap();
    let mut plant = Plant::new(INERTIA, dt, 1.0);
    plant.theta = at;
    // At rest where the encoder reads (a jump there would be a sensor fault): reset
    // walks the index from detent 0.
    knob.reset(plant.read());
    // The finger: 20 N·m/rad, aimed past `at` by what the detent's pull there deflects it.
    let k_hand = 20.0;
    let detent_pull = STIFFNESS * 0.5 * WIDTH;
    let aim = at + detent_pull / k_hand;
    let mut hand = |theta: f64, omega: f64, t: f64| {
        let target = aim + tremor * COUNT * (std::f64::consts::TAU * 7.0 * t).sin();
        -k_hand * (theta - target) - 0.005 * omega
    };
    let (mut changes, mut flips) = (0, 0);
    let mut last_sign = 0.0;
    let mut last_index = None;
    for n in 0..(seconds / dt) as usize {
        let out = knob.update(plant.read());
        if n > 100 {
            if last_index.is_some_and(|i| i != out.detent) {
                changes += 1;
            }
            let sign = if out.torque > 0.0 {
                1.0
            } else if out.torque < 0.0 {
                -1.0
            } else {
                0.0
            };
            if sign != 0.0 && last_sign != 0.0 && sign != last_sign {
                flips += 1;
            }
            if sign != 0.0 {
                last_sign = sign;
            }
        }
        last_index = Some(out.detent);
        plant.step(out.torque * LIMIT, &mut hand);
    }
    (changes, flips)
}

#[test]
fn hysteresis_stops_the_flipping_that_quantisation_causes() {
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        // The same physical detent at every rate: 15 mN·m/rad, 1.5 mN·m at its edge.
        let base = KnobConfig::new(rate, INERTIA, LIMIT, 16384)
            .detent_width(WIDTH)
            .detent_stiffness(STIFFNESS)
            .snap_point(0.5);
        // The switching point sits exactly on a count: the worst case.
        let boundary = (0.5 * WIDTH / COUNT).round() * COUNT;
        let without = hold(&base.hysteresis(0.0), boundary, 1.5, 1.0);
        let with = hold(&base.hysteresis(3.0 * COUNT), boundary, 1.5, 1.0);
        println!(
            "{rate} Hz: index changes / torque sign flips without hysteresis {without:?}, with 3 counts {with:?}"
        );
        assert!(without.0 > 10, "the test must be able to fail: {without:?}");
        assert!(with.0 <= 1, "{rate} Hz: {with:?}");
        // The torque keeps its sign too, at every rate: the damper acts on the filtered
        // velocity, so the tremor's one-count steps do not flip it (with the unfiltered
        // backward difference, 10 kHz flipped it 42 times in a second).
        assert!(with.1 <= 2, "{rate} Hz: {with:?}");
    }
}

#[test]
fn the_snap_point_alone_is_hysteresis() {
    // SmartKnob's way: a snap point of 0.55 switches 5% of a width past the midpoint.
    let config = KnobConfig::new(1_000.0, INERTIA, LIMIT, 16384)
        .detent_width(WIDTH)
        .detent_stiffness(STIFFNESS)
        .snap_point(0.55)
        .hysteresis(0.0);
    let boundary = (0.55 * WIDTH / COUNT).round() * COUNT;
    let (changes, flips) = hold(&config, boundary, 1.5, 1.0);
    assert!(changes <= 1 && flips <= 2, "{changes} {flips}");
}
