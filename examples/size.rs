//! Firmware instrument: minimal firmwares for the flash-size report. `scripts/size-report`
//! builds this example once per configuration, choosing it with `--cfg size="…"`, and
//! measures each ELF (`target/size/report.csv`).
//!
//! | configuration | what the firmware does |
//! |---|---|
//! | `empty` (no cfg) | boots and exits: cortex-m-rt, a panic handler, semihosting exit |
//! | `value_f32_raw` | one `SpringValue<f32, 1>` from raw coefficients in a `const` tuning (`tuning!`), retargeted and stepped |
//! | `value_f32_raw_runtime` | the same from raw coefficients known at run time (validated at run time, in `f64`) |
//! | `value_f32_exact_const` | the same tuned by the exact map at compile time (`tuning!(Tuning::from_frequency(…))`) |
//! | `value_f32_exact_runtime` | the same tuned by the exact map at run time (`Tuning::from_frequency` in `f64`: there is no `f32` set-up path) |
//! | `value_i16f16_raw` | one `SpringValue<I16F16, 1>` from a raw tuning converted to `I16F16` at compile time (`tuning!(…, I16F16)`, `SpringValue::from_tuned_in`) |
//! | `batch16_f32` | a `SpringBatch<f32, 1, 16>` of 16 values from a `const` raw tuning |
//! | `rope_f32` | an `f32` 2D rope `Scene` (8 particles, gravity, exact length kernel) |
//! | `knob_f32` | an `f32` `Knob` with detents and endstops (set up at run time), updated from an encoder |
//! | `knob_f32_const` | the same knob designed at compile time (`knob!`), started with `Knob::from_design` |
//! | `knob_i16f16_const` | the same in `I16F16`, designed at compile time |
//! | `everything` | all of the above in one firmware |
//! | `c_twin_value`, `c_twin_batch`, `c_twin_knob`, and `c_twin_value_q16`, `c_twin_batch_q16`, `c_twin_knob_q16` in `I16F16` | the Rust twins of the C API's size firmwares (`capi/c/m4f/size.c`, `scripts/capi-size`): the same calls with every object kept in memory between them, as a C caller's storage keeps it, so that the difference is the C layer's own |
//!
//! Every input that is not meant to be a constant goes through `black_box`, so that the
//! optimiser cannot fold a scene into constants. The panic handler does not format its
//! message, so that a bounds check in the library does not pull `core::fmt` into the
//! report. On the host the example runs the configured code once.
#![cfg_attr(target_os = "none", no_std, no_main)]

use core::hint::black_box;
#[allow(unused_imports)]
use stiffspring::{SpringValue, Tuning, tuning};

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
    #[cfg(any(size = "value_f32_raw", size = "everything"))]
    value_f32_raw();
    #[cfg(any(size = "value_f32_raw_runtime", size = "everything"))]
    value_f32_raw_runtime();
    #[cfg(any(size = "value_f32_exact_const", size = "everything"))]
    value_f32_exact_const();
    #[cfg(any(size = "value_f32_exact_runtime", size = "everything"))]
    value_f32_exact_runtime();
    #[cfg(any(size = "value_i16f16_raw", size = "everything"))]
    value_i16f16_raw();
    #[cfg(any(size = "batch16_f32", size = "everything"))]
    batch16_f32();
    #[cfg(any(size = "rope_f32", size = "everything"))]
    rope_f32();
    #[cfg(any(size = "knob_f32", size = "everything"))]
    knob_f32();
    #[cfg(any(size = "knob_f32_const", size = "everything"))]
    knob_f32_const();
    #[cfg(any(size = "knob_i16f16_const", size = "everything"))]
    knob_i16f16_const();
    #[cfg(size = "c_twin_value")]
    c_twin::value::<f32>();
    #[cfg(size = "c_twin_batch")]
    c_twin::batch::<f32>();
    #[cfg(size = "c_twin_knob")]
    c_twin::knob::<f32>();
    #[cfg(size = "c_twin_value_q16")]
    c_twin::value::<stiffspring::I16F16>();
    #[cfg(size = "c_twin_batch_q16")]
    c_twin::batch::<stiffspring::I16F16>();
    #[cfg(size = "c_twin_knob_q16")]
    c_twin::knob::<stiffspring::I16F16>();
    black_box(());
}

/// The Rust twins of `capi/c/m4f/size.c`: what its C firmwares do through the C API, in
/// Rust. A C caller's objects (the tuning, the value, the knob's configuration) live in its
/// storage, where the library sees nothing of them at compile time: here `black_box` puts
/// each in memory the optimiser cannot see through, so that the twin pays the library's
/// code as the C firmware does and the difference is the C layer's (its checks, the error
/// codes, one function per call).
#[allow(dead_code)]
mod c_twin {
    use core::hint::black_box;
    use stiffspring::{I16F16, Knob, Scalar, SpringBatch, SpringValue, Tuning};

