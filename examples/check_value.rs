//! Firmware check: UI values springing to their targets, in `f32` and `I16F16`, against
//! golden values from the f64 reference model. Not a starter (see `examples/card.rs`).
//!
//! The same scene code runs on the host and on the microcontrollers:
//!
//! ```text
//! cargo run --release --example check_value                                # host
//! cargo run --release --target thumbv7em-none-eabihf --example check_value # QEMU mps2-an386, Cortex-M4F
//! cargo run --release --target thumbv6m-none-eabi --example check_value    # QEMU microbit, Cortex-M0
//! ```
//!
//! The scene (`firmware/src/scenes/value.rs`) is three values at 60 Hz: a bouncy card that
//! is retargeted mid-flight and flung, a critically damped scroll offset, an overdamped
//! slider dragged in steps. Every value uses the exact map, so its samples should lie on
//! the continuous trajectory; `firmware/src/golden/value.rs` has that trajectory, computed
//! on the host from the analytic solution (`STIFFSPRING_BLESS=1 cargo test --test
//! golden`). Each backend plays every track as a [`SpringValue`] and in two
//! [`SpringBatch`]es (alone, which steps in one straight pass, and beside a value at rest,
//! which steps through the awake list); both must agree with the value to the bit. The
//! program exits with failure when a sample strays from the golden one by more than the
//! backend's tolerance (see [`MOVING`] and [`rest_snap_bound`]). On the Cortex-M0
//! `I16F16` is the backend to use and `f32` runs in soft float, for the comparison.
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(text);

use firmware::Tally;
use firmware::golden::value as golden;
use firmware::scenes::value as scene;
use scene::{DT, Event, FRAMES, TRACKS, Track};
use stiffspring::{BatchIndex, I16F16, RestThreshold, Scalar, SpringBatch, SpringValue, Tuning};

/// How far a moving value may stray from the analytic trajectory, per backend, in the
/// scene's units (amplitudes of about 100). Measured on the host and both machines (the
/// same figures, bit for bit; every run prints them):
///
/// - `f32`: worst 1.05e−5 (card_x, near 137, where an ulp is 1.5e−5): the value is a
///   rounding or two of the position, of each retarget's offset and of each fling's
///   velocity away from the trajectory. 4e−5 is four times that; a wrong coefficient, a
///   lost retarget velocity or a broken fling is off by whole units within a few frames.
/// - `I16F16`: worst 7.6e−6, half an LSB (an LSB is 1.53e−5): the Q24.40 state carries
///   the trajectory far below an LSB, and only the read rounds. 3e−5 is two LSB.
///
/// (The 0.1 release's tolerances were 1e−3 and 5e−3: the old `I16F16` lost up to 49 LSB
/// of amplitude per cycle to truncation.)
const MOVING: [(&str, f64); 2] = [("f32", 4e-5), ("I16F16", 3e-5)];

/// The tolerance of backend `S` while moving.
fn moving_tolerance<S: Scalar>() -> f64 {
    MOVING
        .iter()
        .find(|(name, _)| *name == S::NAME)
        .map_or(0.0, |(_, t)| *t)
}

/// How far a value at rest may be from the analytic trajectory, on top of the
/// arithmetic: it snapped to its target when its offset and step velocity fell inside
/// the rest band, while the continuous trajectory still had that offset and velocity to
/// spend. The band (see [`RestThreshold`]) is the box `|x| ≤ p/√2`,
/// `|u| ≤ min(p·√C_k/√2, v·dt)` with the default threshold (`p` = 0.75e−3 units, `v` =
/// 0.047 units/s), widened in fixed point to one LSB. From an offset `x` and a velocity
/// `u/dt` the free oscillator strays at most about `(1 + ζω/ω_d)·|x| + |u|/(ω_d·dt)`
/// (`ω_d = ω√(1 − ζ²)`; `ω` for `ζ ≥ 1`), which is below `2·|x| + 2·|u|/(ω_d·dt)` for
/// this scene's damping ratios (0.3 to 1.5).
fn rest_snap_bound<S: Scalar>(track: &Track, tuning: &Tuning) -> f64 {
    let threshold = RestThreshold::default();
    let lsb = S::RESOLUTION;
    let box_x = threshold.position() * core::f64::consts::FRAC_1_SQRT_2;
    let box_u = f64::min(
        box_x * firmware::sqrt(tuning.stiffness()),
        threshold.velocity() * DT,
    );
    let (x, u) = (f64::max(box_x, lsb), f64::max(box_u, lsb));
    let omega = 2.0 * core::f64::consts::PI * track.frequency;
    let zeta = track.damping_ratio;
    let omega_d = if zeta < 1.0 {
        omega * firmware::sqrt(1.0 - zeta * zeta)
    } else {
        omega
    };
    2.0 * x + 2.0 * u / (omega_d * DT)
}

/// The worst deviations of one track: while moving, and at rest.
struct Report {
    moving: Tally,
    resting: Tally,
    /// A set-up call or an event was rejected (the check fails).
    rejected: bool,
}

