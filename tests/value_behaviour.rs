//! Behaviour of `SpringValue` and `SpringBatch` in every backend (`f32`, `f64`, `I16F16`,
//! `I32F32`): retargeting, rest, settling time, N-D and batch equivalence, `set_dt`,
//! symmetry, and (with proptest, host only) that stepping never produces NaN/Inf in
//! floats and never wraps in fixed point.
//!
//! Expected values come from the continuous solution of the damped oscillator written out
//! below ([`Continuous`]), from the eigenvalues of the step map computed here
//! ([`dominant_pole`]), from exact integer arithmetic ([`check_fixed_step`]), or from the
//! documented contract; none is copied from a run.
//!
//! `cargo test --test value_behaviour -- --nocapture settle` prints the measured
//! steps-to-rest table.

use std::f64::consts::TAU;
use stiffspring::kernel::Coefficients;
use stiffspring::{
    AndroidDamping, AndroidStiffness, Error, I16F16, I32F32, Oscillator, Parameter,
    ReactSpringPreset, RestThreshold, Scalar, SpringBatch, SpringValue, SwiftUiPreset, Tuning,
};

const DT60: f64 = 1.0 / 60.0;
const DT120: f64 = 1.0 / 120.0;

/// Runs a generic function once per backend.
macro_rules! each_backend {
    ($f:ident $(, $arg:expr)*) => {{
        $f::<f32>($($arg),*);
        $f::<f64>($($arg),*);
        $f::<I16F16>($($arg),*);
        $f::<I32F32>($($arg),*);
    }};
}

fn s<S: Scalar>(x: f64) -> S {
    S::from_f64(x)
}

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

/// The relative precision of a backend's coefficients (`C_k`, `1 − C_d` as stored):
/// the float format itself, Q3.29 and Q3.61 for the fixed-point backends.
fn coef_eps<S: Scalar>() -> f64 {
    match S::NAME {
        "f32" => f32::EPSILON as f64,
        "I16F16" => 2f64.powi(-29),
        _ => f64::EPSILON,
    }
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

    /// `(y(t), y'(t))` from `y(0) = y0`, `y'(0) = v0`; `t` may be negative.
    fn at(&self, y0: f64, v0: f64, t: f64) -> (f64, f64) {
        let (w, z) = (self.omega, self.zeta);
        let sigma = z * w;
        if z < 1.0 {
            let wd = w * ((1.0 - z) * (1.0 + z)).sqrt();
            let (sn, cs) = (wd * t).sin_cos();
            let e = (-sigma * t).exp();
            let b = (v0 + sigma * y0) / wd;
            (
                e * (y0 * cs + b * sn),
                e * (v0 * cs - (sigma * v0 + w * w * y0) / wd * sn),
            )
        } else if z == 1.0 {
            let e = (-w * t).exp();
            let b = v0 + w * y0;
            (e * (y0 + b * t), e * (b - w * (y0 + b * t)))
        } else {
            let q = ((z - 1.0) * (z + 1.0)).sqrt();
            let (r1, r2) = (-w * (z - q), -w * (z + q));
            let b = (v0 - r1 * y0) / (r2 - r1);
            let a = y0 - b;
            let (e1, e2) = ((r1 * t).exp(), (r2 * t).exp());
            (a * e1 + b * e2, a * r1 * e1 + b * r2 * e2)
        }
    }

    /// `(P, Q)` with `u = y(0) − y(−h) = P·y0 + Q·v0`: the step velocity of the sampled
    /// trajectory through `(y0, v0)`.
    fn start_weights(&self, h: f64) -> (f64, f64) {
        let (from_offset, _) = self.at(1.0, 0.0, -h);
        let (from_velocity, _) = self.at(0.0, 1.0, -h);
        (1.0 - from_offset, -from_velocity)
    }
}

/// The dominant eigenvalue of one step on `(x, u)`:
/// `u' = r·u − C_k·x`, `x' = x + u'`, i.e. `M = [[1 − C_k, r], [−C_k, r]]` with
/// `r = 1 − C_d`. Returns `(ρ, c)`: its magnitude, and `|1 − 1/λ|`, the ratio `|u|/|x|`
/// in that mode (`u_n = x_n − x_{n−1}`).
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
        let t = Tuning::from_coefficients(ck, cd).unwrap();
        let (rho, _) = dominant_pole(ck, 1.0 - cd);
        assert!((t.spectral_radius() - rho).abs() < 1e-12, "({ck}, {cd})");
    }
    // Exact map: the poles are e^{s·dt}, so ρ = e^{−ζω·dt} when underdamped.
    let t = Tuning::from_frequency(2.0, 0.3, DT60).unwrap();
    let expected = (-0.3 * TAU * 2.0 * DT60).exp();
    assert!((t.spectral_radius() - expected).abs() < 1e-12);
}

// ---------------------------------------------------------------------------
// Tunings used below
// ---------------------------------------------------------------------------

/// Every UI preset: SwiftUI's, react-spring's, and Android stiffness × damping.
fn ui_oscillators() -> Vec<(String, Oscillator)> {
    let mut all = Vec::new();
    for p in SwiftUiPreset::ALL {
        all.push((format!("SwiftUI {p:?}"), p.oscillator()));
    }
    for p in ReactSpringPreset::ALL {
        all.push((format!("react-spring {p:?}"), p.oscillator()));
    }
    for k in AndroidStiffness::ALL {
        for d in AndroidDamping::ALL {
            let o = Oscillator::android(k.value(), d.value()).unwrap();
            all.push((format!("Android {k:?}/{d:?}"), o));
        }
    }
    all
}

fn sampled(frequency: f64, zeta: f64, dt: f64) -> Tuning {
    Tuning::from_frequency(frequency, zeta, dt).unwrap()
}

fn raw(ck: f64, cd: f64) -> Tuning {
    Tuning::from_coefficients(ck, cd).unwrap()
}

/// Steps `v` until it rests, at most `limit` steps; returns the number of steps.
fn steps_to_rest<S: Scalar, const D: usize>(v: &mut SpringValue<S, D>, limit: usize) -> usize {
    let mut n = 0;
    while !v.is_at_rest() {
        assert!(n < limit, "{}: not at rest after {limit} steps", S::NAME);
        v.step();
        n += 1;
    }
    n
}

