//! Behaviour of `SpringValue` in every backend (`f32`, `f64`, `I16F16`, `I32F32`):
//! retargeting (near and far from the origin), the exact start of releases and flings,
//! retuning to another time step, rest and its threshold, the `Motion` a step reports,
//! N-D values, symmetry, and (with proptest, host only) that stepping never produces
//! NaN or infinity in floats and never wraps in fixed point.
//!
//! Expected values come from the continuous solution of the damped oscillator written out
//! below ([`Continuous`]) or in `lab::reference`, from the eigenvalues of the step map
//! computed here ([`dominant_pole`]), from the study's bit-exact integer model of the
//! fixed-point step (`lab::precision::Kept`), or from the documented contract; none is
//! copied from a run.
//!
//! `cargo test --release --test value_behaviour -- --nocapture` prints the measured
//! steps-to-rest table, the motion left when a value settles and the worst position
//! error of each backend across a retarget.

use lab::reference::analytic;
use std::f64::consts::TAU;
use stiffspring::{I16F16, I32F32, Motion, Oscillator, RestThreshold, Scalar, SpringValue, Tuning};

mod support;
use support::{DT60, DT120, s};

fn f<S: Scalar, const D: usize>(a: [S; D]) -> [f64; D] {
    a.map(|x| x.to_f64())
}

/// Bit-identical: equal, and for floats also the same sign of zero.
fn same<S: Scalar>(a: S, b: S) -> bool {
    a == b && a.to_f64().to_bits() == b.to_f64().to_bits()
}

fn same_all<S: Scalar, const D: usize>(a: [S; D], b: [S; D]) -> bool {
    a.iter().zip(b.iter()).all(|(x, y)| same(*x, *y))
}

/// Relative precision (machine epsilon) of a float backend, 0 for fixed point.
fn eps<S: Scalar>() -> f64 {
    match S::NAME {
        "f32" => f32::EPSILON as f64,
        "f64" => f64::EPSILON,
        _ => 0.0,
    }
}

fn sampled(frequency: f64, zeta: f64, dt: f64) -> Tuning {
    Tuning::from_frequency(frequency, zeta, dt).expect("valid")
}

fn raw(ck: f64, cd: f64, dt: f64) -> Tuning {
    Tuning::from_coefficients(ck, cd, dt).expect("in the square")
}

fn value<S: Scalar, const D: usize>(p: [f64; D], tuning: &Tuning) -> SpringValue<S, D> {
    SpringValue::new(p.map(s), tuning).expect("representable")
}

// ---------------------------------------------------------------------------
// Independent models: the continuous oscillator and the eigenvalues of the step map
// ---------------------------------------------------------------------------

/// `y'' + 2ζω·y' + ω²·y = 0`, solved in closed form (textbook, no code shared with the
/// library).
#[derive(Clone, Copy, Debug)]
struct Continuous {
    omega: f64,
    zeta: f64,
}

impl Continuous {
    fn new(frequency: f64, zeta: f64) -> Self {
        Continuous {
            omega: TAU * frequency,
            zeta,
        }
    }

    /// `(y(t), y'(t))` from `y(0) = y0`, `y'(0) = v0`.
    fn at(&self, y0: f64, v0: f64, t: f64) -> (f64, f64) {
        analytic(y0, v0, self.omega, self.zeta, t)
    }

    /// The largest `|y(t)|` for `t ≥ 0` from `(y0, v0)`: the motion left. Sampled 4096
    /// times over two periods, which hold the largest swing (the envelope decays; an
    /// overdamped spring peaks within a time constant `1/ω`).
    fn motion_left(&self, y0: f64, v0: f64) -> f64 {
        let span = 2.0 * TAU / self.omega;
        (0..=4096)
            .map(|i| self.at(y0, v0, i as f64 * span / 4096.0).0.abs())
            .fold(0.0, f64::max)
    }
}

