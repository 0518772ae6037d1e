//! A haptic knob on a simulated rotor, turned by a scripted hand.
//!
//! ```text
//! cargo run --release --example check_knob                                # host: trace + SVG
//! cargo run --release --target thumbv7em-none-eabihf --example check_knob # QEMU mps2-an386, f32
//! cargo run --release --target thumbv6m-none-eabi --example check_knob    # QEMU microbit, I16F16
//! ```
//!
//! The scene: a 1 kHz control loop (one period of delay, as in SimpleFOC firmware), a
//! rotor of 1e−5 kg·m², a 50 mN·m motor, 20 detents over three quarters of a turn with
//! endstops at both ends, a 14-bit encoder. A hand (a finger as a stiff spring-damper)
//! turns the knob up through the detents, pushes into the upper endstop, lets go, then
//! flicks it back down and lets go again. The rotor is integrated exactly (a constant
//! torque over each period), in `f64` arithmetic that needs no `std`.
//!
//! On the host the example prints the torque trace every 25 ms and writes
//! `target/tour/knob.svg` (angle, detent and torque over time). On the target the same
//! scene runs on the microcontroller, with `f32` on the Cortex-M4F and `I16F16` on the
//! Cortex-M0, and logs every detent change and endstop hit through defmt.
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(defmt);

use firmware::golden::knob as golden;
use firmware::scenes::knob as scene;
use scene::{CONFIG, COUNT, DT, INERTIA, LIMIT, MAX};

use stiffspring::knob::{Endstop, KnobDesign};
use stiffspring::{Knob, KnobOutput, Scalar, knob};

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
type Backend = f32;
#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
type Backend = stiffspring::I16F16;
#[cfg(not(target_os = "none"))]
type Backend = f32;

/// The scene's knob, designed when the example is built: a refused configuration would
/// not compile, and the firmware carries no set-up code.
const DESIGN: KnobDesign<Backend> = knob!(CONFIG, Backend);

/// How long the scene runs, s.
const SECONDS: f64 = 4.0;

/// Where the finger pushes, and whether it touches the knob, at time `t`.
fn hand_target(t: f64) -> Option<f64> {
    match t {
        // Turn up through every detent in 1.2 s, then push 0.2 rad into the endstop.
        t if t < 1.2 => Some(0.1 + (MAX + 0.1) * t / 1.2),
        t if t < 1.6 => Some(MAX + 0.2),
        // Let go: the endstop and the last detent take it.
        t if t < 2.2 => None,
        // Grab it and flick it down, letting go while it moves fast.
        t if t < 2.35 => Some(MAX - 1.8 * (t - 2.2) / 0.15),
        _ => None,
    }
}

/// The finger's torque: 1 N·m/rad and 10 mN·m·s/rad (a firm grip).
fn hand_torque(theta: f64, omega: f64, t: f64) -> f64 {
    match hand_target(t) {
        Some(target) => -(theta - target) - 0.01 * omega,
        None => 0.0,
    }
}

/// One period of the scene, for the host's trace.
#[derive(Clone, Copy, Debug)]
struct Sample {
    t: f64,
    theta: f64,
    torque: f64,
    /// Drawn by the host's plot; unused on the target, which logs the events instead.
    #[cfg_attr(target_os = "none", allow(dead_code))]
    detent: i32,
}

/// Plays the scene on backend `S`, calling `each` after every period. Exact ZOH rotor:
/// the torque computed from the encoder angle of period `n` acts over period `n + 1`
/// (one period of delay); the hand's torque is held over each of 8 sub-steps.
fn play<S: Scalar>(
    design: &KnobDesign<S>,
    mut each: impl FnMut(&Sample, &KnobOutput<S>),
) -> Option<(i32, usize)> {
    let mut knob = Knob::from_design(design, S::ZERO).ok()?;
    let (mut theta, mut omega, mut pending) = (0.0f64, 0.0f64, 0.0f64);
    let mut detent_changes = 0;
    let steps = (SECONDS / DT) as usize;
    const SUB: usize = 8;
    let h = DT / SUB as f64;
    for n in 0..steps {
        let t = n as f64 * DT;
        // The encoder: floor to a count.
        let counts = theta / COUNT;
        let whole = counts as i64 as f64;
        let counts = if whole > counts { whole - 1.0 } else { whole };
        let out = knob.update(S::from_f64(counts * COUNT));
        if out.events.detent_step != 0 {
            detent_changes += 1;
        }
        // The rotor over the period, under last period's command.
        for k in 0..SUB {
            let tau = pending * LIMIT + hand_torque(theta, omega, t + k as f64 * h);
            let a = tau / INERTIA;
            theta += omega * h + 0.5 * a * h * h;
            omega += a * h;
        }
        pending = out.torque.to_f64();
        let sample = Sample {
            t,
            theta,
            torque: pending,
            detent: out.detent,
        };
        each(&sample, &out);
    }
    Some((knob.detent(), detent_changes))
}

