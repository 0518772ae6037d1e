//! Minimal firmwares for the flash-size report: `scripts/size-report` builds this example
//! once per configuration, choosing it with `--cfg size="…"`, and measures each ELF.
//!
//! | configuration | what the firmware does |
//! |---|---|
//! | (none) `empty` | boots and exits: cortex-m-rt, a panic handler, semihosting exit |
//! | `value_f32` | one `SpringValue<f32, 1>` from raw coefficients, retargeted and stepped |
//! | `value_f32_exact` | the same value tuned by the exact map (`Tuning::from_frequency`, libm in f64) |
//! | `value_i16f16` | one `SpringValue<I16F16, 1>` from raw coefficients |
//! | `batch16_f32` | a `SpringBatch<f32, 16>` of 16 values |
//! | `rope_f32` | an f32 2D rope `Scene` (8 particles, gravity, exact length kernel) |
//! | `knob` | an f32 `Knob` with detents and endstops, updated from an encoder |
//! | `everything` | all of the above in one firmware |
//!
//! Every input goes through `black_box`, so that the optimiser cannot fold a scene into
//! constants. The panic handler does not format its message, so that a bounds check in
//! the library does not pull `core::fmt` into the report. On the host the example runs
//! the configured code once.
#![cfg_attr(target_os = "none", no_std, no_main)]

use core::hint::black_box;

#[cfg(target_os = "none")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    semihosting::process::exit(101)
}

#[cfg(target_os = "none")]
#[cortex_m_rt::entry]
fn main() -> ! {
    configured();
    semihosting::process::exit(0)
}

#[cfg(not(target_os = "none"))]
fn main() {
    configured();
}

/// The code of the chosen configuration.
fn configured() {
    #[cfg(any(size = "value_f32", size = "everything"))]
    value_f32();
    #[cfg(any(size = "value_f32_exact", size = "everything"))]
    value_f32_exact();
    #[cfg(any(size = "value_i16f16", size = "everything"))]
    value_i16f16();
    #[cfg(any(size = "batch16_f32", size = "everything"))]
    batch16_f32();
    #[cfg(any(size = "rope_f32", size = "everything"))]
    rope_f32();
    #[cfg(any(size = "knob", size = "everything"))]
    knob();
    black_box(());
}

/// A value from raw coefficients: what a firmware that precomputed `C_k`, `C_d` pays.
#[allow(dead_code)]
fn value_f32() {
    use stiffspring::{SpringValue, Tuning};
    let Ok(tuning) = Tuning::from_coefficients(black_box(0.05), black_box(0.3)) else {
        return;
    };
    let Ok(mut v) = SpringValue::<f32, 1>::new([black_box(0.0)], tuning, black_box(1.0 / 60.0))
    else {
        return;
    };
    let _ = v.set_target([black_box(100.0)]);
    for _ in 0..black_box(60) {
        v.step();
    }
    black_box(v.position());
}

/// A value tuned by the exact map at run time.
#[allow(dead_code)]
fn value_f32_exact() {
    use stiffspring::{SpringValue, Tuning};
    let dt = black_box(1.0 / 60.0);
    let Ok(tuning) = Tuning::from_frequency(black_box(2.0), black_box(0.3), dt) else {
        return;
    };
    let Ok(mut v) = SpringValue::<f32, 1>::new([black_box(0.0)], tuning, dt) else {
        return;
    };
    let _ = v.set_target([black_box(100.0)]);
    for _ in 0..black_box(60) {
        v.step();
    }
    black_box(v.position());
}

/// A fixed-point value from raw coefficients.
#[allow(dead_code)]
fn value_i16f16() {
    use stiffspring::{I16F16, SpringValue, Tuning};
    let Ok(tuning) = Tuning::from_coefficients(black_box(0.05), black_box(0.3)) else {
        return;
    };
    let start = I16F16::from_bits(black_box(0));
    let Ok(mut v) = SpringValue::<I16F16, 1>::new([start], tuning, black_box(1.0 / 60.0)) else {
        return;
    };
    let _ = v.set_target([I16F16::from_bits(black_box(100 << 16))]);
    for _ in 0..black_box(60) {
        v.step();
    }
    black_box(v.position());
}

/// Sixteen values in one batch.
#[allow(dead_code)]
fn batch16_f32() {
    use stiffspring::{SpringBatch, Tuning};
    let Ok(mut batch) = SpringBatch::<f32, 16>::new(black_box(1.0 / 60.0)) else {
        return;
    };
    for i in 0..16 {
        let Ok(tuning) = Tuning::from_coefficients(black_box(0.05), black_box(0.3)) else {
            return;
        };
        if let Ok(k) = batch.push([black_box(0.0)], tuning) {
            let _ = batch.set_target(k, [black_box(10.0 * i as f32)]);
        }
    }
    for _ in 0..black_box(60) {
        batch.step();
    }
    black_box(batch.position(black_box(3)).ok());
}

/// A hanging 2D rope: the scene with the exact length kernel.
#[allow(dead_code)]
fn rope_f32() {
    use stiffspring::Tuning;
    use stiffspring::scene::{Scene, SceneConfig};
    let Ok(config) = SceneConfig::new(black_box(1.0 / 120.0)).and_then(|c| c.gravity([0.0, -9.81]))
    else {
        return;
    };
    let Ok(mut rope) = Scene::<f32, 2, 8, 7>::new(config) else {
        return;
    };
    let Ok(tuning) = Tuning::from_coefficients(black_box(0.3), black_box(0.3)) else {
        return;
    };
    let Ok(mut last) = rope.add_pinned([black_box(0.0), 0.0]) else {
        return;
    };
    for i in 1..8 {
        let Ok(next) = rope.add_particle([black_box(0.1 * i as f32), 0.0], black_box(0.05)) else {
            return;
        };
        let _ = rope.add_spring(last, next, black_box(0.1), tuning);
        last = next;
    }
    for _ in 0..black_box(240) {
        rope.step();
    }
    black_box(rope.position(last).ok());
}

/// A haptic knob with detents and endstops, fed by an encoder.
#[allow(dead_code)]
fn knob() {
    use stiffspring::{Knob, KnobConfig};
    let config = KnobConfig::new(black_box(1e-3), black_box(1e-5), black_box(0.05))
        .endstops(0.0, black_box(3.0))
        .detent_count(black_box(16))
        .detent_strength(black_box(0.05));
    let Ok(mut knob) = Knob::<f32>::new(&config, black_box(0.0)) else {
        return;
    };
    for n in 0..black_box(1000) {
        let out = knob.update(black_box(n as f32 * 1e-3));
        black_box(out.torque);
    }
}
