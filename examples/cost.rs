//! Firmware instrument: instructions per step of every hot kernel, in every backend, on
//! an emulated Cortex-M4F and Cortex-M0, beside hand-written floor loops.
//!
//! ```text
//! scripts/cost                       # both machines: target/cost/m4f.csv, target/cost/m0.csv
//! scripts/cost --twice               # and a second run, which must agree exactly
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
//! and then `N₂` times, with `black_box(&mut bench)` after every step so that the state
//! lives in memory between steps, as a firmware's does between two control periods;
//! `(I(N₂) − I(N₁))/(N₂ − N₁)` removes the call and the timer reads, and the same figure
//! for an empty loop (the loop's own counter and branch) is subtracted. What is left is
//! divided by the values or springs a step moves. The CSV has the columns
//! `kernel,backend,instructions_per_step`, with three decimals (the average of
//! data-dependent paths over the `N₂ − N₁` steps). On the host the same kernels run
//! with a wall clock instead (nanoseconds, noisy), as a smoke test.
//!
//! The values are a lightly damped 2 Hz spring at 1 kHz (`ζ` = 0.02, `C_k` ≈ 1.6e−4,
//! `C_d` ≈ 2.5e−4) with a rest threshold of 1e−30, so that nothing settles while it is
//! measured: `step` pays for the rest test on every step and never for the snap. The
//! floors (`floor_*`) are what the same recurrence costs written by hand over plain
//! arrays, with the coefficients in registers: the reference the library's loops are
//! compared with (docs/firmware.md).
//!
//! **Adding a kernel** is one line in [`kernels!`] below: a name, a backend, and a
//! function that builds an `Option<impl Bench>` (a state with a `step`).
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(text);

use stiffspring::length::{Exact, LengthKernel, Linearised};
use stiffspring::scene::{Angle, AngularScene, Scene, SceneConfig};
use stiffspring::{
    I16F16, I32F32, Knob, KnobConfig, RestThreshold, Scalar, SpringBatch, SpringValue, Tuning,
};

/// Steps in the two measured runs; their difference is what is counted. The longest
/// run (a scene of 8 springs in soft-float `f64` on the M0) stays far below the timer's
/// wrap at 167 M instructions.
const N1: u32 = 32;
const N2: u32 = 32 + 256;

/// Values in the measured batches: the per-step bookkeeping of a batch is spread over
/// this many values. 16 on the Cortex-M0, whose 16 KiB of RAM (the microbit map) holds
/// the stack: a batch of 64 `I32F32` values is 3.4 KB, and the moves while it is built
/// overflowed it.
const BATCH: usize = if cfg!(target_abi = "eabihf") || cfg!(not(target_os = "none")) {
    64
} else {
    16
};

/// Something whose step is counted.
trait Bench {
    /// One step. Inlined into the harness loop.
    fn step(&mut self);
    /// The values or springs one step moves; the count is reported per one of them.
    fn per_step(&self) -> u32 {
        1
    }
    /// The steps of the two measured runs, `(N₁, N₂)`. A kernel whose cost follows a
    /// periodic script measures whole periods: `(P, 2P)`, so that the difference of the
    /// runs is one whole period.
    fn runs(&self) -> (u32, u32) {
        (N1, N2)
    }
}

/// The empty loop: the harness's own overhead per iteration.
struct Empty;
impl Bench for Empty {
    #[inline(always)]
    fn step(&mut self) {}
}

// ---------------------------------------------------------------------------------------
// Values and batches
// ---------------------------------------------------------------------------------------

/// A lightly damped 2 Hz spring at 1 kHz (ζ = 0.02): `C_k` ≈ 1.6e−4, `C_d` ≈ 2.5e−4.
fn tuning() -> Option<Tuning> {
    Tuning::from_frequency(2.0, 0.02, 1e-3).ok()
}

/// A threshold no measured value reaches: `step` always takes the moving path.
fn never() -> Option<RestThreshold> {
    RestThreshold::new(1e-30, 1e-30).ok()
}

fn moving_value<S: Scalar>() -> Option<SpringValue<S, 1>> {
    let mut v = SpringValue::new([S::ZERO], &tuning()?)
        .ok()?
        .with_rest_threshold(never()?);
    v.try_set_target([S::from_f64(100.0)]).ok()?;
    Some(v)
}

