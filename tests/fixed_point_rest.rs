//! Fixed point comes to rest: every damped spring, from every start, ends within one
//! position LSB of its target with no limit cycle larger than that.
//!
//! The values are run with the smallest rest threshold there is (the band is then one
//! LSB of offset and of step velocity), so a value that kept cycling by more than one
//! LSB would never report `Settled`. The spring term of a step is rounded toward zero and
//! the damping term away from zero, so the damping never vanishes while the value moves
//! (see `Scalar`); the state keeps 24 (`I16F16`) or 32 (`I32F32`) bits below a position's
//! last bit, so the dead band `|x| < 1/C_k` state LSB is below a position's LSB.
//!
//! `cargo test --release --test fixed_point_rest -- --nocapture` prints the slowest case
//! and how long a unit move at 1, 5 and 10 kHz takes to settle.

use stiffspring::{I16F16, I32F32, Motion, RestThreshold, Scalar, SpringValue, Tuning};

/// Steps at most before a case counts as never settling.
const LIMIT: usize = 5_000_000;

fn starts<S: Scalar>() -> Vec<(f64, f64)> {
    let lsb = S::RESOLUTION;
    // (offset, velocity as a fraction of ω·offset scale): releases from a few LSB to a
    // hundred units, and flings.
    vec![
        (3.0 * lsb, 0.0),
        (-17.0 * lsb, 0.0),
        (0.37, 0.0),
        (1.0, 0.0),
        (-100.0, 0.0),
        (0.0, 1.0),
        (0.0, -40.0),
        (2.5, -3.0),
    ]
}

/// Steps until `Settled`, or `None`.
fn steps_to_rest<S: Scalar>(f_dt: f64, zeta: f64, start: (f64, f64)) -> Option<usize> {
    let dt = 1e-3;
    let tuning = Tuning::from_frequency(f_dt / dt, zeta, dt).ok()?;
    let tiny = RestThreshold::new(1e-12, 1e-12).ok()?;
    let mut v = SpringValue::<S>::new([S::from_f64(start.0)], &tuning)
        .ok()?
        .with_rest_threshold(tiny);
    v.set_target([S::ZERO]);
    let omega = 2.0 * core::f64::consts::PI * f_dt / dt;
    v.fling([S::from_f64(start.1 * omega)]);
    for n in 1..=LIMIT {
        if v.step() == Motion::Settled {
            assert_eq!(v.position(), [S::ZERO]);
            return Some(n);
        }
    }
    None
}

fn every_start_settles<S: Scalar>() {
    let mut slowest = (0, 0.0, 0.0);
    for &f_dt in &[1e-4, 1e-3, 1e-2, 0.1, 0.3] {
        for &zeta in &[0.05, 0.1, 0.3, 1.0, 2.0] {
            for start in starts::<S>() {
                let steps = steps_to_rest::<S>(f_dt, zeta, start);
                let Some(steps) = steps else {
                    panic!(
                        "{}: f·dt {f_dt}, ζ {zeta}, start {start:?} never settled",
                        S::NAME
                    );
                };
                if steps > slowest.0 {
                    slowest = (steps, f_dt, zeta);
                }
            }
        }
    }
    println!(
        "{}: every start settled; the slowest took {} steps (f·dt {}, ζ {})",
        S::NAME,
        slowest.0,
        slowest.1,
        slowest.2
    );
}

#[test]
fn i16f16_always_settles_within_a_last_bit() {
    every_start_settles::<I16F16>();
}

#[test]
fn i32f32_always_settles_within_a_last_bit() {
    every_start_settles::<I32F32>();
}

/// The unit move that used to teleport: at 5 and 10 kHz a 2 Hz spring's dead band was
/// wider than the move, so the value reached its target on the first step. Now it
/// animates, and does not snap while the continuous spring is farther than the threshold.
#[test]
fn a_unit_move_at_10_khz_animates() {
    for rate in [1000.0, 5000.0, 10_000.0] {
        let dt = 1.0 / rate;
        let tuning = Tuning::from_frequency(2.0, 0.3, dt).expect("valid");
        let mut v = SpringValue::<I16F16>::new([I16F16::ZERO], &tuning).expect("representable");
        v.set_target([I16F16::ONE]);
        let mut steps = 0;
        while v.step() == Motion::Moving {
            steps += 1;
        }
        // ζ = 0.3 at 2 Hz decays by e^{−ζωt}: below the default threshold (7.5e−4) after
        // about 1.7 s.
        let seconds = steps as f64 * dt;
        println!("I16F16, a unit move at {rate} Hz (2 Hz, ζ 0.3): settled after {seconds} s");
        assert!(
            seconds > 1.0 && seconds < 3.0,
            "{rate} Hz: settled after {seconds} s"
        );
    }
}