/// The dominant eigenvalue of one step on `(x, u)`: `u' = r·u − C_k·x`, `x' = x + u'`,
/// i.e. `M = [[1 − C_k, r], [−C_k, r]]` with `r = 1 − C_d`. Returns `(ρ, c)`: its
/// magnitude, and `|1 − 1/λ|`, the ratio `|u|/|x|` in that mode (`u_n = x_n − x_{n−1}`).
fn dominant_pole(ck: f64, r: f64) -> (f64, f64) {
    let trace = 1.0 - ck + r;
    let det = r;
    let disc = trace * trace - 4.0 * det;
    if disc < 0.0 {
        let (re, im) = (0.5 * trace, 0.5 * (-disc).sqrt());
        let rho2 = re * re + im * im;
        // 1 − 1/λ = 1 − conj(λ)/|λ|².
        let (a, b) = (1.0 - re / rho2, im / rho2);
        (rho2.sqrt(), a.hypot(b))
    } else {
        let l1 = 0.5 * (trace + disc.sqrt());
        let l2 = 0.5 * (trace - disc.sqrt());
        let l = if l1.abs() >= l2.abs() { l1 } else { l2 };
        (l.abs(), if l == 0.0 { 0.0 } else { (1.0 - 1.0 / l).abs() })
    }
}

#[test]
fn spectral_radius_matches_the_eigenvalues_of_the_step_map() {
    for (ck, cd) in [
        (0.01, 0.1),
        (0.5, 0.5),
        (1.0, 1.0),
        (0.04, 0.0),
        (0.9, 0.05),
    ] {
        let t = raw(ck, cd, DT60);
        let (rho, _) = dominant_pole(ck, 1.0 - cd);
        assert!((t.spectral_radius() - rho).abs() < 1e-12, "({ck}, {cd})");
    }
    // Exact map: the poles are e^{s·dt}, so ρ = e^{−ζω·dt} when underdamped.
    let t = sampled(2.0, 0.3, DT60);
    let expected = (-0.3 * TAU * 2.0 * DT60).exp();
    assert!((t.spectral_radius() - expected).abs() < 1e-12);
}

// ---------------------------------------------------------------------------
// Retargeting
// ---------------------------------------------------------------------------

/// The position survives a retarget exactly in fixed point (the offset moves by the exact
/// change of the target) and to two roundings in floats; with raw coefficients the step
/// velocity is the article's `v·dt` and is kept exactly.
fn retarget_keeps_position_and_velocity<S: Scalar>() {
    let targets = [-1.5e-7, 1e-3, -37.0, 1234.567, -9000.25, 3.0e4];
    for tuning in [
        sampled(2.0, 0.3, DT60),
        raw(0.05, 0.2, DT60),
        raw(0.3, 0.0, DT60),
    ] {
        let exact_map = tuning.oscillator().is_some();
        for &t in &targets {
            let mut v = value::<S, 1>([1.0], &tuning);
            v.set_target([s(70.0)]);
            for _ in 0..5 {
                v.advance();
            }
            let (p, u) = (v.position()[0], v.step_velocity()[0]);
            v.set_target([s(t)]);
            let (after, t) = (v.position()[0].to_f64(), s::<S>(t));
            let bound = 2.0 * eps::<S>() * ((p.to_f64() - t.to_f64()).abs() + p.to_f64().abs());
            assert!(
                (after - p.to_f64()).abs() <= bound,
                "{}: target {t:?}: {p:?} became {after}",
                S::NAME
            );
            assert!(same(v.target()[0], t));
            if S::RESOLUTION > 0.0 {
                assert!(same(v.position()[0], p), "{}", S::NAME);
            }
            if !exact_map {
                assert!(v.step_velocity()[0] == u, "{}: u changed", S::NAME);
            }
        }
    }
}

#[test]
fn retarget_keeps_the_position_and_a_raw_step_velocity() {
    each_backend!(retarget_keeps_position_and_velocity);
}

/// With the exact map the velocity (units/s) of the continuous trajectory is kept: the
/// step velocity changes by `P·Δx`, with `P` from the continuous solution.
fn retarget_keeps_the_continuous_velocity<S: Scalar>() {
    // The relative precision of the backend's factors (31-/63-bit mantissas in fixed point).
    let factor_eps = match S::NAME {
        "f32" => 2f64.powi(-24),
        "f64" => 2f64.powi(-53),
        "I16F16" => 2f64.powi(-31),
        _ => 2f64.powi(-63),
    };
    for (freq, zeta) in [(2.0, 0.3), (1.5, 1.0), (3.0, 2.0)] {
        let (p_weight, q_weight) = Oscillator::new(freq, zeta)
            .expect("valid")
            .start_weights(DT60);
        let mut v = value::<S, 1>([0.0], &sampled(freq, zeta, DT60));
        v.set_target([s(100.0)]);
        for _ in 0..6 {
            v.advance();
        }
        let (x, u, vel) = (v.offset()[0], v.step_velocity()[0], v.velocity()[0]);
        v.set_target([s(-40.0)]);
        let (x2, u2, vel2) = (v.offset()[0], v.step_velocity()[0], v.velocity()[0]);
        let delta = x2.to_f64() - x.to_f64();
        let scale = u.to_f64().abs() + (p_weight * delta).abs();
        let tol = 4.0 * (eps::<S>() * scale + S::RESOLUTION) + 64.0 * factor_eps * scale;
        let shift = u2.to_f64() - u.to_f64();
        assert!(
            (shift - p_weight * delta).abs() <= tol,
            "{} ζ={zeta}: u shifted by {shift}, expected P·Δ = {}",
            S::NAME,
            p_weight * delta
        );
        let vtol = 2.0 * tol / q_weight + 4.0 * eps::<S>() * vel.to_f64().abs();
        assert!(
            (vel2.to_f64() - vel.to_f64()).abs() <= vtol,
            "{} ζ={zeta}: velocity {vel:?} became {vel2:?}",
            S::NAME
        );
    }
}

