//! `SpringBatch` in every backend: a member is a standalone `SpringValue` with the same
//! tuning, bit for bit, through retargets, flings, retunes and rest, and the batch's step
//! reports exactly the standalone values' events; indices are generational (a removed
//! value's index names nothing, never its successor); resting members cost nothing and
//! never move; capacity, removal and a sparse rest test behave as documented.

use stiffspring::presets::{react_spring, swiftui};
use stiffspring::{
    BatchIndex, BatchMotion, Error, Motion, Parameter, Scalar, SpringBatch, SpringValue, Tuning,
};

mod support;
use support::{DT60, DT120, s};

/// Bit-identical: equal, and for floats also the same sign of zero.
fn same_all<S: Scalar, const D: usize>(a: [S; D], b: [S; D]) -> bool {
    a.iter()
        .zip(b.iter())
        .all(|(x, y)| x == y && x.to_f64().to_bits() == y.to_f64().to_bits())
}

type Batch<S> = SpringBatch<S, 2, 8>;

/// One scripted call on the batch and on the standalone values alike.
fn script<S: Scalar>(n: usize, idx: &[BatchIndex], b: &mut Batch<S>, a: &mut [SpringValue<S, 2>]) {
    let mut target = |i: usize, t: [f64; 2]| {
        b.set_target(idx[i], t.map(s));
        a[i].set_target(t.map(s));
    };
    match n {
        0 => {
            target(0, [50.0, -50.0]);
            target(2, [20.0, 20.0]);
            target(3, [-100.0, 8.0]);
        }
        10 => target(0, [-10.0, 0.0]), // mid-flight
        40 => target(1, [6.0, 6.0]),   // member 1 was resting
        _ => {}
    }
    let mut fling = |i: usize, v: [f64; 2]| {
        b.fling(idx[i], v.map(s));
        a[i].fling(v.map(s));
    };
    match n {
        0 => fling(4, [300.0, -10.0]),
        10 => fling(3, [-500.0, 500.0]),
        _ => {}
    }
    if n == 25 {
        // The display changes rate: every value is retuned, keeping position and velocity.
        let t = b.tuning().with_dt(DT120).expect("valid");
        b.set_tuning(&t).expect("representable");
        for v in a.iter_mut() {
            v.set_tuning(&t).expect("representable");
        }
    }
}

fn member_is_a_standalone_value<S: Scalar>(tuning: &Tuning) {
    let starts = [
        [0.0, 1.0],
        [5.0, -5.0],
        [-20.0, 3.5],
        [100.0, 0.0],
        [0.25, -0.75],
    ];
    let mut batch = Batch::<S>::new(tuning).expect("representable");
    let mut alone: Vec<SpringValue<S, 2>> = Vec::new();
    let mut idx = Vec::new();
    for p in starts {
        idx.push(batch.push(p.map(s)).expect("room"));
        alone.push(SpringValue::new(p.map(s), tuning).expect("representable"));
    }
    for n in 0..5000 {
        script(n, &idx, &mut batch, &mut alone);
        let motion = batch.step();
        let motions: Vec<Motion> = alone.iter_mut().map(|a| a.step()).collect();
        // The same events: how many moved, which settled, which move on.
        let count = |m: Motion| motions.iter().filter(|&&x| x == m).count();
        let expected = BatchMotion {
            moving: count(Motion::Moving),
            settled: count(Motion::Settled),
        };
        assert_eq!(motion, expected, "{} step {n}", S::NAME);
        let settled: Vec<BatchIndex> = batch.just_settled().collect();
        let moving: Vec<BatchIndex> = batch.moving().map(|(i, _)| i).collect();
        for (k, m) in motions.iter().enumerate() {
            assert_eq!(settled.contains(&idx[k]), *m == Motion::Settled, "step {n}");
            assert_eq!(moving.contains(&idx[k]), *m == Motion::Moving, "step {n}");
        }
        for (i, p) in batch.moving() {
            assert!(same_all(p, batch.position(i).expect("live")));
        }
        // The same state, bit for bit.
        for (k, a) in alone.iter().enumerate() {
            let i = idx[k];
            assert!(
                same_all(batch.position(i).expect("live"), a.position()),
                "{} member {k} step {n}",
                S::NAME
            );
            assert!(same_all(batch.velocity(i).expect("live"), a.velocity()));
            assert!(same_all(batch.target(i).expect("live"), a.target()));
            assert_eq!(
                batch.is_at_rest(i),
                Some(a.is_at_rest()),
                "member {k} step {n}"
            );
        }
        assert_eq!(
            batch.awake(),
            alone.iter().filter(|a| !a.is_at_rest()).count()
        );
        if n > 40 && batch.awake() == 0 {
            return;
        }
    }
    panic!("{}: the batch did not come to rest", S::NAME);
}