/// A UI value at 60 Hz, moving: `C_k = 0.05` and `C_d = 0.3` (a moderately damped
/// spring of about 2 Hz), whose damping is above the fixed-point fast path's `2⁻³`:
/// `I16F16` takes its out-of-line lifted step.
fn moving_ui_value<S: Scalar>() -> Option<SpringValue<S, 1>> {
    let tuning = Tuning::from_coefficients(0.05, 0.3, 1.0 / 60.0).ok()?;
    let mut v = SpringValue::new([S::ZERO], &tuning)
        .ok()?
        .with_rest_threshold(never()?);
    v.try_set_target([S::from_f64(100.0)]).ok()?;
    Some(v)
}

/// `SpringValue::<S, 1>::step` of [`moving_ui_value`].
fn ui_value_step<S: Scalar>() -> Option<ValueStep<S>> {
    Some(ValueStep(moving_ui_value()?))
}

/// `SpringValue::<S, 1>::advance`: the spring alone, no rest test.
struct ValueAdvance<S: Scalar>(SpringValue<S, 1>);
impl<S: Scalar> Bench for ValueAdvance<S> {
    #[inline(always)]
    fn step(&mut self) {
        self.0.advance();
    }
}
fn value_advance<S: Scalar>() -> Option<ValueAdvance<S>> {
    Some(ValueAdvance(moving_value()?))
}

/// `SpringValue::<S, 1>::step` of a moving value: the spring, the rest test, the event.
struct ValueStep<S: Scalar>(SpringValue<S, 1>);
impl<S: Scalar> Bench for ValueStep<S> {
    #[inline(always)]
    fn step(&mut self) {
        let _ = self.0.step();
    }
}
fn value_step<S: Scalar>() -> Option<ValueStep<S>> {
    Some(ValueStep(moving_value()?))
}

fn moving_batch<S: Scalar>() -> Option<SpringBatch<S, 1, BATCH>> {
    let mut b = SpringBatch::new(&tuning()?)
        .ok()?
        .with_rest_threshold(never()?);
    for i in 0..BATCH {
        let k = b.push([S::ZERO]).ok()?;
        b.try_set_target(k, [S::from_f64(10.0 + i as f64)]).ok()?;
    }
    Some(b)
}

/// `SpringBatch::<S, 1, BATCH>::step`, all awake, per value.
struct BatchStep<S: Scalar>(SpringBatch<S, 1, BATCH>);
impl<S: Scalar> Bench for BatchStep<S> {
    #[inline(always)]
    fn step(&mut self) {
        let _ = self.0.step();
    }
    fn per_step(&self) -> u32 {
        BATCH as u32
    }
}
fn batch_step<S: Scalar>() -> Option<BatchStep<S>> {
    Some(BatchStep(moving_batch()?))
}
/// [`batch_step`] testing rest every second step.
fn batch_step_every2<S: Scalar>() -> Option<BatchStep<S>> {
    Some(BatchStep(moving_batch()?.with_rest_check_every(2)))
}
/// [`batch_step`] testing rest every fourth step.
fn batch_step_every4<S: Scalar>() -> Option<BatchStep<S>> {
    Some(BatchStep(moving_batch()?.with_rest_check_every(4)))
}

/// `SpringBatch::<S, 1, BATCH>::advance`, per value.
struct BatchAdvance<S: Scalar>(SpringBatch<S, 1, BATCH>);
impl<S: Scalar> Bench for BatchAdvance<S> {
    #[inline(always)]
    fn step(&mut self) {
        self.0.advance();
    }
    fn per_step(&self) -> u32 {
        BATCH as u32
    }
}
fn batch_advance<S: Scalar>() -> Option<BatchAdvance<S>> {
    Some(BatchAdvance(moving_batch()?))
}

/// The floor of a batch in backend `S`: the library's own step (`Scalar::advance`) over
/// plain arrays, the gains copied into a local (registers) once per sweep.
struct Floor<S: Scalar> {
    gains: S::Gains,
    x: [S::State; BATCH],
    v: [S::State; BATCH],
}
impl<S: Scalar> Bench for Floor<S> {
    #[inline(always)]
    fn step(&mut self) {
        let g = self.gains;
        for (x, v) in self.x.iter_mut().zip(self.v.iter_mut()) {
            S::advance(&g, x, v);
        }
    }
    fn per_step(&self) -> u32 {
        BATCH as u32
    }
}
fn floor<S: Scalar>() -> Option<Floor<S>> {
    let t = tuning()?;
    let gains = S::gains(t.stiffness(), t.damping())?;
    let mut x = [S::STATE_ZERO; BATCH];
    for (i, x) in x.iter_mut().enumerate() {
        *x = S::from_f64(-10.0 - i as f64).widen();
    }
    Some(Floor {
        gains,
        x,
        v: [S::STATE_ZERO; BATCH],
    })
}

