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
    let r = refusals::<S>(full);
    for (label, parameter) in &r.refused {
        assert_eq!(
            *parameter,
            Some(stiffspring::Parameter::CountsPerTurn),
            "{} {label}",
            S::NAME
        );
    }
    (r.accepted, r.at[0] + r.at[1])
}

/// What [`refusals`] counts.
struct Refusals {
    /// Configurations accepted at 1 kHz.
    accepted: usize,
    /// Of those, the refusals at 4 kHz and at 10 kHz.
    at: [usize; 2],
    /// Each refusal's configuration and the parameter its error names.
    refused: Vec<(String, Option<stiffspring::Parameter>)>,
}

/// The configurations accepted at 1 kHz and their refusals at 4 and 10 kHz.
fn refusals<S: Scalar>(full: bool) -> Refusals {
    let mut r = Refusals {
        accepted: 0,
        at: [0, 0],
        refused: Vec::new(),
    };
    for (label, config) in grid(full) {
        if Knob::<S>::new(&config(1_000.0), S::ZERO).is_err() {
            continue;
        }
        r.accepted += 1;
        for (i, rate) in [4_000.0, 10_000.0].into_iter().enumerate() {
            if let Err(e) = Knob::<S>::new(&config(rate), S::ZERO) {
                r.at[i] += 1;
                eprintln!(
                    "{} {label}: accepted at 1 kHz, refused at {rate} Hz: {e}",
                    S::NAME
                );
                r.refused
                    .push((format!("{label} at {rate} Hz: {e}"), e.error.parameter()));
            }
        }
    }
    println!(
        "{}: {} accepted at 1 kHz, {} refused at a higher rate",
        S::NAME,
        r.accepted,
        r.at[0] + r.at[1]
    );
    r
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
    let (f32s, f64s) = (refusals::<f32>(true), refusals::<f64>(true));
    let fixed = refusals::<stiffspring::I16F16>(true);
    // docs/knob.md's table, checked by `scripts/check-figures --long`; written before the
    // assertions.
    let cells = |r: &Refusals| {
        let refused = r.at[0] + r.at[1];
        let mut named = std::collections::BTreeMap::<String, usize>::new();
        for (_, p) in &r.refused {
            let name = p.map_or("no parameter".to_string(), |p| format!("`{p:?}`"));
            *named.entry(name).or_default() += 1;
        }
        let named: Vec<String> = named.iter().map(|(p, n)| format!("{n} {p}")).collect();
        vec![
            lab::table::grouped(r.accepted),
            if refused == 0 {
                "0".to_string()
            } else {
                format!(
                    "{refused} of {} checks ({} at 4 kHz, {} at 10 kHz): {}",
                    lab::table::grouped(2 * r.accepted),
                    r.at[0],
                    r.at[1],
                    named.join(", ")
                )
            },
        ]
    };
    let mut rows = Vec::new();
    if cells(&f32s) == cells(&f64s) {
        rows.push([vec!["`f32`, `f64`".to_string()], cells(&f32s)].concat());
    } else {
        rows.push([vec!["`f32`".to_string()], cells(&f32s)].concat());
        rows.push([vec!["`f64`".to_string()], cells(&f64s)].concat());
    }
    rows.push([vec!["`I16F16`".to_string()], cells(&fixed)].concat());
    let header = ["backend", "accepted at 1 kHz", "refused at 4 or 10 kHz"];
    let path = lab::table::write_figures("knob/rates.md", &lab::table::markdown(&header, &rows));
    println!("wrote {}", path.display());
    for r in [&f32s, &f64s] {
        assert!(r.accepted > 4000);
        assert_eq!(r.at[0] + r.at[1], 0);
    }
    assert!(fixed.accepted > 4000);
    // Fixed point's refusals name the encoder (its filter bound) or the damping the
    // format cannot hold at the higher rate, never a stiffness.
    for (label, p) in &fixed.refused {
        assert!(
            matches!(
                p,
                Some(
                    stiffspring::Parameter::CountsPerTurn | stiffspring::Parameter::DampingConstant
                )
            ),
            "{label}"
        );
    }
}
