//! The knob on a simulated rotor (exact ZOH integration, quantising encoder): over the
//! accepted stiffnesses at 1, 4 and 10 kHz, with and without a period of delay, a flicked
//! knob comes to rest; endstops and detents meet cleanly, including a detent on the stop
//! (the regression of issue 13: "released on the last detent").

use lab::knob::sweep::{ENDSTOPS, Rotor, Run, counts};
use stiffspring::knob::{KNEE_COUNTS, Latency, REST_COUNTS};

/// A rotor at rest drifts inside the rest zone, where the torque is zero: at most its
/// width, and one count of the encoder's rounding.
const REST_SWING: i64 = 2 * REST_COUNTS as i64 + 1;
/// A rotor comes to rest within the rest zone and the knee of its rest point.
const REST_OFFSET: f64 = REST_COUNTS + KNEE_COUNTS;
use stiffspring::{Knob, KnobConfig, Scalar};

const INERTIA: f64 = 1e-5; // kg·m², a gimbal motor with a knob cap
const LIMIT: f64 = 0.05; // N·m
const WIDTH: f64 = 0.2; // rad, about 11°

/// The knob closes the loop on `rotor` for `seconds` (the rotor model and the metric are
/// in `lab/src/knob/sweep.rs`).
fn run<S: Scalar>(knob: &mut Knob<S>, rotor: &mut Rotor, count: f64, seconds: f64) -> Run {
    let limit = knob.torque_limit();
    lab::knob::sweep::run(rotor, count, limit, seconds, |angle| {
        let out = knob.update(S::from_f64(angle));
        (out.torque.to_f64(), out.events.endstop_hit.is_some())
    })
}

#[test]
fn every_accepted_stiffness_comes_to_rest_at_every_rate() {
    let mut worst_swing: i64 = 0;
    let mut cases = 0;
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        for (latency, delays) in [
            (Latency::SameStep, &[0usize][..]),
            (Latency::OneStep, &[0, 1][..]),
        ] {
            for zeta in [0.2, 0.5, 0.7, 1.0, 2.0] {
                let base = KnobConfig::new(rate, INERTIA, LIMIT, 16384)
                    .latency(latency)
                    .damping_ratio(zeta)
                    .detent_width(WIDTH);
                let top = base.detent_stiffness_limit::<f32>().unwrap();
                for fraction in [0.001, 0.01, 0.1, 0.5, 1.0] {
                    let config = base.detent_stiffness(fraction * top);
                    let count = config.count();
                    for &delay in delays {
                        // Released 40% of a detent from a centre with a flick of 3 rad/s,
                        // for 3 s.
                        let start = 0.4 * WIDTH;
                        let reading = (counts(start, count) as f64 * count) as f32;
                        let mut knob = Knob::<f32>::new(&config, reading).unwrap();
                        let mut rotor = Rotor::new(INERTIA, 1.0 / rate, delay, start, 3.0);
                        let r = run(&mut knob, &mut rotor, count, 3.0);
                        let what = format!(
                            "{rate} Hz {latency:?} (delay {delay}) ζ {zeta}, {fraction} of {top:.3} N·m/rad"
                        );
                        assert!(!r.oscillating(), "{what}: {r:?}");
                        // At rest: the last 10% within two counts (the rest zone), unless
                        // the spring is so soft that six of its decay times (at half its
                        // designed decay rate) exceed the run.
                        let wn = (fraction * top / INERTIA).sqrt();
                        let slowest = if zeta < 1.0 {
                            zeta * wn
                        } else {
                            wn * (zeta - (zeta * zeta - 1.0).sqrt())
                        };
                        // Half the designed decay rate: the filter and the sampling slow it.
                        let settles = 6.0 / (0.5 * slowest) < 2.7;
                        if settles {
                            assert!(r.pp_counts <= REST_SWING, "{what}: {} counts", r.pp_counts);
                        }
                        // In a detent: within a rest zone plus a count of its centre,
                        // unless the spring is too weak to have finished in 3 s.
                        let centre = (rotor.theta / WIDTH).round() * WIDTH;
                        if settles {
                            assert!(
                                (rotor.theta - centre).abs() <= REST_OFFSET * count,
                                "{what}: rests {} counts off",
                                (rotor.theta - centre) / count
                            );
                        }
                        if settles {
                            worst_swing = worst_swing.max(r.pp_counts);
                        }
                        cases += 1;
                    }
                }
            }
        }
    }
    println!(
        "{cases} cases; worst swing at rest {worst_swing} counts (springs that settle within the run)"
    );
}

