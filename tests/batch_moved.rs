//! `SpringBatch::moved` as a display uses it: a screen model that only ever learns
//! positions from `moved()` (and from its own pushes) shows every value where the batch
//! has it after each frame, whatever the batch did between frames. The reference is the
//! batch's own `position()` read for every value, which `moved()` must never need.

use proptest::prelude::*;
use std::collections::HashMap;
use stiffspring::{BatchIndex, I16F16, Scalar, SpringBatch, Tuning};

const N: usize = 12;

/// What a frame's user does before the frame's steps.
#[derive(Clone, Debug)]
enum Action {
    Target(usize, f64),
    Position(usize, f64),
    Fling(usize, f64),
    Push(f64),
    Remove(usize),
    Nothing,
}

fn action() -> impl Strategy<Value = Action> {
    prop_oneof![
        (0..N, -400.0..400.0f64).prop_map(|(i, t)| Action::Target(i, t)),
        (0..N, -400.0..400.0f64).prop_map(|(i, p)| Action::Position(i, p)),
        (0..N, -2000.0..2000.0f64).prop_map(|(i, v)| Action::Fling(i, v)),
        (-400.0..400.0f64).prop_map(Action::Push),
        (0..N).prop_map(Action::Remove),
        Just(Action::Nothing),
    ]
}

/// Runs the frames; each has its actions, then 0–3 steps, then one `moved()` pass.
fn screen_follows_the_batch<S: Scalar + PartialEq + core::fmt::Debug>(
    frames: &[(Vec<Action>, u8)],
) {
    let tuning = Tuning::from_frequency(4.0, 0.7, 1.0 / 60.0).unwrap();
    let mut batch = SpringBatch::<S, 1, N>::new(&tuning).unwrap();
    let mut ids: Vec<BatchIndex> = Vec::new();
    let mut screen: HashMap<BatchIndex, [S; 1]> = HashMap::new();
    for (frame, (actions, steps)) in frames.iter().enumerate() {
        for a in actions {
            let pick = |i: usize| ids.get(i % ids.len().max(1)).copied();
            match *a {
                Action::Target(i, t) => {
                    if let Some(id) = pick(i) {
                        batch.set_target(id, [S::from_f64(t)]);
                    }
                }
                Action::Position(i, p) => {
                    if let Some(id) = pick(i) {
                        batch.set_position(id, [S::from_f64(p)]);
                    }
                }
                Action::Fling(i, v) => {
                    if let Some(id) = pick(i) {
                        batch.fling(id, [S::from_f64(v)]);
                    }
                }
                Action::Push(p) => {
                    if let Ok(id) = batch.push([S::from_f64(p)]) {
                        ids.push(id);
                        screen.insert(id, [S::from_f64(p)]); // the user draws what it adds
                    }
                }
                Action::Remove(i) => {
                    if let Some(id) = pick(i) {
                        batch.remove(id);
                        ids.retain(|&k| k != id);
                        screen.remove(&id); // and erases what it removes
                    }
                }
                Action::Nothing => {}
            }
        }
        for _ in 0..*steps {
            let _ = batch.step();
        }
        let mut seen = Vec::new();
        for m in batch.moved() {
            assert!(
                !seen.contains(&m.index),
                "{}: frame {frame}: reported twice",
                S::NAME
            );
            seen.push(m.index);
            assert_ne!(
                m.from,
                m.to,
                "{}: frame {frame}: a move that did not move",
                S::NAME
            );
            let drawn = screen.get_mut(&m.index).expect("a removed value reported");
            assert_eq!(
                *drawn,
                m.from,
                "{}: frame {frame}: from is not what was drawn",
                S::NAME
            );
            *drawn = m.to;
        }
        for &id in &ids {
            assert_eq!(
                Some(screen[&id]),
                batch.position(id),
                "{}: frame {frame}: the screen shows {id:?} where it is not",
                S::NAME
            );
        }
    }
}

proptest! {
    #[test]
    fn f32_screen_follows_the_batch(frames in prop::collection::vec((prop::collection::vec(action(), 0..3), 0..4u8), 1..120)) {
        screen_follows_the_batch::<f32>(&frames);
    }

    #[test]
    fn i16f16_screen_follows_the_batch(frames in prop::collection::vec((prop::collection::vec(action(), 0..3), 0..4u8), 1..120)) {
        screen_follows_the_batch::<I16F16>(&frames);
    }
}

/// A settled list visits nothing: after everything came to rest and was reported once,
/// `moved()` yields nothing, and a value woken and settled between two calls is reported
/// once, at its rest.
#[test]
fn settled_values_are_reported_once() {
    let tuning = Tuning::from_frequency(4.0, 1.0, 1.0 / 60.0).unwrap();
    let mut batch = SpringBatch::<f32, 1, 200>::new(&tuning).unwrap();
    let ids: Vec<_> = (0..200).map(|k| batch.push([k as f32]).unwrap()).collect();
    assert_eq!(batch.moved().count(), 0, "nothing moved yet");
    batch.set_target(ids[5], [50.0]);
    while batch.step().any() {}
    let m: Vec<_> = batch.moved().collect();
    assert_eq!(m.len(), 1);
    assert_eq!((m[0].index, m[0].from, m[0].to), (ids[5], [5.0], [50.0]));
    assert_eq!(batch.moved().count(), 0, "reported at rest: off the list");
}