// ---------------------------------------------------------------------------
// Retargeting mid-flight
// ---------------------------------------------------------------------------

fn raw_retarget_keeps_step_velocity_and_position<S: Scalar>() {
    // Raw coefficients: the step velocity is the article's v·dt and is kept as it is.
    for tuning in [raw(0.05, 0.2), raw(0.3, 0.0), Tuning::rigid()] {
        let mut v = SpringValue::<S, 2>::new([s(0.0), s(10.0)], tuning, DT60).unwrap();
        v.set_target([s(100.0), s(-20.0)]).unwrap();
        for _ in 0..7 {
            v.step();
        }
        let (p, u) = (v.position(), v.step_velocity());
        // A new target within a factor of two of the position (same sign): p − t is
        // exact (Sterbenz), so the position is kept exactly in floats too.
        let t = [p[0].sub(s(0.25 * p[0].to_f64())), p[1].add(s(0.5))];
        v.set_target(t).unwrap();
        assert!(same_all(v.step_velocity(), u), "{}: u changed", S::NAME);
        assert!(same_all(v.position(), p), "{}: position moved", S::NAME);
        assert!(same_all(v.target(), t));
        // The offset is the position relative to the new target.
        let expected = [p[0].sub(t[0]), p[1].sub(t[1])];
        assert!(same_all(v.offset(), expected));
    }
}

#[test]
fn retarget_with_raw_coefficients_keeps_step_velocity_and_position_exactly() {
    each_backend!(raw_retarget_keeps_step_velocity_and_position);
}

fn retarget_keeps_position_within_rounding<S: Scalar>() {
    // Any new target: the value stores x = p − t, so p is reproduced as t + (p − t),
    // two roundings in floats: |Δp| ≤ ε·(|p − t| + |p|). Exact in fixed point.
    let targets = [-1.5e-7, 1e-3, -37.0, 1234.567, -9000.25, 3.0e4];
    for tuning in [sampled(2.0, 0.3, DT60), raw(0.05, 0.2)] {
        for &t in &targets {
            let mut v = SpringValue::<S, 1>::new([s(1.0)], tuning, DT60).unwrap();
            v.set_target([s(70.0)]).unwrap();
            for _ in 0..5 {
                v.step();
            }
            let p = v.position()[0].to_f64();
            v.set_target([s(t)]).unwrap();
            let after = v.position()[0].to_f64();
            let t = s::<S>(t).to_f64();
            let bound = eps::<S>() * ((p - t).abs() + p.abs());
            assert!(
                (after - p).abs() <= bound,
                "{}: target {t}: {p} became {after}",
                S::NAME
            );
        }
    }
}

#[test]
fn retarget_keeps_position_up_to_float_rounding_and_exactly_in_fixed_point() {
    each_backend!(retarget_keeps_position_within_rounding);
}

