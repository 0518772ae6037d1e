//! Instruction counts per step of every hot kernel, in every backend, on an emulated
//! Cortex-M4F and Cortex-M0.
//!
//! ```text
//! scripts/cost                       # both machines: target/cost/m4f.csv, target/cost/m0.csv
//! cargo run --release --target thumbv7em-none-eabihf --example cost   # CSV on stdout
//! ```
//!
//! On the target the harness reads the CMSDK TIMER0 of QEMU's MPS2 boards while QEMU
//! runs with `-icount shift=10,align=off,sleep=off` (scripts/qemu-run does both for
//! examples named `cost`): every instruction then advances the virtual clock by exactly
//! 1024 ns, the timer ticks at 25 MHz, and `instructions = Δticks·40/1024` is exact and
//! identical from run to run. The ARMv6-M build runs on `mps2-an385`, which executes
//! it instruction for instruction like a Cortex-M0 (the microbit has no CMSDK timer).
//! These are instructions, not cycles.
//!
//! Each kernel is stepped in an `#[inline(never)]` loop between two timer reads, `N₁`
//! and then `N₂` times; `(I(N₂) − I(N₁))/(N₂ − N₁)` removes the call and the timer
//! reads, and the same figure for an empty loop (the loop's own counter and branch) is
//! subtracted. What is left is divided by the springs a step moves. The CSV has the
//! columns `kernel,backend,instructions_per_step`, with three decimals (the average of
//! data-dependent paths over the `N₂ − N₁` steps). On the host the same kernels run
//! with a wall clock instead, as a smoke test.
//!
//! **Adding a kernel** is one line in [`kernels!`] below: a name, a backend, and an
//! expression that builds an `Option<impl Bench>` (a state with a `step`).
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(text);

use stiffspring::kernel::Coefficients;
use stiffspring::length::{Exact, LengthKernel, Linearised};
use stiffspring::scene::{AngularScene, Scene, SceneConfig, WrappedAngle};
use stiffspring::{
    I16F16, I32F32, Knob, KnobConfig, RestThreshold, Scalar, SpringBatch, SpringValue, Tuning,
};

/// Steps in the two measured runs; their difference is what is counted. The longest
/// run (f64 in soft float on the M0, a scene of 8 springs) stays far below the timer's
/// wrap at 167 M instructions.
const N1: u32 = 32;
const N2: u32 = 32 + 256;

/// Something whose step is counted.
trait Bench {
    /// One step. Inlined into the harness loop.
    fn step(&mut self);
    /// The springs (or values) one step moves; the count is reported per spring.
    fn per_step(&self) -> u32 {
        1
    }
}

/// The empty loop: the harness's own overhead per iteration.
struct Empty;
impl Bench for Empty {
    #[inline(always)]
    fn step(&mut self) {}
}

// ---------------------------------------------------------------------------------------
// The kernels
// ---------------------------------------------------------------------------------------

/// An undamped spring that never comes to rest: every step takes the moving path.
fn never_resting() -> Option<Tuning> {
    Tuning::from_coefficients(0.01, 0.0).ok()
}

/// `SpringValue::<S, 1>::step` of a moving value: the kernel, the rest check.
struct Value<S: Scalar>(SpringValue<S, 1>);
impl<S: Scalar> Bench for Value<S> {
    #[inline(always)]
    fn step(&mut self) {
        self.0.step();
    }
}
fn value<S: Scalar>() -> Option<Value<S>> {
    let never = RestThreshold::new(1e-30, 1e-30).ok()?;
    let mut v = SpringValue::new([S::ZERO], never_resting()?, 1e-3)
        .ok()?
        .with_rest_threshold(never);
    v.set_target([S::from_f64(100.0)]).ok()?;
    Some(Value(v))
}

/// The bare two multiply-adds: `u ← respond(x, u)`, `x ← x + u`.
struct Kernel1<S: Scalar> {
    c: Coefficients<S>,
    x: S,
    u: S,
}
impl<S: Scalar> Bench for Kernel1<S> {
    #[inline(always)]
    fn step(&mut self) {
        self.u = self.c.respond(self.x, self.u);
        self.x = self.x.add(self.u);
    }
}
fn kernel_1d<S: Scalar>() -> Option<Kernel1<S>> {
    Some(Kernel1 {
        c: Coefficients::new(&never_resting()?),
        x: S::from_f64(100.0),
        u: S::ZERO,
    })
}