#[test]
fn retarget_with_the_exact_map_keeps_the_continuous_velocity() {
    each_backend!(retarget_keeps_the_continuous_velocity);
}

/// Tolerance on positions of magnitude ~100 after ~100 steps, per backend.
fn trajectory_tolerance<S: Scalar>() -> f64 {
    match S::NAME {
        "f64" => 1e-9,
        "f32" => 1e-4,
        "I16F16" => 1e-4,
        _ => 1e-8,
    }
}

/// A value released toward a target samples the continuous spring released at that
/// instant, exactly at every step; retargeted mid-flight, it samples the continuous
/// spring whose target jumped there, keeping its position and velocity.
fn follows_the_continuous_spring<S: Scalar>() {
    // The largest position error over the springs, before and after the retarget.
    let mut worst: f64 = 0.0;
    for (freq, zeta) in [(2.0, 0.3), (1.5, 1.0), (1.0, 2.5)] {
        let osc = Continuous::new(freq, zeta);
        let mut v = value::<S, 1>([0.0], &sampled(freq, zeta, DT60));
        let tol = trajectory_tolerance::<S>();
        v.set_target([s(100.0)]);
        for n in 1..=20 {
            v.advance();
            let (y, dy) = osc.at(-100.0, 0.0, n as f64 * DT60);
            let p = v.position()[0].to_f64();
            worst = worst.max((p - (100.0 + y)).abs());
            assert!(
                (p - (100.0 + y)).abs() < tol,
                "{} ζ={zeta} step {n}: {p}",
                S::NAME
            );
            let vel = v.velocity()[0].to_f64();
            assert!(
                (vel - dy).abs() < 60.0 * tol,
                "{} step {n}: v {vel} vs {dy}",
                S::NAME
            );
        }
        let (y20, v20) = osc.at(-100.0, 0.0, 20.0 * DT60);
        v.set_target([s(-50.0)]);
        for n in 1..=80 {
            v.advance();
            let (y, _) = osc.at(100.0 + y20 + 50.0, v20, n as f64 * DT60);
            let p = v.position()[0].to_f64();
            worst = worst.max((p - (-50.0 + y)).abs());
            assert!(
                (p - (-50.0 + y)).abs() < tol,
                "{} ζ={zeta} step {n} after the retarget: {p} vs {}",
                S::NAME,
                -50.0 + y
            );
        }
    }
    println!(
        "{}: worst position error across the retargets {worst:.1e} (amplitude ≈ 100)",
        S::NAME
    );
}

#[test]
fn exact_map_value_follows_the_continuous_spring_across_a_retarget() {
    each_backend!(follows_the_continuous_spring);
}

/// Issue 11: `set_target` in `f32` far from the origin used to rebuild the offset from
/// the rounded position, losing up to half an ulp of it at every retarget: 1.8e−5 of a
/// unit move at 1000 and 3.7e−3 at 1e5. The offset now moves by the change of the target,
/// so the position is kept to the bit and the motion after the retarget is the one an
/// `f64` value computes, to the precision of an offset (about 1e−7 of the move).
#[test]
fn f32_far_from_the_origin_retargets_without_losing_the_motion() {
    let tuning = sampled(2.0, 0.3, DT60);
    for origin in [1e3, 1e5] {
        let mut a = value::<f32, 1>([origin], &tuning);
        let mut b = value::<f64, 1>([origin], &tuning);
        a.set_target([(origin + 1.0) as f32]);
        b.set_target([origin + 1.0]);
        let mut worst = 0.0f64;
        for n in 0..200 {
            if n % 7 == 3 {
                // A retarget every few frames, mid-flight, up and down by a unit.
                let t = origin + if n % 2 == 0 { 2.0 } else { -1.0 };
                let before = a.position();
                a.set_target([t as f32]);
                b.set_target([t]);
                assert_eq!(a.position(), before, "at {origin}: the position moved");
            }
            a.advance();
            b.advance();
            let offset = f64::from(a.offset()[0]) - b.offset()[0];
            worst = worst.max(offset.abs());
        }
        println!("f32 at {origin}: worst offset error {worst:.1e} of a unit move");
        assert!(worst < 1e-6, "at {origin}: {worst:e}");
    }
}

