//! Firmware check: the 2D rope of `firmware/src/scenes/rope.rs` (12 particles pinned at
//! one end, released level under gravity at 240 Hz) in `f32` and `I16F16`, against the
//! golden positions of the f64 reference network model. Not a starter (see
//! `examples/rope.rs`).
//!
//! ```text
//! cargo run --release --example check_rope                                # host
//! cargo run --release --target thumbv7em-none-eabihf --example check_rope # QEMU mps2-an386, Cortex-M4F
//! cargo run --release --target thumbv6m-none-eabi --example check_rope    # QEMU microbit, Cortex-M0
//! ```
//!
//! Every particle is compared every `golden::EVERY` steps with
//! `firmware/src/golden/rope.rs`, the reference model's Gauss-Seidel rope in f64
//! (`STIFFSPRING_BLESS=1 cargo test --test golden`); the program exits with failure when
//! one strays further than its backend's [`TOLERANCE`]. On the Cortex-M0 `f32` runs in
//! soft float.
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(text);

use firmware::golden::rope as golden;
use firmware::scenes::rope as scene;
use stiffspring::length::Exact;
use stiffspring::{I16F16, Scalar};

/// How far each backend's rope may stray from the f64 reference, in metres, on a rope of
/// 1.1 m swinging through 2 m. Measured on the host and both machines (the same figures,
/// bit for bit; every run prints them):
///
/// - `f32`: worst 2.3e−6 m, late in the swing (step 390). The library in `f64` follows
///   the reference to rounding, so what is left is `f32` rounding of the impulses and
///   positions (an ulp of a position near 1 m is 1.2e−7), amplified by this chaotic
///   multi-pendulum. 1e−5 m is four times that; another length kernel (the linearised
///   one), a skipped spring or lost gravity is off by 1e−3 m or more.
/// - `I16F16`: worst 4.0e−4 m at the same step. Gravity (`g·dt² = 1.7e−4` m per step, 11
///   LSB) is kept exactly by the Q24.40 state; what is left is the rounding of each
///   spring's impulse, amplified the same way. 1e−3 m is 2.5 times that, and still catches
///   a rope that falls apart, does not swing or swings the wrong way (errors of a metre).
///
/// (The 0.1 release needed 0.2 m for `I16F16`: its truncated impulses dragged the swing
/// by 7.9e−2 m.)
const TOLERANCE: [(&str, f64); 2] = [("f32", 1e-5), ("I16F16", 1e-3)];

/// Plays the rope in backend `S` and compares it with the golden positions.
///
/// Not inlined: the Cortex-M0 has 16 KiB of RAM, and with both backends inlined into
/// `run` their frames (the scene and its moves out of `build`) were summed into one of
/// 9.5 KB, which overflowed the stack with the formatting of the report.
#[inline(never)]
fn check_backend<S: Scalar>() -> bool {
    let tolerance = TOLERANCE
        .iter()
        .find(|(name, _)| *name == S::NAME)
        .map_or(0.0, |(_, t)| *t);
    let Ok((mut rope, ids)) = scene::build::<S, Exact>() else {
        say!("check_rope {}: set-up failed", S::NAME);
        return false;
    };
    let mut tally = firmware::Tally::new();
    for n in 0..=scene::STEPS {
        if n % golden::EVERY == 0 {
            let Some(sample) = golden::POSITIONS.get(n / golden::EVERY) else {
                return false;
            };
            for (i, id) in ids.iter().enumerate() {
                let Ok(p) = rope.position(*id) else {
                    return false;
                };
                for k in 0..2 {
                    tally.check(n, p[k].to_f64(), sample[2 * i + k], tolerance);
                }
            }
        }
        if n < scene::STEPS {
            let _ = rope.step();
        }
    }
    let ok = tally.passed() && tally.samples == golden::POSITIONS.len() * 2 * scene::PARTICLES;
    say!(
        "check_rope {}: worst |p - golden| = {} m at step {} (tolerance {} m, {} samples): {}",
        S::NAME,
        tally.worst,
        tally.worst_step,
        tolerance,
        tally.samples,
        if ok { "ok" } else { "FAILED" }
    );
    ok
}

fn run() -> bool {
    say!(
        "check_rope: {} particles, {} steps at 240 Hz, on {}",
        scene::PARTICLES,
        scene::STEPS,
        firmware::MACHINE
    );
    let f32_ok = check_backend::<f32>();
    let fixed_ok = check_backend::<I16F16>();
    f32_ok && fixed_ok
}

firmware::main!(run);