    /// The numbers a C firmware passes: `float`s, or Q16.16 `int32_t`s that the C API takes
    /// as the bits of an `I16F16` (no conversion in either).
    pub trait Input: Scalar {
        /// `x`, as the C firmware writes it (`10 * i` for a batch's targets, say).
        fn input(x: i32) -> Self;
        /// The encoder angle of period `n`, about 1e−3 rad a period.
        fn angle(n: i32) -> Self;
    }
    impl Input for f32 {
        fn input(x: i32) -> f32 {
            x as f32
        }
        fn angle(n: i32) -> f32 {
            n as f32 * 1e-3
        }
    }
    impl Input for I16F16 {
        fn input(x: i32) -> I16F16 {
            I16F16::from_bits(x << 16)
        }
        fn angle(n: i32) -> I16F16 {
            I16F16::from_bits(n * 66)
        }
    }

    fn tuning() -> Option<Tuning> {
        let t = Tuning::from_frequency(black_box(2.0), black_box(0.7), black_box(1.0 / 60.0));
        t.ok().map(black_box)
    }

    pub fn value<S: Input>() {
        let Some(t) = tuning() else { return };
        let Ok(v) = SpringValue::<S, 1>::new([black_box(S::input(0))], &t) else {
            return;
        };
        let mut v = black_box(v);
        v.set_target([black_box(S::input(100))]);
        for _ in 0..black_box(60) {
            let _ = black_box(v.step());
        }
        black_box(v.position());
    }

    pub fn batch<S: Input>() {
        let Some(t) = tuning() else { return };
        let Ok(b) = SpringBatch::<S, 1, 16>::new(&t) else {
            return;
        };
        let mut b = black_box(b);
        let mut last = None;
        for i in 0..16 {
            if let Ok(k) = b.push([black_box(S::input(0))]) {
                b.set_target(k, [S::input(10 * i)]);
                last = Some(k);
            }
        }
        for _ in 0..black_box(60) {
            let _ = black_box(b.step());
        }
        if let Some(k) = last {
            black_box(b.position(k));
        }
    }

    pub fn knob<S: Input>() {
        let config = super::run_time_knob_config();
        let config = black_box(config);
        let Ok(knob) = Knob::<S>::new(&config, black_box(S::input(0))) else {
            return;
        };
        let mut knob = black_box(knob);
        for n in 0..black_box(1000) {
            let out = knob.update(S::angle(n));
            black_box(out.torque);
        }
    }
}

/// A UI value at 60 Hz: set up from `tuning`, sent to a target, stepped for a second.
#[allow(dead_code)]
#[inline(always)]
fn run_value(tuning: &Tuning) {
    let Ok(mut v) = SpringValue::<f32, 1>::new([black_box(0.0)], tuning) else {
        return;
    };
    v.set_target([black_box(100.0)]);
    for _ in 0..black_box(60) {
        let _ = black_box(v.step());
    }
    black_box(v.position());
}

/// A value from raw coefficients, its tuning a `const`: what a firmware that
/// precomputed `C_k`, `C_d` pays.
#[allow(dead_code)]
fn value_f32_raw() {
    const T: Tuning = tuning!(Tuning::from_coefficients(0.05, 0.3, 1.0 / 60.0));
    run_value(&T);
}

/// Raw coefficients known only at run time: validated at run time, in `f64`.
#[allow(dead_code)]
fn value_f32_raw_runtime() {
    let dt = black_box(1.0 / 60.0);
    if let Ok(t) = Tuning::from_coefficients(black_box(0.05), black_box(0.3), dt) {
        run_value(&t);
    }
}

/// A value tuned by the exact map at compile time: two coefficients, no libm.
#[allow(dead_code)]
fn value_f32_exact_const() {
    const T: Tuning = tuning!(Tuning::from_frequency(2.0, 0.7, 1.0 / 60.0));
    run_value(&T);
}

/// A value tuned by the exact map at run time (`f64`).
#[allow(dead_code)]
fn value_f32_exact_runtime() {
    let dt = black_box(1.0 / 60.0);
    if let Ok(t) = Tuning::from_frequency(black_box(2.0), black_box(0.7), dt) {
        run_value(&t);
    }
}

/// A fixed-point value from a raw tuning converted to `I16F16` when the firmware is built
/// (`tuning!` with the backend), started in place (`SpringValue::from_tuned_in`).
#[allow(dead_code)]
fn value_i16f16_raw() {
    use stiffspring::{I16F16, Tuned};
    const T: Tuned<I16F16> = tuning!(Tuning::from_coefficients(0.05, 0.3, 1.0 / 60.0), I16F16);
    let start = I16F16::from_bits(black_box(0));
    let mut slot = core::mem::MaybeUninit::uninit();
    let Ok(v) = SpringValue::<I16F16, 1>::from_tuned_in(&mut slot, [start], &T) else {
        return;
    };
    v.set_target([I16F16::from_bits(black_box(100 << 16))]);
    for _ in 0..black_box(60) {
        let _ = black_box(v.step());
    }
    black_box(v.position());
}