/// `SpringBatch::<S, 16>::step` with all 16 values moving, per value.
struct Batch<S: Scalar>(SpringBatch<S, 16>);
impl<S: Scalar> Bench for Batch<S> {
    #[inline(always)]
    fn step(&mut self) {
        self.0.step();
    }
    fn per_step(&self) -> u32 {
        16
    }
}
fn batch_16<S: Scalar>() -> Option<Batch<S>> {
    let never = RestThreshold::new(1e-30, 1e-30).ok()?;
    let mut b = SpringBatch::new(1e-3).ok()?;
    for i in 0..16 {
        let k = b
            .push_with_threshold([S::ZERO], never_resting()?, never)
            .ok()?;
        b.set_target(k, [S::from_f64(10.0 + i as f64)]).ok()?;
    }
    Some(Batch(b))
}

/// A scene step, per spring.
struct SceneStep<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>(
    Scene<S, D, P, K, L>,
);
impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>> Bench
    for SceneStep<S, D, P, K, L>
{
    #[inline(always)]
    fn step(&mut self) {
        self.0.step();
    }
    fn per_step(&self) -> u32 {
        K as u32
    }
}

/// Lightly damped, inside the network limit of two springs per particle.
fn chain_tuning() -> Option<Tuning> {
    Tuning::from_coefficients(0.2, 0.01).ok()
}

/// The 2D distance spring with length kernel `L`: a free chain of 9 particles and 8
/// springs, zig-zagged so that every spring is stretched, without gravity or sleep. Per
/// spring, the particles' integration included.
fn distance_2d<S: Scalar, L: LengthKernel<S>>() -> Option<SceneStep<S, 2, 9, 8, L>> {
    let config = SceneConfig::new(1e-3).ok()?.no_sleep();
    let mut scene = Scene::<S, 2, 9, 8, L>::new(config).ok()?;
    let mut previous = None;
    for i in 0..9 {
        let y = if i % 2 == 0 { 0.0 } else { 0.3 };
        let p = scene
            .add_particle([S::from_f64(i as f64), S::from_f64(y)], 1.0)
            .ok()?;
        if let Some(q) = previous {
            scene.add_spring(q, p, 1.0, chain_tuning()?).ok()?;
        }
        previous = Some(p);
    }
    Some(SceneStep(scene))
}

/// The angular spring with angle kernel `L`: a free chain of 9 bodies and 8 springs, wound
/// alternately. Per spring, the bodies' integration included.
fn angular<S: Scalar, L: LengthKernel<S>>() -> Option<SceneStep<S, 1, 9, 8, L>> {
    let config = SceneConfig::new(1e-3).ok()?.no_sleep();
    let mut scene = AngularScene::<S, 9, 8, L>::new(config).ok()?;
    let mut previous = None;
    for i in 0..9 {
        let angle = if i % 2 == 0 { 0.0 } else { 0.5 };
        let p = scene.add_particle([S::from_f64(angle)], 1e-3).ok()?;
        if let Some(q) = previous {
            scene.add_spring(q, p, 0.0, chain_tuning()?).ok()?;
        }
        previous = Some(p);
    }
    Some(SceneStep(scene))
}

/// `Knob::update` at 1 kHz with 16 detents between endstops, fed by a scripted encoder
/// that sweeps the whole range and beyond both endstops (the script is one add and one
/// compare per step).
struct KnobUpdate<S: Scalar> {
    knob: Knob<S>,
    angle: S,
    increment: S,
    low: S,
    high: S,
}
impl<S: Scalar> Bench for KnobUpdate<S> {
    #[inline(always)]
    fn step(&mut self) {
        let out = self.knob.update(self.angle);
        core::hint::black_box(out.torque);
        self.angle = self.angle.add(self.increment);
        if self.angle > self.high {
            self.angle = self.low;
        }
    }
}
fn knob_torque<S: Scalar>() -> Option<KnobUpdate<S>> {
    let config = KnobConfig::new(1e-3, 1e-5, 0.05)
        .endstops(0.0, 3.0)
        .detent_count(16)
        .detent_strength(0.3);
    Some(KnobUpdate {
        knob: Knob::new(&config, 0.0).ok()?,
        angle: S::from_f64(-0.2),
        // 256 steps cover 3.4 rad: both endstops and every detent.
        increment: S::from_f64(3.4 / 256.0),
        low: S::from_f64(-0.2),
        high: S::from_f64(3.2),
    })
}

