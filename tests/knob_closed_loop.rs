//! The knob on a simulated rotor (exact ZOH integration, 14-bit encoder): over the whole
//! accepted strength range, at 1, 4 and 10 kHz, with and without a period of delay,
//! after a flick the loop neither grows nor keeps oscillating above the encoder's
//! quantisation, and the torque clamp does not break that.

use lab::knob::{COUNT, Plant};
use stiffspring::knob::{Latency, spectral_radius};
use stiffspring::{Knob, KnobConfig};

const INERTIA: f64 = 1e-5; // kg·m², a gimbal motor with a knob cap
const LIMIT: f64 = 0.05; // N·m
const WIDTH: f64 = 0.2; // rad, about 11°

struct Outcome {
    /// The largest distance from the settled detent's centre after the first period.
    peak: f64,
    /// Peak-to-peak angle over the last fifth of the run.
    tail_swing: f64,
    /// Peak-to-peak torque (fraction) over the last fifth.
    tail_torque: f64,
    settled_offset: f64,
}

/// Runs long enough for the slowest mode to shrink a thousandfold (from the loop's own
/// spectral radius), and at least `seconds`.
fn run(config: &KnobConfig, delay: f64, start: f64, flick: f64, seconds: f64) -> Outcome {
    let dt = config.dt();
    let mut knob = Knob::<f64>::new(config, start).unwrap();
    let (ck, cd) = knob.loop_coefficients()[0];
    let rho = spectral_radius(ck, cd, knob.strength_map().latency());
    let settle = (1e-3f64).ln() / rho.ln();
    let seconds = seconds.max(settle * dt / 0.8);
    let mut plant = Plant::new(INERTIA, dt, delay);
    plant.theta = start;
    plant.omega = flick;
    let n = (seconds / dt) as usize;
    let mut angles = Vec::with_capacity(n);
    let mut torques = Vec::with_capacity(n);
    for _ in 0..n {
        let out = knob.update(plant.read());
        assert!(out.torque.is_finite() && out.torque.abs() <= 1.0);
        plant.step(out.torque * LIMIT, &mut lab::knob::no_hand);
        angles.push(plant.theta);
        torques.push(out.torque);
    }
    let centre = (plant.theta / WIDTH).round() * WIDTH;
    let peak = angles
        .iter()
        .skip(1)
        .fold(0.0f64, |m, a| m.max((a - centre).abs()));
    let tail = n - n / 5;
    let swing = |v: &[f64]| {
        let lo = v.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        hi - lo
    };
    Outcome {
        peak,
        tail_swing: swing(&angles[tail..]),
        tail_torque: swing(&torques[tail..]),
        settled_offset: (plant.theta - centre).abs(),
    }
}