/// A retarget of a heavily overdamped, undersampled spring (ζ = 2 at ω·dt = 8.5, whose
/// exact start extrapolates one step back by a factor `P ≈ 5·10¹²`; ζ = 13 at f·dt = 1.4,
/// whose step velocity `ũ/(1 − C_d)` is 10¹⁰⁰ times its kept one) across the whole float
/// range: the infallible setters saturate what the state cannot hold, every read stays
/// finite (saturating at `±Scalar::MAX`), and the value comes to rest.
fn extreme_retargets_stay_finite<S: Scalar>() {
    let f = 8.5 / TAU / DT60;
    let tunings = [
        sampled(f, 2.0, DT60),
        sampled(14.5, 13.0, 0.098),
        sampled(3.0, 0.0, DT60),
        Tuning::rigid(DT60).expect("dt"),
    ];
    for tuning in tunings {
        let top = s::<S>(S::MAX);
        let mut v = SpringValue::<S>::new([top], &tuning).expect("representable");
        v.set_target([top.neg()]);
        v.fling([top]);
        for n in 0..2000 {
            let all = [
                v.position()[0],
                v.offset()[0],
                v.step_velocity()[0],
                v.velocity()[0],
            ];
            assert!(
                all.iter().all(|c| c.to_f64().is_finite()),
                "{} step {n}: {all:?}",
                S::NAME
            );
            let _ = v.step();
        }
        if tuning.damping() > 0.0 {
            assert!(v.is_at_rest(), "{} {tuning:?}", S::NAME);
        }
    }
}

#[test]
fn extreme_retargets_saturate_and_stay_finite() {
    extreme_retargets_stay_finite::<f32>();
    extreme_retargets_stay_finite::<f64>();
}

// ---------------------------------------------------------------------------
// Exact starts
// ---------------------------------------------------------------------------

/// Issue 11: `I16F16` refused a ζ = 10 fling at 60 Hz for a 5 Hz spring (its exact start
/// asked for `u₀ ≈ 34 000`). The value keeps `(1 − C_d)·u₀` instead, which is of the order
/// of the amplitude: the fling is accepted and every sample is on the continuous
/// trajectory to the rounding of the read position.
#[test]
fn i16f16_flings_a_heavily_overdamped_spring_exactly() {
    let (freq, zeta) = (5.0, 10.0);
    let omega = TAU * freq;
    let mut v = value::<I16F16, 1>([0.0], &sampled(freq, zeta, DT60));
    v.try_fling([I16F16::from_num(omega)])
        .expect("representable");
    let mut moved = 0.0f64;
    for n in 1..=120 {
        v.advance();
        let (x, _) = analytic(0.0, omega, omega, zeta, n as f64 * DT60);
        let p = v.position()[0].to_f64();
        assert!(
            (p - x).abs() <= 2.0 * I16F16::RESOLUTION,
            "step {n}: {p} vs {x}"
        );
        moved = moved.max(p.abs());
    }
    assert!(moved > 0.01);
}

/// Issue 10: `f64` with ζ = 300 at f·dt = 0.2 lost a fling (`x(dt) = 0` against 1.3e−4).
/// Its exact start `u₀` is `e^{2ζω·dt}` ≈ 10³²⁷ times too large for `f64`; the kept
/// velocity is not, and the first step lands on the continuous trajectory.
#[test]
fn f64_flings_an_extremely_overdamped_spring_exactly() {
    let (freq, dt, zeta, v0) = (2.0, 0.1, 300.0, 1.0);
    let omega = TAU * freq;
    let mut v = value::<f64, 1>([0.0], &sampled(freq, zeta, dt));
    v.try_fling([v0]).expect("representable");
    for n in 1..=50 {
        v.advance();
        let (x, _) = analytic(0.0, v0, omega, zeta, n as f64 * dt);
        if n == 1 {
            assert!((x - 1.3e-4).abs() < 0.05e-4, "{x}");
        }
        let p = v.position()[0];
        assert!((p - x).abs() <= 1e-12 * x.abs(), "step {n}: {p:e} vs {x:e}");
    }
}