/// Applies the events of `frame` through `apply(event) -> accepted`.
fn events_at(track: &Track, frame: usize, mut apply: impl FnMut(&Event) -> bool) -> bool {
    let mut ok = true;
    for event in track.events {
        let at = match *event {
            Event::Target { frame, .. } | Event::Fling { frame, .. } => frame,
        };
        if at == frame {
            ok &= apply(event);
        }
    }
    ok
}

/// Plays `track` on a [`SpringValue`], records its `positions` and compares them with
/// the golden ones. The events go through the `try_` setters, so that a saturated
/// retarget or fling fails the check instead of passing silently.
fn play<S: Scalar>(track: &Track, golden: &[f64], positions: &mut [S]) -> Report {
    let mut report = Report {
        moving: Tally::new(),
        resting: Tally::new(),
        rejected: true,
    };
    let Ok(tuning) = Tuning::from_frequency(track.frequency, track.damping_ratio, DT) else {
        return report;
    };
    let Ok(mut value) = SpringValue::<S, 1>::new([S::from_f64(track.start)], &tuning) else {
        return report;
    };
    report.rejected = false;
    let moving = moving_tolerance::<S>();
    let at_rest = moving + rest_snap_bound::<S>(track, &tuning);
    for frame in 0..=FRAMES {
        let x = value.position()[0];
        positions[frame] = x;
        let tally = if value.is_at_rest() {
            (&mut report.resting, at_rest)
        } else {
            (&mut report.moving, moving)
        };
        tally.0.check(frame, x.to_f64(), golden[frame], tally.1);
        report.rejected |= !events_at(track, frame, |event| match *event {
            Event::Target { to, .. } => value.try_set_target([S::from_f64(to)]).is_ok(),
            Event::Fling { velocity, .. } => value.try_fling([S::from_f64(velocity)]).is_ok(),
        });
        let _ = value.step();
    }
    report
}

/// Plays `track` in a batch, `idle` values at rest beside it, and counts the frames at
/// which its position differs from the separate value's `positions`.
fn play_batch<S: Scalar, const N: usize>(track: &Track, idle: usize, positions: &[S]) -> usize {
    let Ok(tuning) = Tuning::from_frequency(track.frequency, track.damping_ratio, DT) else {
        return usize::MAX;
    };
    let Ok(mut batch) = SpringBatch::<S, 1, N>::new(&tuning) else {
        return usize::MAX;
    };
    let Ok(index): Result<BatchIndex, _> = batch.push([S::from_f64(track.start)]) else {
        return usize::MAX;
    };
    for _ in 0..idle {
        if batch.push([S::ZERO]).is_err() {
            return usize::MAX;
        }
    }
    let mut mismatches = 0;
    for (frame, played) in positions.iter().enumerate() {
        if batch.position(index) != Some([*played]) {
            mismatches += 1;
        }
        let accepted = events_at(track, frame, |event| match *event {
            Event::Target { to, .. } => batch.try_set_target(index, [S::from_f64(to)]).is_ok(),
            Event::Fling { velocity, .. } => {
                batch.try_fling(index, [S::from_f64(velocity)]).is_ok()
            }
        });
        if !accepted {
            mismatches += 1;
        }
        let _ = batch.step();
    }
    mismatches
}

/// Plays the scene in backend `S`; true when every sample is within tolerance of the
/// golden one and the batches agree with the values.
fn play_backend<S: Scalar>() -> bool {
    let mut ok = true;
    let mut positions = [S::ZERO; FRAMES + 1];
    for (i, track) in TRACKS.iter().enumerate() {
        let r = play(track, golden::POSITIONS[i], &mut positions);
        let passed = !r.rejected && r.moving.passed() && r.resting.passed();
        say!(
            "value {} {}: worst |x - golden| moving {} (frame {}, tolerance {}), at rest {} (frame {}): {}",
            S::NAME,
            track.name,
            r.moving.worst,
            r.moving.worst_step,
            moving_tolerance::<S>(),
            r.resting.worst,
            r.resting.worst_step,
            if passed { "ok" } else { "FAILED" }
        );
        let alone = play_batch::<S, 1>(track, 0, &positions);
        let beside = play_batch::<S, 2>(track, 1, &positions);
        say!(
            "value {} {}: frames where a batch differs from the value: alone {}, beside one at rest {}: {}",
            S::NAME,
            track.name,
            alone,
            beside,
            if alone == 0 && beside == 0 {
                "ok"
            } else {
                "FAILED"
            }
        );
        ok &= passed && alone == 0 && beside == 0;
    }
    ok
}

fn run() -> bool {
    say!(
        "check_value: {} values, {} frames at 60 Hz, on {}",
        TRACKS.len(),
        FRAMES,
        firmware::MACHINE
    );
    let f32_ok = play_backend::<f32>();
    let fixed_ok = play_backend::<I16F16>();
    let ok = f32_ok && fixed_ok;
    say!(
        "check_value: {}",
        if ok {
            "all samples match the golden values"
        } else {
            "MISMATCH"
        }
    );
    ok
}

firmware::main!(run);