/// The `f32` batch floor written out by hand, independent of the library:
/// `u = ũ − k·x; x += u; ũ = u − d·u` over plain arrays.
struct FloorHand {
    k: f32,
    d: f32,
    x: [f32; BATCH],
    v: [f32; BATCH],
}
impl Bench for FloorHand {
    #[inline(always)]
    fn step(&mut self) {
        let (k, d) = (self.k, self.d);
        for (x, v) in self.x.iter_mut().zip(self.v.iter_mut()) {
            let u = *v - k * *x;
            *x += u;
            *v = u - d * u;
        }
    }
    fn per_step(&self) -> u32 {
        BATCH as u32
    }
}
fn floor_hand() -> Option<FloorHand> {
    let t = tuning()?;
    let mut x = [0.0; BATCH];
    for (i, x) in x.iter_mut().enumerate() {
        *x = -10.0 - i as f32;
    }
    Some(FloorHand {
        k: t.stiffness() as f32,
        d: t.damping() as f32,
        x,
        v: [0.0; BATCH],
    })
}

/// One `f32` value stepped by hand, its state and coefficients in memory as a
/// `SpringValue`'s are (the harness keeps nothing in registers between steps): the
/// single-value floor.
struct FloorValue {
    x: f32,
    v: f32,
    k: f32,
    d: f32,
}
impl Bench for FloorValue {
    #[inline(always)]
    fn step(&mut self) {
        let u = self.v - self.k * self.x;
        self.x += u;
        self.v = u - self.d * u;
    }
}
fn floor_value() -> Option<FloorValue> {
    let t = tuning()?;
    Some(FloorValue {
        x: -100.0,
        v: 0.0,
        k: t.stiffness() as f32,
        d: t.damping() as f32,
    })
}