// ---------------------------------------------------------------------------
// Another time step
// ---------------------------------------------------------------------------

/// The display switches from 60 to 120 Hz: `set_tuning(&t.with_dt(..))` resamples the same
/// oscillator, keeps the position and the velocity, and the value goes on sampling the
/// same continuous trajectory.
fn retune_to_120_hz<S: Scalar>() {
    for (freq, zeta) in [(2.0, 0.3), (1.5, 1.0), (3.0, 2.0)] {
        let osc = Continuous::new(freq, zeta);
        let t60 = sampled(freq, zeta, DT60);
        let mut v = value::<S, 1>([0.0], &t60);
        v.set_target([s(100.0)]);
        for _ in 0..12 {
            v.advance();
        }
        let (p, vel) = (v.position(), v.velocity()[0].to_f64());
        let t120 = t60.with_dt(DT120).expect("valid");
        assert_eq!(t120.oscillator(), t60.oscillator());
        v.set_tuning(&t120).expect("representable");
        assert!(same_all(v.position(), p), "{}: position moved", S::NAME);
        let vtol = 4.0 * (eps::<S>() * (vel.abs() + 100.0 / DT120) + S::RESOLUTION / DT120);
        let vel2 = v.velocity()[0].to_f64();
        assert!(
            (vel2 - vel).abs() <= vtol,
            "{}: {vel} became {vel2}",
            S::NAME
        );
        let (y12, v12) = osc.at(-100.0, 0.0, 12.0 * DT60);
        for n in 1..=120 {
            v.advance();
            let (y, _) = osc.at(y12, v12, n as f64 * DT120);
            let got = v.position()[0].to_f64();
            assert!(
                (got - (100.0 + y)).abs() < trajectory_tolerance::<S>(),
                "{} ζ={zeta} step {n} at 120 Hz: {got} vs {}",
                S::NAME,
                100.0 + y
            );
        }
    }
}

#[test]
fn retuning_to_another_rate_samples_the_same_oscillator_and_keeps_the_velocity() {
    each_backend!(retune_to_120_hz);
}

/// Raw coefficients keep their per-step meaning at another `dt` (the article): the
/// coefficients stay, the velocity in units/s is kept, so the step velocity halves at
/// twice the rate.
fn retune_raw<S: Scalar>() {
    let t = raw(0.05, 0.2, DT60);
    let mut v = value::<S, 1>([0.0], &t);
    v.set_target([s(100.0)]);
    for _ in 0..5 {
        v.advance();
    }
    let (u, vel) = (v.step_velocity()[0].to_f64(), v.velocity()[0].to_f64());
    let t2 = t.with_dt(DT120).expect("valid");
    assert_eq!((t2.stiffness(), t2.damping(), t2.dt()), (0.05, 0.2, DT120));
    v.set_tuning(&t2).expect("representable");
    let u2 = v.step_velocity()[0].to_f64();
    let utol = 4.0 * (eps::<S>() * u.abs() + S::RESOLUTION);
    assert!((u2 - u / 2.0).abs() <= utol, "{}: {u} became {u2}", S::NAME);
    let vtol = 4.0 * (eps::<S>() * vel.abs() + S::RESOLUTION / DT120);
    assert!(
        (v.velocity()[0].to_f64() - vel).abs() <= vtol,
        "{}",
        S::NAME
    );
}

#[test]
fn retuning_raw_coefficients_keeps_them_and_the_velocity() {
    each_backend!(retune_raw);
}

// ---------------------------------------------------------------------------
// When a value settles
// ---------------------------------------------------------------------------

