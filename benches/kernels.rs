//! Criterion micro-benchmarks of every hot kernel in every backend.
//!
//! ```sh
//! cargo bench --bench kernels                 # all, about two minutes
//! cargo bench --bench kernels -- value_1d     # a filter
//! ```
//!
//! Each benchmark steps a state that keeps moving (an undamped spring, restarted in the
//! rare case that fixed-point rounding lets it settle; a network without sleep), so that
//! every iteration takes the moving path, and reports the
//! time per step of one value, one spring, or one knob update (`Throughput::Elements`
//! gives the per-spring figure for the scenes). These are wall-clock figures on the host;
//! the instruction counts on the Cortex-M4F and Cortex-M0 come from
//! `examples/cost.rs` on QEMU, and the comparison with the peer crates from
//! `cargo bench --bench pareto`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use stiffspring::length::{Approximate, ApproximateNewton, Exact, LengthKernel, Linearised};
use stiffspring::scene::{Angle, AngularScene, Scene, SceneConfig, WrappedAngle};
use stiffspring::{
    I16F16, I32F32, Knob, KnobConfig, RestThreshold, Scalar, SpringBatch, SpringValue, Tuning,
};

/// The time step of every benchmark: 1 kHz.
const DT: f64 = 1e-3;

/// An undamped spring: never at rest, every step the moving path.
fn undamped() -> Tuning {
    Tuning::from_coefficients(0.01, 0.0, DT).expect("valid")
}

/// Rest thresholds nothing reaches.
fn never() -> RestThreshold {
    RestThreshold::new(1e-30, 1e-30).expect("positive")
}

/// A value moving toward 100 units, with a rest threshold it never reaches.
fn moving_value<S: Scalar, const D: usize>(target: [f64; D]) -> SpringValue<S, D> {
    let mut v = SpringValue::<S, D>::new([S::ZERO; D], &undamped())
        .expect("valid")
        .with_rest_threshold(never());
    v.set_target(target.map(S::from_f64));
    v
}

/// `SpringValue::<S, 1>::step` of a moving value: the step with its rest test.
fn value_1d<S: Scalar>(c: &mut Criterion) {
    let mut v = moving_value::<S, 1>([100.0]);
    let start = v.clone();
    c.bench_function(&format!("value_1d/{}", S::NAME), |b| {
        b.iter(|| {
            let _ = v.step();
            // An undamped spring never settles in any backend (fixed point rounds its
            // spring term toward zero, which conserves the energy); restart if one did.
            if v.is_at_rest() {
                v.clone_from(&start);
            }
            black_box(&mut v);
        })
    });
}

/// `SpringValue::<S, 1>::advance`: the step without the rest test.
fn value_1d_advance<S: Scalar>(c: &mut Criterion) {
    let mut v = moving_value::<S, 1>([100.0]);
    c.bench_function(&format!("value_1d_advance/{}", S::NAME), |b| {
        b.iter(|| {
            v.advance();
            black_box(&mut v);
        })
    });
}

/// `SpringValue::<S, 2>::step`: a UI position.
fn value_2d<S: Scalar>(c: &mut Criterion) {
    let mut v = moving_value::<S, 2>([100.0, -40.0]);
    let start = v.clone();
    c.bench_function(&format!("value_2d/{}", S::NAME), |b| {
        b.iter(|| {
            let _ = v.step();
            if v.is_at_rest() {
                v.clone_from(&start);
            }
            black_box(&mut v);
        })
    });
}

/// The bare kernel `Scalar::advance`: `u = ũ − C_k·x; x += u; ũ = u − C_d·u` on the
/// backend's state.
fn kernel_1d<S: Scalar>(c: &mut Criterion) {
    let t = undamped();
    let gains = S::gains(t.stiffness(), t.damping()).expect("representable");
    let (mut x, mut u) = (S::state_from_f64(100.0), S::STATE_ZERO);
    c.bench_function(&format!("kernel_1d/{}", S::NAME), |b| {
        b.iter(|| {
            S::advance(&gains, black_box(&mut x), &mut u);
        })
    });
}

/// `SpringBatch::<S, 16>::step` with every value moving, per value.
fn batch_16<S: Scalar>(c: &mut Criterion) {
    let mut batch = SpringBatch::<S, 1, 16>::new(&undamped())
        .expect("valid")
        .with_rest_threshold(never());
    for i in 0..16 {
        let k = batch.push([S::ZERO]).expect("room");
        batch.set_target(k, [S::from_f64(10.0 + i as f64)]);
    }
    let start = batch.clone();
    let mut group = c.benchmark_group("batch_16");
    group.throughput(Throughput::Elements(16));
    group.bench_function(S::NAME, |b| {
        b.iter(|| {
            let _ = batch.step();
            if batch.awake() < 16 {
                batch.clone_from(&start);
            }
            black_box(&mut batch);
        })
    });
    group.finish();
}

/// One length measurement `L::measure` of a 2D separation.
fn length<S: Scalar, L: LengthKernel<S>>(c: &mut Criterion) {
    let rest = L::rest(S::ONE);
    let d = [S::from_f64(0.8).widen(), S::from_f64(0.75).widen()];
    c.bench_function(&format!("length/{}/{}", L::NAME, S::NAME), |b| {
        b.iter(|| L::measure(black_box(&d), black_box(&rest)))
    });
}