/// One `I16F16` value stepped by hand in the library's own representation (issue 21's
/// floor): a Q24.40 state in an `i64`, each gain a mantissa `m` of 31 bits with
/// `C = m/2^(32+k)`, applied as `⌊x·m/2^32⌋` and then `⌊·/2^k⌋`. Plainer than the
/// library: it rounds both products down (the library rounds the spring's toward zero and
/// the damping's away from it, so that neither drifts) and tests no range (the library's
/// step tests the state's headroom, and takes its saturating step outside it). The ratio
/// of the library's `advance` to this is what the library's code costs over the
/// representation's. Each core gets the arithmetic that is cheapest on it (`FloorGain`).
struct FloorValueQ16 {
    x: i64,
    v: i64,
    k: FloorGain,
    d: FloorGain,
}
impl Bench for FloorValueQ16 {
    #[inline(always)]
    fn step(&mut self) {
        let u = self.v.wrapping_sub(floor_product(self.x, self.k));
        self.x = self.x.wrapping_add(u);
        self.v = u.wrapping_sub(floor_product(u, self.d));
    }
}
/// A gain of the hand floor: `(m, 2^(32−k))` where the core has a long multiply (the
/// shift by `k` as a multiply: `smull`/`umull` on the Cortex-M4F, where a 64-bit shift by
/// a variable amount costs more), `(m, k)` on a Cortex-M0.
type FloorGain = (i32, i32);
/// `⌊x·m/2^(32+k)⌋`: two long multiplies per step of the shift.
#[cfg(not(no_long_multiply))]
#[inline(always)]
fn floor_product(x: i64, (m, scale): FloorGain) -> i64 {
    let (xh, xl) = ((x >> 32) as i32, x as u32);
    let t = xh as i64 * m as i64 + ((xl as u64 * m as u32 as u64) >> 32) as i64;
    let (th, tl) = ((t >> 32) as i32, t as u32);
    th as i64 * scale as i64 + ((tl as u64 * scale as u32 as u64) >> 32) as i64
}
/// `⌊x·m/2^(32+k)⌋` on a Cortex-M0, whose `muls` keeps the low 32 bits of a product: `x·m`
/// from the eight products of `x`'s four 16-bit pieces and `m`'s two (the top piece of
/// `x` signed), then the shift by `k` as two 32-bit shifts. `m < 2³¹`, so each product
/// fits 32 bits (`|x₃·m₁| < 2³⁰`).
#[cfg(no_long_multiply)]
#[inline(always)]
fn floor_product(x: i64, (m, k): FloorGain) -> i64 {
    let (m0, m1) = ((m & 0xffff) as u32, (m >> 16) as u32);
    let (x0, x1) = (x as u32 & 0xffff, (x as u32) >> 16);
    let (x2, x3) = ((x >> 32) as u32 & 0xffff, (x >> 48) as i32);
    // x·m = Σ xᵢ·mⱼ·2^(16(i+j)); ⌊x·m/2^32⌋ needs the low word's carry only.
    let low = (x0 * m0) as u64 + (((x1 * m0) as u64 + (x0 * m1) as u64) << 16);
    let mid = (x1 * m1) as u64 + (x2 * m0) as u64 + (low >> 32);
    let t = (((x3 * m1 as i32) as i64) << 32)
        + ((((x3 * m0 as i32) as i64) + (x2 * m1) as i64) << 16)
        + mid as i64;
    let (th, tl) = ((t >> 32) as i32, t as u32);
    let ql = (tl >> k) | ((th as u32) << (32 - k));
    (((th >> k) as i64) << 32) | ql as i64
}
/// The [`FloorGain`] of `c`, with `2^30 ≤ m < 2^31` and `2 ≤ k ≤ 30`.
fn floor_gain(c: f64) -> Option<FloorGain> {
    // `no_std`: 2^(32+k) from the exponent field, as the library's own conversions do.
    let pow2 = |e: i32| f64::from_bits(((1023 + e) as u64) << 52);
    let mut k = 2;
    while c * pow2(32 + k) < pow2(30) && k < 30 {
        k += 1;
    }
    let m = c * pow2(32 + k) + 0.5;
    let second = if cfg!(no_long_multiply) {
        k
    } else {
        1 << (32 - k)
    };
    (m < pow2(31)).then_some((m as i32, second))
}
fn floor_value_q16() -> Option<FloorValueQ16> {
    let t = tuning()?;
    Some(FloorValueQ16 {
        x: -100 << 40,
        v: 0,
        k: floor_gain(t.stiffness())?,
        d: floor_gain(t.damping())?,
    })
}

// ---------------------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------------------

/// A scene step, per spring.
struct SceneStep<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>(
    Scene<S, D, P, K, L>,
);
impl<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>> Bench
    for SceneStep<S, D, P, K, L>
{
    #[inline(always)]
    fn step(&mut self) {
        let _ = self.0.step();
    }
    fn per_step(&self) -> u32 {
        K as u32
    }
}

/// Springs of the measured chains (9 particles).
const CHAIN: usize = 8;
/// The chains' time step.
const CHAIN_DT: f64 = 1e-3;

/// Lightly damped, inside the network limit of two springs per particle.
fn chain_tuning() -> Option<Tuning> {
    Tuning::from_coefficients(0.2, 0.01, CHAIN_DT).ok()
}

/// The 2D distance spring with length kernel `L`: a free rope of 9 particles and 8
/// springs, zig-zagged so that every spring is stretched, without gravity or sleep. Per
/// spring, the particles' integration included.
fn distance_2d<S: Scalar, L: LengthKernel<S>>() -> Option<SceneStep<S, 2, 9, CHAIN, L>> {
    let config = SceneConfig::new(CHAIN_DT).ok()?.no_sleep();
    let mut scene = Scene::<S, 2, 9, CHAIN, L>::new(config);
    let mut previous = None;
    for i in 0..=CHAIN {
        let y = if i % 2 == 0 { 0.0 } else { 0.3 };
        let p = scene
            .add_particle([S::from_f64(i as f64), S::from_f64(y)], S::ONE)
            .ok()?;
        if let Some(q) = previous {
            scene.add_spring(q, p, S::ONE, &chain_tuning()?).ok()?;
        }
        previous = Some(p);
    }
    Some(SceneStep(scene))
}

