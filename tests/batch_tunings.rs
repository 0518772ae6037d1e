//! A tuning per value in a batch. Each value of a batch of several tunings steps exactly
//! as a lone `SpringValue` with its tuning (a value and a batch of one tuning step the
//! same, to the bit); a value given another tuning mid-flight goes on from its position
//! and velocity on the new spring, checked against the analytic oscillator of the
//! reference model (`lab::reference::analytic`); and the set-up refuses
//! what cannot work, changing nothing.

use lab::reference;
use stiffspring::{
    Error, I16F16, Oscillator, RestThreshold, Scalar, SpringBatch, SpringValue, Tuning, TuningSlot,
};

const DT: f64 = 1.0 / 60.0;
const ROWS: usize = 200;

/// 200 rows, every third one bouncy and every third one slow, moved by one row: each
/// matches a lone value of its tuning at every frame, and all come to rest together
/// with them.
fn rows_match_lone_values<S: Scalar + PartialEq + core::fmt::Debug>() {
    let tunings = [
        Tuning::from_frequency(3.0, 1.0, DT).unwrap(),
        Tuning::from_frequency(3.0, 0.3, DT).unwrap(),
        Tuning::from_frequency(1.0, 0.7, DT).unwrap(),
    ];
    let mut list = SpringBatch::<S, 1, ROWS, 3>::new(&tunings[0]).unwrap();
    let slots: Vec<TuningSlot> = tunings
        .iter()
        .map(|t| list.add_tuning(t).unwrap())
        .collect();
    assert_eq!(slots[0], TuningSlot::FIRST);
    let row = |k: usize| S::from_f64(k as f64 * 24.0);
    let ids: Vec<_> = (0..ROWS)
        .map(|k| list.push_with_tuning([row(k)], slots[k % 3]).unwrap())
        .collect();
    let mut lone: Vec<_> = (0..ROWS)
        .map(|k| SpringValue::<S, 1>::new([row(k)], &tunings[k % 3]).unwrap())
        .collect();
    for (k, &i) in ids.iter().enumerate() {
        list.set_target(i, [row(k + 1)]);
        lone[k].set_target([row(k + 1)]);
    }
    for frame in 1..2_000 {
        let moved = list.step();
        let mut awake = 0;
        for (k, v) in lone.iter_mut().enumerate() {
            if v.step() != stiffspring::Motion::Resting {
                awake += 1;
            }
            assert_eq!(
                list.position(ids[k]),
                Some(v.position()),
                "{}: row {k} (tuning {}), frame {frame}",
                S::NAME,
                k % 3
            );
            assert_eq!(
                list.is_at_rest(ids[k]),
                Some(v.is_at_rest()),
                "{}: row {k}",
                S::NAME
            );
        }
        if !moved.any() {
            assert_eq!(awake, 0, "{}: the lone values rest with the batch", S::NAME);
            return;
        }
    }
    panic!("{}: the list never settled", S::NAME);
}

#[test]
fn f32_rows_of_three_tunings_match_lone_values() {
    rows_match_lone_values::<f32>();
}

#[test]
fn i16f16_rows_of_three_tunings_match_lone_values() {
    rows_match_lone_values::<I16F16>();
}