/// The case: 24 detents between endstops at ±135° (the last on each stop), weak
/// detents, the default endstop, released 3 counts inside the stop, for 10 s.
#[test]
fn endstops_and_weak_detents_do_not_fight() {
    let (lo, hi) = ENDSTOPS;
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        for latency in [Latency::SameStep, Latency::OneStep] {
            // 0.003–0.015 N·m/rad: the weak detents that cycled at 1 kHz (strengths
            // 0.01–0.05 of the old map).
            for detent in [0.003, 0.009, 0.015] {
                let config = KnobConfig::new(rate, INERTIA, 0.02, 16384)
                    .latency(latency)
                    .damping_ratio(0.2)
                    .endstops(lo, hi)
                    .detent_count(24)
                    .detent_stiffness(detent);
                let count = config.count();
                for &delay in if latency == Latency::OneStep {
                    &[0usize, 1][..]
                } else {
                    &[0][..]
                } {
                    for start in [hi - 3.0 * count, hi + 3.0 * count] {
                        let reading = counts(start, count) as f64 * count;
                        let mut knob = Knob::<f64>::new(&config, reading).unwrap();
                        let mut rotor = Rotor::new(INERTIA, 1.0 / rate, delay, start, 0.0);
                        let r = run(&mut knob, &mut rotor, count, 10.0);
                        let what = format!(
                            "{rate} Hz {latency:?} delay {delay}, {detent} N·m/rad, from {:.0} counts",
                            (start - hi) / count
                        );
                        assert!(r.pp_counts <= REST_SWING, "{what}: {} counts", r.pp_counts);
                        assert!(r.hits <= 1, "{what}: {} endstop hits", r.hits);
                        assert!((rotor.theta - hi).abs() <= REST_OFFSET * count, "{what}");
                    }
                }
            }
        }
    }
}

/// Regression: released on the last detent, which lies exactly on the endstop, at rest
/// and with a nudge either way, at every rate and encoder: no cycle, no repeated hits.
#[test]
fn released_on_the_last_detent() {
    let (lo, hi) = ENDSTOPS;
    let mut worst_hits = 0;
    let mut worst_ripple: f64 = 0.0;
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        for bits in [10u32, 12, 14, 16] {
            for latency in [Latency::SameStep, Latency::OneStep] {
                let base = KnobConfig::new(rate, INERTIA, LIMIT, 1 << bits)
                    .latency(latency)
                    .endstops(lo, hi)
                    .detent_count(24);
                let top = base.detent_stiffness_limit::<f32>().unwrap();
                for fraction in [0.01, 0.3, 1.0] {
                    let config = base.detent_stiffness(fraction * top);
                    let count = config.count();
                    for nudge in [-0.5, 0.0, 0.5] {
                        for &delay in if latency == Latency::OneStep {
                            &[0usize, 1][..]
                        } else {
                            &[0][..]
                        } {
                            let reading = (counts(hi, count) as f64 * count) as f32;
                            let mut knob = Knob::<f32>::new(&config, reading).unwrap();
                            assert_eq!(knob.detent(), 23);
                            let mut rotor = Rotor::new(INERTIA, 1.0 / rate, delay, hi, nudge);
                            let r = run(&mut knob, &mut rotor, count, 2.0);
                            let what = format!(
                                "{rate} Hz {bits} bits {latency:?} delay {delay} {fraction} of {top:.3}, nudge {nudge}"
                            );
                            assert!(r.pp_counts <= REST_SWING, "{what}: {} counts", r.pp_counts);
                            // At rest, no hit; nudged into the stop, a bounce or two.
                            let most = if nudge == 0.0 { 1 } else { 3 };
                            assert!(r.hits <= most, "{what}: {} hits", r.hits);
                            assert_eq!(knob.detent(), 23, "{what}");
                            worst_hits = worst_hits.max(r.hits);
                            worst_ripple = worst_ripple.max(r.tail_torque);
                        }
                    }
                }
            }
        }
    }
    println!(
        "released on the last detent: at most {worst_hits} endstop hit, torque ripple at rest ≤ {:.2} mN·m",
        worst_ripple * 1e3
    );
}

#[test]
fn every_layer_at_once_settles_after_a_flick_into_the_endstop() {
    // Detents, magnets and the return spring inside, the default endstop; a flick of
    // 60 rad/s (SmartKnob cuts its motor above that) from 0.2 rad before the upper end,
    // then nothing: the endstop catches it, and it settles within two counts.
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        for latency in [Latency::SameStep, Latency::OneStep] {
            let config = KnobConfig::new(rate, INERTIA, LIMIT, 16384)
                .latency(latency)
                .endstops(0.0, 3.0)
                .detent_count(16)
                .detent_stiffness(0.05)
                .magnets(&[0.5, 1.5, 2.5])
                .magnet_stiffness(0.1)
                .magnet_radius(0.1)
                .return_to_centre(1.5, 0.005);
            let count = config.count();
            let mut knob = Knob::<f32>::new(&config, 2.8).unwrap();
            let delay = usize::from(latency == Latency::OneStep);
            let mut rotor = Rotor::new(INERTIA, 1.0 / rate, delay, 2.8, 60.0);
            let r = run(&mut knob, &mut rotor, count, 3.0);
            assert!(r.hits >= 1, "{rate} {latency:?}");
            assert!(
                r.pp_counts <= REST_SWING,
                "{rate} {latency:?}: {}",
                r.pp_counts
            );
            assert!(
                rotor.theta <= 3.0 + REST_OFFSET * count,
                "{rate} {latency:?}: rests beyond the end"
            );
        }
    }
}