/// The same rope pulled by a drag handle: the 2D point spring (zero rest length) of a
/// pinned handle on every particle. Per spring.
// Measured on the M4F and the host only (see `measure_scenes`).
#[cfg_attr(all(target_os = "none", not(target_abi = "eabihf")), allow(dead_code))]
fn point_2d<S: Scalar>() -> Option<SceneStep<S, 2, 16, CHAIN, Exact>> {
    let config = SceneConfig::new(CHAIN_DT).ok()?.no_sleep();
    let mut scene = Scene::<S, 2, 16, CHAIN, Exact>::new(config);
    let t = chain_tuning()?;
    for i in 0..CHAIN {
        let p = scene
            .add_particle([S::from_f64(i as f64), S::ZERO], S::ONE)
            .ok()?;
        scene
            .add_anchor([S::from_f64(i as f64), S::from_f64(0.3)], p, S::ZERO, &t)
            .ok()?;
    }
    Some(SceneStep(scene))
}

/// The angular spring: a free chain of 9 bodies and 8 springs, wound alternately. Per
/// spring, the bodies' integration included.
// Measured on the M4F and the host only (see `measure_scenes`).
#[cfg_attr(all(target_os = "none", not(target_abi = "eabihf")), allow(dead_code))]
fn angular<S: Scalar>() -> Option<SceneStep<S, 1, 9, CHAIN, Angle>> {
    let config = SceneConfig::new(CHAIN_DT).ok()?.no_sleep();
    let mut scene = AngularScene::<S, 9, CHAIN, Angle>::new(config);
    let mut previous = None;
    for i in 0..=CHAIN {
        let angle = if i % 2 == 0 { 0.0 } else { 0.5 };
        let p = scene
            .add_particle([S::from_f64(angle)], S::from_f64(1e-3))
            .ok()?;
        if let Some(q) = previous {
            scene.add_spring(q, p, S::ZERO, &chain_tuning()?).ok()?;
        }
        previous = Some(p);
    }
    Some(SceneStep(scene))
}

/// The floor of the 2D distance spring with the hardware root: the same rope as
/// [`distance_2d`] written by hand over plain arrays, with what the library's step must
/// keep (each spring's rest length and body weights read from memory, the zero-length
/// guard, the integration of every particle) and nothing else: no index lists, no
/// bounds checks. Per spring.
///
/// Two of the library's safety and accuracy features can be switched on, to measure what
/// each costs without the rest of the bookkeeping: `GUARD`, the network bound tested on
/// `|x + u| + |u|` of every particle (as the library's fast path does, with `abs` as
/// `vabs`), and `CARRY`, positions that carry their rounding remainder (the separation
/// reads it, the integration keeps it by a two-sum).
#[cfg(target_abi = "eabihf")]
struct FloorRope<const GUARD: bool, const CARRY: bool> {
    k: f32,
    d: f32,
    rest: [f32; CHAIN],
    weights: [(f32, f32); CHAIN],
    x: [[f32; 2]; CHAIN + 1],
    r: [[f32; 2]; CHAIN + 1],
    u: [[f32; 2]; CHAIN + 1],
}
#[cfg(target_abi = "eabihf")]
impl<const GUARD: bool, const CARRY: bool> Bench for FloorRope<GUARD, CARRY> {
    #[inline(always)]
    fn step(&mut self) {
        let (k, d) = (self.k, self.d);
        for i in 0..CHAIN {
            let (a, b) = (self.x[i], self.x[i + 1]);
            let (mut dx, mut dy) = (b[0] - a[0], b[1] - a[1]);
            if CARRY {
                let (ra, rb) = (self.r[i], self.r[i + 1]);
                dx += rb[0] - ra[0];
                dy += rb[1] - ra[1];
            }
            let length = vsqrt(dx * dx + dy * dy);
            let inverse = if length > 0.0 { 1.0 / length } else { 0.0 };
            let (nx, ny) = (dx * inverse, dy * inverse);
            let (ua, ub) = (self.u[i], self.u[i + 1]);
            let relative = (ub[0] - ua[0]) * nx + (ub[1] - ua[1]) * ny;
            let delta = -(k * (length - self.rest[i]) + d * relative);
            let (wa, wb) = self.weights[i];
            let (da, db) = (-(delta * wa), delta * wb);
            self.u[i] = [ua[0] + da * nx, ua[1] + da * ny];
            self.u[i + 1] = [ub[0] + db * nx, ub[1] + db * ny];
        }
        for ((x, r), u) in self.x.iter_mut().zip(self.r.iter_mut()).zip(&self.u) {
            let (mut next, mut rest) = (*x, *r);
            for c in 0..2 {
                if CARRY {
                    // Two-sum of x + (u + r): the sum and its exact rounding error.
                    let y = u[c] + r[c];
                    let s = x[c] + y;
                    let t = s - x[c];
                    (next[c], rest[c]) = (s, (x[c] - (s - t)) + (y - t));
                } else {
                    next[c] = x[c] + u[c];
                }
            }
            if GUARD {
                let total = u[0].abs() + next[0].abs() + u[1].abs() + next[1].abs();
                let within = total <= 1e18; // false for NaN too
                if !within {
                    // The library clamps here; this rope never comes near the bound.
                    continue;
                }
            }
            *x = next;
            *r = rest;
        }
    }
    fn per_step(&self) -> u32 {
        CHAIN as u32
    }
}