/// Sixteen values in one batch sharing a `const` raw tuning.
#[allow(dead_code)]
fn batch16_f32() {
    use stiffspring::SpringBatch;
    const T: Tuning = tuning!(Tuning::from_coefficients(0.05, 0.3, 1.0 / 60.0));
    let Ok(mut batch) = SpringBatch::<f32, 1, 16>::new(&T) else {
        return;
    };
    let mut last = None;
    for i in 0..16 {
        if let Ok(k) = batch.push([black_box(0.0)]) {
            batch.set_target(k, [black_box(10.0 * i as f32)]);
            last = Some(k);
        }
    }
    for _ in 0..black_box(60) {
        let _ = black_box(batch.step());
    }
    if let Some(k) = last {
        black_box(batch.position(k));
    }
}

/// A hanging 2D rope: the scene with the exact length kernel.
#[allow(dead_code)]
fn rope_f32() {
    use stiffspring::scene::{Scene, SceneConfig};
    const DT: f64 = 1.0 / 120.0;
    const T: Tuning = tuning!(Tuning::from_coefficients(0.3, 0.3, DT));
    let Ok(config) = SceneConfig::new(DT).and_then(|c| c.gravity([0.0, black_box(-9.81)])) else {
        return;
    };
    let mut rope = Scene::<f32, 2, 8, 7>::new(config);
    let Ok(mut last) = rope.add_pinned([black_box(0.0), 0.0]) else {
        return;
    };
    for i in 1..8 {
        let Ok(next) = rope.add_particle([black_box(0.1 * i as f32), 0.0], black_box(0.05)) else {
            return;
        };
        let _ = rope.add_spring(last, next, black_box(0.1), &T);
        last = next;
    }
    for _ in 0..black_box(240) {
        let _ = black_box(rope.step());
    }
    black_box(rope.position(last).ok());
}

/// The knob of [`knob_f32`], as a `const` configuration.
#[allow(dead_code)]
const KNOB: stiffspring::KnobConfig = stiffspring::KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
    .endstops(0.0, 3.0)
    .detent_count(16)
    .detent_stiffness(0.05);

/// The knob of [`knob_f32`] designed at compile time: the firmware starts it from the
/// design and updates it from an encoder.
#[allow(dead_code)]
fn knob_f32_const() {
    use stiffspring::Knob;
    let mut slot = core::mem::MaybeUninit::uninit();
    let design = stiffspring::knob!(KNOB, f32);
    let Ok(knob) = Knob::from_design_in(&mut slot, &design, black_box(0.0)) else {
        return;
    };
    for n in 0..black_box(1000) {
        let out = knob.update(black_box(n as f32 * 1e-3));
        black_box(out.torque);
    }
}

/// [`knob_f32_const`] in `I16F16`: the encoder's angle is a Q16.16 number from the start
/// (no float on the way).
#[allow(dead_code)]
fn knob_i16f16_const() {
    use stiffspring::{I16F16, Knob};
    let mut slot = core::mem::MaybeUninit::uninit();
    let design = stiffspring::knob!(KNOB, I16F16);
    let Ok(knob) = Knob::from_design_in(&mut slot, &design, black_box(I16F16::ZERO)) else {
        return;
    };
    for n in 0..black_box(1000) {
        // About 1e−3 rad per period, as the f32 knob's encoder.
        let out = knob.update(black_box(I16F16::from_bits(n * 66)));
        black_box(out.torque);
    }
}

/// The knob of [`KNOB`], every number hidden from the optimiser: a configuration that
/// arrives at run time (shared by [`knob_f32`] and the C API's twin).
#[allow(dead_code)]
fn run_time_knob_config() -> stiffspring::KnobConfig {
    stiffspring::KnobConfig::new(
        black_box(1_000.0),
        black_box(1e-5),
        black_box(0.05),
        black_box(16384),
    )
    .endstops(0.0, black_box(3.0))
    .detent_count(black_box(16))
    .detent_stiffness(black_box(0.05))
}

/// A haptic knob with detents and endstops, fed by an encoder.
#[allow(dead_code)]
fn knob_f32() {
    use stiffspring::Knob;
    let config = run_time_knob_config();
    let Ok(mut knob) = Knob::<f32>::new(&config, black_box(0.0)) else {
        return;
    };
    for n in 0..black_box(1000) {
        let out = knob.update(black_box(n as f32 * 1e-3));
        black_box(out.torque);
    }
}