/// A value thrown toward its target on a critically damped spring is switched, after
/// `switch` frames, to a bouncy one: from then on it follows the analytic oscillator of
/// the new spring started from the state it had, within `tolerance` of the amplitude.
fn switch_follows_the_new_spring<S: Scalar>(tolerance: f64) {
    const AMPLITUDE: f64 = 100.0;
    let calm = Oscillator::new(3.0, 1.0).unwrap();
    let bouncy = Oscillator::new(4.0, 0.15).unwrap();
    for switch in [1usize, 5, 17] {
        // A rest band too narrow to settle within the run: a snap to the target would
        // be the band's error, not the switch's.
        let mut b = SpringBatch::<S, 1, 4, 2>::new(&calm.tuning(DT).unwrap())
            .unwrap()
            .with_rest_threshold(RestThreshold::new(1e-300, 1e-300).unwrap());
        let hot = b.add_tuning(&bouncy.tuning(DT).unwrap()).unwrap();
        let i = b.push([S::from_f64(AMPLITUDE)]).unwrap();
        b.set_target(i, [S::ZERO]);
        for _ in 0..switch {
            let _ = b.step();
        }
        // The calm spring's analytic state at the switch, the start of the new one.
        let (x0, v0) = reference::analytic(
            AMPLITUDE,
            0.0,
            calm.angular_frequency(),
            1.0,
            switch as f64 * DT,
        );
        b.set_tuning_of(i, hot);
        assert_eq!(b.tuning_of(i), Some(hot));
        let mut worst: f64 = 0.0;
        for n in 1..=240 {
            let _ = b.step();
            let (x, _) = reference::analytic(
                x0,
                v0,
                bouncy.angular_frequency(),
                bouncy.damping_ratio(),
                n as f64 * DT,
            );
            worst = worst.max((b.position(i).unwrap()[0].to_f64() - x).abs() / AMPLITUDE);
        }
        assert!(
            worst <= tolerance,
            "{}: switched after {switch} frames: {worst:e} of the amplitude off the new spring",
            S::NAME
        );
    }
}

#[test]
fn f32_switch_mid_flight_follows_the_new_spring() {
    switch_follows_the_new_spring::<f32>(1e-5);
}

#[test]
fn i16f16_switch_mid_flight_follows_the_new_spring() {
    switch_follows_the_new_spring::<I16F16>(1e-4);
}

#[test]
fn f64_switch_mid_flight_follows_the_new_spring() {
    switch_follows_the_new_spring::<f64>(1e-9);
}

#[test]
fn set_up_refuses_what_cannot_work_and_changes_nothing() {
    let t = Tuning::from_frequency(3.0, 1.0, DT).unwrap();
    let other = Tuning::from_frequency(5.0, 0.5, DT).unwrap();
    // One tuning (the default): another is full, the same one is its own slot.
    let mut one = SpringBatch::<f32, 1, 4>::new(&t).unwrap();
    assert_eq!(one.add_tuning(&t), Ok(TuningSlot::FIRST));
    assert_eq!(
        one.add_tuning(&other),
        Err(Error::CapacityFull { capacity: 1 })
    );
    // Another time step: every value steps together.
    let mut two = SpringBatch::<f32, 1, 4, 2>::new(&t).unwrap();
    assert_eq!(
        two.add_tuning(&other.with_dt(1.0 / 120.0).unwrap()),
        Err(Error::TimeStepMismatch {
            expected: DT,
            found: 1.0 / 120.0
        })
    );
    assert_eq!(two.tuning_in(TuningSlot::FIRST), Some(t));
    let s = two.add_tuning(&other).unwrap();
    let i = two.push_with_tuning([1.0], s).unwrap();
    // A new tuning for all: the added slot is stale, the value has the new tuning.
    two.set_tuning(&t).unwrap();
    assert_eq!(two.tuning_of(i), Some(TuningSlot::FIRST));
    assert_eq!(two.tuning_in(s), None);
    assert!(matches!(
        two.try_set_tuning_of(i, s),
        Err(Error::Stale { .. })
    ));
    assert!(matches!(
        two.push_with_tuning([0.0], s),
        Err(Error::Stale { .. })
    ));
    assert_eq!(two.len(), 1, "nothing added");
    two.set_tuning_of(i, s); // ignored
    assert_eq!(two.tuning_of(i), Some(TuningSlot::FIRST));
    // A stale value.
    two.remove(i);
    assert!(matches!(
        two.try_set_tuning_of(i, TuningSlot::FIRST),
        Err(Error::Stale { .. })
    ));
}