// `vsqrt.f32` out of line, as the library's `HardwareSqrt` reaches it: stable Rust's
// inline assembly names single-precision registers only with the unstable `vfp2` target
// feature, and LLVM emits `vsqrt` only for `f32::sqrt`, which `core` lacks.
#[cfg(target_abi = "eabihf")]
core::arch::global_asm!(
    ".section .text.cost_vsqrt,\"ax\",%progbits",
    ".global cost_vsqrt",
    ".type cost_vsqrt,%function",
    ".fpu fpv4-sp-d16",
    ".thumb_func",
    "cost_vsqrt:",
    "vsqrt.f32 s0, s0",
    "bx lr",
    ".size cost_vsqrt, . - cost_vsqrt",
);
#[cfg(target_abi = "eabihf")]
unsafe extern "C" {
    fn cost_vsqrt(x: f32) -> f32;
}
/// `√x` by `vsqrt.f32`.
#[cfg(target_abi = "eabihf")]
#[inline(always)]
fn vsqrt(x: f32) -> f32 {
    // SAFETY: reads and writes s0 only, defined above for this hard-float signature.
    unsafe { cost_vsqrt(x) }
}
#[cfg(target_abi = "eabihf")]
fn floor_rope<const GUARD: bool, const CARRY: bool>() -> Option<FloorRope<GUARD, CARRY>> {
    let t = chain_tuning()?;
    let mut x = [[0.0; 2]; CHAIN + 1];
    for (i, x) in x.iter_mut().enumerate() {
        *x = [i as f32, if i % 2 == 0 { 0.0 } else { 0.3 }];
    }
    Some(FloorRope {
        k: t.stiffness() as f32,
        d: t.damping() as f32,
        rest: [1.0; CHAIN],
        weights: [(0.5, 0.5); CHAIN],
        x,
        r: [[0.0; 2]; CHAIN + 1],
        u: [[0.0; 2]; CHAIN + 1],
    })
}

// ---------------------------------------------------------------------------------------
// The knob
// ---------------------------------------------------------------------------------------

/// Updates in one sweep of the knob's scripted encoder.
const SWEEP: u32 = 256;

/// `Knob::update` at 1 kHz with 16 detents between endstops, fed by a scripted encoder
/// that sweeps the whole range and beyond both endstops in [`SWEEP`] updates (the script
/// is one add and one compare per step). Measured over whole sweeps, after one sweep
/// that lets the knob reach its periodic motion: a window that is not a whole number of
/// sweeps weighs some detents and endstops more than others.
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
        // Up and down (a jump back to the start would be a sensor fault, and measure
        // the screen's cold path).
        let next = self.angle.add(self.increment);
        if next > self.high || next < self.low {
            self.increment = self.increment.neg();
        }
        self.angle = self.angle.add(self.increment);
    }
    fn runs(&self) -> (u32, u32) {
        // Whole sweeps, up and down.
        (2 * SWEEP, 4 * SWEEP)
    }
}
/// The scene's knob, designed at compile time (`knob!`): the firmware carries no run-time
/// design, as a product's would not.
const KNOB_CONFIG: KnobConfig = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
    .endstops(0.0, 3.0)
    .detent_count(16)
    .detent_stiffness(0.05);