fn sampled_retarget_keeps_continuous_velocity<S: Scalar>() {
    // With the exact map the velocity v (units/s) of the continuous trajectory is kept:
    // u changes by P·Δx, with P from the continuous solution.
    for (freq, zeta) in [(2.0, 0.3), (1.5, 1.0), (3.0, 2.0)] {
        let tuning = sampled(freq, zeta, DT60);
        let (p_weight, q_weight) = Continuous::new(freq, zeta).start_weights(DT60);
        let mut v = SpringValue::<S, 1>::new([s(0.0)], tuning, DT60).unwrap();
        v.set_target([s(100.0)]).unwrap();
        for _ in 0..6 {
            v.step();
        }
        let (x, u, vel) = (v.offset()[0], v.step_velocity()[0], v.velocity()[0]);
        let (p, t_new) = (v.position()[0], s::<S>(-40.0));
        v.set_target([t_new]).unwrap();
        let (x2, u2, vel2) = (v.offset()[0], v.step_velocity()[0], v.velocity()[0]);
        let delta = x2.to_f64() - x.to_f64();
        if S::RESOLUTION > 0.0 {
            // Exact in fixed point (floats: see retarget_keeps_position_within_rounding).
            assert!(same(v.position()[0], p), "{}: position moved", S::NAME);
        }
        // u₂ − u = P·Δ, up to one rounding of u₂ and the backend's rounding of C_k and
        // 1 − C_d, from which the library recovers P.
        let scale = u.to_f64().abs() + (p_weight * delta).abs();
        let tol = 4.0 * (eps::<S>() * scale + S::RESOLUTION)
            + 1e3 * coef_eps::<S>() * (p_weight * delta).abs();
        let shift = u2.to_f64() - u.to_f64();
        assert!(
            (shift - p_weight * delta).abs() <= tol,
            "{} ζ={zeta}: u shifted by {shift}, expected P·Δ = {}",
            S::NAME,
            p_weight * delta
        );
        // The velocity (u − P·x)/Q is kept to the same accuracy, divided by Q.
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
    each_backend!(sampled_retarget_keeps_continuous_velocity);
}

/// Tolerance on positions of magnitude ~100 after ~100 steps, per backend: accumulated
/// rounding (float ε or one LSB per step) plus the rounding of the coefficients.
fn trajectory_tolerance<S: Scalar>() -> f64 {
    match S::NAME {
        "f64" => 1e-9,
        "f32" => 2e-3,
        "I16F16" => 1e-2,
        _ => 1e-6,
    }
}

fn follows_continuous_trajectory<S: Scalar>() {
    for (freq, zeta) in [(2.0, 0.3), (1.5, 1.0), (1.0, 2.5)] {
        let osc = Continuous::new(freq, zeta);
        let mut v = SpringValue::<S, 1>::new([s(0.0)], sampled(freq, zeta, DT60), DT60).unwrap();
        let tol = trajectory_tolerance::<S>();
        // Released from rest at 0 toward 100: y = p − 100 starts at −100 with v = 0.
        v.set_target([s(100.0)]).unwrap();
        for n in 1..=20 {
            v.step();
            let (y, dy) = osc.at(-100.0, 0.0, n as f64 * DT60);
            let p = v.position()[0].to_f64();
            assert!(
                (p - (100.0 + y)).abs() < tol,
                "{} ζ={zeta} step {n}: {p} vs {}",
                S::NAME,
                100.0 + y
            );
            let vel = v.velocity()[0].to_f64();
            assert!(
                (vel - dy).abs() < 60.0 * tol,
                "{} step {n}: v {vel} vs {dy}",
                S::NAME
            );
        }
        // Mid-flight retarget to −50: the continuous spring whose target jumps keeps
        // its position and velocity, y restarts from p + 50.
        let (y20, v20) = osc.at(-100.0, 0.0, 20.0 * DT60);
        v.set_target([s(-50.0)]).unwrap();
        for n in 1..=80 {
            v.step();
            let (y, _) = osc.at(100.0 + y20 + 50.0, v20, n as f64 * DT60);
            let p = v.position()[0].to_f64();
            assert!(
                (p - (-50.0 + y)).abs() < tol,
                "{} ζ={zeta} step {n} after retarget: {p} vs {}",
                S::NAME,
                -50.0 + y
            );
        }
    }
}

#[test]
fn exact_map_value_follows_the_continuous_spring_across_a_retarget() {
    each_backend!(follows_continuous_trajectory);
}

#[test]
fn retarget_of_a_heavily_overdamped_undersampled_value_stays_finite() {
    // ζ = 2 at ω·dt = 8.5: P = 1 − x(−dt)/x₀ ≈ 4.6e12 (the fast mode, extrapolated one
    // step back). A retarget by 1e27 would ask for u ≈ 5e39, beyond f32::MAX; the value
    // must still stay finite (SAFE_MAGNITUDE leaves headroom "so that the transient
    // growth of a stable spring can never reach infinity").
    let f = 8.5 / TAU / DT60;
    let (p_weight, _) = Continuous::new(f, 2.0).start_weights(DT60);
    assert!(p_weight > 1e12);
    let t = sampled(f, 2.0, DT60);
    let mut v = SpringValue::<f32, 1>::new([1e27], t, DT60).unwrap();
    v.set_target([0.0]).unwrap();
    let mut w = SpringValue::<f64, 1>::new([1e300], t, DT60).unwrap();
    w.set_target([-1e300]).unwrap();
    for _ in 0..2000 {
        assert!(v.position()[0].is_finite() && v.step_velocity()[0].is_finite());
        assert!(w.position()[0].is_finite() && w.step_velocity()[0].is_finite());
        v.step();
        w.step();
    }
    assert!(v.is_at_rest() && w.is_at_rest());
}

// ---------------------------------------------------------------------------
// Rest
// ---------------------------------------------------------------------------

#[derive(Debug, PartialEq)]
struct State<S, const D: usize> {
    position: [S; D],
    target: [S; D],
    offset: [S; D],
    step_velocity: [S; D],
    velocity: [S; D],
    at_rest: bool,
}

fn state<S: Scalar, const D: usize>(v: &SpringValue<S, D>) -> State<S, D> {
    State {
        position: v.position(),
        target: v.target(),
        offset: v.offset(),
        step_velocity: v.step_velocity(),
        velocity: v.velocity(),
        at_rest: v.is_at_rest(),
    }
}

fn rest_is_exact_and_stable<S: Scalar>() {
    let tunings = [
        sampled(2.0, 0.3, DT60),
        sampled(4.0, 1.0, DT60),
        raw(0.05, 0.3),
        raw(0.5, 0.01),
        Tuning::rigid(),
    ];
    for tuning in tunings {
        let mut v = SpringValue::<S, 2>::new([s(10.0), s(-3.0)], tuning, DT60).unwrap();
        assert!(v.is_at_rest(), "a new value is at rest");
        let target = [s(37.25), s(-81.5)];
        v.set_target(target).unwrap();
        assert!(!v.is_at_rest());
        steps_to_rest(&mut v, 100_000);
        // Snapped exactly.
        assert!(
            same_all(v.position(), target),
            "{}: {:?}",
            S::NAME,
            v.position()
        );
        assert!(same_all(v.offset(), [S::ZERO; 2]));
        assert!(same_all(v.step_velocity(), [S::ZERO; 2]));
        assert_eq!(f(v.velocity()), [0.0; 2]);
        // Stepping a value at rest changes nothing.
        let before = state(&v);
        for _ in 0..100 {
            v.step();
        }
        assert_eq!(state(&v), before);
        // Retargeting to where it already is moves nothing, so it stays at rest.
        v.set_target(target).unwrap();
        assert_eq!(state(&v), before);
        // A real retarget wakes it; the first step moves the first component toward
        // the new target and leaves the second (Δ = 0, u = 0) exactly where it is.
        v.set_target([s(0.0), s(-81.5)]).unwrap();
        assert!(!v.is_at_rest());
        v.step();
        let p = f(v.position());
        assert!(p[0] < 37.25 && p[0] >= -37.25, "{}: {p:?}", S::NAME);
        assert_eq!(p[1], -81.5);
    }
}

#[test]
fn at_rest_the_value_sits_exactly_on_its_target_and_stays() {
    each_backend!(rest_is_exact_and_stable);
}

/// The predicted number of steps to rest from an offset `amplitude`: the slowest mode
/// decays by ρ per step, and rest needs both |x| ≤ p and |u| ≤ u_max, where |u| ≈ c·|x|
/// in that mode. So the envelope must fall to min(p, u_max/c):
/// n* = ln(min(p, u_max/c) / amplitude) / ln ρ.
fn predicted_steps(tuning: &Tuning, p: f64, u_max: f64, amplitude: f64) -> f64 {
    let (rho, c) = dominant_pole(tuning.stiffness(), tuning.retention());
    let threshold = if c > 0.0 { p.min(u_max / c) } else { p };
    (threshold / amplitude).ln() / rho.ln()
}

fn settles_within_the_predicted_time<S: Scalar>(table: &mut Vec<String>) {
    let threshold = RestThreshold::default();
    for dt in [DT60, DT120] {
        for (name, osc) in ui_oscillators() {
            let tuning = osc.tuning(dt).unwrap();
            let mut v = SpringValue::<S, 1>::new([s(0.0)], tuning, dt).unwrap();
            v.set_target([s(100.0)]).unwrap();
            let n = steps_to_rest(&mut v, 100_000);
            assert!(same_all(v.position(), [s(100.0)]));
            // The band actually used: the threshold, widened in fixed point to the dead
            // band (rest_offset); the step velocity threshold is v·dt (≥ 1 LSB).
            let p = v.rest_offset().to_f64().max(threshold.position());
            let u_max = (threshold.velocity() * dt).max(S::RESOLUTION);
            let n_star = predicted_steps(&v.tuning(), p, u_max, 100.0);
            // The initial amplitude of the slow mode is 100 times a factor of order one
            // (eigenvector conditioning, the critical double pole's n·ρⁿ): allow a factor
            // 2 plus 20 steps above, a factor 1/3 below.
            let (lo, hi) = (n_star / 3.0, 2.0 * n_star + 20.0);
            table.push(format!(
                "{:7} {:4.0} Hz  {:38} n = {n:5}  n* = {n_star:7.1}  n/n* = {:.2}",
                S::NAME,
                1.0 / dt,
                name,
                n as f64 / n_star
            ));
            assert!(
                (n as f64) >= lo && (n as f64) <= hi,
                "{} {name} at {:.0} Hz: {n} steps, predicted {n_star:.1}",
                S::NAME,
                1.0 / dt
            );
        }
    }
}

#[test]
fn settle_every_ui_preset_in_every_backend_within_the_decay_bound() {
    let mut table = Vec::new();
    each_backend!(settles_within_the_predicted_time, &mut table);
    println!("steps to rest from an offset of 100, default threshold:");
    for line in &table {
        println!("{line}");
    }
}

/// The largest offset (in LSB) at which a fixed-point spring with zero velocity does not
/// move at all: measured on the kernel, whatever its rounding.
fn measured_dead_band<S: Scalar>(tuning: &Tuning) -> f64 {
    let c = Coefficients::<S>::new(tuning);
    let ck = S::coef_to_f64(c.stiffness());
    let lsb = S::RESOLUTION;
    let mut n = 0.0;
    while n < 4.0 / ck + 4.0 {
        let x = s::<S>((n + 1.0) * lsb);
        if c.respond(x, S::ZERO) != S::ZERO {
            break;
        }
        n += 1.0;
    }
    n
}

fn fixed_point_settles_with_a_tiny_threshold<S: Scalar>(table: &mut Vec<String>) {
    let tiny = RestThreshold::new(1e-9, 1e-9).unwrap();
    let lsb = S::RESOLUTION;
    for dt in [DT60, DT120] {
        for (name, osc) in ui_oscillators() {
            let tuning = osc.tuning(dt).unwrap();
            let mut v = SpringValue::<S, 1>::new([s(0.0)], tuning, dt)
                .unwrap()
                .with_rest_threshold(tiny);
            let ck = v.tuning().stiffness();
            let rest = v.rest_offset().to_f64();
            // The documented widening covers at least half an LSB of response...
            assert!(rest >= 0.5 / ck * lsb, "{} {name}: {rest}", S::NAME);
            // ...and in fact the whole measured dead band of the kernel.
            let dead = measured_dead_band::<S>(&v.tuning());
            assert!(
                rest >= dead * lsb,
                "{} {name}: rest offset {rest} < dead band {dead} LSB",
                S::NAME
            );
            for start in [100.0, -3.0, 0.01] {
                v.set_position([s(start)]).unwrap();
                let n = steps_to_rest(&mut v, 1_000_000);
                assert!(same_all(v.position(), [S::ZERO]));
                if start == 100.0 {
                    table.push(format!(
                        "{:7} {:4.0} Hz  {name:38} n = {n:5}  dead band {dead:6.0} LSB, rest offset {:8.1} LSB",
                        S::NAME,
                        1.0 / dt,
                        rest / lsb
                    ));
                }
            }
        }
    }
}

#[test]
fn settle_in_fixed_point_even_with_a_tiny_threshold() {
    let mut table = Vec::new();
    fixed_point_settles_with_a_tiny_threshold::<I16F16>(&mut table);
    fixed_point_settles_with_a_tiny_threshold::<I32F32>(&mut table);
    println!("steps to rest from 100 with RestThreshold::new(1e-9, 1e-9):");
    for line in &table {
        println!("{line}");
    }
}

// ---------------------------------------------------------------------------
// N-D values and batches
// ---------------------------------------------------------------------------

fn three_d_equals_three_1d<S: Scalar>() {
    let starts = [3.0, -40.0, 0.5];
    let targets = [100.0, 12.5, -7.25];
    let flings = [0.0, 30.0, -200.0];
    let tunings = [
        SwiftUiPreset::Bouncy.oscillator().tuning(DT60).unwrap(),
        ReactSpringPreset::Molasses
            .oscillator()
            .tuning(DT120)
            .unwrap(),
        raw(0.02, 0.1),
    ];
    for tuning in tunings {
        let mut v3 = SpringValue::<S, 3>::new(starts.map(s), tuning, DT60).unwrap();
        v3.set_target(targets.map(s)).unwrap();
        v3.fling(flings.map(s)).unwrap();
        let mut v1: Vec<SpringValue<S, 1>> = (0..3)
            .map(|k| {
                let mut v = SpringValue::new([s(starts[k])], tuning, DT60).unwrap();
                v.set_target([s(targets[k])]).unwrap();
                v.fling([s(flings[k])]).unwrap();
                v
            })
            .collect();
        let mut rest_step = [None; 3];
        let mut compared = 0;
        for n in 1..100_000 {
            v3.step();
            for (k, v) in v1.iter_mut().enumerate() {
                v.step();
                if v.is_at_rest() && rest_step[k].is_none() {
                    rest_step[k] = Some(n);
                }
            }
            if rest_step.iter().all(Option::is_none) {
                // While every 1-D value moves, the 3-D value is the same, bit for bit.
                for (k, v) in v1.iter().enumerate() {
                    assert!(same(v3.offset()[k], v.offset()[0]), "{} step {n}", S::NAME);
                    assert!(same(v3.step_velocity()[k], v.step_velocity()[0]));
                    assert!(same(v3.position()[k], v.position()[0]));
                }
                compared += 1;
            }
            if v3.is_at_rest() {
                // It rests only once every component has reached its band, so never
                // before the last 1-D value.
                let last = rest_step.iter().map(|r| r.unwrap_or(usize::MAX)).max();
                assert!(
                    Some(n) >= last,
                    "{}: 3-D at rest at {n}, 1-D at {rest_step:?}",
                    S::NAME
                );
                assert!(same_all(v3.position(), targets.map(s)));
                break;
            }
        }
        assert!(v3.is_at_rest());
        assert!(compared > 10, "{}: compared only {compared} steps", S::NAME);
    }
}

#[test]
fn a_3d_value_is_three_1d_values_bit_for_bit() {
    each_backend!(three_d_equals_three_1d);
}

fn batch_member_equals_standalone<S: Scalar>() {
    let tunings = [
        SwiftUiPreset::Snappy.oscillator().tuning(DT60).unwrap(),
        raw(0.05, 0.25),
        Tuning::rigid(),
        ReactSpringPreset::Wobbly.oscillator().tuning(DT60).unwrap(),
        sampled(1.0, 2.0, DT60),
    ];
    let starts = [
        [0.0, 1.0],
        [5.0, -5.0],
        [-20.0, 3.5],
        [100.0, 0.0],
        [0.25, -0.75],
    ];
    let mut batch = SpringBatch::<S, 8, 2>::new(DT60).unwrap();
    let mut alone: Vec<SpringValue<S, 2>> = Vec::new();
    for (i, (t, p)) in tunings.iter().zip(starts.iter()).enumerate() {
        assert_eq!(batch.push(p.map(s), *t), Ok(i));
        alone.push(SpringValue::new(p.map(s), *t, DT60).unwrap());
    }
    // The same calls on both, at the same steps (never a retarget to the current
    // target, see batch_retarget_to_the_current_target_keeps_a_resting_member_asleep).
    let script = |n: usize, b: &mut SpringBatch<S, 8, 2>, a: &mut [SpringValue<S, 2>]| {
        let target =
            |i: usize, t: [f64; 2], b: &mut SpringBatch<S, 8, 2>, a: &mut [SpringValue<S, 2>]| {
                b.set_target(i, t.map(s)).unwrap();
                a[i].set_target(t.map(s)).unwrap();
            };
        let fling =
            |i: usize, v: [f64; 2], b: &mut SpringBatch<S, 8, 2>, a: &mut [SpringValue<S, 2>]| {
                b.fling(i, v.map(s)).unwrap();
                a[i].fling(v.map(s)).unwrap();
            };
        match n {
            0 => {
                target(0, [50.0, -50.0], b, a);
                target(2, [20.0, 20.0], b, a);
                target(3, [-100.0, 8.0], b, a);
                fling(4, [300.0, -10.0], b, a);
            }
            10 => {
                target(0, [-10.0, 0.0], b, a); // mid-flight
                fling(3, [-500.0, 500.0], b, a);
                let t = sampled(3.0, 0.5, DT60);
                b.set_tuning(2, t).unwrap();
                a[2].set_tuning(t).unwrap();
            }
            40 => target(1, [6.0, 6.0], b, a), // member 1 was resting
            _ => {}
        }
    };
    for n in 0..5000 {
        script(n, &mut batch, &mut alone);
        for (i, a) in alone.iter().enumerate() {
            assert!(
                same_all(batch.position(i).unwrap(), a.position()),
                "{} member {i} step {n}",
                S::NAME
            );
            assert!(same_all(batch.step_velocity(i).unwrap(), a.step_velocity()));
            assert!(same_all(batch.target(i).unwrap(), a.target()));
            assert_eq!(
                batch.is_at_rest(i).unwrap(),
                a.is_at_rest(),
                "member {i} step {n}"
            );
        }
        let awake = alone.iter().filter(|a| !a.is_at_rest()).count();
        assert_eq!(batch.awake(), awake);
        if n > 40 && awake == 0 {
            return;
        }
        batch.step();
        for a in alone.iter_mut() {
            a.step();
        }
    }
    panic!("{}: the batch did not come to rest", S::NAME);
}

#[test]
fn a_batch_member_is_a_standalone_value_bit_for_bit() {
    each_backend!(batch_member_equals_standalone);
}

fn batch_skips_resting_members<S: Scalar>() {
    let t = SwiftUiPreset::Smooth.oscillator().tuning(DT60).unwrap();
    let mut b = SpringBatch::<S, 5>::new(DT60).unwrap();
    for k in 0..5 {
        assert_eq!(b.push([s(k as f64)], t), Ok(k));
    }
    assert_eq!((b.len(), b.awake()), (5, 0));
    b.set_target(1, [s(40.0)]).unwrap();
    b.set_target(3, [s(-40.0)]).unwrap();
    assert_eq!(b.awake(), 2);
    let resting: Vec<bool> = (0..5).map(|i| b.is_at_rest(i).unwrap()).collect();
    assert_eq!(resting, [true, false, true, false, true]);
    let mut n = 0;
    while b.awake() > 0 {
        b.step();
        n += 1;
        assert!(n < 10_000);
        // The resting members never move.
        for i in [0, 2, 4] {
            assert!(same_all(b.position(i).unwrap(), [s(i as f64)]));
        }
    }
    assert!(same_all(b.position(1).unwrap(), [s(40.0)]));
    assert!(same_all(b.position(3).unwrap(), [s(-40.0)]));
    // Retargeting one resting member wakes exactly that one.
    let before: Vec<[S; 1]> = (0..5).map(|i| b.position(i).unwrap()).collect();
    b.set_target(2, [s(-7.0)]).unwrap();
    assert_eq!(b.awake(), 1);
    b.step();
    for (i, p) in before.iter().enumerate() {
        let moved = !same_all(b.position(i).unwrap(), *p);
        assert_eq!(moved, i == 2, "{} member {i}", S::NAME);
        assert_eq!(b.is_at_rest(i).unwrap(), i != 2);
    }
}

#[test]
fn a_batch_steps_only_awake_members_and_a_retarget_wakes_exactly_one() {
    each_backend!(batch_skips_resting_members);
}

fn batch_fills_to_capacity<S: Scalar>() {
    let mut b = SpringBatch::<S, 7, 3>::new(DT120).unwrap();
    assert!(b.is_empty());
    for k in 0..7 {
        assert_eq!(b.push([s(k as f64); 3], raw(0.1, 0.5)), Ok(k));
        assert_eq!(b.len(), k + 1);
    }
    assert_eq!(
        b.push([S::ZERO; 3], raw(0.1, 0.5)),
        Err(Error::CapacityFull)
    );
    for k in 0..7 {
        assert!(same_all(b.target(k).unwrap(), [s(k as f64); 3]));
        assert!(b.is_at_rest(k).unwrap());
    }
}

#[test]
fn a_batch_holds_exactly_its_capacity() {
    each_backend!(batch_fills_to_capacity);
}

fn batch_same_target_keeps_rest<S: Scalar>() {
    let t = raw(0.1, 0.5);
    let mut b = SpringBatch::<S, 2>::new(DT60).unwrap();
    b.push([s(3.0)], t).unwrap();
    let mut v = SpringValue::<S, 1>::new([s(3.0)], t, DT60).unwrap();
    b.set_target(0, [s(3.0)]).unwrap();
    v.set_target([s(3.0)]).unwrap();
    // SpringValue documents that a resting value stays at rest when nothing moved, and
    // SpringBatch::set_target that it acts "as SpringValue::set_target does".
    assert!(v.is_at_rest());
    assert_eq!(b.is_at_rest(0), Ok(true), "{}", S::NAME);
    assert_eq!(b.awake(), 0);
}

#[test]
fn batch_retarget_to_the_current_target_keeps_a_resting_member_asleep() {
    each_backend!(batch_same_target_keeps_rest);
}

// ---------------------------------------------------------------------------
// set_dt
// ---------------------------------------------------------------------------

fn set_dt_resamples_the_same_oscillator<S: Scalar>() {
    for (freq, zeta) in [(2.0, 0.3), (1.5, 1.0), (3.0, 2.0)] {
        let osc = Continuous::new(freq, zeta);
        let t60 = sampled(freq, zeta, DT60);
        let mut v = SpringValue::<S, 1>::new([s(0.0)], t60, DT60).unwrap();
        v.set_target([s(100.0)]).unwrap();
        for _ in 0..12 {
            v.step();
        }
        let (p, vel) = (v.position(), v.velocity()[0].to_f64());
        v.set_dt(DT120).unwrap();
        assert_eq!(v.dt(), DT120);
        assert!(same_all(v.position(), p), "{}: position moved", S::NAME);
        assert!(v.tuning().samples_oscillator());
        // The same oscillator, up to the rounding of the backend's coefficients.
        let back = v.tuning().oscillator(DT120).unwrap();
        let rel = 1e3 * coef_eps::<S>() + 1e-12;
        assert!(
            (back.frequency() - freq).abs() <= rel * freq,
            "{} ζ={zeta}: {} Hz",
            S::NAME,
            back.frequency()
        );
        assert!(
            (back.damping_ratio() - zeta).abs() <= rel * zeta.max(1.0),
            "{}: ζ {}",
            S::NAME,
            back.damping_ratio()
        );
        // The velocity in units/s is kept (one rounding of u at the new rate).
        let vtol = 4.0 * (eps::<S>() * (vel.abs() + 100.0 / DT120) + S::RESOLUTION / DT120);
        let vel2 = v.velocity()[0].to_f64();
        assert!(
            (vel2 - vel).abs() <= vtol,
            "{}: {vel} became {vel2}",
            S::NAME
        );
        // And the value goes on sampling the same continuous trajectory at 120 Hz.
        let (y12, v12) = osc.at(-100.0, 0.0, 12.0 * DT60);
        for n in 1..=120 {
            v.step();
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
fn set_dt_from_60_to_120_hz_samples_the_same_oscillator_and_keeps_the_velocity() {
    each_backend!(set_dt_resamples_the_same_oscillator);
}

fn set_dt_keeps_raw_coefficients<S: Scalar>() {
    let t = raw(0.05, 0.2);
    let mut v = SpringValue::<S, 1>::new([s(0.0)], t, DT60).unwrap();
    v.set_target([s(100.0)]).unwrap();
    for _ in 0..5 {
        v.step();
    }
    let (tuning, u, vel) = (
        v.tuning(),
        v.step_velocity()[0].to_f64(),
        v.velocity()[0].to_f64(),
    );
    v.set_dt(DT120).unwrap();
    // Raw coefficients keep their per-step meaning (the article): unchanged.
    assert_eq!(v.tuning(), tuning);
    assert!(!v.tuning().samples_oscillator());
    // u = v·dt: half the step velocity at twice the rate, the same velocity.
    let u2 = v.step_velocity()[0].to_f64();
    assert!(
        (u2 - u / 2.0).abs() <= eps::<S>() * u.abs() + S::RESOLUTION,
        "{}",
        S::NAME
    );
    let vtol = 4.0 * (eps::<S>() * vel.abs() + S::RESOLUTION / DT120);
    assert!((v.velocity()[0].to_f64() - vel).abs() <= vtol);
}

#[test]
fn set_dt_keeps_raw_coefficients_and_the_velocity() {
    each_backend!(set_dt_keeps_raw_coefficients);
}

// ---------------------------------------------------------------------------
// Symmetry
// ---------------------------------------------------------------------------

fn trajectories_are_symmetric<S: Scalar>() {
    let tunings = [
        SwiftUiPreset::Bouncy.oscillator().tuning(DT60).unwrap(),
        ReactSpringPreset::Molasses
            .oscillator()
            .tuning(DT60)
            .unwrap(),
        Oscillator::android(10_000.0, 0.2)
            .unwrap()
            .tuning(DT60)
            .unwrap(),
        raw(0.05, 0.2),
        raw(0.5, 0.0),
        Tuning::from_coefficients_extended(1.5, 0.5).unwrap(),
        Tuning::rigid(),
    ];
    let starts = [
        (100.0, 0.0, 0.0),
        (37.5, -12.25, 250.0),
        (-0.001, 3.0, -1.0),
        (1.0 / 3.0, 0.0, 7.0),
    ];
    for tuning in tunings {
        for (x0, t0, v0) in starts {
            let mut a = SpringValue::<S, 1>::new([s(x0)], tuning, DT60).unwrap();
            let mut b = SpringValue::<S, 1>::new([s(-x0)], tuning, DT60).unwrap();
            a.set_target([s(t0)]).unwrap();
            b.set_target([s(-t0)]).unwrap();
            a.fling([s(v0)]).unwrap();
            b.fling([s(-v0)]).unwrap();
            for n in 0..20_000 {
                // Equal as numbers: an exact cancellation gives +0 on both sides in IEEE
                // arithmetic, so the sign of a zero is not mirrored.
                let (pa, pb) = (a.position()[0], b.position()[0]);
                assert!(pb == pa.neg(), "{} step {n}: {pa:?} vs {pb:?}", S::NAME);
                assert!(b.step_velocity()[0] == a.step_velocity()[0].neg());
                assert!(b.offset()[0] == a.offset()[0].neg());
                assert_eq!(a.is_at_rest(), b.is_at_rest());
                if a.is_at_rest() {
                    break;
                }
                a.step();
                b.step();
            }
            // (The undamped raw spring rings forever: compared over 20 000 steps.)
            let damped = tuning.damping() > 0.0;
            assert!(
                a.is_at_rest() || !damped,
                "{}: {tuning:?} did not settle",
                S::NAME
            );
        }
    }
}

#[test]
fn the_trajectory_from_minus_x0_is_the_exact_negation() {
    each_backend!(trajectories_are_symmetric);
}

// ---------------------------------------------------------------------------
// Fixed point: saturation, never wrapping
// ---------------------------------------------------------------------------

/// Raw access to the fixed-point backends, for the exact-arithmetic check.
trait FixedBits: Scalar {
    /// Fractional bits of the coefficient format (Q3.29, Q3.61).
    const COEF_FRAC: u32;
    const MIN_BITS: i128;
    const MAX_BITS: i128;
    fn bits(self) -> i128;
    fn from_raw(bits: i128) -> Self;
    fn coef_bits(c: Self::Coef) -> i128;
}

impl FixedBits for I16F16 {
    const COEF_FRAC: u32 = 29;
    const MIN_BITS: i128 = i32::MIN as i128;
    const MAX_BITS: i128 = i32::MAX as i128;
    fn bits(self) -> i128 {
        self.to_bits() as i128
    }
    fn from_raw(bits: i128) -> Self {
        I16F16::from_bits(bits as i32)
    }
    fn coef_bits(c: Self::Coef) -> i128 {
        c.to_bits() as i128
    }
}

impl FixedBits for I32F32 {
    const COEF_FRAC: u32 = 61;
    const MIN_BITS: i128 = i64::MIN as i128;
    const MAX_BITS: i128 = i64::MAX as i128;
    fn bits(self) -> i128 {
        self.to_bits() as i128
    }
    fn from_raw(bits: i128) -> Self {
        I32F32::from_bits(bits as i64)
    }
    fn coef_bits(c: Self::Coef) -> i128 {
        c.to_bits() as i128
    }
}

/// One step from `(x, u)` (raw bits) gave `(x2, u2)`. Checks it against exact integer
/// arithmetic: `u2` is `(1 − C_d)·u − C_k·x`, computed exactly, rounded once to one of
/// the two adjacent LSBs (whichever the rounding mode picks) and saturated; `x2` is the
/// saturated sum `x + u2`. A wrapped result would be off by about 2³².
fn check_fixed_step<S: FixedBits>(c: &Coefficients<S>, x: i128, u: i128, x2: i128, u2: i128) {
    let (k, r) = (S::coef_bits(c.stiffness()), S::coef_bits(c.retention()));
    // |u·r| < 2⁶³·2⁶¹ and |x·k| < 2⁶³·2⁶³: the exact difference fits in i128.
    let exact = u * r - x * k;
    let floor = exact >> S::COEF_FRAC;
    let ceil = floor + i128::from(exact & ((1 << S::COEF_FRAC) - 1) != 0);
    let clamp = |v: i128| v.clamp(S::MIN_BITS, S::MAX_BITS);
    assert!(
        u2 == clamp(floor) || u2 == clamp(ceil),
        "{}: u' = {u2}, exact {floor}..{ceil} (x = {x}, u = {u})",
        S::NAME
    );
    assert_eq!(
        x2,
        clamp(x + u2),
        "{}: x' = {x2} for x = {x}, u' = {u2}",
        S::NAME
    );
}

/// Steps `v` up to `steps` times, checking every step that does not end at rest.
fn step_checked<S: FixedBits>(v: &mut SpringValue<S, 1>, c: &Coefficients<S>, steps: usize) {
    for _ in 0..steps {
        if v.is_at_rest() {
            assert!(same_all(v.position(), v.target()));
            return;
        }
        let (x, u) = (v.offset()[0].bits(), v.step_velocity()[0].bits());
        v.step();
        if !v.is_at_rest() {
            check_fixed_step::<S>(c, x, u, v.offset()[0].bits(), v.step_velocity()[0].bits());
        }
    }
}

fn extremes_saturate<S: FixedBits>() {
    let (min, max) = (S::from_raw(S::MIN_BITS), S::from_raw(S::MAX_BITS));
    let tunings = [
        sampled(2.0, 0.3, DT60),
        Oscillator::android(10_000.0, 0.2)
            .unwrap()
            .tuning(DT60)
            .unwrap(),
        raw(0.05, 0.2),
        raw(1.0, 0.0),
        Tuning::rigid(),
    ];
    for tuning in tunings {
        let c = Coefficients::<S>::new(&tuning);
        for (from, to) in [
            (max, min),
            (min, max),
            (max, S::ZERO),
            (min, S::ZERO),
            (S::ZERO, max),
        ] {
            let mut v = SpringValue::<S, 1>::new([from], tuning, DT60).unwrap();
            if v.set_target([to]).is_err() {
                // An offset across the whole range is rejected (tested below).
                assert!((from.to_f64() - to.to_f64()).abs() > S::SAFE_MAGNITUDE / 2.0);
                continue;
            }
            // The first step moves toward the target and stays in range.
            let before = v.position()[0];
            v.step();
            let after = v.position()[0];
            let toward = if to > before {
                after > before
            } else {
                after < before
            };
            assert!(
                toward,
                "{} {from:?} → {to:?}: {before:?} then {after:?}",
                S::NAME
            );
            // Every later step is the exact, saturated arithmetic.
            step_checked(&mut v, &c, 5000);
        }
    }
}

#[test]
fn fixed_point_extremes_saturate_and_move_toward_the_target() {
    extremes_saturate::<I16F16>();
    extremes_saturate::<I32F32>();
}

/// An offset `p − t` beyond the range cannot be stored: set_target and set_position
/// reject it with `OutOfRange(Position)` and leave the value as it was (a saturated
/// offset would silently teleport it).
fn retarget_across_the_range_is_rejected<S: FixedBits>() {
    let (min, max) = (S::from_raw(S::MIN_BITS), S::from_raw(S::MAX_BITS));
    let half = S::from_raw(S::MAX_BITS / 2 + 1000);
    for (from, to) in [(max, min), (min, max), (half, half.neg())] {
        let mut v = SpringValue::<S, 1>::new([from], raw(0.1, 0.5), DT60).unwrap();
        assert_eq!(
            v.set_target([to]),
            Err(stiffspring::Error::OutOfRange(
                stiffspring::Parameter::Position
            ))
        );
        assert!(same(v.position()[0], from), "{}", S::NAME);
        assert!(same(v.target()[0], from) && v.is_at_rest());
        let mut w = SpringValue::<S, 1>::new([to], raw(0.1, 0.5), DT60).unwrap();
        assert!(w.set_position([from]).is_err());
        assert!(same(w.position()[0], to), "{}", S::NAME);
    }
    // Just inside the range still works and keeps the position exactly.
    let quarter = S::from_raw(S::MAX_BITS / 4);
    let mut v = SpringValue::<S, 1>::new([quarter], raw(0.1, 0.5), DT60).unwrap();
    v.set_target([quarter.neg()]).unwrap();
    assert!(same(v.position()[0], quarter));
}

#[test]
fn fixed_point_retarget_across_more_than_half_the_range_is_rejected() {
    retarget_across_the_range_is_rejected::<I16F16>();
    retarget_across_the_range_is_rejected::<I32F32>();
}

// ---------------------------------------------------------------------------
// Properties (proptest, host only)
// ---------------------------------------------------------------------------

#[cfg(not(target_os = "none"))]
mod properties {
    use super::*;
    use proptest::prelude::*;

    /// A coefficient in [0, 1], with the corners drawn often.
    fn unit() -> impl Strategy<Value = f64> {
        prop_oneof![1 => Just(0.0), 1 => Just(1.0), 6 => 0.0..=1.0f64]
    }

    /// Valid tunings: raw coefficients over [0, 1]², and the exact map over
    /// f·dt ∈ [1e−3, 0.45], ζ ∈ [0, 5], at 60 Hz.
    fn tunings() -> impl Strategy<Value = Tuning> {
        prop_oneof![
            (unit(), unit()).prop_map(|(k, d)| Tuning::from_coefficients(k, d).unwrap()),
            (
                1e-3..=0.45f64,
                prop_oneof![1 => Just(0.0), 1 => Just(1.0), 6 => 0.0..=5.0f64]
            )
                .prop_map(|(fdt, z)| Tuning::from_frequency(fdt / DT60, z, DT60).unwrap()),
        ]
    }

    /// A fraction in [−1, 1] of a magnitude, with 0 and ±1 drawn often.
    fn fraction() -> impl Strategy<Value = f64> {
        prop_oneof![1 => Just(0.0), 1 => Just(1.0), 1 => Just(-1.0), 6 => -1.0..=1.0f64]
    }

    fn floats_stay_finite<S: Scalar>(
        tuning: Tuning,
        (p, t, v): (f64, f64, f64),
    ) -> Result<(), TestCaseError> {
        let lim = S::SAFE_MAGNITUDE / 1e6;
        let mut value = SpringValue::<S, 1>::new([s(p * lim)], tuning, DT60).unwrap();
        value.set_target([s(t * lim)]).unwrap();
        match value.fling([s(v * lim)]) {
            // Documented: u₀ may leave the range for a large velocity.
            Ok(()) | Err(Error::OutOfRange(Parameter::Velocity)) => {}
            Err(e) => return Err(TestCaseError::fail(format!("fling: {e:?}"))),
        }
        for n in 0..2000 {
            value.step();
            let all = [
                value.position()[0],
                value.offset()[0],
                value.step_velocity()[0],
                value.velocity()[0],
            ];
            prop_assert!(
                all.iter().all(|x| x.to_f64().is_finite()),
                "{} step {n}: {all:?} ({tuning:?})",
                S::NAME
            );
        }
        Ok(())
    }

    fn fixed_never_wraps<S: FixedBits>(
        tuning: Tuning,
        (p, t, v): (i128, i128, i128),
    ) -> Result<(), TestCaseError> {
        let c = Coefficients::<S>::new(&tuning);
        let mut value = SpringValue::<S, 1>::new([S::from_raw(p)], tuning, DT60).unwrap();
        match value.set_target([S::from_raw(t)]) {
            Ok(()) => {}
            // An offset beyond the range is rejected, documented; nothing to step.
            Err(Error::OutOfRange(Parameter::Position)) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("set_target: {e:?}"))),
        }
        match value.fling([S::from_raw(v)]) {
            Ok(()) | Err(Error::OutOfRange(Parameter::Velocity)) => {}
            Err(e) => return Err(TestCaseError::fail(format!("fling: {e:?}"))),
        }
        step_checked(&mut value, &c, 2000);
        Ok(())
    }

    /// Raw bits of a fixed-point value: anywhere, near the ends, or near zero.
    fn bits(min: i128, max: i128) -> impl Strategy<Value = i128> {
        prop_oneof![
            4 => min..=max,
            1 => Just(min),
            1 => Just(max),
            1 => (0i128..4096).prop_map(move |d| min + d),
            1 => (0i128..4096).prop_map(move |d| max - d),
            2 => -1_000_000i128..1_000_000,
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn f32_never_produces_nan_or_inf(t in tunings(), x in (fraction(), fraction(), fraction())) {
            floats_stay_finite::<f32>(t, x)?;
        }

        #[test]
        fn f64_never_produces_nan_or_inf(t in tunings(), x in (fraction(), fraction(), fraction())) {
            floats_stay_finite::<f64>(t, x)?;
        }

        #[test]
        fn i16f16_steps_are_exact_and_saturate(
            t in tunings(),
            p in bits(i32::MIN as i128, i32::MAX as i128),
            g in bits(i32::MIN as i128, i32::MAX as i128),
            v in bits(i32::MIN as i128, i32::MAX as i128),
        ) {
            fixed_never_wraps::<I16F16>(t, (p, g, v))?;
        }

        #[test]
        fn i32f32_steps_are_exact_and_saturate(
            t in tunings(),
            p in bits(i64::MIN as i128, i64::MAX as i128),
            g in bits(i64::MIN as i128, i64::MAX as i128),
            v in bits(i64::MIN as i128, i64::MAX as i128),
        ) {
            fixed_never_wraps::<I32F32>(t, (p, g, v))?;
        }
    }
}