/// Runs the scene and logs every detent change and endstop hit; on the host also the
/// trace and the SVG. Succeeds when the knob ends at rest in a detent after the flick.
fn run() -> bool {
    say!(
        "knob on {}: 20 detents over 270°, 1 kHz, one period of delay",
        firmware::MACHINE
    );
    #[cfg(not(target_os = "none"))]
    let mut trace: Vec<Sample> = Vec::new();
    let mut last = (0.0, 0.0);
    let result = play(&DESIGN, |s, out| {
        if out.events.detent_step != 0 {
            say!("t = {} ms: detent {}", (s.t * 1e3) as i32, out.detent);
        }
        match out.events.endstop_hit {
            Some(Endstop::Max) => say!("t = {} ms: upper endstop", (s.t * 1e3) as i32),
            Some(Endstop::Min) => say!("t = {} ms: lower endstop", (s.t * 1e3) as i32),
            None => {}
        }
        last = (s.theta, s.torque);
        #[cfg(not(target_os = "none"))]
        trace.push(*s);
    });
    let Some((detent, changes)) = result else {
        say!("the configuration was rejected");
        return false;
    };
    let width = MAX / 19.0;
    let offset = last.0 - detent as f64 * width;
    say!(
        "ended in detent {} after {} changes, {} counts from its centre, torque {} of the limit",
        detent,
        changes,
        (offset / COUNT) as i32,
        last.1 as f32
    );
    #[cfg(not(target_os = "none"))]
    host::report(&trace);
    // At rest in a detent: within a few counts of its centre, with almost no torque.
    let settled = firmware::abs(offset) < 4.0 * COUNT && firmware::abs(last.1) < 0.05;
    settled & sweep(&DESIGN)
}

/// The scripted encoder sweep, open loop, against the golden torques and detents
/// (`firmware/src/golden/knob.rs`, from the `f64` model of the torque law in
/// `tests/knob_golden.rs`, which the library's `f64` knob follows to 2.2e−16). The torque
/// may differ by the backend's rounding: measured on this sweep, `f32` within 5.6e−6 of
/// the limit and `I16F16` within 2.0e−4 (its own rounding, up to 5.5e−5 in
/// `tests/knob_fixed.rs`, plus the angle's rounding to Q16.16 times the spring's and the
/// damper's gains);
/// the tolerances, 1e−4 and 2e−3, are about ten times that. The detent index must match,
/// except in the period next to a change of the golden index: an angle within a rounding
/// of a switching point may switch one period apart (I16F16 rounds the detent boundaries
/// to Q16.16), and there the torque is not compared either.
fn sweep<S: Scalar>(design: &KnobDesign<S>) -> bool {
    let Ok(mut knob) = Knob::from_design(design, S::from_f64(scene::sweep_angle(0))) else {
        say!("the configuration was rejected");
        return false;
    };
    let tolerance = if S::RESOLUTION > 0.0 { 2e-3 } else { 1e-4 };
    let (torques, detents) = (golden::SWEEP[0], golden::SWEEP[1]);
    let mut tally = firmware::Tally::new();
    let mut detent_mismatches = 0;
    for n in 0..scene::SWEEP_STEPS {
        let out = knob.update(S::from_f64(scene::sweep_angle(n)));
        let near_change = (n.saturating_sub(1)..=(n + 1).min(scene::SWEEP_STEPS - 1))
            .any(|k| k > 0 && detents[k] != detents[k - 1]);
        if f64::from(out.detent) != detents[n] {
            if !near_change {
                detent_mismatches += 1;
            }
            continue;
        }
        if !near_change {
            tally.check(n, out.torque.to_f64(), torques[n], tolerance);
        }
    }
    say!(
        "sweep: {} periods against the golden f64 torques, worst difference {} of the limit (tolerance {}), {} detent mismatches",
        tally.samples,
        tally.worst as f32,
        tolerance as f32,
        detent_mismatches
    );
    tally.failures == 0 && detent_mismatches == 0
}

#[cfg(not(target_os = "none"))]
mod host {
    use super::Sample;
    use lab::plot;
    use std::path::Path;

    /// Prints the trace every 25 ms and writes `target/tour/knob.svg`.
    pub fn report(trace: &[Sample]) {
        println!("\n   t (ms)   angle (°)  detent  torque (fraction of limit)");
        for s in trace.iter().step_by(25) {
            let bar = ((s.torque * 20.0).round() as i32).clamp(-20, 20);
            let graph: String = (-20..=20)
                .map(|k| match k {
                    0 => '|',
                    k if (k < 0 && k >= bar) || (k > 0 && k <= bar) => '#',
                    _ => ' ',
                })
                .collect();
            println!(
                "{:8.0} {:10.2} {:7} {:+8.3} {graph}",
                s.t * 1e3,
                s.theta.to_degrees(),
                s.detent,
                s.torque
            );
        }
        let angle = plot::Plot::new("Knob: angle under a scripted hand (1 kHz, 20 detents)")
            .x_label("time [s]")
            .y_label("angle [°]")
            .series(plot::Series::line(
                "rotor angle",
                trace.iter().map(|s| (s.t, s.theta.to_degrees())),
            ))
            .series(
                plot::Series::line(
                    "detent centre",
                    trace
                        .iter()
                        .map(|s| (s.t, (s.detent as f64 * super::MAX / 19.0).to_degrees())),
                )
                .dashed(),
            );
        let torque = plot::Plot::new("Knob: commanded torque")
            .x_label("time [s]")
            .y_label("torque / limit")
            .series(plot::Series::line(
                "torque",
                trace.iter().map(|s| (s.t, s.torque)),
            ));
        let grid = plot::Grid::new("stiffspring haptic knob")
            .columns(1)
            .plot(angle)
            .plot(torque);
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/tour/knob.svg");
        match grid.write(&path) {
            Ok(()) => println!("\nwrote {}", path.display()),
            Err(e) => println!("\ncould not write {}: {e}", path.display()),
        }
    }
}

firmware::main!(run);
