//! The structure of a value: a `D`-dimensional value is `D` one-dimensional values, bit
//! for bit, until it settles (it settles when the last of them would); and the trajectory
//! from the mirrored start is the exact mirror, in every backend (in fixed point, read
//! with its one asymmetry: a state half-way between two positions reads as the upper).

use stiffspring::presets::{android, react_spring, swiftui};
use stiffspring::{Motion, Scalar, SpringValue, Tuning};

mod support;
use support::{DT60, DT120, s};

/// Bit-identical: equal, and for floats also the same sign of zero.
fn same<S: Scalar>(a: S, b: S) -> bool {
    a == b && a.to_f64().to_bits() == b.to_f64().to_bits()
}

fn same_all<S: Scalar, const D: usize>(a: [S; D], b: [S; D]) -> bool {
    a.iter().zip(b.iter()).all(|(x, y)| same(*x, *y))
}

fn raw(ck: f64, cd: f64, dt: f64) -> Tuning {
    Tuning::from_coefficients(ck, cd, dt).expect("in the square")
}

fn value<S: Scalar, const D: usize>(p: [f64; D], tuning: &Tuning) -> SpringValue<S, D> {
    SpringValue::new(p.map(s), tuning).expect("representable")
}

fn three_d_equals_three_1d<S: Scalar>() {
    let starts = [3.0, -40.0, 0.5];
    let targets = [100.0, 12.5, -7.25];
    let flings = [0.0, 30.0, -200.0];
    let tunings = [
        swiftui::BOUNCY.tuning(DT60).expect("valid"),
        react_spring::MOLASSES.tuning(DT120).expect("valid"),
        raw(0.02, 0.1, DT60),
    ];
    for tuning in tunings {
        let mut v3 = value::<S, 3>(starts, &tuning);
        v3.set_target(targets.map(s));
        v3.fling(flings.map(s));
        let mut v1: Vec<SpringValue<S>> = (0..3)
            .map(|k| {
                let mut v = value::<S, 1>([starts[k]], &tuning);
                v.set_target([s(targets[k])]);
                v.fling([s(flings[k])]);
                v
            })
            .collect();
        let mut rest_step = [None; 3];
        let mut compared = 0;
        for n in 1..100_000 {
            let moved = v3.step();
            for (k, v) in v1.iter_mut().enumerate() {
                if v.step() == Motion::Settled {
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
            if moved == Motion::Settled {
                // It rests only once every component is inside its band, so never before
                // the last 1-D value.
                let last = rest_step.iter().map(|r| r.unwrap_or(usize::MAX)).max();
                assert!(
                    Some(n) >= last,
                    "{}: 3-D at {n}, 1-D at {rest_step:?}",
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

fn trajectories_are_symmetric<S: Scalar>() {
    let tunings = [
        swiftui::BOUNCY.tuning(DT60).expect("valid"),
        react_spring::MOLASSES.tuning(DT60).expect("valid"),
        android::spring_force(10_000.0, 0.2)
            .expect("valid")
            .tuning(DT60)
            .expect("valid"),
        raw(0.05, 0.2, DT60),
        raw(0.5, 0.0, DT60),
        Tuning::from_coefficients_extended(1.5, 0.5, DT60).expect("stable"),
        Tuning::rigid(DT60).expect("dt"),
    ];
    let starts = [
        (100.0, 0.0, 0.0),
        (37.5, -12.25, 250.0),
        (-0.001, 3.0, -1.0),
        (1.0 / 3.0, 0.0, 7.0),
    ];
    for tuning in tunings {
        for (x0, t0, v0) in starts {
            let mut a = value::<S, 1>([x0], &tuning);
            let mut b = value::<S, 1>([-x0], &tuning);
            a.set_target([s(t0)]);
            b.set_target([s(-t0)]);
            a.fling([s(v0)]);
            b.fling([s(-v0)]);
            let mut ties = 0;
            for n in 0..20_000 {
                // Floats: equal as numbers (an exact cancellation gives +0 on both sides
                // in IEEE arithmetic, so the sign of a zero is not mirrored). Fixed point:
                // the state is the exact mirror (both roundings of the step are odd), and
                // a read rounds it half up, so where it lies exactly half-way between two
                // positions the mirrored reads are one last bit apart.
                for (ra, rb) in [
                    (a.position()[0], b.position()[0]),
                    (a.offset()[0], b.offset()[0]),
                    (a.step_velocity()[0], b.step_velocity()[0]),
                ] {
                    if rb != ra.neg() {
                        let gap = (ra.to_f64() + rb.to_f64()).abs();
                        assert!(
                            S::RESOLUTION > 0.0 && gap <= S::RESOLUTION,
                            "{} step {n}: {ra:?} vs {rb:?}",
                            S::NAME
                        );
                        ties += 1;
                    }
                }
                let (ma, mb) = (a.step(), b.step());
                assert_eq!(ma, mb);
                if ma == Motion::Resting {
                    break;
                }
            }
            // Half-way states are rare: a few per run.
            assert!(
                ties <= 30,
                "{} {tuning:?}: {ties} reads a bit apart",
                S::NAME
            );
            // (The undamped raw spring rings for ever: compared over 20 000 steps.)
            assert!(
                a.is_at_rest() || tuning.damping() == 0.0,
                "{}: {tuning:?}",
                S::NAME
            );
        }
    }
}

#[test]
fn the_trajectory_from_minus_x0_is_the_exact_negation() {
    each_backend!(trajectories_are_symmetric);
}