/// A value settles only when the motion it has left (the largest offset of the continuous
/// spring through its state, from then on) is below the position threshold, to the factor
/// `1 + θ/4` of `RestThreshold`'s documentation (`θ = ω·dt`). Issue 11: the offset and
/// velocity test alone (Android's) let a 1 Hz spring with ζ = 0.1 snap with 6.4e−3 of a
/// unit move left, 8.5 times the threshold; measured here on the same runs.
fn settles_with_less_than_the_threshold_left<S: Scalar>(table: &mut Vec<String>) -> f64 {
    let threshold = RestThreshold::default();
    let p = threshold.position();
    let mut android_worst = 0.0f64;
    for rate in [60.0, 120.0, 1000.0, 10_000.0] {
        let dt = 1.0 / rate;
        for (freq, zeta) in [(1.0, 0.1), (0.5, 0.05), (2.0, 0.3), (1.0, 0.7), (3.0, 1.0)] {
            let osc = Continuous::new(freq, zeta);
            let tuning = sampled(freq, zeta, dt);
            let mut v = value::<S, 1>([0.0], &tuning);
            let never = RestThreshold::new(1e-300, 1e-300).expect("positive");
            let mut twin = value::<S, 1>([0.0], &tuning).with_rest_threshold(never);
            v.set_target([s(1.0)]);
            twin.set_target([s(1.0)]);
            let mut android = None;
            let left = loop {
                let motion = v.step();
                twin.advance();
                let (x, vel) = (twin.offset()[0].to_f64(), twin.velocity()[0].to_f64());
                if android.is_none() && x.abs() < p && vel.abs() < threshold.velocity() {
                    android = Some(osc.motion_left(x, vel));
                }
                if motion == Motion::Settled {
                    break osc.motion_left(x, vel);
                }
            };
            let theta = osc.omega * dt;
            let bound = p * (1.0 + theta / 4.0) * (1.0 + 1e-3) + S::RESOLUTION;
            let android = android.expect("the offset test passes before the band");
            android_worst = android_worst.max(android);
            table.push(format!(
                "{:7} {rate:5} Hz  {freq} Hz ζ {zeta:<4}  left {:.2} × threshold (Android's rule: {:.2})",
                S::NAME,
                left / p,
                android / p
            ));
            assert!(
                left <= bound,
                "{} {freq} Hz ζ {zeta} at {rate} Hz: {left:e}",
                S::NAME
            );
        }
    }
    android_worst / p
}

#[test]
fn a_value_settles_only_when_the_motion_left_is_below_the_threshold() {
    let mut table = Vec::new();
    let mut android = 0.0f64;
    for worst in [
        settles_with_less_than_the_threshold_left::<f32>(&mut table),
        settles_with_less_than_the_threshold_left::<f64>(&mut table),
        settles_with_less_than_the_threshold_left::<I16F16>(&mut table),
        settles_with_less_than_the_threshold_left::<I32F32>(&mut table),
    ] {
        android = android.max(worst);
    }
    for line in &table {
        println!("{line}");
    }
    // The grid has springs that the offset and velocity test alone would snap early.
    assert!(android > 5.0, "{android}");
}

/// What a step reports: `Moving` while the value moves, `Settled` once, in the step that
/// snaps it onto its target, then `Resting` (and nothing moves) until it is moved again.
fn motion_is_reported<S: Scalar>() {
    let rigid = Tuning::rigid(DT60).expect("dt");
    for tuning in [sampled(2.0, 0.3, DT60), raw(0.05, 0.3, DT60), rigid] {
        let mut v = value::<S, 2>([1.0, -2.0], &tuning);
        assert_eq!(v.step(), Motion::Resting, "a new value rests");
        v.set_target([s(1.0), s(-2.0)]); // where it is: nothing moves
        v.set_position([s(1.0), s(-2.0)]);
        assert_eq!(v.step(), Motion::Resting);
        v.set_target([s(40.0), s(-2.0)]);
        let mut counts = [0usize; 3];
        let mut last = v.position();
        for _ in 0..10_000 {
            let m = v.step();
            counts[m as usize] += 1;
            assert_eq!(m.moved(), v.position() != last || m == Motion::Settled);
            last = v.position();
            if m == Motion::Resting {
                break;
            }
        }
        // Resting once (the step after), Moving until then, Settled exactly once.
        assert_eq!(
            (
                counts[Motion::Resting as usize],
                counts[Motion::Settled as usize]
            ),
            (1, 1)
        );
        assert_eq!(f(v.position()), [40.0, -2.0], "{}", S::NAME);
        // A bare step never settles, and a value at rest stays at rest through it.
        v.advance();
        assert!(v.is_at_rest());
        v.fling([s(5.0), S::ZERO]);
        assert!(!v.is_at_rest());
        v.advance();
        assert!(!v.is_at_rest());
        // (A rigid spring keeps no velocity: `C_d = 1` takes all of a fling.)
        let expected = if tuning == rigid {
            Motion::Settled
        } else {
            Motion::Moving
        };
        assert_eq!(v.step(), expected);
    }
}

#[test]
fn a_step_reports_moving_then_settled_once_then_resting() {
    each_backend!(motion_is_reported);
}