fn knob_update_f32() -> Option<KnobUpdate<f32>> {
    knob_update(&stiffspring::knob!(KNOB_CONFIG, f32))
}
fn knob_update_i16f16() -> Option<KnobUpdate<I16F16>> {
    knob_update(&stiffspring::knob!(KNOB_CONFIG, I16F16))
}
fn knob_update<S: Scalar>(design: &stiffspring::knob::KnobDesign<S>) -> Option<KnobUpdate<S>> {
    // 1 kHz, 1e−5 kg·m², 50 mN·m, a 14-bit encoder (the knob module's example).
    let mut bench = KnobUpdate {
        // At rest where the sweep starts: the sensor screen sees no jump.
        knob: Knob::from_design(design, S::from_f64(-0.2)).ok()?,
        angle: S::from_f64(-0.2),
        // One way covers 3.4 rad, both endstops and every detent, in SWEEP updates (the
        // angle turns back before `high` with a margin far above the rounding of the
        // increments); up and down, the script repeats every 2·SWEEP updates.
        increment: S::from_f64(3.4 / (f64::from(SWEEP) - 0.5)),
        low: S::from_f64(-0.2),
        high: S::from_f64(3.2),
    };
    // The warm-up sweep through the measured function itself, so that `Knob::update` is
    // not inlined a second time here (the M0 firmware's flash holds one copy).
    let _ = count(&mut bench, SWEEP);
    Some(bench)
}

/// `Knob::update` at rest on a detent's centre, its reading toggling between two
/// adjacent counts every period, as a rotor's between two counts does: the period a knob
/// spends most of its life in.
struct KnobAtRest<S: Scalar> {
    knob: Knob<S>,
    angle: S,
    toggle: S,
}
impl<S: Scalar> Bench for KnobAtRest<S> {
    #[inline(always)]
    fn step(&mut self) {
        let out = self.knob.update(self.angle);
        core::hint::black_box(out.torque);
        self.angle = self.angle.add(self.toggle);
        self.toggle = self.toggle.neg();
    }
}
fn knob_rest_f32() -> Option<KnobAtRest<f32>> {
    knob_rest(&stiffspring::knob!(KNOB_CONFIG, f32))
}
fn knob_rest_i16f16() -> Option<KnobAtRest<I16F16>> {
    knob_rest(&stiffspring::knob!(KNOB_CONFIG, I16F16))
}
fn knob_rest<S: Scalar>(design: &stiffspring::knob::KnobDesign<S>) -> Option<KnobAtRest<S>> {
    // The centre of detent 5 (16 detents over 3 rad, 0.2 rad apart), and one count of
    // the 14-bit encoder.
    let centre = S::from_f64(1.0);
    Some(KnobAtRest {
        knob: Knob::from_design(design, centre).ok()?,
        angle: centre,
        toggle: S::from_f64(core::f64::consts::TAU / 16384.0),
    })
}

// ---------------------------------------------------------------------------------------
// The table
// ---------------------------------------------------------------------------------------

/// The table of kernels: `"name", Backend => function giving an Option<impl Bench>;`.
/// `None` (a configuration the backend rejects) is reported as a failure.
macro_rules! kernels {
    ($fn:ident: $($name:literal, $S:ty => $make:expr;)*) => {
        /// Measures every kernel of its table; false when one could not be built.
        fn $fn() -> bool {
            let mut ok = true;
            $( ok &= report($name, <$S as Scalar>::NAME, $make); )*
            ok
        }
    };
}

kernels! {
    measure_all:
    "value_advance", f32 => value_advance::<f32>;
    "value_step", f32 => value_step::<f32>;
    "floor_value", f32 => floor_value;
    "batch_step", f32 => batch_step::<f32>;
    "batch_step_every2", f32 => batch_step_every2::<f32>;
    "batch_step_every4", f32 => batch_step_every4::<f32>;
    "batch_advance", f32 => batch_advance::<f32>;
    "floor_hand", f32 => floor_hand;
    "floor", f32 => floor::<f32>;
    "value_advance", I16F16 => value_advance::<I16F16>;
    "value_step", I16F16 => value_step::<I16F16>;
    "ui_value_step", f32 => ui_value_step::<f32>;
    "ui_value_step", I16F16 => ui_value_step::<I16F16>;
    "batch_step", I16F16 => batch_step::<I16F16>;
    "batch_advance", I16F16 => batch_advance::<I16F16>;
    "floor", I16F16 => floor::<I16F16>;
    "floor_value", I16F16 => floor_value_q16;
    "value_advance", I32F32 => value_advance::<I32F32>;
    "value_step", I32F32 => value_step::<I32F32>;
    "batch_step", I32F32 => batch_step::<I32F32>;
    "batch_advance", I32F32 => batch_advance::<I32F32>;
    "floor", I32F32 => floor::<I32F32>;
    "value_step", f64 => value_step::<f64>;
    "distance_2d/exact", f32 => distance_2d::<f32, Exact>;
    "distance_2d/linearised", f32 => distance_2d::<f32, Linearised>;
    "distance_2d/linearised", I16F16 => distance_2d::<I16F16, Linearised>;
    "knob_update", f32 => knob_update_f32;
    "knob_update", I16F16 => knob_update_i16f16;
    "knob_rest", f32 => knob_rest_f32;
    "knob_rest", I16F16 => knob_rest_i16f16;
}

