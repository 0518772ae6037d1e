//! Choreography over a batch: a `Stagger` hands targets over a delay apart, and a `Trail`
//! makes values follow one another. Checked against independent `SpringValue`s (a value
//! and a batch with the same tuning step the same, to the bit) and against the
//! properties of a critically damped spring driven by a delayed, monotone target.

use stiffspring::{I16F16, Scalar, SpringBatch, SpringValue, Stagger, Trail, Tuning};

const ROWS: usize = 200;

/// 200 rows scrolling up by a row, each `spacing` frames after the one above: every row
/// moves exactly as a lone value that got its target `k·spacing` frames late.
fn stagger_matches_delayed_values<S: Scalar + PartialEq + core::fmt::Debug>(spacing: u32) {
    let tuning = Tuning::from_frequency(3.0, 0.8, 1.0 / 60.0).unwrap();
    let row = |k: usize| S::from_f64(k as f64 * 20.0);
    let mut list = SpringBatch::<S, 1, ROWS>::new(&tuning).unwrap();
    let ids: Vec<_> = (0..ROWS).map(|k| list.push([row(k)]).unwrap()).collect();
    let mut lone: Vec<_> = (0..ROWS)
        .map(|k| SpringValue::<S, 1>::new([row(k)], &tuning).unwrap())
        .collect();
    let mut stagger = Stagger::<S, 1, ROWS>::new();
    stagger.schedule_all(
        ids.iter().enumerate().map(|(k, &i)| (i, [row(k + 1)])),
        0,
        spacing,
    );
    let mut frames = 0;
    loop {
        for (k, v) in lone.iter_mut().enumerate() {
            if frames == k as u32 * spacing {
                v.set_target([row(k + 1)]);
            }
            let _ = v.step();
        }
        let moved = stagger.step(&mut list);
        frames += 1;
        for (k, v) in lone.iter().enumerate() {
            assert_eq!(
                list.position(ids[k]),
                Some(v.position()),
                "{}: row {k}, frame {frames}",
                S::NAME
            );
        }
        if !moved.any() && stagger.pending() == 0 {
            break;
        }
        assert!(frames < 10_000, "the list never settled");
    }
    for (k, &i) in ids.iter().enumerate() {
        assert_eq!(
            list.position(i),
            Some([row(k + 1)]),
            "{}: row {k} at rest on its target",
            S::NAME
        );
    }
    // The last row started (ROWS − 1)·spacing frames late.
    assert!(frames > (ROWS as u32 - 1) * spacing);
}

#[test]
fn a_stagger_is_each_row_moving_as_a_value_a_delay_later() {
    for spacing in [1, 3] {
        stagger_matches_delayed_values::<f32>(spacing);
        stagger_matches_delayed_values::<I16F16>(spacing);
    }
}

#[test]
fn a_stagger_ignores_what_it_cannot_hand_over() {
    let tuning = Tuning::rigid(0.01).unwrap();
    let mut b = SpringBatch::<f32, 1, 2>::new(&tuning).unwrap();
    let gone = b.push([0.0]).unwrap();
    let kept = b.push([0.0]).unwrap();
    b.remove(gone);
    let mut s = Stagger::<f32, 1, 2>::new();
    s.schedule(gone, [f32::NAN], 0);
    s.schedule(kept, [f32::NAN], 0);
    s.schedule(kept, [3.0], 1); // replaces the NaN
    assert_eq!(s.pending(), 2);
    let _ = s.step(&mut b);
    let _ = s.step(&mut b);
    assert_eq!(s.pending(), 0);
    assert_eq!(b.target(kept), Some([3.0]));
    assert_eq!(b.position(gone), None);
}

/// A chain of 20 dots, critically damped, the leader sent 100 units along x: each
/// follower is driven by its predecessor's (monotone) path, delayed, so it never passes
/// it, and the chain comes to rest in its original shape around the leader's target.
fn trail_lags_and_keeps_its_shape<S: Scalar + PartialEq + core::fmt::Debug>(tolerance: f64) {
    const DOTS: usize = 20;
    let tuning = Tuning::from_frequency(2.0, 1.0, 1.0 / 120.0).unwrap();
    let mut dots = SpringBatch::<S, 2, DOTS>::new(&tuning).unwrap();
    let ids: Vec<_> = (0..DOTS)
        .map(|k| {
            dots.push([S::from_f64(-(k as f64) * 4.0), S::from_f64(1.0)])
                .unwrap()
        })
        .collect();
    let mut trail = Trail::new(&dots, ids.iter().copied());
    assert_eq!(trail.len(), DOTS);
    trail.set_target(&mut dots, [S::from_f64(100.0), S::from_f64(1.0)]);
    let mut frames = 0;
    while trail.step(&mut dots).any() {
        frames += 1;
        assert!(frames < 20_000, "the trail never settled");
        for k in 1..DOTS {
            let lead = dots.position(ids[k - 1]).unwrap()[0].to_f64() + (k as f64 - 1.0) * 4.0;
            let follow = dots.position(ids[k]).unwrap()[0].to_f64() + k as f64 * 4.0;
            assert!(
                follow <= lead + tolerance && follow >= -tolerance,
                "{}: dot {k} at {follow} passed dot {} at {lead}, frame {frames}",
                S::NAME,
                k - 1
            );
        }
    }
    for (k, &i) in ids.iter().enumerate() {
        assert_eq!(
            dots.position(i),
            Some([S::from_f64(100.0 - k as f64 * 4.0), S::from_f64(1.0)]),
            "{}: dot {k} at rest",
            S::NAME
        );
    }
    // Each follower is at least a frame behind: the chain takes longer than one dot.
    let alone = tuning
        .settling_steps(100.0, 0.0, stiffspring::RestThreshold::default())
        .unwrap();
    assert!(
        frames > alone as usize + DOTS,
        "{frames} frames, one dot {alone}"
    );
}

#[test]
fn a_trail_lags_its_leader_and_keeps_its_shape() {
    trail_lags_and_keeps_its_shape::<f32>(1e-3);
    trail_lags_and_keeps_its_shape::<I16F16>(1e-3);
}
