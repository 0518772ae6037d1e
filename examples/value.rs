//! UI values springing to their targets, in `f32` and `I16F16`, checked against golden
//! values from the f64 reference model.
//!
//! The same scene code runs on the host and on the microcontrollers:
//!
//! ```text
//! cargo run --release --example value                                # host
//! cargo run --release --target thumbv7em-none-eabihf --example value # QEMU mps2-an386, Cortex-M4F
//! cargo run --release --target thumbv6m-none-eabi --example value    # QEMU microbit, Cortex-M0
//! ```
//!
//! The scene (`firmware/src/scenes/value.rs`) is three values at 60 Hz: a bouncy card that
//! is retargeted mid-flight and flung, a critically damped scroll offset, an overdamped
//! slider dragged in steps. Every value uses the exact map, so its samples should lie on
//! the continuous trajectory; `firmware/src/golden/value.rs` has that trajectory, computed on
//! the host by the reference model (`STIFFSPRING_BLESS=1 cargo test --test golden`).
//! Each backend plays the scene twice, as separate [`SpringValue`]s and as one
//! [`SpringBatch`] (which must agree with the values to the bit), and the program exits
//! with failure when a sample strays from the golden one by more than the backend's
//! tolerance (see `ARITHMETIC_F32` and `rest_snap_bound`). On the Cortex-M0 `I16F16` is
//! the backend to use and `f32` runs in soft float, for the comparison.
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(text);

use firmware::Tally;
use firmware::golden::value as golden;
use firmware::scenes::value as scene;
use scene::{DT, Event, FRAMES, TRACKS, Track};
use stiffspring::{I16F16, RestThreshold, Scalar, SpringBatch, SpringValue, Tuning};

/// How far a backend's arithmetic may take a moving value from the analytic trajectory,
/// in the scene's units (its amplitudes are about 100), while the value moves.
///
/// - `f32`: positions up to 140 carry an ulp of 1.5e−5, and each of the 240 frames
///   rounds `u` and `x` once; added up without any damping that is at most 3.7e−3. The
///   README measures 2.8e−6 of the amplitude (2.8e−4 units here) in the worst case over
///   10 000 steps at this `f·dt`. 1e−3 lies between the two.
/// - `I16F16` (LSB 1.5e−5): products are truncated toward zero, a drag that costs a
///   lightly damped spring up to `2/C_k` LSB of amplitude per cycle (the 2 Hz card has
///   `C_k = 0.041`: 49 LSB = 7.4e−4 units per cycle, 4 cycles per retarget at most),
///   plus the retarget and fling velocities, rounded to an LSB each. The README's
///   10 000-step worst case at this `f·dt` is 2.6e−3 of an amplitude of 100. 5e−3 covers
///   the per-cycle loss over this scene's segments with a margin.
///
/// Both are far below the errors a real fault makes here (a wrong coefficient, a lost
/// retarget velocity or a broken fling are off by whole units within a few frames), and
/// every run prints the worst errors it saw, which are several times smaller.
const ARITHMETIC_F32: f64 = 1e-3;
/// See [`ARITHMETIC_F32`].
const ARITHMETIC_I16F16: f64 = 5e-3;

/// How far a value at rest may be from the analytic trajectory, on top of the
/// arithmetic: it snapped to its target when its offset and velocity fell inside the
/// rest band, while the continuous trajectory still had that offset and velocity to
/// spend. From an offset `p` and a velocity `v` the free oscillator strays at most about
/// `(1 + ζω/ω_d)·p + v/ω_d` (`ω_d = ω√(1 − ζ²)`; `ω` for `ζ ≥ 1`), which is bounded by
/// `2·p + 2·v/ω_d` for this scene's damping ratios (0.3 to 1.5). The band is the
/// default [`RestThreshold`] (0.75e−3 units, 0.047 units/s), widened in fixed point to
/// the dead band `1/C_k + 1` LSB and to one LSB per step, as the library does.
fn rest_snap_bound<S: Scalar>(track: &Track, tuning: &Tuning) -> f64 {
    let threshold = RestThreshold::default();
    let lsb = S::RESOLUTION;
    let p = f64::max(threshold.position(), (1.0 / tuning.stiffness() + 1.0) * lsb);
    let v = f64::max(threshold.velocity(), lsb / DT);
    let omega = 2.0 * core::f64::consts::PI * track.frequency;
    let zeta = track.damping_ratio;
    let omega_d = if zeta < 1.0 {
        omega * firmware::sqrt(1.0 - zeta * zeta)
    } else {
        omega
    };
    2.0 * p + 2.0 * v / omega_d
}

/// The worst deviations of one track: while moving, and at rest.
struct Report {
    moving: Tally,
    resting: Tally,
    setup_failed: bool,
}