// The rest of the scene kernels: each scene step is a monomorphised function of 30–70 KB,
// and these would not fit in the Cortex-M0 firmware's 256 KiB of flash (the microbit
// map) beside the others.
#[cfg(any(target_abi = "eabihf", not(target_os = "none")))]
kernels! {
    measure_scenes:
    "distance_2d/exact", I16F16 => distance_2d::<I16F16, Exact>;
    "distance_2d/exact", I32F32 => distance_2d::<I32F32, Exact>;
    "distance_2d/exact", f64 => distance_2d::<f64, Exact>;
    "point_2d", f32 => point_2d::<f32>;
    "point_2d", I16F16 => point_2d::<I16F16>;
    "angular", f32 => angular::<f32>;
    "angular", I16F16 => angular::<I16F16>;
}
#[cfg(all(not(target_abi = "eabihf"), target_os = "none"))]
fn measure_scenes() -> bool {
    true
}

/// The Cortex-M4F's `vsqrt.f32` kernel and its floor exist only on hard-float ARM
/// targets.
#[cfg(target_abi = "eabihf")]
fn measure_hardware() -> bool {
    report(
        "distance_2d/hardware_sqrt",
        "f32",
        distance_2d::<f32, stiffspring::length::HardwareSqrt>,
    ) & report(
        "floor_rope/hardware_sqrt",
        "f32",
        floor_rope::<false, false>,
    ) & report(
        "floor_rope_guard/hardware_sqrt",
        "f32",
        floor_rope::<true, false>,
    ) & report(
        "floor_rope_carry/hardware_sqrt",
        "f32",
        floor_rope::<false, true>,
    ) & report(
        "floor_rope_guard_carry/hardware_sqrt",
        "f32",
        floor_rope::<true, true>,
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

/// The MPS2 boards' timer (`firmware::timer`), read under `-icount shift=10`
/// (`scripts/cost`): one instruction is 2^10 ns of virtual time, 25.6 ticks.
#[cfg(target_os = "none")]
use firmware::timer;
#[cfg(target_os = "none")]
const ICOUNT_SHIFT: u32 = 10;

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
    u64::from(timer::instructions(start.wrapping_sub(end), ICOUNT_SHIFT))
}

/// The cost of `n` steps of `bench`: nanoseconds of wall clock on the host.
#[cfg(not(target_os = "none"))]
#[inline(never)]
fn count<B: Bench>(bench: &mut B, n: u32) -> u64 {
    let n = core::hint::black_box(n);
    let start = std::time::Instant::now();
    for _ in 0..n {
        bench.step();
        core::hint::black_box(&mut *bench);
    }
    start.elapsed().as_nanos() as u64
}

/// Thousandths of a unit per step of `bench`, harness included: `(I(N₂) − I(N₁))`
/// over `N₂ − N₁` steps ([`Bench::runs`]).
fn per_step_milli<B: Bench>(bench: &mut B) -> i64 {
    let (n1, n2) = bench.runs();
    let first = count(bench, n1) as i64;
    let second = count(bench, n2) as i64;
    (second - first) * 1000 / (n2 - n1) as i64
}

/// Builds a bench with `make`, measures it and prints its CSV line; false when it could
/// not be built. Never inlined, so that each bench lives in this frame only while it is
/// measured (the Cortex-M0's stack is 16 KiB).
#[inline(never)]
fn report<B: Bench>(kernel: &str, backend: &str, make: fn() -> Option<B>) -> bool {
    let Some(mut bench) = make() else {
        say!("{},{},FAILED (set-up rejected)", kernel, backend);
        return false;
    };
    let overhead = per_step_milli(&mut Empty);
    let gross = per_step_milli(&mut bench);
    let net = (gross - overhead) / bench.per_step() as i64;
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
    measure_all() & measure_scenes() & measure_hardware()
}

firmware::main!(run_all);
