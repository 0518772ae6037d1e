//! Rest: a value at rest sits exactly on its target and stays there; every UI preset
//! settles within the time the decay of its slowest mode predicts; fixed point settles
//! even with a threshold far below its last bit.
//!
//! The prediction comes from the eigenvalues of the step map, computed here; the rest
//! band is the one `RestThreshold` documents (offset within `p/√2`, kept step velocity
//! within `min(p·√C_k/√2, v·dt)`). When a value settles relative to the continuous motion
//! it has left is measured in `tests/value_behaviour.rs`.
//!
//! `cargo test --release --test value_rest -- --nocapture` prints the steps-to-rest tables.

use stiffspring::presets::{android, react_spring, swiftui};
use stiffspring::{I16F16, I32F32, Motion, Oscillator, RestThreshold, Scalar, SpringValue, Tuning};

mod support;
use support::{DT60, DT120, s};

/// Every UI preset: SwiftUI's, react-spring's, and Android stiffness × damping.
fn ui_oscillators() -> Vec<(String, Oscillator)> {
    let mut all = Vec::new();
    for (name, o) in swiftui::ALL {
        all.push((format!("SwiftUI {name}"), o));
    }
    for (name, o) in react_spring::ALL {
        all.push((format!("react-spring {name}"), o));
    }
    for (k, stiffness) in android::STIFFNESSES {
        for (d, ratio) in android::DAMPING_RATIOS {
            let o = android::spring_force(stiffness, ratio).expect("valid");
            all.push((format!("Android {k}/{d}"), o));
        }
    }
    all
}

/// Steps `v` until it settles, at most `limit` steps; returns the number of steps.
fn steps_to_rest<S: Scalar, const D: usize>(v: &mut SpringValue<S, D>, limit: usize) -> usize {
    for n in 1..=limit {
        if v.step() == Motion::Settled {
            return n;
        }
    }
    panic!("{}: not at rest after {limit} steps", S::NAME);
}

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
        Tuning::from_frequency(2.0, 0.3, DT60),
        Tuning::from_frequency(4.0, 1.0, DT60),
        Tuning::from_coefficients(0.05, 0.3, DT60),
        Tuning::from_coefficients(0.5, 0.01, DT60),
        Tuning::rigid(DT60),
    ];
    for tuning in tunings.map(|t| t.expect("valid")) {
        let mut v = SpringValue::<S, 2>::new([s(10.0), s(-3.0)], &tuning).expect("valid");
        assert!(v.is_at_rest(), "a new value is at rest");
        let target = [s(37.25), s(-81.5)];
        v.set_target(target);
        assert!(!v.is_at_rest());
        steps_to_rest(&mut v, 100_000);
        // Snapped exactly, with nothing left.
        assert_eq!(v.position(), target, "{}", S::NAME);
        assert_eq!(v.offset(), [S::ZERO; 2]);
        assert_eq!(v.step_velocity(), [S::ZERO; 2]);
        assert_eq!(v.velocity(), [S::ZERO; 2]);
        // Stepping a value at rest changes nothing: `step` runs the spring on the zero
        // state (it tests no flag first), which must stay zero to the bit, sign included.
        let before = state(&v);
        let bits = |v: &SpringValue<S, 2>| {
            let (x, u) = (v.offset(), v.step_velocity());
            [x[0], x[1], u[0], u[1], v.position()[0], v.position()[1]].map(|c| c.to_f64().to_bits())
        };
        let before_bits = bits(&v);
        for _ in 0..100 {
            assert_eq!(v.step(), Motion::Resting);
            assert_eq!(bits(&v), before_bits, "{}", S::NAME);
            v.advance();
        }
        assert_eq!(state(&v), before);
        assert_eq!(bits(&v), before_bits, "{}", S::NAME);
        // Retargeting to where it already is moves nothing, so it stays at rest.
        v.set_target(target);
        assert_eq!(state(&v), before);
        // A real retarget wakes it; the first step moves the first component toward
        // the new target and leaves the second (no offset, no velocity) where it is.
        v.set_target([s(0.0), s(-81.5)]);
        assert!(!v.is_at_rest());
        let _ = v.step();
        let p = v.position().map(|c| c.to_f64());
        assert!(p[0] < 37.25 && p[0] >= -37.25, "{}: {p:?}", S::NAME);
        assert_eq!(p[1], -81.5);
    }
}

#[test]
fn at_rest_the_value_sits_exactly_on_its_target_and_stays() {
    each_backend!(rest_is_exact_and_stable);
}

