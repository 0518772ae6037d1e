//! A knob accepted at one rate is accepted at every higher rate: over a grid of
//! configurations (rotors, motors, damping, latencies, layouts, encoders, stiffnesses),
//! every configuration accepted at 1 kHz is accepted at 4 and 10 kHz in `f32` and `f64`.
//!
//! In fixed point the velocity filter is at most 63 periods long (its state keeps its
//! truncation errors for about that many), 6.3 ms at 10 kHz against 63 ms at 1 kHz; a
//! knob whose damper needs a longer filter to keep one count's torque within an eighth of
//! the limit (a coarse encoder on a heavy rotor) is refused at the higher rate, with the
//! counts per turn that would pass. The whole grid counts them
//! (`cargo test --release --test knob_rates -- --ignored --nocapture`).

use stiffspring::knob::Latency;
use stiffspring::{Knob, KnobConfig, Scalar};

/// The grid: `(label, config at rate)` for every combination, stiffness given as a
/// fraction of `0.04·J·(1 kHz)²`, about the stiffest detent a 1 kHz loop holds.
/// A configuration as a function of the rate.
type AtRate = Box<dyn Fn(f64) -> KnobConfig>;

fn grid(full: bool) -> Vec<(String, AtRate)> {
    let mut out: Vec<(String, AtRate)> = Vec::new();
    let inertias: &[f64] = if full { &[1e-6, 1e-5, 1e-4] } else { &[1e-5] };
    let limits: &[f64] = if full { &[0.02, 0.1, 0.5] } else { &[0.05] };
    let zetas: &[f64] = if full { &[0.2, 0.7, 2.0] } else { &[0.7] };
    let bits: &[u32] = if full { &[10, 12, 14, 16] } else { &[10, 14] };
    let fractions: &[f64] = &[0.01, 0.03, 0.1, 0.3, 1.0];
    for &j in inertias {
        for &limit in limits {
            for &zeta in zetas {
                for latency in [Latency::OneStep, Latency::SameStep] {
                    for detents in [2u32, 24, 100] {
                        for stops in [false, true] {
                            for &b in bits {
                                for &f in fractions {
                                    let k = f * 0.04 * j * 1e6;
                                    let label = format!(
                                        "J {j:e} limit {limit} ζ {zeta} {latency:?} {detents} detents stops {stops} {b} bits k {k:e}"
                                    );
                                    out.push((
                                        label,
                                        Box::new(move |rate| {
                                            let c = KnobConfig::new(rate, j, limit, 1 << b)
                                                .latency(latency)
                                                .damping_ratio(zeta);
                                            let c = if stops {
                                                c.endstops(-2.356, 2.356).detent_count(detents)
                                            } else {
                                                c.detent_width(
                                                    core::f64::consts::TAU / detents as f64,
                                                )
                                            };
                                            c.detent_stiffness(k)
                                        }),
                                    ));
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    out
}

/// Configurations accepted at 1 kHz, and refusals at 4 or 10 kHz of those; every refusal
/// names the encoder (fixed point's filter bound), never a stiffness.
fn monotone<S: Scalar>(full: bool) -> (usize, usize) {
    let (mut accepted, mut refused_later) = (0, 0);
    for (label, config) in grid(full) {
        if Knob::<S>::new(&config(1_000.0), S::ZERO).is_err() {
            continue;
        }
        accepted += 1;
        for rate in [4_000.0, 10_000.0] {
            if let Err(e) = Knob::<S>::new(&config(rate), S::ZERO) {
                refused_later += 1;
                eprintln!(
                    "{} {label}: accepted at 1 kHz, refused at {rate} Hz: {e}",
                    S::NAME
                );
                assert_eq!(
                    e.error.parameter(),
                    Some(stiffspring::Parameter::CountsPerTurn),
                    "{} {label}: {e}",
                    S::NAME
                );
            }
        }
    }
    println!(
        "{}: {accepted} accepted at 1 kHz, {refused_later} refused at a higher rate",
        S::NAME
    );
    (accepted, refused_later)
}

#[test]
fn accepted_at_1_khz_is_accepted_at_4_and_10_khz() {
    let (accepted, refused) = monotone::<f32>(false);
    assert!(accepted > 20);
    assert_eq!(refused, 0);
    let (accepted, _) = monotone::<stiffspring::I16F16>(false);
    assert!(accepted > 20);
}

/// The whole grid in every backend (`cargo test --release --test knob_rates -- --ignored
/// --nocapture`).
#[test]
#[ignore]
fn the_whole_grid_is_monotone_in_the_rate() {
    for (a, r) in [monotone::<f32>(true), monotone::<f64>(true)] {
        assert!(a > 4000);
        assert_eq!(r, 0);
    }
    let (a, r) = monotone::<stiffspring::I16F16>(true);
    assert!(a > 4000);
    // Measured: 70 of 8,268 (16 at 4 kHz, 54 at 10 kHz), all with 10-bit encoders.
    assert!(r <= 70, "{r}");
}