/// The table of kernels: `"name", Backend => expression giving an Option<impl Bench>;`.
/// `None` (a configuration the backend rejects) is reported as a failure.
macro_rules! kernels {
    ($($name:literal, $S:ty => $make:expr;)*) => {
        /// Measures every kernel of the table; false when one could not be built.
        fn measure_all() -> bool {
            let mut ok = true;
            $( ok &= report($name, <$S as Scalar>::NAME, $make); )*
            ok
        }
    };
}

kernels! {
    "value_1d", f32 => value::<f32>();
    "value_1d", f64 => value::<f64>();
    "value_1d", I16F16 => value::<I16F16>();
    "value_1d", I32F32 => value::<I32F32>();
    "kernel_1d", f32 => kernel_1d::<f32>();
    "kernel_1d", f64 => kernel_1d::<f64>();
    "kernel_1d", I16F16 => kernel_1d::<I16F16>();
    "kernel_1d", I32F32 => kernel_1d::<I32F32>();
    "batch_16", f32 => batch_16::<f32>();
    "batch_16", I16F16 => batch_16::<I16F16>();
    "distance_2d/exact", f32 => distance_2d::<f32, Exact>();
    "distance_2d/exact", f64 => distance_2d::<f64, Exact>();
    "distance_2d/exact", I16F16 => distance_2d::<I16F16, Exact>();
    "distance_2d/exact", I32F32 => distance_2d::<I32F32, Exact>();
    "distance_2d/linearised", f32 => distance_2d::<f32, Linearised>();
    "distance_2d/linearised", I16F16 => distance_2d::<I16F16, Linearised>();
    "distance_2d/linearised", I32F32 => distance_2d::<I32F32, Linearised>();
    "distance_2d/approximate", f32 => distance_2d::<f32, stiffspring::length::Approximate>();
    "distance_2d/approximate_newton", f32 => distance_2d::<f32, stiffspring::length::ApproximateNewton>();
    "angular/angle", f32 => angular::<f32, stiffspring::scene::Angle>();
    "angular/angle", I16F16 => angular::<I16F16, stiffspring::scene::Angle>();
    "angular/wrapped", f32 => angular::<f32, WrappedAngle>();
    "angular/wrapped", I16F16 => angular::<I16F16, WrappedAngle>();
    "knob_torque", f32 => knob_torque::<f32>();
    "knob_torque", f64 => knob_torque::<f64>();
    "knob_torque", I16F16 => knob_torque::<I16F16>();
    "knob_torque", I32F32 => knob_torque::<I32F32>();
}

/// The Cortex-M4F's `vsqrt.f32` kernel exists only on hard-float ARM targets.
#[cfg(target_abi = "eabihf")]
fn measure_hardware() -> bool {
    report(
        "distance_2d/hardware_sqrt",
        "f32",
        distance_2d::<f32, stiffspring::length::HardwareSqrt>(),
    )
}
#[cfg(not(target_abi = "eabihf"))]
fn measure_hardware() -> bool {
    true
}

// `HardwareSqrt` exists only on hard-float ARM targets, so `tests/defmt_format.rs` (on
// the host) cannot check that it is `defmt::Format` like every public type; this does.
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
const _: () = {
    const fn is_format<T: defmt::Format>() {}
    is_format::<stiffspring::length::HardwareSqrt>();
};

// ---------------------------------------------------------------------------------------
// The harness
// ---------------------------------------------------------------------------------------