fn members_are_standalone_values<S: Scalar>() {
    for tuning in [
        swiftui::SNAPPY.tuning(DT60),
        Tuning::from_coefficients(0.05, 0.25, DT60),
        Tuning::rigid(DT60),
        react_spring::WOBBLY.tuning(DT60),
        Tuning::from_frequency(1.0, 2.0, DT60),
    ] {
        member_is_a_standalone_value::<S>(&tuning.expect("valid"));
    }
}

#[test]
fn a_batch_member_is_a_standalone_value_bit_for_bit() {
    each_backend!(members_are_standalone_values);
}

fn indices_are_generational<S: Scalar>() {
    let tuning = swiftui::SMOOTH.tuning(DT60).expect("valid");
    let mut b = SpringBatch::<S, 1, 4>::new(&tuning).expect("representable");
    let keep = b.push([s(1.0)]).expect("room");
    let old = b.push([s(2.0)]).expect("room");
    b.set_target(old, [s(10.0)]);
    let _ = b.step();
    let at = b.position(old).expect("live");
    assert_eq!(b.remove(old), Some(at));
    assert_eq!((b.len(), b.awake()), (1, 0));
    let new = b.push([s(3.0)]).expect("room");
    assert_eq!(new.slot(), old.slot()); // the slot is reused...
    assert_ne!(new, old); // ...the index is not
    // The old index names nothing: reads give None, the infallible setters ignore it,
    // the `try_` setters say so, and the new value is untouched.
    assert_eq!(b.position(old), None);
    assert_eq!(
        (b.target(old), b.velocity(old), b.is_at_rest(old)),
        (None, None, None)
    );
    b.set_target(old, [s(-5.0)]);
    b.set_position(old, [s(-5.0)]);
    b.fling(old, [s(-5.0)]);
    let stale = Err(Error::Stale {
        parameter: Parameter::Index,
    });
    assert_eq!(b.try_set_target(old, [s(-5.0)]), stale);
    assert_eq!(b.try_fling(old, [s(-5.0)]), stale);
    assert_eq!(b.remove(old), None);
    assert_eq!(b.position(new), Some([s(3.0)]));
    assert_eq!((b.is_at_rest(new), b.awake()), (Some(true), 0));
    assert_eq!(b.position(keep), Some([s(1.0)]));
    let listed: Vec<BatchIndex> = b.iter().map(|(i, _)| i).collect();
    assert_eq!(listed, [keep, new]);
}

#[test]
fn a_removed_value_s_index_never_names_its_successor() {
    each_backend!(indices_are_generational);
}