/// The dominant eigenvalue of one step on `(x, u)`: `M = [[1 − C_k, r], [−C_k, r]]` with
/// `r = 1 − C_d`. Returns `(ρ, c)`: its magnitude, and `|1 − 1/λ|`, the ratio `|u|/|x|` in
/// that mode (`u_n = x_n − x_{n−1}`).
fn dominant_pole(ck: f64, r: f64) -> (f64, f64) {
    let trace = 1.0 - ck + r;
    let disc = trace * trace - 4.0 * r;
    if disc < 0.0 {
        let (re, im) = (0.5 * trace, 0.5 * (-disc).sqrt());
        let rho2 = re * re + im * im;
        let (a, b) = (1.0 - re / rho2, im / rho2);
        (rho2.sqrt(), a.hypot(b))
    } else {
        let (l1, l2) = (0.5 * (trace + disc.sqrt()), 0.5 * (trace - disc.sqrt()));
        let l = if l1.abs() >= l2.abs() { l1 } else { l2 };
        (l.abs(), if l == 0.0 { 0.0 } else { (1.0 - 1.0 / l).abs() })
    }
}

/// The predicted number of steps to rest from an offset `amplitude`: the slowest mode
/// decays by `ρ` per step, and rest needs `|x| ≤ p/√2` and `|ũ| ≤ u_max`, where the kept
/// step velocity is `|ũ| = (1 − C_d)·c·|x|` in that mode. So the envelope must fall to
/// `min(p/√2, u_max/((1 − C_d)·c))`: `n* = ln(that / amplitude) / ln ρ`.
fn predicted_steps<S: Scalar>(tuning: &Tuning, t: &RestThreshold, amplitude: f64) -> f64 {
    let (ck, r) = (tuning.stiffness(), tuning.retention());
    let (rho, c) = dominant_pole(ck, r);
    let p = (t.position() / 2f64.sqrt()).max(S::RESOLUTION);
    let u_max = (p * ck.sqrt())
        .min(t.velocity() * tuning.dt())
        .max(S::RESOLUTION * ck.sqrt());
    let kept = (r * c).abs();
    let threshold = if kept > 0.0 { p.min(u_max / kept) } else { p };
    (threshold / amplitude).ln() / rho.ln()
}

fn settles_within_the_predicted_time<S: Scalar>(table: &mut Vec<String>) {
    let threshold = RestThreshold::default();
    for dt in [DT60, DT120] {
        for (name, osc) in ui_oscillators() {
            let tuning = osc.tuning(dt).expect("valid");
            let mut v = SpringValue::<S>::new([s(0.0)], &tuning).expect("valid");
            v.set_target([s(100.0)]);
            let n = steps_to_rest(&mut v, 100_000);
            assert_eq!(v.position(), [s(100.0)]);
            let n_star = predicted_steps::<S>(&tuning, &threshold, 100.0);
            // The initial amplitude of the slow mode is 100 times a factor of order one
            // (eigenvector conditioning, the critical double pole's n·ρⁿ): allow a factor
            // 1.6 plus 20 steps above, a factor 1/2 below (measured: 0.95 to 1.28).
            let (lo, hi) = (n_star / 2.0, 1.6 * n_star + 20.0);
            table.push(format!(
                "{:7} {:4.0} Hz  {name:38} n = {n:5}  n* = {n_star:7.1}  n/n* = {:.2}",
                S::NAME,
                1.0 / dt,
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
fn every_ui_preset_settles_in_every_backend_within_the_decay_bound() {
    let mut table = Vec::new();
    each_backend!(settles_within_the_predicted_time, &mut table);
    println!("steps to rest from an offset of 100, default threshold:");
    for line in &table {
        println!("{line}");
    }
}

/// With a threshold far below the last bit, a fixed-point value still settles: its step
/// ends on a fixed point inside the state's dead band (`1/C_k` of the state's last bits,
/// below a position's), and the band is at least a position's last bit.
fn fixed_point_settles_with_a_tiny_threshold<S: Scalar>(table: &mut Vec<String>) {
    let tiny = RestThreshold::new(1e-9, 1e-9).expect("positive");
    for dt in [DT60, DT120] {
        for (name, osc) in ui_oscillators() {
            let tuning = osc.tuning(dt).expect("valid");
            let mut v = SpringValue::<S>::new([s(0.0)], &tuning)
                .expect("valid")
                .with_rest_threshold(tiny);
            for start in [100.0, -3.0, 0.01] {
                v.set_position([s(start)]);
                let n = steps_to_rest(&mut v, 1_000_000);
                assert_eq!(v.position(), [S::ZERO]);
                if start == 100.0 {
                    table.push(format!(
                        "{:7} {:4.0} Hz  {name:38} n = {n:5}",
                        S::NAME,
                        1.0 / dt
                    ));
                }
            }
        }
    }
}

#[test]
fn fixed_point_settles_even_with_a_tiny_threshold() {
    let mut table = Vec::new();
    fixed_point_settles_with_a_tiny_threshold::<I16F16>(&mut table);
    fixed_point_settles_with_a_tiny_threshold::<I32F32>(&mut table);
    println!("steps to rest from 100 with RestThreshold::new(1e-9, 1e-9):");
    for line in &table {
        println!("{line}");
    }
}