/// Plays `track` on a [`SpringValue`], records its `positions` and compares them with
/// the golden ones.
fn play<S: Scalar>(track: &Track, golden: &[f64], positions: &mut [S], arithmetic: f64) -> Report {
    let mut report = Report {
        moving: Tally::new(),
        resting: Tally::new(),
        setup_failed: true,
    };
    let Ok(tuning) = Tuning::from_frequency(track.frequency, track.damping_ratio, DT) else {
        return report;
    };
    let Ok(mut value) = SpringValue::<S, 1>::new([S::from_f64(track.start)], tuning, DT) else {
        return report;
    };
    report.setup_failed = false;
    let at_rest = arithmetic + rest_snap_bound::<S>(track, &tuning);
    for frame in 0..=FRAMES {
        let x = value.position()[0];
        positions[frame] = x;
        if value.is_at_rest() {
            report
                .resting
                .check(frame, x.to_f64(), golden[frame], at_rest);
        } else {
            report
                .moving
                .check(frame, x.to_f64(), golden[frame], arithmetic);
        }
        for event in track.events {
            let applied = match *event {
                Event::Target { frame: f, to } if f == frame => value.set_target([S::from_f64(to)]),
                Event::Fling { frame: f, velocity } if f == frame => {
                    value.fling([S::from_f64(velocity)])
                }
                _ => Ok(()),
            };
            report.setup_failed |= applied.is_err();
        }
        value.step();
    }
    report
}

/// Plays all tracks together in one [`SpringBatch`] and counts the samples that differ
/// from the separate values' `positions` (`[track][frame]`).
fn play_batch<S: Scalar>(positions: &[[S; FRAMES + 1]; TRACKS.len()]) -> usize {
    let mut mismatches = 0;
    let Ok(mut batch) = SpringBatch::<S, { TRACKS.len() }>::new(DT) else {
        return usize::MAX;
    };
    for track in &TRACKS {
        let pushed = Tuning::from_frequency(track.frequency, track.damping_ratio, DT)
            .and_then(|t| batch.push([S::from_f64(track.start)], t));
        if pushed.is_err() {
            return usize::MAX;
        }
    }
    for frame in 0..=FRAMES {
        for (i, (track, played)) in TRACKS.iter().zip(positions).enumerate() {
            if batch.position(i).map(|p| p[0]) != Ok(played[frame]) {
                mismatches += 1;
            }
            for event in track.events {
                let applied = match *event {
                    Event::Target { frame: f, to } if f == frame => {
                        batch.set_target(i, [S::from_f64(to)])
                    }
                    Event::Fling { frame: f, velocity } if f == frame => {
                        batch.fling(i, [S::from_f64(velocity)])
                    }
                    _ => Ok(()),
                };
                if applied.is_err() {
                    mismatches += 1;
                }
            }
        }
        batch.step();
    }
    mismatches
}

/// Plays the scene in backend `S`; true when every sample is within tolerance of the
/// golden one and the batch agrees with the values.
fn play_backend<S: Scalar>(arithmetic: f64) -> bool {
    let mut ok = true;
    let mut positions = [[S::ZERO; FRAMES + 1]; TRACKS.len()];
    for (i, track) in TRACKS.iter().enumerate() {
        let r = play(track, golden::POSITIONS[i], &mut positions[i], arithmetic);
        let passed = !r.setup_failed && r.moving.passed() && r.resting.passed();
        say!(
            "value {} {}: worst |x - golden| moving {} (frame {}, tolerance {}), at rest {} (frame {}): {}",
            S::NAME,
            track.name,
            r.moving.worst,
            r.moving.worst_step,
            arithmetic,
            r.resting.worst,
            r.resting.worst_step,
            if passed { "ok" } else { "FAILED" }
        );
        ok &= passed;
    }
    let mismatches = play_batch(&positions);
    say!(
        "value {} batch of {}: {} samples differ from the separate values: {}",
        S::NAME,
        TRACKS.len(),
        mismatches,
        if mismatches == 0 { "ok" } else { "FAILED" }
    );
    ok && mismatches == 0
}

fn run() -> bool {
    say!(
        "value: {} values, {} frames at 60 Hz, on {}",
        TRACKS.len(),
        FRAMES,
        firmware::MACHINE
    );
    let f32_ok = play_backend::<f32>(ARITHMETIC_F32);
    let fixed_ok = play_backend::<I16F16>(ARITHMETIC_I16F16);
    let ok = f32_ok && fixed_ok;
    say!(
        "value: {}",
        if ok {
            "all samples match the golden values"
        } else {
            "MISMATCH"
        }
    );
    ok
}

firmware::main!(run);