fn removal_and_capacity<S: Scalar>() {
    let tuning = Tuning::from_coefficients(0.1, 0.5, DT120).expect("valid");
    let mut b = SpringBatch::<S, 3, 7>::new(&tuning).expect("representable");
    assert!(b.is_empty());
    let idx: Vec<BatchIndex> = (0..7)
        .map(|k| b.push([s(k as f64); 3]).expect("room"))
        .collect();
    assert_eq!(
        b.push([S::ZERO; 3]),
        Err(Error::CapacityFull { capacity: 7 })
    );
    assert_eq!(b.len(), 7);
    // Removing a moving value: it leaves the awake list and is never reported.
    b.set_target(idx[2], [s(50.0); 3]);
    b.set_target(idx[5], [s(-50.0); 3]);
    let _ = b.step();
    assert_eq!(b.awake(), 2);
    assert!(b.remove(idx[2]).is_some());
    assert_eq!((b.len(), b.awake()), (6, 1));
    while b.step().any() {
        assert!(b.just_settled().all(|i| i == idx[5]));
        assert!(b.moving().all(|(i, _)| i == idx[5]));
    }
    assert_eq!(b.position(idx[5]), Some([s(-50.0); 3]));
    // The freed slot takes the next value.
    let again = b.push([s(9.0); 3]).expect("room");
    assert_eq!(again.slot(), idx[2].slot());
    assert_eq!(
        b.push([S::ZERO; 3]),
        Err(Error::CapacityFull { capacity: 7 })
    );
}

#[test]
fn a_batch_holds_its_capacity_and_removes_moving_values_cleanly() {
    each_backend!(removal_and_capacity);
}

fn resting_members_never_move<S: Scalar>() {
    let t = swiftui::SMOOTH.tuning(DT60).expect("valid");
    let mut b = SpringBatch::<S, 1, 5>::new(&t).expect("representable");
    let idx: Vec<BatchIndex> = (0..5)
        .map(|k| b.push([s(k as f64)]).expect("room"))
        .collect();
    assert_eq!(b.awake(), 0);
    // A retarget to where a value is moves nothing: it stays asleep.
    b.set_target(idx[0], [s(0.0)]);
    assert_eq!((b.is_at_rest(idx[0]), b.awake()), (Some(true), 0));
    b.set_target(idx[1], [s(40.0)]);
    b.set_target(idx[3], [s(-40.0)]);
    assert_eq!(b.awake(), 2);
    let mut n = 0;
    while b.step().any() {
        n += 1;
        assert!(n < 10_000);
        for i in [0, 2, 4] {
            assert_eq!(b.position(idx[i]), Some([s(i as f64)]));
        }
    }
    assert_eq!(b.position(idx[1]), Some([s(40.0)]));
    assert_eq!(b.position(idx[3]), Some([s(-40.0)]));
    // Retargeting one resting member wakes exactly that one.
    let before: Vec<_> = idx.iter().map(|&i| b.position(i)).collect();
    b.set_target(idx[2], [s(-7.0)]);
    assert_eq!(
        b.step(),
        BatchMotion {
            moving: 1,
            settled: 0
        }
    );
    for (k, p) in before.iter().enumerate() {
        assert_eq!(b.position(idx[k]) != *p, k == 2, "{} member {k}", S::NAME);
    }
}

#[test]
fn a_batch_steps_only_awake_members_and_a_retarget_wakes_exactly_one() {
    each_backend!(resting_members_never_move);
}

/// With the rest test every `k` steps, a value settles at the first test after it entered
/// its band, on its target: up to `k − 1` steps after a batch that tests every step.
fn sparse_rest_test<S: Scalar>() {
    let t = Tuning::from_frequency(3.0, 0.8, DT60).expect("valid");
    let settle_step = |every: u16| {
        let mut b = SpringBatch::<S, 1, 2>::new(&t)
            .expect("representable")
            .with_rest_check_every(every);
        let i = b.push([s(0.0)]).expect("room");
        b.set_target(i, [s(100.0)]);
        let mut n = 0;
        loop {
            n += 1;
            if b.step().settled == 1 {
                assert_eq!(b.position(i), Some([s(100.0)]));
                return n;
            }
        }
    };
    let every_step = settle_step(1);
    for k in [2u16, 4, 7] {
        let n = settle_step(k);
        assert!(
            n >= every_step && n < every_step + k as usize,
            "{} every {k}: {n}",
            S::NAME
        );
        assert_eq!(n % k as usize, 0, "tested at steps k, 2k, 3k, …");
    }
}

#[test]
fn a_sparse_rest_test_settles_within_its_period() {
    each_backend!(sparse_rest_test);
}
