//! The knob torque scene: [`Knob::update`] once per control period, fed by an encoder.
//!
//! A knob of `1e−5 kg·m²` with a 50 mN·m limit, endstops at 0 and 3 rad (0.15 N·m/rad)
//! and 16 detents of 0.1 N·m/rad between them, read
//! by a 14-bit encoder while a hand turns it through `θ(t) = 1.5 + 1.7·sin(π·t)` rad: both
//! endstops and every detent, in both directions, in 2 s, at 1 and 10 kHz.
//!
//! No peer crate has a haptic knob, so the rows are the library's backends; the error
//! is the worst `|τ − τ_f64|` over the run, in fractions of the torque limit (the
//! torque's own unit), against the `f64` knob on the same angles (so `f64` itself reads
//! 0). The timed loop is `update` on a precomputed array of angles in the backend.

use lab::measure::Candidate;
use std::hint::black_box;
use stiffspring::{I16F16, I32F32, Knob, KnobConfig, Scalar};

/// The control rates, in Hz.
pub const RATES: [f64; 2] = [1000.0, 10_000.0];
/// How long the hand turns the knob, in seconds.
pub const DURATION: f64 = 2.0;

/// The knob's configuration at `rate`.
pub fn config(rate: f64) -> KnobConfig {
    KnobConfig::new(rate, 1e-5, 0.05, 16384)
        .endstops(0.0, 3.0)
        .endstop_stiffness(0.15)
        .detent_count(16)
        .detent_stiffness(0.1)
}

/// The encoder's readings, one per control period.
pub fn angles(rate: f64) -> Vec<f64> {
    let count = std::f64::consts::TAU / 16384.0;
    let steps = (DURATION * rate).round() as usize;
    (1..=steps)
        .map(|n| {
            let t = n as f64 / rate;
            let theta = 1.5 + 1.7 * (std::f64::consts::PI * t).sin();
            (theta / count).round() * count
        })
        .collect()
}

/// The knob at rest where the encoder first reads, as a firmware starts it. (The hand's
/// path starts at 1.5 rad, the midpoint between detents 7 and 8: a knob started there
/// takes either, as its backend's rounding of the tie falls, and the first periods'
/// torques of two backends then differ by the whole detent.)
fn start<S: Scalar>(rate: f64) -> Option<Knob<S>> {
    let first = *angles(rate).first()?;
    Knob::<S>::new(&config(rate), S::from_f64(first)).ok()
}

/// The torque of every period, in `f64`; `None` if the backend rejects the knob.
fn torques<S: Scalar>(rate: f64) -> Option<Vec<f64>> {
    let mut knob = start::<S>(rate)?;
    Some(
        angles(rate)
            .iter()
            .map(|&a| knob.update(S::from_f64(a)).torque.to_f64())
            .collect(),
    )
}

/// One row: backend, error, timing closure.
pub struct Entry {
    /// The `backend` column.
    pub backend: &'static str,
    /// `max_rel_error`.
    pub error: f64,
    /// The timing closure.
    pub candidate: Candidate<'static>,
}

fn entry<S: Scalar>(rate: f64, reference: &[f64]) -> Option<Entry> {
    let error = torques::<S>(rate)?
        .iter()
        .zip(reference)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let start = start::<S>(rate)?;
    let mut knob = start.clone();
    let angles: Vec<S> = angles(rate).into_iter().map(S::from_f64).collect();
    let steps = angles.len();
    Some(Entry {
        backend: S::NAME,
        error,
        candidate: Candidate::new(steps, move |runs| {
            for _ in 0..runs {
                knob.clone_from(&start);
                black_box(&mut knob);
                for &a in &angles {
                    black_box(knob.update(a).torque);
                }
            }
        }),
    })
}

/// Every backend at `rate`.
pub fn entries(rate: f64) -> Vec<Entry> {
    let Some(reference) = torques::<f64>(rate) else {
        eprintln!("knob: f64 rejected the configuration at {rate} Hz");
        return Vec::new();
    };
    [
        entry::<f64>(rate, &reference),
        entry::<f32>(rate, &reference),
        entry::<I32F32>(rate, &reference),
        entry::<I16F16>(rate, &reference),
    ]
    .into_iter()
    .flatten()
    .collect()
}