/// A free 2D chain of 9 particles and 8 lightly damped springs, zig-zagged so that every
/// spring is stretched, without gravity or sleep: `Scene::step`, per spring.
fn distance_2d<S: Scalar, L: LengthKernel<S>>(c: &mut Criterion) {
    let config = SceneConfig::new(DT).expect("valid").no_sleep();
    let mut scene = Scene::<S, 2, 9, 8, L>::new(config);
    let tuning = Tuning::from_coefficients(0.2, 0.01, DT).expect("valid");
    let mut previous = None;
    for i in 0..9 {
        let y = if i % 2 == 0 { 0.0 } else { 0.3 };
        let p = scene
            .add_particle([S::from_f64(i as f64), S::from_f64(y)], S::ONE)
            .expect("room");
        if let Some(q) = previous {
            scene
                .add_spring(q, p, S::ONE, &tuning)
                .expect("within the limit");
        }
        previous = Some(p);
    }
    let mut group = c.benchmark_group("distance_2d");
    group.throughput(Throughput::Elements(8));
    group.bench_function(format!("{}/{}", L::NAME, S::NAME), |b| {
        b.iter(|| {
            let _ = scene.step();
            black_box(&mut scene);
        })
    });
    group.finish();
}

/// A free chain of 9 rotors and 8 angular springs, wound alternately: per spring.
fn angular<S: Scalar, L: LengthKernel<S>>(c: &mut Criterion) {
    let config = SceneConfig::new(DT).expect("valid").no_sleep();
    let mut scene = AngularScene::<S, 9, 8, L>::new(config);
    let tuning = Tuning::from_coefficients(0.2, 0.01, DT).expect("valid");
    let mut previous = None;
    for i in 0..9 {
        let angle = if i % 2 == 0 { 0.0 } else { 0.5 };
        let p = scene
            .add_particle([S::from_f64(angle)], S::from_f64(1e-3))
            .expect("room");
        if let Some(q) = previous {
            scene
                .add_spring(q, p, S::ZERO, &tuning)
                .expect("within the limit");
        }
        previous = Some(p);
    }
    let mut group = c.benchmark_group("angular");
    group.throughput(Throughput::Elements(8));
    group.bench_function(format!("{}/{}", L::NAME, S::NAME), |b| {
        b.iter(|| {
            let _ = scene.step();
            black_box(&mut scene);
        })
    });
    group.finish();
}

/// `Knob::update` at 1 kHz, 16 detents of 0.1 N·m/rad between endstops, a 14-bit encoder
/// sweeping past both.
fn knob<S: Scalar>(c: &mut Criterion) {
    let config = KnobConfig::new(1.0 / DT, 1e-5, 0.05, 16384)
        .endstops(0.0, 3.0)
        .endstop_stiffness(0.15)
        .detent_count(16)
        .detent_stiffness(0.1);
    let mut knob = Knob::<S>::new(&config, S::ZERO).expect("valid");
    let angles: Vec<S> = (0..256)
        .map(|i| S::from_f64(-0.2 + 3.4 * i as f64 / 256.0))
        .collect();
    let mut i = 0;
    c.bench_function(&format!("knob_torque/{}", S::NAME), |b| {
        b.iter(|| {
            i = (i + 1) & 255;
            black_box(knob.update(angles[i]).torque)
        })
    });
}

fn values(c: &mut Criterion) {
    value_1d::<f64>(c);
    value_1d::<f32>(c);
    value_1d::<I32F32>(c);
    value_1d::<I16F16>(c);
    value_1d_advance::<f64>(c);
    value_1d_advance::<f32>(c);
    value_1d_advance::<I32F32>(c);
    value_1d_advance::<I16F16>(c);
    value_2d::<f32>(c);
    value_2d::<I16F16>(c);
    kernel_1d::<f64>(c);
    kernel_1d::<f32>(c);
    kernel_1d::<I32F32>(c);
    kernel_1d::<I16F16>(c);
    batch_16::<f64>(c);
    batch_16::<f32>(c);
    batch_16::<I32F32>(c);
    batch_16::<I16F16>(c);
}

fn lengths(c: &mut Criterion) {
    length::<f64, Exact>(c);
    length::<f64, Linearised>(c);
    length::<f32, Exact>(c);
    length::<f32, Linearised>(c);
    length::<f32, Approximate>(c);
    length::<f32, ApproximateNewton>(c);
    length::<I32F32, Exact>(c);
    length::<I32F32, Linearised>(c);
    length::<I16F16, Exact>(c);
    length::<I16F16, Linearised>(c);
}

fn scenes(c: &mut Criterion) {
    distance_2d::<f64, Exact>(c);
    distance_2d::<f64, Linearised>(c);
    distance_2d::<f32, Exact>(c);
    distance_2d::<f32, Linearised>(c);
    distance_2d::<f32, Approximate>(c);
    distance_2d::<f32, ApproximateNewton>(c);
    distance_2d::<I32F32, Exact>(c);
    distance_2d::<I32F32, Linearised>(c);
    distance_2d::<I16F16, Exact>(c);
    distance_2d::<I16F16, Linearised>(c);
    angular::<f32, Angle>(c);
    angular::<f32, WrappedAngle>(c);
    angular::<I16F16, Angle>(c);
    angular::<I16F16, WrappedAngle>(c);
    knob::<f64>(c);
    knob::<f32>(c);
    knob::<I32F32>(c);
    knob::<I16F16>(c);
}

/// Short runs: the kernels take nanoseconds, so a second per benchmark gives millions of
/// samples; the whole suite stays around two minutes on two cores.
fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
        .sample_size(30)
}

criterion_group! {
    name = benches;
    config = config();
    targets = values, lengths, scenes
}
criterion_main!(benches);