#[test]
fn every_accepted_strength_settles_at_every_rate() {
    let mut worst_swing = 0.0f64;
    let mut cases = 0;
    let mut relay = 0;
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        let dt = 1.0 / rate;
        for (latency, delays) in [
            (Latency::SameStep, &[0.0][..]),
            (Latency::OneStep, &[0.0, 0.5, 1.0][..]),
        ] {
            for zeta in [0.2, 0.3, 0.5, 0.7, 1.0, 2.0] {
                for strength in [0.001, 0.01, 0.1, 0.5, 1.0] {
                    let config = KnobConfig::new(dt, INERTIA, LIMIT)
                        .latency(latency)
                        .damping_ratio(zeta)
                        .detent_width(WIDTH)
                        .detent_strength(strength)
                        .hysteresis(2.0 * COUNT);
                    for &delay in delays {
                        // Released 40% of a detent from a centre with a flick of 3 rad/s.
                        let o = run(&config, delay, 0.4 * WIDTH, 3.0, 3.0);
                        let what = format!(
                            "{rate} Hz, {latency:?} (delay {delay}), ζ {zeta}, strength {strength}"
                        );
                        // No growth: never farther from the final detent than a detent
                        // and a half (a flick crosses a few detents, then is caught).
                        assert!(o.peak < 10.0 * WIDTH, "{what}: peak {}", o.peak);
                        // No sustained oscillation above the quantisation: the rotor
                        // ends still within two counts, torque ripple within what one
                        // count of extension and velocity gives.
                        // The torque (as a fraction of the limit) that one count of
                        // extension and of velocity command together.
                        let knob = Knob::<f64>::new(&config, 0.0).unwrap();
                        let (ck, cd) = knob.loop_coefficients()[0];
                        let per_count = (ck + cd) * INERTIA / (dt * dt * LIMIT) * COUNT;
                        // Given the encoder's resolution, the knob refuses exactly the
                        // strengths beyond that point.
                        let refused =
                            Knob::<f64>::new(&config.encoder_resolution(COUNT), 0.0).is_err();
                        assert_eq!(refused, per_count > 1.0, "{what}");
                        if per_count <= 1.0 {
                            assert!(
                                o.tail_swing <= 2.0 * COUNT,
                                "{what}: swing {}",
                                o.tail_swing / COUNT
                            );
                        } else {
                            // One count commands more than the whole torque (refused with
                            // an encoder resolution): the clamp turns the loop into a
                            // relay, whose cycle is a few counts.
                            assert!(
                                o.tail_swing <= 4.0 * COUNT,
                                "{what}: swing {}",
                                o.tail_swing / COUNT
                            );
                            println!(
                                "{what}: one count = {per_count:.1}× the limit, swing {:.2} counts, torque p-p {:.2}",
                                o.tail_swing / COUNT,
                                o.tail_torque
                            );
                            relay += 1;
                        }
                        assert!(o.settled_offset <= WIDTH / 2.0, "{what}");
                        if per_count <= 1.0 {
                            worst_swing = worst_swing.max(o.tail_swing / COUNT);
                        }
                        let _ = o.tail_torque;
                        cases += 1;
                    }
                }
            }
        }
    }
    println!(
        "{cases} cases; worst swing at rest {worst_swing:.2} counts where one count commands \
         at most the torque limit; {relay} cases beyond"
    );
}

#[test]
fn every_layer_at_once_settles_after_a_flick_into_the_endstop() {
    // Detents, magnets and the return spring inside (strengths summing to 1), the endstop
    // with what the return spring leaves; a flick of 60 rad/s (SmartKnob cuts its motor
    // above that) from 0.2 rad before the upper end,
    // then nothing: the endstop catches it, and it settles within two counts.
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        for latency in [Latency::SameStep, Latency::OneStep] {
            let config = KnobConfig::new(1.0 / rate, INERTIA, LIMIT)
                .latency(latency)
                .endstops(0.0, 3.0)
                .detent_count(16)
                .detent_strength(0.3)
                .magnets(&[0.5, 1.5, 2.5])
                .magnet_strength(0.6)
                .magnet_radius(0.1)
                .return_to_centre(1.5, 0.1)
                .hysteresis(2.0 * COUNT);
            let dt = 1.0 / rate;
            let mut knob = Knob::<f32>::new(&config, 2.8).unwrap();
            let mut plant = Plant::new(
                INERTIA,
                dt,
                if latency == Latency::OneStep {
                    1.0
                } else {
                    0.0
                },
            );
            plant.theta = 2.8;
            plant.omega = 60.0;
            let n = (3.0 / dt) as usize;
            let mut tail = (f64::INFINITY, f64::NEG_INFINITY);
            let mut hit = false;
            for k in 0..n {
                let out = knob.update(plant.read() as f32);
                hit |= out.events.endstop_hit.is_some();
                plant.step(f64::from(out.torque) * LIMIT, &mut lab::knob::no_hand);
                assert!(
                    plant.theta < 3.5,
                    "{rate} {latency:?}: ran through the endstop"
                );
                if k > n - n / 5 {
                    tail = (tail.0.min(plant.theta), tail.1.max(plant.theta));
                }
            }
            assert!(hit, "{rate} {latency:?}");
            assert!(
                tail.1 - tail.0 <= 2.0 * COUNT,
                "{rate} {latency:?}: {}",
                (tail.1 - tail.0) / COUNT
            );
            assert!(
                tail.1 <= 3.0 + 2.0 * COUNT,
                "{rate} {latency:?}: rests beyond the end"
            );
        }
    }
}