/// The CMSDK TIMER0 of the MPS2 boards: QEMU does not implement the DWT cycle counter,
/// but with `-icount shift=10` this 25 MHz timer advances by exactly 40/1024 of a tick
/// per instruction (ARM's MPS2 documentation for the address, QEMU's for `-icount`).
#[cfg(target_os = "none")]
mod timer {
    const CTRL: *mut u32 = 0x4000_0000 as *mut u32;
    const VALUE: *mut u32 = 0x4000_0004 as *mut u32;
    const RELOAD: *mut u32 = 0x4000_0008 as *mut u32;

    /// Starts the timer counting down from `u32::MAX`.
    pub fn start() {
        // SAFETY: the MPS2 boards map TIMER0's registers here; nothing else uses them.
        unsafe {
            RELOAD.write_volatile(u32::MAX);
            VALUE.write_volatile(u32::MAX);
            CTRL.write_volatile(1);
        }
    }

    /// The current count (it counts down).
    #[inline(always)]
    pub fn now() -> u32 {
        // SAFETY: as in `start`; a read has no side effect.
        unsafe { VALUE.read_volatile() }
    }

    /// Instructions in `ticks`: one instruction is 2^10 ns of virtual time at
    /// `-icount shift=10`, one tick 40 ns (25 MHz), so 25.6 ticks per instruction.
    pub fn instructions(ticks: u32) -> u64 {
        (ticks as u64 * 40 + 512) / 1024
    }
}

/// The cost of `n` steps of `bench`: instructions on the target. Never inlined, so
/// that the instructions between the two timer reads other than the steps are the same
/// for every `n` (they cancel in [`per_step_milli`]); `n` is opaque to the optimiser.
#[cfg(target_os = "none")]
#[inline(never)]
fn count<B: Bench>(bench: &mut B, n: u32) -> u64 {
    let n = core::hint::black_box(n);
    let start = timer::now();
    for _ in 0..n {
        bench.step();
        // Keeps the loop from being unrolled and the state from living in registers
        // across steps: a firmware's state lives in memory between two control periods.
        core::hint::black_box(&mut *bench);
    }
    let end = timer::now();
    timer::instructions(start.wrapping_sub(end))
}

/// The cost of `n` steps of `bench`: nanoseconds of wall clock on the host.
#[cfg(not(target_os = "none"))]
#[inline(never)]
fn count<B: Bench>(bench: &mut B, n: u32) -> u64 {
    let n = core::hint::black_box(n);
    let start = std::time::Instant::now();
    for _ in 0..n {
        bench.step();
        // Keeps the loop from being unrolled and the state from living in registers
        // across steps: a firmware's state lives in memory between two control periods.
        core::hint::black_box(&mut *bench);
    }
    start.elapsed().as_nanos() as u64
}

/// Thousandths of a unit per step of `bench`, harness included: `(I(N₂) − I(N₁))`
/// over `N₂ − N₁` steps.
fn per_step_milli<B: Bench>(bench: &mut B) -> i64 {
    let first = count(bench, N1) as i64;
    let second = count(bench, N2) as i64;
    (second - first) * 1000 / (N2 - N1) as i64
}

/// Prints one CSV line for `bench`; false when it could not be built.
fn report<B: Bench>(kernel: &str, backend: &str, bench: Option<B>) -> bool {
    let Some(mut bench) = bench else {
        say!("{},{},FAILED (set-up rejected)", kernel, backend);
        return false;
    };
    let overhead = per_step_milli(&mut Empty);
    let gross = per_step_milli(&mut bench);
    let per = bench.per_step() as i64;
    let net = (gross - overhead) / per;
    let sign = if net < 0 { "-" } else { "" };
    say!(
        "{},{},{}{}.{}{}{}",
        kernel,
        backend,
        sign,
        net.abs() / 1000,
        net.abs() / 100 % 10,
        net.abs() / 10 % 10,
        net.abs() % 10
    );
    true
}

fn run_all() -> bool {
    #[cfg(target_os = "none")]
    {
        timer::start();
        say!("kernel,backend,instructions_per_step");
    }
    #[cfg(not(target_os = "none"))]
    {
        say!(
            "# host: wall clock, noisy; the exact instruction counts come from QEMU (scripts/cost)"
        );
        say!("kernel,backend,nanoseconds_per_step");
    }
    measure_all() & measure_hardware()
}

firmware::main!(run_all);
